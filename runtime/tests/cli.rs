//! The command line as users run it: exit codes, diagnostics on standard error, and no partial
//! output files.

use crate::common::{root, scratch, sdfc, write};
use std::process::Command;

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
            "--channel",
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
        "--channel",
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
        crate::common::refused(args, message, &out_path);
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

/// `-o/--output` names the file for every command (`--out` is kept as an alias); the channel
/// is `--channel`. The old spelling `--output depth` is answered with the new one.
#[test]
fn render_output_is_the_file_and_channel_the_kind() {
    let dir = scratch("output-flag");
    let scene = root().join("examples/gem.sdf");
    let scene = scene.to_str().unwrap();
    for flag in ["-o", "--output", "--out"] {
        let out = dir.join(format!("gem{flag}.png"));
        let o = sdfc(&[
            "render",
            scene,
            flag,
            out.to_str().unwrap(),
            "--size",
            "16x9",
            "--channel",
            "normal",
        ]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{flag}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(out.exists(), "{flag}: nothing written");
    }
    let o = sdfc(&["render", scene, "--output", "depth"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("the channel is `--channel depth`"), "{err}");
    assert!(!std::path::Path::new("depth").exists());
    let _ = std::fs::remove_dir_all(dir);
}
