//! The generated source compiles (`include!`) and renders with fixshade: the
//! committed `tests/generated/rocket.rs` drawn textured into
//! `target/tmp/rocket.png`, and the two-material `tests/generated/crate.rs`
//! (two parts, two textures) in one frame into `target/tmp/crate.png`.

mod common;

#[allow(dead_code)] // (what a firmware would use; the tests read some)
mod generated {
    include!("generated/rocket.rs");
}

#[allow(dead_code)]
mod crate_model {
    include!("generated/crate.rs");
}

use fixshade::num::Mat4;
use fixshade::prelude::{Rgb888, RgbColor};

#[test]
fn generated_statics_agree_with_the_importer() {
    let model =
        fixshade_import::import(&common::asset("rocket.obj"), &common::rocket_options()).unwrap();
    let m = model.mesh();
    assert_eq!(generated::ROCKET.vertex_count(), m.positions.len());
    assert_eq!(generated::ROCKET.triangle_count(), m.triangles.len());
    assert_eq!(generated::ROCKET.frac(), generated::ROCKET_FRAC);
    assert_eq!(generated::ROCKET.positions(), &m.positions[..]);
    assert_eq!(
        generated::ROCKET.texcoords(),
        &m.texcoords.as_ref().unwrap()[..]
    );
    assert_eq!(
        generated::ROCKET.tangents(),
        &m.tangents.as_ref().unwrap()[..]
    );
    assert_eq!(generated::ROCKET_TEXTURE.width(), 128);
    // the counts, the buffers alias, the material and the parts list
    assert_eq!(generated::ROCKET_VERTICES, m.positions.len());
    assert_eq!(generated::ROCKET_TRIANGLE_COUNT, m.triangles.len());
    assert_eq!(generated::ROCKET_MAX_VERTICES, generated::ROCKET_VERTICES);
    type Buffers = generated::ROCKET_BUFFERS<
        [u16; 3],
        { fixshade::render::bins_len(generated::ROCKET_TRIANGLE_COUNT, 8) },
        64,
    >;
    assert_eq!(
        core::mem::size_of::<Buffers>(),
        core::mem::size_of::<fixshade::render::MeshBuffers<[u16; 3], 687, { 784 + 18 }, 64>>()
    );
    assert_eq!(generated::ROCKET_MATERIAL, model.parts[0].material.desc);
    assert_eq!(generated::ROCKET_MATERIAL.diffuse, [1.0; 3]);
    assert_eq!(generated::ROCKET_MATERIAL.shininess, 40.0);
    assert_eq!(generated::ROCKET_OPACITY, 1.0);
    assert_eq!(generated::ROCKET_PART_COUNT, 1);
    let (mesh, material, texture) = generated::ROCKET_PARTS[0];
    assert_eq!(mesh, generated::ROCKET);
    assert_eq!(material, generated::ROCKET_MATERIAL);
    assert_eq!(texture, Some(generated::ROCKET_TEXTURE));
}

#[test]
fn generated_crate_parts_agree_with_the_importer() {
    let model = fixshade_import::import(
        &common::asset("crate.obj"),
        &fixshade_import::Options::new("CRATE"),
    )
    .unwrap();
    assert_eq!(model.parts.len(), 2);
    assert_eq!(crate_model::CRATE_PART_COUNT, 2);
    for (k, part) in model.parts.iter().enumerate() {
        let (mesh, material, texture) = crate_model::CRATE_PARTS[k];
        assert_eq!(mesh.positions(), &part.mesh.positions[..]);
        assert_eq!(mesh.triangles(), &part.mesh.triangles[..]);
        assert_eq!(mesh.frac(), crate_model::CRATE_FRAC);
        assert_eq!(material, part.material.desc);
        assert_eq!(texture.map(|t| t.width()), Some(32));
    }
    // wood: the four sides (8 triangles), metal: the lids (4)
    assert_eq!(crate_model::CRATE_PART0_TRIANGLE_COUNT, 8);
    assert_eq!(crate_model::CRATE_PART1_TRIANGLE_COUNT, 4);
    assert_eq!(crate_model::CRATE_PART0_VERTICES, 16);
    assert_eq!(crate_model::CRATE_MAX_VERTICES, 16);
    assert_eq!(crate_model::CRATE_MAX_TRIANGLES, 8);
    assert_eq!(crate_model::CRATE_PART0_MATERIAL.diffuse, [0.9, 0.8, 0.7]);
    assert_eq!(crate_model::CRATE_PART1_MATERIAL.specular, [0.9; 3]);
    assert_eq!(crate_model::CRATE_PART1_MATERIAL.shininess, 80.0);
    // one buffers type for every part
    let _buffers: [crate_model::CRATE_BUFFERS<
        [u16; 3],
        { fixshade::render::bins_len(crate_model::CRATE_MAX_TRIANGLES, 1) },
        16,
    >; crate_model::CRATE_PART_COUNT] = [
        fixshade::render::MeshBuffers::new(),
        fixshade::render::MeshBuffers::new(),
    ];
}

#[test]
fn the_generated_crate_renders_both_parts_in_one_frame() {
    let side = 160;
    // from above: the metal lid and two wooden sides
    let model = Mat4::rotate_x(0.6).mul(&Mat4::rotate_y(0.7));
    let px = common::render::render_parts(&crate_model::CRATE_PARTS, &model, side);
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("crate.png");
    common::render::write_png(&path, side, &px);
    let lit: Vec<&Rgb888> = px.iter().filter(|&&p| p != common::render::BG).collect();
    // wood is orange-brown (red well over blue), metal blue-grey (blue over red)
    let wood = lit
        .iter()
        .filter(|p| u32::from(p.r()) > u32::from(p.b()) + 40)
        .count();
    let metal = lit
        .iter()
        .filter(|p| u32::from(p.b()) > u32::from(p.r()) + 10)
        .count();
    eprintln!(
        "lit {}, wood {wood}, metal {metal}: {}",
        lit.len(),
        path.display()
    );
    assert!(lit.len() > 3000, "lit {}", lit.len());
    assert!(wood > 1000 && metal > 500, "wood {wood} metal {metal}");
}

#[test]
fn the_generated_rocket_renders() {
    let side = 200;
    // the portholes (u = 1/4, the +x side) turned towards the camera
    let model = Mat4::rotate_x(0.25).mul(&Mat4::rotate_y(-1.2));
    let px = common::render::render(
        generated::ROCKET,
        Some(generated::ROCKET_TEXTURE),
        &model,
        side,
    );
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rocket.png");
    common::render::write_png(&path, side, &px);
    let lit: Vec<usize> = (0..px.len())
        .filter(|&i| px[i] != common::render::BG)
        .collect();
    let share = lit.len() as f64 / px.len() as f64;
    // a tall object: more rows than columns covered
    let rows = lit
        .iter()
        .map(|i| i / side as usize)
        .collect::<std::collections::BTreeSet<_>>()
        .len();
    let cols = lit
        .iter()
        .map(|i| i % side as usize)
        .collect::<std::collections::BTreeSet<_>>()
        .len();
    // the red nose and the white body show through the lighting
    let red = lit
        .iter()
        .filter(|&&i| u32::from(px[i].r()) > 2 * u32::from(px[i].g()) + 20)
        .count();
    let bright = lit
        .iter()
        .filter(|&&i| px[i].r().min(px[i].g()).min(px[i].b()) > 100)
        .count();
    eprintln!(
        "lit {share:.3}, rows {rows}, cols {cols}, red {red}, bright {bright}: {}",
        path.display()
    );
    assert!((0.08..0.5).contains(&share), "lit share {share}");
    assert!(rows > cols, "rows {rows} cols {cols}");
    assert!(red > 300 && bright > 300, "red {red} bright {bright}");
}

#[test]
fn untextured_import_renders_too() {
    let mut o = fixshade_import::Options::new("ROCKET");
    o.texture = fixshade_import::TextureChoice::None;
    o.process.texcoords = false;
    let model = fixshade_import::import(&common::asset("rocket.obj"), &o).unwrap();
    // the renderer keeps the mesh for 'static: leak the arrays of this test
    let mesh: fixshade::mesh::Mesh<'static> =
        Box::leak(Box::new(model.mesh().clone())).mesh().unwrap();
    assert_eq!(mesh.vertex_count(), model.mesh().positions.len());
    let side = 120;
    let px = common::render::render(mesh, None, &Mat4::rotate_y(0.4), side);
    let lit = px.iter().filter(|&&p| p != common::render::BG).count();
    assert!(lit > 1000, "{lit}");
}
