//! Regenerates the demo asset `assets/rocket.{obj,mtl,png}` (the generator is
//! `tests/common/rocket.rs`, shared with the test that checks the committed
//! files against it):
//!
//! ```text
//! cargo run --example make_assets
//! ```

#[path = "../tests/common/rocket.rs"]
mod rocket;

fn main() -> std::io::Result<()> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    std::fs::create_dir_all(&dir)?;
    for (name, bytes) in rocket::files() {
        let path = dir.join(name);
        std::fs::write(&path, &bytes)?;
        println!("wrote {} ({} bytes)", path.display(), bytes.len());
    }
    Ok(())
}
