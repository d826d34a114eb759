//! Flags validated by their meaning, reads bounded, and a command's outputs written together or
//! not at all (issue 32): each case an error that says what to give, exit 1, nothing written.

use crate::common::{root, scratch, sdfc};
use std::process::{Command, Stdio};

fn refused(args: &[&str], said: &str) {
    let o = sdfc(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.contains(said), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// A time f32 cannot hold (the shape vanished at 1e39, exit 0), a billion bench rounds (ran
/// until killed), and an endless reference file (3.6 GB read before failing) are refused.
#[test]
fn flags_out_of_their_meaning_are_refused() {
    let lamp = root().join("examples/lamp.sdf");
    let lamp = lamp.to_str().unwrap();
    let out = scratch("bounded").join("x.png");
    let out = out.to_str().unwrap();
    refused(
        &["render", lamp, "-o", out, "--time", "1e39"],
        "within ±1e6 seconds",
    );
    refused(
        &["render", lamp, "-o", out, "--param", "time=-2e6"],
        "within ±1e6 seconds",
    );
    let gem = root().join("examples/gem.sdf");
    let gem = gem.to_str().unwrap();
    refused(
        &["bench", gem, "--repeat", "1000000000"],
        "give 1 to 1000 rounds",
    );
    refused(
        &["bench", gem, "--reference", "/dev/zero"],
        "larger than 16 MiB",
    );
    assert!(!std::path::Path::new(out).exists());
}

/// `emit`'s shader and manifest: both or neither. A manifest into a missing folder (the
/// shader was written, exit 1), a manifest to a full standard output (`--manifest -`, which
/// wrote a file named `-`, exit 0), both to standard output: refused, no file left.
#[test]
fn emit_writes_both_outputs_or_neither() {
    let dir = scratch("both-or-neither");
    let lamp = root().join("examples/lamp.sdf");
    let lamp = lamp.to_str().unwrap();
    let shader = dir.join("lamp.wgsl");
    let s = shader.to_str().unwrap();
    let missing = dir.join("nowhere/lamp.json");
    refused(
        &[
            "emit",
            lamp,
            "-o",
            s,
            "--manifest",
            missing.to_str().unwrap(),
        ],
        "the folder",
    );
    assert!(
        !shader.exists(),
        "the shader was written without its manifest"
    );
    refused(
        &["emit", lamp, "--manifest", "-"],
        "both go to standard output",
    );
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(["emit", lamp, "-o", s, "--manifest", "-"])
        .current_dir(&dir)
        .stdout(Stdio::from(full))
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        !shader.exists(),
        "the shader was written though its manifest failed"
    );
    assert!(
        !dir.join("-").exists(),
        "`--manifest -` wrote a file named `-`"
    );
    // And to a working standard output: the manifest there, the shader in its file.
    let o = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(["emit", lamp, "-o", s, "--manifest", "-"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0));
    let m: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(m["format"], "sdfc-manifest 1");
    assert!(shader.exists());
}

/// A scene in a folder whose name is not UTF-8 (`café` in Latin-1) imports the file beside it
/// and renders into that folder: paths stay bytes end to end, only their display is lossy
/// (the import was looked for under the lossy text of the folder's name).
#[cfg(unix)]
#[test]
fn paths_that_are_not_utf8_are_followed_as_bytes() {
    use std::os::unix::ffi::OsStrExt;
    let dir = scratch("latin-1").join(std::ffi::OsStr::from_bytes(b"caf\xe9"));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("lib.sdf"), "let thing = sphere(1)\n").unwrap();
    std::fs::write(dir.join("main.sdf"), "import \"lib.sdf\"\nthing\n").unwrap();
    let main = dir.join("main.sdf");
    let png = dir.join("out.png");
    for args in [
        vec!["check".as_ref(), main.as_os_str()],
        vec![
            "render".as_ref(),
            main.as_os_str(),
            "--size".as_ref(),
            "16x12".as_ref(),
            "-o".as_ref(),
            png.as_os_str(),
        ],
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_sdfc"))
            .args(&args)
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    assert!(png.exists());
}
