//! The `fixshade-import` binary: output, summary, exit codes.

mod common;

use std::process::Command;

fn tool() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fixshade-import"))
}

#[test]
fn imports_the_asset_and_reports_frac_and_step() {
    let dir = common::scratch("cli");
    let out = dir.join("rocket.rs");
    let run = tool()
        .arg(common::asset("rocket.obj"))
        .args([
            "--name",
            "ROCKET",
            "--tangents",
            "--texture-format",
            "palette8",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains("frac = 14, step 2^-14 = 0.00006103515625"),
        "{stderr}"
    );
    assert!(stderr.contains("quantised to 256"), "{stderr}");
    // the same bytes as the committed file (same flags)
    let committed =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/generated/rocket.rs");
    assert_eq!(
        std::fs::read(&out).unwrap(),
        std::fs::read(committed).unwrap()
    );
    // without --out the source goes to standard output
    let run = tool()
        .arg(common::asset("rocket.obj"))
        .arg("-q")
        .output()
        .unwrap();
    assert!(run.status.success());
    assert!(run.stderr.is_empty());
    assert!(String::from_utf8_lossy(&run.stdout)
        .contains("pub static ROCKET: ::fixshade::mesh::Mesh<'static>"));
}

#[test]
fn exit_codes_and_messages() {
    let dir = common::scratch("cli_errors");
    let bad = common::write(&dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 x\nf 1 2 3\n");
    let run = tool().arg(&bad).output().unwrap();
    assert_eq!(run.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("bad.obj:3: position parse error: `v 0 1 x`"),
        "{stderr}"
    );
    let run = tool()
        .args(["a.obj", "--texture-format", "rgb888"])
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let run = tool().arg("--help").output().unwrap();
    assert!(String::from_utf8_lossy(&run.stdout).contains("--crease-angle DEG"));
}
