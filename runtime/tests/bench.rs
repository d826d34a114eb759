//! `sdfc bench` smoke test: the command runs on a tiny image and its JSON has every field.
//! (Benchmarks are never timed assertions; this only checks the command and its output.)

use std::process::Command;

fn sdfc(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(args)
        .output()
        .expect("run sdfc")
}

fn example(name: &str) -> String {
    format!("{}/../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn bench_json_has_every_field() {
    let scene = example("composition.sdf");
    let plot = std::env::temp_dir().join(format!("sdfc-bench-{}.svg", std::process::id()));
    let o = sdfc(&[
        "bench",
        &scene,
        "--size",
        "32x20",
        "--tracers",
        "basic,enhanced",
        "--steps",
        "8,64",
        "--repeat",
        "1",
        "--target-error",
        "1",
        "--json",
        "--plot",
        plot.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    for key in [
        "scene",
        "width",
        "height",
        "adapter",
        "backend",
        "timing",
        "repeat",
        "truth",
        "cells",
        "target_error",
        "max_mismatch",
        "fastest",
    ] {
        assert!(v.get(key).is_some(), "no `{key}` in {v}");
    }
    for key in [
        "steps",
        "epsilon",
        "bisections",
        "pixels",
        "escaped",
        "seconds",
    ] {
        assert!(v["truth"].get(key).is_some(), "no `truth.{key}`");
    }
    assert_eq!(v["truth"]["pixels"], 640);
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 4);
    for c in cells {
        for key in [
            "tracer",
            "steps",
            "seconds",
            "seconds_each",
            "evals_mean",
            "evals_max",
            "mse",
            "mismatch",
            "error_x_time",
        ] {
            assert!(c.get(key).is_some(), "no `{key}` in {c}");
        }
        let evals = c["evals_mean"].as_f64().unwrap();
        let steps = c["steps"].as_f64().unwrap();
        assert!(evals > 0.0 && evals <= steps, "{c}");
        assert!(c["mse"].as_f64().unwrap().is_finite());
    }
    let svg = std::fs::read_to_string(&plot).expect("plot written");
    assert!(svg.contains("<svg") && svg.contains("enhanced"));
    let _ = std::fs::remove_file(plot);
}

#[test]
fn bench_csv_and_table() {
    let scene = example("squircle.sdf");
    let common = [
        "--size",
        "16x10",
        "--tracers",
        "auto",
        "--steps",
        "16",
        "--repeat",
        "1",
    ];
    let o = sdfc(&[&["bench", &scene, "--csv"][..], &common].concat());
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8_lossy(&o.stdout);
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("tracer,steps,seconds,evals_mean,evals_max,mse,mismatch,error_x_time")
    );
    assert!(lines.next().unwrap().starts_with("auto,16,"));
    let o = sdfc(&[&["bench", &scene][..], &common].concat());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("ground truth") && text.contains("auto"),
        "{text}"
    );
}

#[test]
fn bench_refuses_bad_input() {
    let scene = example("squircle.sdf");
    for (args, message) in [
        (vec!["--tracers", "fast"], "unknown tracer `fast`"),
        (
            vec!["--steps", "0"],
            "`--steps` must be a whole number from 1 to 100000",
        ),
        (vec!["--repeat", "0"], "`--repeat` must be at least 1"),
        (
            vec!["--target-error", "-1"],
            "`--target-error -1` must be a number > 0",
        ),
        (vec!["--plot", "x.pdf"], "give a `.svg` or `.png` file"),
        (vec!["--size", "0x3"], "empty"),
    ] {
        let size: &[&str] = if args[0] == "--size" {
            &[]
        } else {
            &["--size", "8x8"]
        };
        let o = sdfc(&[&["bench", &scene][..], size, &args].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(message), "{args:?}: {err}");
    }
}
