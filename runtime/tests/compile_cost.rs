//! The driver's compile as a limit: shaders predicted too slow to compile are refused at once
//! (or drawn without their box trees when those are what makes them slow), and the pipeline
//! cache on disk.

use crate::common::{root, scratch, sdfc, write};
use std::process::Command;

/// A union of `n` small spheres scattered in a 6-unit cube (a fixed linear congruential
/// sequence, so every run draws the same scene).
fn scattered(n: usize) -> String {
    let mut state: u64 = 12345;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 33) as f64 / (1u64 << 31) as f64 * 6.0 - 3.0
    };
    let parts: String = (0..n)
        .map(|_| {
            format!(
                "  sphere(0.1) at ({:.3}, {:.3}, {:.3})\n",
                next(),
                next(),
                next()
            )
        })
        .collect();
    format!("camera {{ eye (0, 3, -9) target (0, 0, 0) }}\nunion {{\n{parts}}}\n")
}

/// A shader predicted to take the driver far past 30 s (a flat union of 4 097 spheres
/// compiled inline, `--form inline`: the model says minutes, with or without box trees; by
/// default the data form draws it, `data_form.rs`): `render`, `bench` and `view` refuse it
/// before a device is opened, with the scene's span and the prediction; `check` prints the
/// prediction, `emit` writes the shader (other engines' drivers differ).
#[test]
fn a_shader_predicted_too_slow_is_refused_at_once() {
    let dir = scratch("driver-limit");
    let parts: String = (0..4097)
        .map(|i| {
            format!(
                "  sphere(0.1) at ({}, 0, {})\n",
                (i % 64) as f64 * 0.5,
                (i / 64) as f64 * 0.5
            )
        })
        .collect();
    let file = write(&dir, "big.sdf", &format!("union {{\n{parts}}}\n"));
    let out = dir.join("big.png");
    let out = out.to_str().unwrap();
    for args in [
        vec![
            "render", &file, "-o", out, "--size", "8x8", "--form", "inline",
        ],
        vec![
            "render", &file, "-o", out, "--size", "8x8", "--no-bvh", "--form", "inline",
        ],
        vec![
            "bench",
            &file,
            "--form",
            "inline",
            "--size",
            "8x8",
            "--tracers",
            "basic",
            "--steps",
            "8",
        ],
    ] {
        let o = sdfc(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("too large for the GPU driver to compile in reasonable time")
                && err.contains("big.sdf:1:1")
                && err.contains("predicted compile:")
                && err.contains("min on lavapipe")
                && err.contains("--allow-slow-compile"),
            "{args:?}: {err}"
        );
    }
    assert!(!std::path::Path::new(out).exists(), "nothing is written");
    // The viewer refuses it before opening a window (the display is never contacted).
    let o = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(["view", &file, "--form", "inline"])
        .env("DISPLAY", ":31999")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("predicted compile:"), "{err}");
    let wgsl = dir.join("big.wgsl");
    let o = sdfc(&["emit", &file, "-o", wgsl.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let o = sdfc(&["check", &file]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0));
    assert!(
        text.contains("driver compile: ") && text.contains("min predicted on lavapipe"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// 512 scattered spheres: with the default box tree the driver would take about 40 s
/// (measured 32–43 s on lavapipe), without it about 5 s, so `render` draws it without the tree
/// and says so; with `--bvh` (asked for) it is refused instead.
#[test]
fn box_trees_are_left_out_when_they_make_the_compile_too_slow() {
    let dir = scratch("driver-fallback");
    let file = write(&dir, "many.sdf", &scattered(512));
    let out = dir.join("many.png");
    let out = out.to_str().unwrap();
    let o = sdfc(&[
        "render", &file, "-o", out, "--size", "8x8", "--form", "inline",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(err.contains("the unions' box trees are left out"), "{err}");
    assert!(std::path::Path::new(out).exists());
    let o = sdfc(&[
        "render", &file, "-o", out, "--size", "8x8", "--bvh", "--form", "inline",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("predicted compile:"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

/// The pipeline cache lives where `SDFC_CACHE_DIR` says: written after a render (Vulkan),
/// ignored when it is garbage (the same picture), and a folder that cannot be made is only a
/// warning; `off` writes none.
#[test]
fn the_pipeline_cache_is_kept_where_asked_and_never_breaks_a_render() {
    let dir = scratch("pipeline-cache");
    let scene = root().join("examples/gem.sdf");
    let render = |cache: &str, name: &str| {
        let out = dir.join(name);
        let o = Command::new(env!("CARGO_BIN_EXE_sdfc"))
            .args([
                "render",
                scene.to_str().unwrap(),
                "--size",
                "16x9",
                "--backend",
                "vulkan",
            ])
            .arg("-o")
            .arg(&out)
            .env("SDFC_CACHE_DIR", cache)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        assert_eq!(o.status.code(), Some(0), "{err}");
        (std::fs::read(out).unwrap(), err)
    };
    let cache = dir.join("cache");
    let (first, _) = render(cache.to_str().unwrap(), "a.png");
    let files: Vec<_> = std::fs::read_dir(&cache)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(files.len(), 1, "{files:?}");
    let name = files[0].file_name().unwrap().to_string_lossy().to_string();
    assert!(
        name.starts_with("wgpu_pipeline_cache_vulkan_") && name.ends_with(".bin"),
        "{name}"
    );
    assert!(std::fs::metadata(&files[0]).unwrap().len() > 0);
    std::fs::write(&files[0], b"not a pipeline cache").unwrap();
    let (again, _) = render(cache.to_str().unwrap(), "b.png");
    assert_eq!(first, again, "a garbage cache changed the picture");
    let blocked = write(&dir, "a-file", "");
    let (third, err) = render(&format!("{blocked}/cache"), "c.png");
    assert_eq!(first, third);
    assert!(
        err.contains("warning: cannot save the pipeline cache"),
        "{err}"
    );
    let off = dir.join("off");
    render("off", "d.png");
    assert!(!off.exists());
    let _ = std::fs::remove_dir_all(dir);
}
