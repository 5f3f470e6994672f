//! The generated source compiles (`include!`) and renders with fixshade: the
//! committed `tests/generated/rocket.rs` drawn textured into
//! `target/tmp/rocket.png`.

mod common;

mod generated {
    include!("generated/rocket.rs");
}

use fixshade::camera::Mat4;
use fixshade::prelude::RgbColor;

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
