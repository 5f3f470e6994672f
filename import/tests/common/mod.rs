//! Helpers shared by the integration tests.

#![allow(dead_code)]

pub mod crate_model;
pub mod render;
pub mod rocket;

use std::path::{Path, PathBuf};

/// A fresh folder for one test's files, under Cargo's target tmp dir.
pub fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `text` to `dir/name` and returns the path.
pub fn write(dir: &Path, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The committed asset `assets/name`.
pub fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets")
        .join(name)
}

/// The options the committed generated file was made with (README:
/// `cargo run -- assets/rocket.obj --name ROCKET --tangents
/// --texture-format palette8 --out tests/generated/rocket.rs`).
pub fn rocket_options() -> fixshade_import::Options {
    let mut o = fixshade_import::Options::new("ROCKET");
    o.process.tangents = true;
    o.texture_format = fixshade_import::TextureFormat::Palette8;
    o
}

/// A 2 × 2 × 2 cube around the origin as OBJ text: 8 shared positions, six
/// quads counter-clockwise from outside, each face preceded by `smoothing`
/// (e.g. `"s 1"`, `"s off"`, or `""`).
pub fn cube_obj(smoothing: &str) -> String {
    let mut s = String::new();
    for i in 0..8 {
        let c = |bit: usize| if i & bit != 0 { 1 } else { -1 };
        s += &format!("v {} {} {}\n", c(1), c(2), c(4));
    }
    // corners: bit 0 = +x, bit 1 = +y, bit 2 = +z (1-based in the file)
    for f in [
        [1, 3, 4, 2], // -z
        [5, 6, 8, 7], // +z
        [1, 2, 6, 5], // -y
        [3, 7, 8, 4], // +y
        [1, 5, 7, 3], // -x
        [2, 4, 8, 6], // +x
    ] {
        if !smoothing.is_empty() {
            s += smoothing;
            s += "\n";
        }
        s += &format!("f {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    s
}
