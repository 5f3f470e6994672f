//! The committed demo assets are what their generators make (byte for byte),
//! and the committed generated sources are what the importer makes of them.

mod common;

#[test]
fn committed_assets_equal_a_fresh_generation() {
    for (name, fresh) in common::rocket::files()
        .into_iter()
        .chain(common::crate_model::files())
    {
        let committed = std::fs::read(common::asset(name)).unwrap();
        assert!(
            committed == fresh,
            "assets/{name} differs from its generator: run `cargo run --example make_assets`"
        );
    }
    // and twice in a row gives the same bytes
    assert_eq!(common::rocket::files(), common::rocket::files());
    assert_eq!(common::crate_model::files(), common::crate_model::files());
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
    let model = fixshade_import::import(
        &common::asset("crate.obj"),
        &fixshade_import::Options::new("CRATE"),
    )
    .unwrap();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/generated/crate.rs");
    let committed = std::fs::read_to_string(&path).unwrap();
    assert!(
        committed == model.to_rust(),
        "tests/generated/crate.rs is stale: run `cargo run -- assets/crate.obj --name CRATE \
         --out tests/generated/crate.rs`"
    );
}

/// `rustfmt --check` on a file (when rustfmt is installed).
fn rustfmt_clean(path: &std::path::Path) {
    match std::process::Command::new("rustfmt")
        .args(["--edition", "2021", "--check"])
        .arg(path)
        .output()
    {
        Ok(out) => assert!(
            out.status.success(),
            "rustfmt --check {}: {}",
            path.display(),
            String::from_utf8_lossy(&out.stdout)
        ),
        Err(e) => eprintln!("rustfmt not run: {e}"),
    }
}

/// The generated sources are rustfmt-clean: the committed ones, and the
/// crate's with names short and long (where rustfmt breaks lines).
#[test]
fn generated_source_is_rustfmt_clean() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/generated");
    rustfmt_clean(&dir.join("rocket.rs"));
    rustfmt_clean(&dir.join("crate.rs"));
    let scratch = common::scratch("rustfmt");
    // (much longer names compile too, but rustfmt breaks their longest
    // lines elsewhere)
    for name in ["C", "CRAT", "CRATE_WITH_A_RATHER_LONG_NAME"] {
        let model = fixshade_import::import(
            &common::asset("crate.obj"),
            &fixshade_import::Options::new(name),
        )
        .unwrap();
        rustfmt_clean(&common::write(
            &scratch,
            &format!("{name}.rs"),
            model.to_rust(),
        ));
        let mut o = common::rocket_options();
        o.name = name.to_string();
        let model = fixshade_import::import(&common::asset("rocket.obj"), &o).unwrap();
        rustfmt_clean(&common::write(
            &scratch,
            &format!("{name}_1.rs"),
            model.to_rust(),
        ));
    }
}
