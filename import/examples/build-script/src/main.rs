//! Checks the generated statics on the host: counts, frac, texture.

use fixshade_import_build_script_example::{ROCKET, ROCKET_FRAC, ROCKET_POSITIONS, ROCKET_TEXTURE};

fn main() {
    let (v, t) = (ROCKET.vertex_count(), ROCKET.triangle_count());
    println!(
        "ROCKET: {v} vertices, {t} triangles, frac {ROCKET_FRAC}, texture {} x {}",
        ROCKET_TEXTURE.width(),
        ROCKET_TEXTURE.height()
    );
    // the demo asset's figures (import/README.md)
    assert_eq!((v, t), (687, 784));
    assert_eq!(ROCKET_FRAC, 14);
    assert_eq!(ROCKET_POSITIONS.len(), v);
    assert_eq!(ROCKET.texcoords().len(), v);
    assert_eq!(ROCKET.tangents().len(), v);
    assert_eq!(
        (ROCKET_TEXTURE.width(), ROCKET_TEXTURE.height()),
        (128, 128)
    );
    println!("ok");
}
