//! Imports the demo rocket into `$OUT_DIR/model.rs` and the two-material
//! crate into `$OUT_DIR/crate_model.rs` at build time (and again whenever an
//! OBJ, its MTL or a PNG change).

use fixshade_import::{build, Options, TextureFormat};

fn main() {
    let mut options = Options::new("ROCKET");
    options.process.tangents = true;
    options.texture_format = TextureFormat::Palette8;
    // paths are relative to this package's folder
    if let Err(e) = build::generate("../../assets/rocket.obj", "model.rs", &options) {
        panic!("fixshade-import: {e}");
    }
    // two materials, two textures: two parts (CRATE_PART0, CRATE_PART1, CRATE_PARTS);
    // strict: a missing file or a material value OpenGL rejects fails the build
    let mut options = Options::new("CRATE");
    options.strict = true;
    if let Err(e) = build::generate("../../assets/crate.obj", "crate_model.rs", &options) {
        panic!("fixshade-import: {e}");
    }
}
