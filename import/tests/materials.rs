//! Materials as artists export them: the MTL's values in the generated
//! `MaterialDesc`, OpenGL's ranges enforced (clamp and warn, or `--strict`),
//! a missing MTL or texture a warning and a default, several materials and
//! textures as parts, and the build-script route's `cargo:` lines.

mod common;

use common::{scratch, write};
use fixshade::lighting::MaterialDesc;
use fixshade_import::{build, import, Error, FileKind, Options, TextureChoice};

/// A unit square in two triangles with texture coordinates, `usemtl` each.
fn square(mtllib: &str, materials: [&str; 2]) -> String {
    format!(
        "mtllib {mtllib}\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         usemtl {}\nf 1/1 2/2 3/3\nusemtl {}\nf 1/1 3/3 4/4\n",
        materials[0], materials[1]
    )
}

/// A 2 × 2 PNG.
fn png() -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, 2, 2);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header()
            .unwrap()
            .write_image_data(&[255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255])
            .unwrap();
    }
    out
}

fn strict(name: &str) -> Options {
    Options {
        strict: true,
        ..Options::new(name)
    }
}

#[test]
fn mtl_values_become_the_material_desc() {
    let dir = scratch("mtl_values");
    write(
        &dir,
        "m.mtl",
        "newmtl copper\nKa 0.1 0.05 0.02\nKd 0.8 0.4 0.2\nKs 0.5 0.5 0.5\nNs 40\nKe 0.1 0 0\nd 0.75\n",
    );
    let p = write(&dir, "m.obj", square("m.mtl", ["copper", "copper"]));
    let m = import(&p, &Options::new("M")).unwrap();
    assert_eq!(m.parts.len(), 1);
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    let mat = &m.parts[0].material;
    assert_eq!(mat.name.as_deref(), Some("copper"));
    assert_eq!(
        mat.desc,
        MaterialDesc {
            emission: [0.1, 0.0, 0.0],
            ambient: [0.1, 0.05, 0.02],
            diffuse: [0.8, 0.4, 0.2],
            specular: [0.5; 3],
            shininess: 40.0,
            ..MaterialDesc::default()
        }
    );
    assert_eq!(mat.opacity, 0.75);
    // in the generated source, for Material::new
    let src = m.to_rust();
    for line in [
        "pub const M_MATERIAL: ::fixshade::lighting::MaterialDesc = ::fixshade::lighting::MaterialDesc {",
        "    diffuse: [0.8, 0.4, 0.2],",
        "    ambient: [0.1, 0.05, 0.02],",
        "    specular: [0.5, 0.5, 0.5],",
        "    emission: [0.1, 0.0, 0.0],",
        "    shininess: 40.0,",
        "pub const M_OPACITY: f32 = 0.75;",
        "pub const M_VERTICES: usize = 4;",
        "pub const M_TRIANGLE_COUNT: usize = 2;",
        "pub type M_BUFFERS<V, const NB: usize, const NC: usize> =",
        "    (M, M_MATERIAL, ::core::option::Option::None),",
    ] {
        assert!(src.contains(line), "{line}\n{src}");
    }
    // Tr without d: opacity 1 − Tr
    write(&dir, "m.mtl", "newmtl copper\nKd 1 1 1\nTr 0.25\n");
    let m = import(&p, &Options::new("M")).unwrap();
    assert_eq!(m.parts[0].material.opacity, 0.75);
}

#[test]
fn absent_statements_keep_opengl_defaults() {
    let dir = scratch("mtl_defaults");
    write(&dir, "m.mtl", "newmtl red\nKd 1 0 0\n");
    let p = write(&dir, "m.obj", square("m.mtl", ["red", "red"]));
    let m = import(&p, &Options::new("M")).unwrap();
    let d = MaterialDesc::default();
    // OpenGL's default material: ambient 0.2, diffuse 0.8, specular 0, shininess 0
    assert_eq!(
        (d.ambient, d.diffuse, d.specular),
        ([0.2; 3], [0.8; 3], [0.0; 3])
    );
    assert_eq!((d.shininess, d.emission), (0.0, [0.0; 3]));
    assert_eq!(
        m.parts[0].material.desc,
        MaterialDesc {
            diffuse: [1.0, 0.0, 0.0],
            ..d
        }
    );
    assert_eq!(m.parts[0].material.opacity, 1.0);
}

#[test]
fn values_outside_opengl_ranges_clamp_with_a_warning_or_fail_with_strict() {
    let dir = scratch("mtl_ranges");
    write(
        &dir,
        "m.mtl",
        "newmtl shiny\nKd 0.5 -0.25 0.5\nNs 250\nd 1.5\n",
    );
    let p = write(&dir, "m.obj", square("m.mtl", ["shiny", "shiny"]));
    let m = import(&p, &Options::new("M")).unwrap();
    let d = &m.parts[0].material.desc;
    assert_eq!(d.diffuse, [0.5, 0.0, 0.5]);
    assert_eq!(d.shininess, 128.0);
    assert_eq!(m.parts[0].material.opacity, 1.0);
    let w = m.warnings.join("\n");
    for expected in [
        "material `shiny`: Kd[1] -0.25 is outside ≥ 0: clamped to 0",
        "material `shiny`: Ns 250 is outside 0..=128: clamped to 128",
        "material `shiny`: d 1.5 is outside 0..=1: clamped to 1",
    ] {
        assert!(w.contains(expected), "{expected}\n{w}");
    }
    match import(&p, &strict("M")) {
        Err(e @ Error::Material { .. }) => {
            assert!(
                e.to_string().contains("material `shiny`: Kd[1] -0.25"),
                "{e}"
            )
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_missing_mtl_is_a_warning_and_the_default_material() {
    let dir = scratch("missing_mtl");
    let p = write(&dir, "m.obj", square("nowhere.mtl", ["a", "b"]));
    let missing = dir.join("nowhere.mtl");
    for texture in [TextureChoice::FromModel, TextureChoice::None] {
        let o = Options {
            texture,
            ..Options::new("M")
        };
        let m = import(&p, &o).unwrap();
        // one part: the faces' materials are all unknown, i.e. the default
        assert_eq!(m.parts.len(), 1);
        assert_eq!(m.parts[0].material.name, None);
        assert_eq!(m.parts[0].material.desc, MaterialDesc::default());
        assert!(m.texture().is_none());
        assert_eq!(
            m.warnings,
            [format!(
                "material library file not found: {}: its materials are OpenGL's default \
                 material, untextured",
                missing.display()
            )]
        );
        assert!(m.files.contains(&missing));
        assert!(m
            .to_rust()
            .contains("/// `M`'s material, from OpenGL's default material"));
    }
    // --strict: the error of before
    match import(&p, &strict("M")) {
        Err(
            e @ Error::MissingFile {
                kind: FileKind::MaterialLibrary,
                ..
            },
        ) => assert_eq!(
            e.to_string(),
            format!("material library file not found: {}", missing.display())
        ),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_material_no_library_defines_is_the_default_material() {
    let dir = scratch("unfound_material");
    write(&dir, "m.mtl", "newmtl a\nKd 1 0 0\n");
    let p = write(&dir, "m.obj", square("m.mtl", ["a", "b"]));
    let m = import(&p, &Options::new("M")).unwrap();
    assert_eq!(
        m.warnings,
        ["no material library defines `b`: OpenGL's default material used"]
    );
    assert_eq!(m.parts.len(), 2);
    assert_eq!(m.parts[0].material.desc.diffuse, [1.0, 0.0, 0.0]);
    assert_eq!(m.parts[1].material.name, None);
    assert_eq!(m.parts[1].material.desc, MaterialDesc::default());
}

#[test]
fn a_missing_texture_is_a_warning_and_no_texture() {
    let dir = scratch("missing_texture");
    write(&dir, "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nmap_Kd gone.png\n");
    let p = write(&dir, "m.obj", square("m.mtl", ["a", "a"]));
    let m = import(&p, &Options::new("M")).unwrap();
    assert!(m.texture().is_none());
    assert_eq!(
        m.warnings,
        [format!(
            "texture file not found: {} (material `a`): drawn untextured",
            dir.join("gone.png").display()
        )]
    );
    // the material is kept; the texture coordinates too (a texture may be given later)
    assert_eq!(m.parts[0].material.desc.diffuse, [0.5; 3]);
    assert!(m.mesh().texcoords.is_some());
    assert!(!m.to_rust().contains("M_TEXTURE"));
    match import(&p, &strict("M")) {
        Err(Error::MissingFile {
            kind: FileKind::Texture,
            path,
        }) => assert_eq!(path, dir.join("gone.png")),
        other => panic!("{other:?}"),
    }
}

#[test]
fn two_materials_and_two_textures_make_two_parts() {
    let dir = scratch("two_materials");
    write(&dir, "a.png", png());
    write(&dir, "b.png", png());
    write(
        &dir,
        "m.mtl",
        "newmtl a\nKd 1 0 0\nmap_Kd a.png\nnewmtl b\nKd 0 0 1\nmap_Kd b.png\n",
    );
    let p = write(&dir, "m.obj", square("m.mtl", ["a", "b"]));
    let m = import(&p, &Options::new("SQ")).unwrap();
    assert_eq!(m.parts.len(), 2);
    assert_eq!(m.textures.len(), 2);
    for (k, (name, diffuse)) in [("SQ_PART0", [1.0, 0.0, 0.0]), ("SQ_PART1", [0.0, 0.0, 1.0])]
        .into_iter()
        .enumerate()
    {
        let part = &m.parts[k];
        assert_eq!(part.name, name);
        assert_eq!(part.material.desc.diffuse, diffuse);
        assert_eq!(part.mesh.triangles.len(), 1);
        assert_eq!(part.mesh.positions.len(), 3);
        assert_eq!(part.texture, Some(k));
        assert_eq!(part.mesh.frac, m.report.frac);
    }
    let src = m.to_rust();
    assert!(src.contains("pub const SQ_PART_COUNT: usize = 2;"));
    assert!(src.contains("pub static SQ_PART1_TEXTURE: ::fixshade::texture::Texture<'static> ="));
    assert!(!src.contains("pub static SQ:"), "no single mesh named SQ");
    // one texture for both: converted and stored once
    write(
        &dir,
        "m.mtl",
        "newmtl a\nKd 1 0 0\nmap_Kd a.png\nnewmtl b\nKd 0 0 1\nmap_Kd a.png\n",
    );
    let m = import(&p, &Options::new("SQ")).unwrap();
    assert_eq!(m.textures.len(), 1);
    assert_eq!((m.parts[0].texture, m.parts[1].texture), (Some(0), Some(0)));
    let src = m.to_rust();
    assert!(src.contains("pub static SQ_PART1_TEXTURE: ::fixshade::texture::Texture<'static> = SQ_PART0_TEXTURE;"), "{src}");
    assert_eq!(src.matches("_TEXELS: [u16; 4]").count(), 1);
    // --texture FILE: every part gets it
    let o = Options {
        texture: TextureChoice::File(dir.join("b.png")),
        ..Options::new("SQ")
    };
    let m = import(&p, &o).unwrap();
    assert_eq!(m.textures.len(), 1);
    assert!(m.parts.iter().all(|p| p.texture == Some(0)));
}

#[test]
fn the_build_route_prints_warnings_and_watches_missing_files() {
    let dir = scratch("build_route");
    let p = write(&dir, "m.obj", square("nowhere.mtl", ["a", "a"]));
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let mut cargo = Vec::new();
    let written = build::generate_in(&p, &out, "m.rs", &Options::new("M"), &mut cargo).unwrap();
    assert_eq!(written, out.join("m.rs"));
    let cargo = String::from_utf8(cargo).unwrap();
    assert!(
        cargo.contains(&format!(
            "cargo:warning=m.obj: material library file not found: {}",
            dir.join("nowhere.mtl").display()
        )),
        "{cargo}"
    );
    // the missing MTL's folder: the script reruns when it appears
    assert!(
        cargo.contains(&format!("cargo:rerun-if-changed={}\n", dir.display())),
        "{cargo}"
    );
    assert!(std::fs::read_to_string(&written)
        .unwrap()
        .contains("pub const M_MATERIAL"));
    // Options::strict: the error
    let mut cargo = Vec::new();
    assert!(matches!(
        build::generate_in(&p, &out, "m.rs", &strict("M"), &mut cargo),
        Err(Error::MissingFile {
            kind: FileKind::MaterialLibrary,
            ..
        })
    ));
}
