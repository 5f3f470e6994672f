//! Checks the generated statics on the host: counts, frac, texture, material.

use fixshade_import_build_script_example::{
    rocket_material, RocketBuffers, ROCKET, ROCKET_FRAC, ROCKET_MATERIAL, ROCKET_PARTS,
    ROCKET_POSITIONS, ROCKET_TEXTURE, ROCKET_TRIANGLE_COUNT, ROCKET_VERTICES,
};

fn main() {
    let (v, t) = (ROCKET.vertex_count(), ROCKET.triangle_count());
    println!(
        "ROCKET: {v} vertices, {t} triangles, frac {ROCKET_FRAC}, texture {} x {}, shininess {}",
        ROCKET_TEXTURE.width(),
        ROCKET_TEXTURE.height(),
        ROCKET_MATERIAL.shininess
    );
    // the demo asset's figures (import/README.md)
    assert_eq!((v, t), (687, 784));
    assert_eq!((ROCKET_VERTICES, ROCKET_TRIANGLE_COUNT), (v, t));
    assert_eq!(ROCKET_FRAC, 14);
    assert_eq!(ROCKET_POSITIONS.len(), v);
    assert_eq!(ROCKET.texcoords().len(), v);
    assert_eq!(ROCKET.tangents().len(), v);
    assert_eq!(
        (ROCKET_TEXTURE.width(), ROCKET_TEXTURE.height()),
        (128, 128)
    );
    // the MTL's Kd 1 1 1, Ks 0.4, Ns 40
    assert_eq!(ROCKET_MATERIAL.diffuse, [1.0; 3]);
    assert_eq!(ROCKET_MATERIAL.shininess, 40.0);
    assert!(rocket_material().is_ok());
    assert_eq!(ROCKET_PARTS.len(), 1);
    assert_eq!(ROCKET_PARTS[0].0, ROCKET);
    let buffers = RocketBuffers::new();
    // 687 cached vertices of 12 bytes, 784 + 18 bins, 64 records of 6 bytes
    assert_eq!(
        core::mem::size_of_val(&buffers),
        687 * 12 + (784 + 18) * 2 + 64 * 6
    );
    // the crate: two parts sharing one frac, one buffers type for both
    use fixshade_import_build_script_example::crate_model::*;
    assert_eq!(CRATE_PARTS.len(), CRATE_PART_COUNT);
    assert_eq!(CRATE_PART_COUNT, 2);
    for (mesh, material, texture) in CRATE_PARTS {
        assert_eq!(mesh.frac(), CRATE_FRAC);
        assert!(mesh.vertex_count() <= CRATE_MAX_VERTICES);
        assert!(fixshade::lighting::Material::<fixshade::num::Q14>::new(&material).is_ok());
        assert!(texture.is_some());
    }
    let _buffers: [CRATE_BUFFERS<
        [u16; 3],
        { fixshade::render::bins_len(CRATE_MAX_TRIANGLES, 8) },
        16,
    >; CRATE_PART_COUNT] = [
        fixshade::render::MeshBuffers::new(),
        fixshade::render::MeshBuffers::new(),
    ];
    println!(
        "CRATE: {CRATE_PART_COUNT} parts, {} + {} triangles",
        CRATE_PART0_TRIANGLE_COUNT, CRATE_PART1_TRIANGLE_COUNT
    );
    println!("ok");
}
