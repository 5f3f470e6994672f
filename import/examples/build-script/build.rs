//! Imports the demo rocket into `$OUT_DIR/model.rs` at build time (and again
//! whenever the OBJ, its MTL or its PNG change).

use fixshade_import::{build, Options, TextureFormat};

fn main() {
    let mut options = Options::new("ROCKET");
    options.process.tangents = true;
    options.texture_format = TextureFormat::Palette8;
    // paths are relative to this package's folder
    if let Err(e) = build::generate("../../assets/rocket.obj", "model.rs", &options) {
        panic!("fixshade-import: {e}");
    }
}
