//! `sdfc bench` smoke test: the command runs on a tiny image and its JSON has every field.
//! (Benchmarks are never timed assertions; this only checks the command and its output.)

use crate::common::{root, scratch, sdfc};

fn example(name: &str) -> String {
    root().join("examples").join(name).display().to_string()
}

fn reference(name: &str) -> String {
    let path = root().join("runtime/benches/reference").join(name);
    path.display().to_string()
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
        "--passes",
        "2",
        "--reference",
        &reference("bare.wgsl"),
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
    // Two tracers × two budgets, each in one pass and in two.
    assert_eq!(cells.len(), 8);
    for c in cells {
        for key in [
            "tracer",
            "steps",
            "passes",
            "seconds",
            "seconds_each",
            "frame_seconds",
            "frame_seconds_each",
            "evals_mean",
            "evals_max",
            "shading_evals_mean",
            "mse",
            "mismatch",
            "error_x_time",
            "reference",
        ] {
            assert!(c.get(key).is_some(), "no `{key}` in {c}");
        }
        let evals = c["evals_mean"].as_f64().unwrap();
        let steps = c["steps"].as_f64().unwrap();
        // With passes, a pixel counts the coarse passes' steps at its ancestors too.
        assert!(evals > 0.0 && evals <= 2.0 * steps, "{c}");
        assert!(c["mse"].as_f64().unwrap().is_finite());
        assert!(c["shading_evals_mean"].as_f64().unwrap() > 0.0, "{c}");
        // The bare reference traces nothing: no evaluations, no hits (the composition's floor
        // fills most of the picture, so its hit masks cannot agree everywhere).
        let r = &c["reference"];
        assert_eq!(r["evals_mean"].as_f64(), Some(0.0), "{c}");
        assert!(r["mask_agreement"].as_f64().unwrap() < 0.9, "{c}");
        assert_eq!(r["seconds_each"].as_array().unwrap().len(), 1);
    }
    assert_eq!(cells.iter().filter(|c| c["passes"] == 2).count(), 4);
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
        Some(
            "tracer,steps,passes,seconds,frame_seconds,evals_mean,evals_max,shading_evals_mean,mse,mismatch,error_x_time,reference_seconds,reference_evals_mean"
        )
    );
    assert!(lines.next().unwrap().starts_with("auto,16,1,"));
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
        (vec!["--repeat", "0"], "`--repeat 0`: give 1 to 1000 rounds"),
        (
            vec!["--target-error", "-1"],
            "`--target-error -1` must be a number > 0",
        ),
        (vec!["--plot", "x.pdf"], "give a `.svg` or `.png` file"),
        (vec!["--size", "0x3"], "empty"),
        (
            vec!["--passes", "3"],
            "`--passes 3`: there are schedules for",
        ),
        (
            vec!["--reference", "/nonexistent.wgsl"],
            "cannot read the reference",
        ),
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

#[test]
fn a_reference_that_does_not_compile_is_a_user_error() {
    let dir = scratch("bench-ref");
    let bad = dir.join("bad.wgsl");
    std::fs::write(&bad, "fn main( {").unwrap();
    let o = sdfc(&[
        "bench",
        &example("squircle.sdf"),
        "--size",
        "8x8",
        "--tracers",
        "basic",
        "--steps",
        "8",
        "--reference",
        bad.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("error: expected identifier") && err.contains("bad.wgsl:1:10"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// `--count-primitives` counts what every primitive's function is called for: with every
/// part evaluated at every step (`--no-bvh`), the trace's primitive evaluations are the parts
/// times its evaluations, pixel for pixel on average; the data form's, pruned per cell, are
/// fewer for the same picture; `--form data` reports its pre-pass.
#[test]
fn bench_counts_primitive_evaluations() {
    let dir = scratch("bench-primitives");
    let balls: Vec<String> = (0..24)
        .map(|i| {
            let a = i as f64 * 0.9;
            format!(
                "sphere(0.12) at ({:.3}, {:.3}, {:.3})",
                a.cos(),
                (i as f64 * 0.37).sin() * 0.8,
                a.sin()
            )
        })
        .collect();
    let scene = crate::common::write(
        &dir,
        "balls.sdf",
        &format!(
            "camera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nunion {{\n{}\n}}\n",
            balls.join("\n")
        ),
    );
    let run = |extra: &[&str]| {
        let mut args = vec![
            "bench",
            &scene,
            "--size",
            "48x27",
            "--tracers",
            "basic",
            "--steps",
            "64",
            "--repeat",
            "1",
            "--json",
            "--count-primitives",
        ];
        args.extend_from_slice(extra);
        let o = crate::common::succeeded(&args);
        serde_json::from_slice::<serde_json::Value>(&o.stdout).expect("JSON")
    };
    let inline = run(&["--no-bvh"]);
    let cell = &inline["cells"][0];
    let evals = cell["evals_mean"].as_f64().unwrap();
    let traced = cell["primitives"][0].as_f64().unwrap();
    assert!(
        (traced - 24.0 * evals).abs() < 1e-6 * traced,
        "{traced} primitive evaluations, {evals} evaluations of 24 parts"
    );
    let data = run(&["--form", "data"]);
    assert_eq!(data["form"], "data");
    assert!(data["prepass"]["cells"].as_u64().unwrap() > 1);
    let pruned = data["cells"][0]["primitives"][0].as_f64().unwrap();
    assert!(
        pruned > 0.0 && pruned < traced / 4.0,
        "data form {pruned}, inline {traced}"
    );
}
