//! Regenerates the demo assets `assets/rocket.{obj,mtl,png}` and
//! `assets/crate.{obj,mtl}`, `assets/crate_{wood,metal}.png` (the generators
//! are `tests/common/rocket.rs` and `tests/common/crate_model.rs`, shared with
//! the test that checks the committed files against them):
//!
//! ```text
//! cargo run --example make_assets
//! ```

#[path = "../tests/common/crate_model.rs"]
mod crate_model;
#[path = "../tests/common/rocket.rs"]
mod rocket;

fn main() -> std::io::Result<()> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    std::fs::create_dir_all(&dir)?;
    for (name, bytes) in rocket::files().into_iter().chain(crate_model::files()) {
        let path = dir.join(name);
        std::fs::write(&path, &bytes)?;
        println!("wrote {} ({} bytes)", path.display(), bytes.len());
    }
    Ok(())
}
