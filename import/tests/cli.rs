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

#[test]
fn a_missing_mtl_is_a_warning_and_strict_the_error() {
    let dir = common::scratch("cli_missing_mtl");
    let p = common::write(
        &dir,
        "m.obj",
        "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n",
    );
    let missing = dir.join("nowhere.mtl");
    for extra in [&[][..], &["--no-texture"][..]] {
        let run = tool().arg(&p).args(extra).output().unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(0), "{stderr}");
        assert!(
            stderr.contains(&format!(
                "warning: material library file not found: {}: its materials are OpenGL's \
                 default material, untextured",
                missing.display()
            )),
            "{stderr}"
        );
        assert!(String::from_utf8_lossy(&run.stdout).contains("pub const M_MATERIAL"));
    }
    let run = tool().arg(&p).arg("--strict").output().unwrap();
    assert_eq!(run.status.code(), Some(1));
    assert_eq!(
        String::from_utf8_lossy(&run.stderr),
        format!(
            "fixshade-import: error: material library file not found: {}\n",
            missing.display()
        )
    );
}

#[test]
fn over_the_limit_the_message_says_split() {
    let dir = common::scratch("cli_limit");
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    text += &"f 1 2 3\n".repeat(65536);
    let p = common::write(&dir, "many.obj", text);
    let run = tool().arg(&p).arg("-q").output().unwrap();
    assert_eq!(run.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains(&format!(
            "fixshade-import: error: {}: 65536 triangles (3 positions): more than the 65535",
            p.display()
        )) && stderr.contains("pass --split"),
        "{stderr}"
    );
    let run = tool().arg("--help").output().unwrap();
    let help = String::from_utf8_lossy(&run.stdout);
    for flag in ["--strict", "--flip-winding", "--split"] {
        assert!(help.contains(flag), "{flag}");
    }
}
