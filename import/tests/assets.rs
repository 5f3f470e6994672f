//! The committed demo asset is what its generator makes (byte for byte), and
//! the committed generated source is what the importer makes of it.

mod common;

#[test]
fn committed_assets_equal_a_fresh_generation() {
    for (name, fresh) in common::rocket::files() {
        let committed = std::fs::read(common::asset(name)).unwrap();
        assert!(
            committed == fresh,
            "assets/{name} differs from its generator: run `cargo run --example make_assets`"
        );
    }
    // and twice in a row gives the same bytes
    assert_eq!(common::rocket::files(), common::rocket::files());
}

#[test]
fn asset_sizes_are_small() {
    let model =
        fixshade_import::import(&common::asset("rocket.obj"), &common::rocket_options()).unwrap();
    assert!(model.mesh().triangles.len() <= 1500);
    let tex = model.texture().unwrap();
    assert!(tex.converted.log2_width <= 7 && tex.converted.log2_height <= 7);
}

#[test]
fn committed_generated_source_is_current() {
    let model =
        fixshade_import::import(&common::asset("rocket.obj"), &common::rocket_options()).unwrap();
    let fresh = model.to_rust();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/generated/rocket.rs");
    let committed = std::fs::read_to_string(&path).unwrap();
    assert!(
        committed == fresh,
        "tests/generated/rocket.rs is stale: run `cargo run -- assets/rocket.obj --name ROCKET \
         --tangents --texture-format palette8 --out tests/generated/rocket.rs`"
    );
}

/// The generated source is rustfmt-clean (when rustfmt is installed).
#[test]
fn generated_source_is_rustfmt_clean() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/generated/rocket.rs");
    match std::process::Command::new("rustfmt")
        .args(["--edition", "2021", "--check"])
        .arg(&path)
        .output()
    {
        Ok(out) => assert!(
            out.status.success(),
            "rustfmt --check: {}",
            String::from_utf8_lossy(&out.stdout)
        ),
        Err(e) => eprintln!("rustfmt not run: {e}"),
    }
}
