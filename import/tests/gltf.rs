//! glTF 2.0 import: `.gltf` with a `data:` buffer or an external `.bin`, and
//! `.glb`; node transforms, mirrored nodes, embedded PNG textures, errors.

mod common;

use std::path::PathBuf;

use base64::Engine as _;
use common::{cube_obj, scratch, write};
use fixshade_import::{import, Error, FileKind, NormalSource, Options};

/// The cube of `common::cube_obj` as glTF binary data: 8 positions and 36
/// `u16` indices (no normals), optionally 4 texture coordinates per vertex
/// set by position; returns (bin, accessors JSON, attributes JSON, views
/// JSON, indices accessor index).
fn cube_bin() -> Vec<u8> {
    let mut bin = Vec::new();
    for i in 0..8 {
        for bit in [1, 2, 4] {
            let c: f32 = if i & bit != 0 { 1.0 } else { -1.0 };
            bin.extend(c.to_le_bytes());
        }
    }
    // the OBJ cube's quads, 0-based, fanned
    let quads = [
        [0u16, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    for q in quads {
        for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            for i in t {
                bin.extend(i.to_le_bytes());
            }
        }
    }
    bin
}

/// A glTF document for the cube; `uri` is the buffer's URI (`None` for the
/// GLB's BIN chunk); `node` the node's JSON fields besides `"mesh": 0`.
fn cube_json(uri: Option<&str>, len: usize, node: &str) -> String {
    let buffer = match uri {
        Some(u) => format!(r#"{{"byteLength": {len}, "uri": "{u}"}}"#),
        None => format!(r#"{{"byteLength": {len}}}"#),
    };
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0{node}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "buffers": [{buffer}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 96}},
    {{"buffer": 0, "byteOffset": 96, "byteLength": 72}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
      "min": [-1, -1, -1], "max": [1, 1, 1]}},
    {{"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}}
  ]
}}
"#
    )
}

fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::new();
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((j.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(j);
    out.extend((b.len() as u32).to_le_bytes());
    out.extend(0x004E_4942u32.to_le_bytes());
    out.extend(b);
    out
}

fn data_uri(bin: &[u8]) -> String {
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bin)
    )
}

fn volume(m: &fixshade_import::CompactMesh) -> f64 {
    let p = |i: u16| m.positions[usize::from(i)].map(|x| f64::from(x) * m.step());
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(p);
            (a[0] * (b[1] * c[2] - b[2] * c[1])
                + a[1] * (b[2] * c[0] - b[0] * c[2])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0
        })
        .sum()
}

#[test]
fn gltf_glb_and_obj_agree() {
    let dir = scratch("gltf_agree");
    let bin = cube_bin();
    let embedded = write(
        &dir,
        "cube.gltf",
        cube_json(Some(&data_uri(&bin)), bin.len(), ""),
    );
    write(&dir, "cube.bin", &bin);
    let external = write(&dir, "ext.gltf", cube_json(Some("cube.bin"), bin.len(), ""));
    let binary = write(&dir, "cube.glb", glb(&cube_json(None, bin.len(), ""), &bin));
    let obj = write(&dir, "cube.obj", cube_obj(""));
    let reference = import(&obj, &Options::new("C")).unwrap();
    for p in [&embedded, &external, &binary] {
        let m = import(p, &Options::new("C")).unwrap();
        // no normals in the file: the 60° crease splits the cube into 24
        assert_eq!(m.report.normals, NormalSource::CreaseAngle(60.0));
        assert_eq!(m.mesh(), reference.mesh(), "{}", p.display());
        assert!((volume(m.mesh()) - 8.0).abs() < 1e-9);
    }
    assert!(import(&external, &Options::new("C"))
        .unwrap()
        .files
        .iter()
        .any(|f| f.ends_with("cube.bin")));
}

#[test]
fn node_transforms_apply_and_mirrors_keep_the_winding() {
    let dir = scratch("gltf_nodes");
    let bin = cube_bin();
    let uri = data_uri(&bin);
    let moved = write(
        &dir,
        "moved.gltf",
        cube_json(
            Some(&uri),
            bin.len(),
            r#", "translation": [10, 0, 0], "scale": [0.5, 0.5, 0.5]"#,
        ),
    );
    let m = import(&moved, &Options::new("C")).unwrap();
    let b = m.report.bounds;
    assert_eq!(b, [[9.5, -0.5, -0.5], [10.5, 0.5, 0.5]]);
    assert!((volume(m.mesh()) - 1.0).abs() < 1e-9);
    // mirrored in x: the importer reverses the winding, the volume stays positive
    let mirrored = write(
        &dir,
        "mirror.gltf",
        cube_json(Some(&uri), bin.len(), r#", "scale": [-1, 1, 1]"#),
    );
    let m = import(&mirrored, &Options::new("C")).unwrap();
    assert!((volume(m.mesh()) - 8.0).abs() < 1e-9);
}

/// A GLB with normals, texture coordinates and an embedded PNG texture.
#[test]
fn glb_with_an_embedded_texture() {
    let dir = scratch("gltf_texture");
    // one quad facing +z; positions, normals, uvs, indices, then the PNG
    let mut bin = Vec::new();
    let pos: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    for p in pos {
        for c in p {
            bin.extend(c.to_le_bytes());
        }
    }
    for _ in 0..4 {
        for c in [0.0f32, 0.0, 1.0] {
            bin.extend(c.to_le_bytes());
        }
    }
    for uv in [[0.0f32, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]] {
        for c in uv {
            bin.extend(c.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        bin.extend(i.to_le_bytes());
    }
    let mut png_data = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png_data, 2, 2);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header()
            .unwrap()
            .write_image_data(&[255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255])
            .unwrap();
    }
    let png_offset = bin.len(); // 140, a multiple of 4
    bin.extend(&png_data);
    let json = format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}},
                               "indices": 3, "material": 0}}]}}],
  "materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}}}}}],
  "textures": [{{"source": 0}}],
  "images": [{{"bufferView": 4, "mimeType": "image/png"}}],
  "buffers": [{{"byteLength": {len}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 96, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": 128, "byteLength": 12}},
    {{"buffer": 0, "byteOffset": {png_offset}, "byteLength": {png_len}}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}}
  ]
}}"#,
        len = bin.len(),
        png_len = png_data.len()
    );
    let p = write(&dir, "quad.glb", glb(&json, &bin));
    let m = import(&p, &Options::new("Q")).unwrap();
    assert_eq!(m.report.normals, NormalSource::File);
    assert_eq!(m.mesh().positions.len(), 4);
    assert_eq!(m.mesh().normals, [[0, 0, 16384]; 4]);
    // glTF's v already runs down the image: kept as is
    assert_eq!(
        m.mesh().texcoords.as_deref().unwrap(),
        [[0, 4096], [4096, 4096], [4096, 0], [0, 0]]
    );
    let t = m.texture().unwrap();
    assert_eq!(t.name, "image 0");
    assert_eq!(
        t.converted.texels,
        fixshade_import::texture::TexelData::Rgb565(vec![0xF800, 0x07E0, 0x001F, 0xFFFF])
    );
}

#[test]
fn gltf_errors() {
    let dir = scratch("gltf_errors");
    let bin = cube_bin();
    // a missing external buffer
    let p = write(
        &dir,
        "lost.gltf",
        cube_json(Some("lost.bin"), bin.len(), ""),
    );
    match import(&p, &Options::new("C")) {
        Err(Error::MissingFile {
            kind: FileKind::GltfBuffer,
            path,
        }) => assert_eq!(path, dir.join("lost.bin")),
        other => panic!("{other:?}"),
    }
    // invalid JSON: its line
    let p = write(
        &dir,
        "bad.gltf",
        "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"scenes\": [\n    oops\n  ]\n}\n",
    );
    match import(&p, &Options::new("C")) {
        Err(Error::Parse { line, .. }) => assert_eq!(line, Some(4)),
        other => panic!("{other:?}"),
    }
    // a buffer shorter than declared
    let p = write(
        &dir,
        "short.gltf",
        cube_json(Some(&data_uri(&bin[..100])), bin.len(), ""),
    );
    assert!(matches!(
        import(&p, &Options::new("C")),
        Err(Error::Parse { line: None, .. })
    ));
    let _: PathBuf = p;
}

/// The cube of `cube_bin` as several meshes, one per entry of `materials`
/// (a glTF material's JSON, or `None` for a primitive without one), side by
/// side along x, with `images` (JSON) for textures.
fn materials_json(bin_uri: &str, len: usize, materials: &[Option<&str>], images: &str) -> String {
    let mut meshes = Vec::new();
    let mut nodes = Vec::new();
    let mut list = Vec::new();
    for (i, m) in materials.iter().enumerate() {
        let material = match m {
            Some(json) => {
                list.push(json.to_string());
                format!(r#", "material": {}"#, list.len() - 1)
            }
            None => String::new(),
        };
        meshes.push(format!(
            r#"{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1{material}}}]}}"#
        ));
        nodes.push(format!(
            r#"{{"mesh": {i}, "translation": [{}, 0, 0]}}"#,
            3 * i
        ));
    }
    let scene: Vec<String> = (0..materials.len()).map(|i| i.to_string()).collect();
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [{}]}}],
  "nodes": [{}],
  "meshes": [{}],
  "materials": [{}],
  {images}
  "buffers": [{{"byteLength": {len}, "uri": "{bin_uri}"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 96}},
    {{"buffer": 0, "byteOffset": 96, "byteLength": 72}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
      "min": [-1, -1, -1], "max": [1, 1, 1]}},
    {{"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}}
  ]
}}
"#,
        scene.join(", "),
        nodes.join(", "),
        meshes.join(", "),
        list.join(", ")
    )
}

fn close(a: [f32; 3], b: [f64; 3]) -> bool {
    (0..3).all(|k| (f64::from(a[k]) - b[k]).abs() < 1e-6)
}

/// glTF metallic-roughness to Blinn-Phong as the README states: diffuse =
/// base · (1 − metallic), ambient = base, specular = 0.04 · (1 − metallic) +
/// base · metallic, shininess 2/α² − 2 with α = roughness² (0..=128),
/// emission = emissive, opacity = alpha unless OPAQUE; one part per material.
#[test]
fn gltf_metallic_roughness_maps_as_documented() {
    let dir = scratch("gltf_materials");
    let bin = cube_bin();
    let materials = [
        Some(
            r#"{"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.4, 0.2, 1],
               "metallicFactor": 0, "roughnessFactor": 0.5}}"#,
        ),
        Some(
            r#"{"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.3, 1],
               "metallicFactor": 1, "roughnessFactor": 0.3}, "emissiveFactor": [0.1, 0, 0]}"#,
        ),
        Some(
            r#"{"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 0.25],
               "metallicFactor": 0.5, "roughnessFactor": 0.8}, "alphaMode": "BLEND"}"#,
        ),
        // glTF's defaults: base colour 1, metallic 1, roughness 1
        Some(r#"{"name": "plain"}"#),
        None,
    ];
    let p = write(
        &dir,
        "materials.gltf",
        materials_json(&data_uri(&bin), bin.len(), &materials, ""),
    );
    let m = import(&p, &Options::new("M")).unwrap();
    assert_eq!(m.parts.len(), 5);
    let names: Vec<_> = m.parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        ["M_PART0", "M_PART1", "M_PART2", "M_PART3", "M_PART4"]
    );
    let d: Vec<_> = m.parts.iter().map(|p| &p.material).collect();
    // clay: a rough dielectric
    assert_eq!(d[0].name.as_deref(), Some("clay"));
    assert!(close(d[0].desc.diffuse, [0.8, 0.4, 0.2]));
    assert!(close(d[0].desc.ambient, [0.8, 0.4, 0.2]));
    assert!(close(d[0].desc.specular, [0.04; 3]));
    assert_eq!(d[0].desc.shininess, 30.0); // α = 0.25: 2/0.0625 − 2
    assert_eq!(d[0].opacity, 1.0);
    // gold: a metal, shininess 2/0.0081 − 2 = 244.9 clamped to OpenGL's 128
    assert!(close(d[1].desc.diffuse, [0.0; 3]));
    assert!(close(d[1].desc.ambient, [1.0, 0.8, 0.3]));
    assert!(close(d[1].desc.specular, [1.0, 0.8, 0.3]));
    assert_eq!(d[1].desc.shininess, 128.0);
    assert!(close(d[1].desc.emission, [0.1, 0.0, 0.0]));
    // glass: half metal, blended: its alpha is the opacity
    assert!(close(d[2].desc.diffuse, [0.25; 3]));
    assert!(close(d[2].desc.specular, [0.02 + 0.25; 3]));
    let a: f64 = 0.8 * 0.8;
    assert!((f64::from(d[2].desc.shininess) - (2.0 / (a * a) - 2.0)).abs() < 1e-5);
    assert_eq!(d[2].opacity, 0.25);
    // glTF's default values: a rough white metal (Blinn-Phong draws it flat)
    assert!(close(d[3].desc.diffuse, [0.0; 3]));
    assert!(close(d[3].desc.specular, [1.0; 3]));
    assert_eq!(d[3].desc.shininess, 0.0);
    // no material: OpenGL's default, as for an OBJ without one
    assert_eq!(d[4].name, None);
    assert_eq!(d[4].desc, fixshade::lighting::MaterialDesc::default());
    for p in &m.parts {
        assert!(fixshade::lighting::Material::<fixshade::num::Q14>::new(&p.material.desc).is_ok());
    }
    // every part is the whole cube, one frac for all
    assert!(m.parts.iter().all(|p| p.mesh.triangles.len() == 12));
    assert!(m.parts.iter().all(|p| p.mesh.frac == m.report.frac));
    let src = m.to_rust();
    assert!(src.contains("pub const M_PART1_MATERIAL: ::fixshade::lighting::MaterialDesc"));
    assert!(
        src.contains("pub const M_PART2_OPACITY: f32 = 0.25;"),
        "{src}"
    );
    assert!(src.contains("pub const M_PART_COUNT: usize = 5;"));
}

#[test]
fn gltf_missing_image_is_a_warning_and_no_texture() {
    let dir = scratch("gltf_missing_image");
    let bin = cube_bin();
    let materials = [Some(
        r#"{"name": "painted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}"#,
    )];
    let images = r#""textures": [{"source": 0}], "images": [{"uri": "paint.png"}],"#;
    let p = write(
        &dir,
        "painted.gltf",
        materials_json(&data_uri(&bin), bin.len(), &materials, images),
    );
    let m = import(&p, &Options::new("P")).unwrap();
    assert!(m.texture().is_none());
    let w = m.warnings.join("\n");
    assert!(
        w.contains(&format!(
            "texture file not found: {}",
            dir.join("paint.png").display()
        )) && w.contains("(material `painted`): drawn untextured"),
        "{w}"
    );
    // the rest of the material is kept
    assert!(close(m.parts[0].material.desc.specular, [0.04; 3]));
    // --strict: the error
    let strict = Options {
        strict: true,
        ..Options::new("P")
    };
    match import(&p, &strict) {
        Err(Error::MissingFile {
            kind: FileKind::Texture,
            path,
        }) => assert_eq!(path, dir.join("paint.png")),
        other => panic!("{other:?}"),
    }
}
