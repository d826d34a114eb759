//! The command line as users run it: exit codes, diagnostics on standard error, and no partial
//! output files.

use std::path::PathBuf;
use std::process::{Command, Output};

fn sdfc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(args)
        .output()
        .expect("run sdfc")
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sdfc-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

#[test]
fn check_reports_a_summary_or_the_errors() {
    let d = scratch("check");
    let good = write(
        &d,
        "good.sdf",
        "material red { color #f00 }\nsphere(1) : red\n",
    );
    let out = sdfc(&["check", &good]);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("nodes: 1") && text.contains("materials: 1") && text.contains("root λ: 1"),
        "{text}"
    );

    let bad = write(&d, "bad.sdf", "shpere(1)\nbox(-1)\n");
    let out = sdfc(&["check", &bad]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.sdf:1:1")
            && err.contains("did you mean `sphere`")
            && err.contains("bad.sdf:2:5"),
        "{err}"
    );
    assert!(err.contains("^^^^^^"), "no caret:\n{err}");
}

#[test]
fn check_reads_standard_input() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(["check", "-"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"torus(1, 0.25)")
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stdout).contains("<stdin>: ok"));
}

#[test]
fn a_missing_file_is_a_user_error() {
    let out = sdfc(&["check", "/nonexistent/scene.sdf"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read"));
}

#[test]
fn emit_of_a_bad_file_prints_diagnostics_and_writes_nothing() {
    let d = scratch("emit-bad");
    let bad = write(&d, "bad.sdf", "sphere(1) : gold\n");
    let target = d.join("out.wgsl");
    let out = sdfc(&[
        "emit",
        &bad,
        "--target",
        "wgsl",
        "-o",
        target.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown material `gold`"));
    assert!(!target.exists(), "a partial output file was left behind");
}

#[test]
fn emit_writes_every_target_to_a_file() {
    let d = scratch("emit-good");
    let scene = root().join("examples/jewel.sdf");
    for (t, ext) in [
        ("wgsl", "wgsl"),
        ("spirv", "spv"),
        ("glsl", "comp"),
        ("msl", "metal"),
        ("hlsl", "hlsl"),
    ] {
        let target = d.join(format!("out.{ext}"));
        let out = sdfc(&[
            "emit",
            scene.to_str().unwrap(),
            "--target",
            t,
            "-o",
            target.to_str().unwrap(),
        ]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{t}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            std::fs::metadata(&target).unwrap().len() > 100,
            "{t}: empty output"
        );
    }
    let spv = std::fs::read(d.join("out.spv")).unwrap();
    assert_eq!(
        &spv[..4],
        &0x0723_0203u32.to_le_bytes(),
        "SPIR-V magic number"
    );
}

#[test]
fn emit_to_an_unwritable_path_fails_cleanly() {
    let scene = root().join("examples/jewel.sdf");
    let out = sdfc(&[
        "emit",
        scene.to_str().unwrap(),
        "-o",
        "/nonexistent/dir/out.wgsl",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot write"));
}

#[test]
fn bad_flags_are_user_errors() {
    assert_eq!(
        sdfc(&["emit", "x.sdf", "--target", "cobol"]).status.code(),
        Some(1)
    );
    assert_eq!(sdfc(&["frobnicate"]).status.code(), Some(1));
    assert_eq!(sdfc(&["--help"]).status.code(), Some(0));
}

#[test]
fn render_writes_a_png_for_every_output_kind() {
    let d = scratch("render");
    let scene = root().join("examples/jewel.sdf");
    for kind in ["color", "depth", "normal", "steps", "material"] {
        let out_path = d.join(format!("{kind}.png"));
        let out = sdfc(&[
            "render",
            scene.to_str().unwrap(),
            "-o",
            out_path.to_str().unwrap(),
            "--size",
            "64x40",
            "--output",
            kind,
        ]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{kind}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let bytes = std::fs::read(&out_path).unwrap();
        assert_eq!(&bytes[1..4], b"PNG", "{kind}: not a PNG");
    }
    let npy = d.join("depth.npy");
    let out = sdfc(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        npy.to_str().unwrap(),
        "--size",
        "64x40",
        "--output",
        "depth",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&npy).unwrap();
    assert!(
        bytes.starts_with(b"\x93NUMPY")
            && bytes.len().is_multiple_of(64)
            && bytes.len() > 64 * 40 * 4
    );
    let ss = d.join("aa.png");
    let out = sdfc(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        ss.to_str().unwrap(),
        "--size",
        "64x40",
        "--samples",
        "4",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn render_refuses_bad_input_cleanly() {
    let d = scratch("render-bad");
    let scene = root().join("examples/jewel.sdf");
    let scene = scene.to_str().unwrap();
    let out_path = d.join("out.png");
    let out = out_path.to_str().unwrap();
    let cases: [(&[&str], &str); 15] = [
        (&["render", "/nonexistent.sdf", "-o", out], "cannot read"),
        (
            &[
                "render",
                scene,
                "-o",
                "/nonexistent/dir/out.png",
                "--size",
                "8x8",
            ],
            "cannot write",
        ),
        (&["render", scene, "-o", out, "--size", "0x10"], "empty"),
        (
            &["render", scene, "-o", out, "--size", "100000x100000"],
            "too large",
        ),
        (
            &["render", scene, "-o", out, "--size", "big"],
            "WIDTHxHEIGHT",
        ),
        (
            &[
                "render", scene, "-o", out, "--size", "8x8", "--tracer", "fast",
            ],
            "unknown tracer",
        ),
        (
            &[
                "render",
                scene,
                "-o",
                out,
                "--size",
                "8x8",
                "--samples",
                "3",
            ],
            "square number",
        ),
        (
            &[
                "render", scene, "-o", out, "--tracer", "relaxed", "--omega", "2",
            ],
            "`--omega` must be a number in [1, 2)",
        ),
        (
            &[
                "render", scene, "-o", out, "--tracer", "auto", "--omega", "1.5",
            ],
            "has no parameter `omega`",
        ),
        (
            &["render", scene, "-o", out, "--steps", "0"],
            "`--steps` must be a whole number from 1 to 100000",
        ),
        (
            &["render", scene, "-o", out, "--epsilon", "-1"],
            "`--epsilon` must be a number > 0 or `pixel`",
        ),
        (
            &["render", scene, "-o", out, "--epsilon", "NaN"],
            "`--epsilon` must be",
        ),
        (
            &[
                "render",
                scene,
                "-o",
                out,
                "--tracer",
                "relaxed",
                "--antialias",
                "cone",
            ],
            "has no parameter `antialias`",
        ),
        (
            &[
                "render",
                scene,
                "-o",
                out,
                "--tracer",
                "basic",
                "--antialias",
                "yes",
            ],
            "`--antialias` must be one of `none`, `cone`",
        ),
        (
            &["render", scene, "-o", out, "--passes", "3"],
            "there are schedules for 1, 2, 4, 6 passes",
        ),
    ];
    for (args, message) in cases {
        let o = sdfc(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!out_path.exists(), "{args:?} left a file behind");
    }
}

/// A too-small annotation renders (exit 0), but `render`, `emit` and `check` say so on standard
/// error, with the place; `check --lipschitz` too.
#[test]
fn a_wrong_annotation_is_a_warning_on_render_emit_and_check() {
    let d = scratch("lipschitz");
    let scene = root().join("tests/lipschitz/wrong/uniform_sphere_times3.sdf");
    let scene = scene.display().to_string();
    let png = d.join("w.png").display().to_string();
    for args in [
        vec![
            "render",
            scene.as_str(),
            "-o",
            png.as_str(),
            "--size",
            "32x18",
        ],
        vec!["emit", scene.as_str()],
        vec!["check", scene.as_str()],
        vec!["check", "--lipschitz", scene.as_str()],
    ] {
        let out = sdfc(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {err}");
        assert!(
            err.contains("the annotated Lipschitz bound is too small")
                && err.contains("uniform_sphere_times3.sdf:"),
            "{args:?}: {err}"
        );
    }
}

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
