//! The command line against hostile surroundings: full or closed standard streams, inputs
//! without end or with odd bytes, output paths that are pipes, links or devices, concurrent
//! writers, and the SPIR-V version asked for.

use crate::common::{scratch, sdfc, write};
use std::process::Command;

/// Standard output that is full or closed, and inputs without end or with a byte-order mark.
#[test]
fn hostile_streams_end_cleanly() {
    let d = scratch("streams");
    let good = write(&d, "good.sdf", "sphere(1)\n");
    // A full device: an error, exit 1 (it panicked before).
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(["check", good.as_str()])
        .stdout(full)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("error: cannot write to standard output"),
        "{err}"
    );
    // A full standard error: the diagnostics are lost, the exit code is still 1 (it panicked).
    let bad = write(&d, "bad.sdf", "sphere(-1)\n");
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(["check", bad.as_str()])
        .stderr(full)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    // A closed pipe (`sdfc check x.sdf | head -0`): ends quietly, no panic.
    let mut child = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(["check", "--list"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    // An input without end: refused after the source limit, not read until memory runs out.
    let out = sdfc(&["check", "/dev/zero"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("larger than the source limit"), "{err}");
    assert!(err.contains("/dev/zero:1:1:"), "{err}");
    // Invalid UTF-8 is located by line and column.
    let bad = d.join("bad.sdf");
    std::fs::write(&bad, b"sphere(1)\nsphere(2) \xff\n").unwrap();
    let out = sdfc(&["check", bad.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("an invalid byte at 2:11"), "{err}");
    // 300 errors: the first 100 shown, the rest counted.
    let many = write(&d, "many.sdf", &"sphere(-1)\n".repeat(300));
    let out = sdfc(&["check", many.as_str()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.matches("error:").count(), 100, "{err}");
    assert!(
        err.contains("and 200 more (200 errors, 0 warnings) not shown"),
        "{err}"
    );
    // A name of 100 000 characters against another: "did you mean" skips what cannot be close.
    let long = write(
        &d,
        "long.sdf",
        &format!(
            "let {} = sphere(1)\n{}b\n",
            "a".repeat(100_000),
            "a".repeat(99_999)
        ),
    );
    let out = sdfc(&["check", long.as_str()]);
    assert_eq!(out.status.code(), Some(1));
    // …and the report stays short: the name and the line are shown by excerpts.
    assert!(
        out.stderr.len() < 4_000,
        "{} bytes of diagnostics",
        out.stderr.len()
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains(":2:1"));
    // A UTF-8 byte-order mark, as Windows editors write it, is accepted.
    let bom = write(&d, "bom.sdf", "\u{feff}sphere(1)\n");
    let out = sdfc(&["check", bom.as_str()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Output paths that are not plain files: a FIFO, a symbolic link and a device are written
/// straight through and stay what they are; a full device and a missing folder are errors
/// that leave nothing behind; two writers of one stem never mix their files.
#[test]
fn output_paths_are_written_whole_and_never_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let d = scratch("paths");
    let scene = write(&d, "s.sdf", "sphere(1)\n");
    let expected = sdfc(&["emit", scene.as_str()]).stdout;
    assert!(expected.len() > 100);
    // A FIFO, read while sdfc writes it.
    let fifo = d.join("pipe.wgsl");
    let _ = std::fs::remove_file(&fifo);
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let out = sdfc(&["emit", scene.as_str(), "-o", fifo.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(reader.join().unwrap(), expected);
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo()
    );
    // A symbolic link: the file it points to gets the text, the link stays a link.
    let target = d.join("target.wgsl");
    let link = d.join("link.wgsl");
    let _ = std::fs::remove_file(&link);
    std::fs::write(&target, "old").unwrap();
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let out = sdfc(&["emit", scene.as_str(), "-o", link.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read(&target).unwrap(), expected);
    // Devices: /dev/null takes it and stays a device; /dev/full is an error (no space).
    let out = sdfc(&["emit", scene.as_str(), "-o", "/dev/null"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        std::fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );
    let out = sdfc(&["emit", scene.as_str(), "-o", "/dev/full"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot write `/dev/full`"), "{err}");
    assert!(
        std::fs::metadata("/dev/full")
            .unwrap()
            .file_type()
            .is_char_device()
    );
    // A missing folder: an error, nothing written, no temporary file left.
    let missing = d.join("no/such/folder/x.wgsl");
    let out = sdfc(&["emit", scene.as_str(), "-o", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    // Two writers of one stem at once, many times: each file whole and right.
    let spirv = {
        let p = d.join("ref.spv");
        assert!(
            sdfc(&[
                "emit",
                scene.as_str(),
                "--target",
                "spirv",
                "-o",
                p.to_str().unwrap()
            ])
            .status
            .success()
        );
        std::fs::read(p).unwrap()
    };
    let (w, s) = (d.join("x.wgsl"), d.join("x.spv"));
    for _ in 0..40 {
        let a = Command::new(env!("CARGO_BIN_EXE_sdfc"))
            .args(["emit", scene.as_str(), "-o", w.to_str().unwrap()])
            .spawn()
            .unwrap();
        let b = Command::new(env!("CARGO_BIN_EXE_sdfc"))
            .args([
                "emit",
                scene.as_str(),
                "--target",
                "spirv",
                "-o",
                s.to_str().unwrap(),
            ])
            .spawn()
            .unwrap();
        assert!(a.wait_with_output().unwrap().status.success());
        assert!(b.wait_with_output().unwrap().status.success());
        assert_eq!(std::fs::read(&w).unwrap(), expected);
        assert_eq!(std::fs::read(&s).unwrap(), spirv);
    }
    let leftovers: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".partial"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
}

/// `emit --spirv-version` writes the version asked for (the word after the magic number), and
/// refuses one that does not exist.
#[test]
fn emit_writes_the_spirv_version_asked_for() {
    let d = scratch("spirv-version");
    let scene = write(&d, "s.sdf", "sphere(1)\n");
    for (flag, word) in [
        ("1.0", 0x0001_0000u32),
        ("1.3", 0x0001_0300),
        ("1.6", 0x0001_0600),
    ] {
        let out_path = d.join(format!("s{flag}.spv"));
        let out = sdfc(&[
            "emit",
            scene.as_str(),
            "--target",
            "spirv",
            "--spirv-version",
            flag,
            "-o",
            out_path.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let bytes = std::fs::read(&out_path).unwrap();
        assert_eq!(
            u32::from_le_bytes(bytes[4..8].try_into().unwrap()),
            word,
            "{flag}"
        );
    }
    let out = sdfc(&[
        "emit",
        scene.as_str(),
        "--target",
        "spirv",
        "--spirv-version",
        "2.0",
    ]);
    assert_eq!(out.status.code(), Some(1));
}
