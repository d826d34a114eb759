//! sdfc's GLSL ES 3.00 in Chrome's WebGL2 (ANGLE on SwiftShader), as a web page would use it:
//! every example's fragment entry, library and Shadertoy shader compiles and links, and the
//! WebGL2 host (`examples/hosts/webgl2`, driven by the manifest alone) draws what `sdfc
//! render` draws — through both of GL's render targets (a plain RGBA8 one, where the entry
//! encodes sRGB, and an SRGB8_ALPHA8 one, where GL does), with GL's origin flag and without it.
//!
//! Needs what `browser.rs` needs (Chromium and `npm ci` in `examples/hosts/test`).

use crate::browser::browser;
use crate::common::{compile, examples, gpu, render, scratch, sdfc, within_levels};
use sdfc_compiler::view::View;
use std::collections::HashMap;
use std::path::Path;
use std::process::Command;

/// Most 8-bit levels a channel may differ by, and the share of pixels that must be within it.
const LEVELS: i32 = 2;
const SHARE: f64 = 0.999;

/// Every example's GLSL ES 3.00 — the fragment entry and the library (whole shaders: the
/// library has its placeholder `main`), each with the default bounding volumes and every
/// union's tree (`--bvh`), and the Shadertoy shader inside Shadertoy's prelude — compiled and
/// linked by Chrome's WebGL2: none refused.
#[test]
fn every_example_links_in_chromes_webgl2() {
    let Some((chrome, driver)) = browser() else {
        return;
    };
    let dir = scratch("webgl2-link");
    let mut written = 0;
    for path in &examples() {
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let file = path.to_str().unwrap();
        for (entry, bvh) in [
            ("fragment", false),
            ("fragment", true),
            ("library", false),
            ("library", true),
        ] {
            let out = dir.join(format!(
                "{stem}.{entry}{}.frag",
                if bvh { "-bvh" } else { "" }
            ));
            let mut args = vec!["emit", file, "--target", "glsl", "--glsl-version", "300es"];
            args.extend(["--entry", entry, "-q", "-o", out.to_str().unwrap()]);
            if bvh {
                args.push("--bvh");
            }
            emitted(&args);
            written += 1;
        }
        let toy = dir.join(format!("{stem}.shadertoy.glsl"));
        let toy_args = [
            "emit",
            file,
            "--entry",
            "shadertoy",
            "-q",
            "-o",
            toy.to_str().unwrap(),
        ];
        // A baked part is a 3D texture a Shadertoy tab cannot be given: refused, no file.
        if !compile(&std::fs::read_to_string(path).unwrap())
            .volumes()
            .is_empty()
        {
            let out = sdfc(&toy_args);
            let said = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{stem}: {said}");
            assert!(
                said.contains("Shadertoy tab has no input"),
                "{stem}: {said}"
            );
            assert!(!toy.exists(), "{stem}: a Shadertoy file was written");
            continue;
        }
        emitted(&toy_args);
        written += 1;
    }
    // And the scenes the suites aim at the edges: the fragment entry.
    let es300 = sdfc_compiler::emit::Settings {
        glsl_version: sdfc_compiler::emit::GlslVersion::Es300,
        ..Default::default()
    };
    for (stem, scene) in crate::common::edge_scenes() {
        use sdfc_compiler::emit::{self, Output, Target};
        use sdfc_compiler::lower::{Entry, tracer::Options};
        let (m, info) =
            emit::module(&scene, Entry::Fragment, &Options::from_scene(&scene)).unwrap();
        let Output::Text(code) =
            emit::write_with(&m, &info, Target::Glsl, Entry::Fragment, &es300).unwrap()
        else {
            unreachable!("GLSL is text")
        };
        std::fs::write(dir.join(format!("{stem}.fragment.frag")), code).unwrap();
        written += 1;
    }
    let run = node(&chrome, &driver, &["compile", dir.to_str().unwrap()]);
    let said = String::from_utf8_lossy(&run.stdout).to_string();
    let refused: Vec<&str> = said.lines().filter(|l| l.starts_with("error")).collect();
    println!("{}", said.lines().last().unwrap_or(""));
    assert!(
        run.status.success() && refused.is_empty(),
        "WebGL2 refused {} of {written} shaders:\n{}{}",
        refused.len(),
        refused.join("\n"),
        String::from_utf8_lossy(&run.stderr)
    );
    let ok = said.lines().filter(|l| l.starts_with("ok ")).count();
    assert_eq!(ok, written, "{said}");
    crate::common::report(&format!(
        "Chrome's WebGL2 (ANGLE): {ok} of {written} GLSL ES 3.00 shaders (every example x fragment/library x default/--bvh, Shadertoy; hostile and extremes scenes' fragment entries) compiled and linked, 0 refused"
    ));
    assert!(written >= 16 * 5 + 20, "{written}");
}

/// One picture the page draws and what it must equal.
struct Job {
    json: serde_json::Value,
    scene: String,
    values: HashMap<String, Vec<f64>>,
    /// The page drew with y down (the origin flag off in a GL host): the picture is upside down.
    flipped: bool,
    /// Alpha is the library's hit flag (the host writes `color`'s `w`).
    hit_alpha: bool,
}

/// Five examples (one with parameters, the lamp; some with unions of five parts and more) and a
/// scene whose material colour, specular, lights and shapes read parameters: each drawn by the
/// WebGL2 host from its fragment entry into an RGBA8 and an SRGB8_ALPHA8 target, with the
/// origin flag off (upside down, as a GL host without the flag sees it), from its library, and
/// as a Shadertoy shader; the parametric ones also at other values. Each equals `sdfc render`
/// within 2 levels on 99.9% of pixels; the library's hit mask (its alpha) equals render's.
#[test]
fn webgl2_draws_what_render_draws() {
    let Some((chrome, driver)) = browser() else {
        return;
    };
    let dir = scratch("webgl2-draw");
    let (w, h) = (96u32, 64u32);
    let mut jobs: Vec<Job> = Vec::new();
    for (name, file, settings) in &crate::browser::drawn_scenes(&dir) {
        let file = &file.display().to_string();
        let at = |s: &str| dir.join(s).display().to_string();
        let es = ["--target", "glsl", "--glsl-version", "300es"];
        let mut fragment = vec!["emit", file, "--entry", "fragment", "-q", "-o"];
        let (frag, json) = (at(&format!("{name}.frag")), at(&format!("{name}.json")));
        fragment.extend([frag.as_str(), "--manifest", json.as_str()]);
        fragment.extend(es);
        emitted(&fragment);
        let (lib, lib_json) = (
            at(&format!("{name}-lib.glsl")),
            at(&format!("{name}-lib.json")),
        );
        let mut library = vec!["emit", file, "--entry", "library", "-q", "-o", lib.as_str()];
        library.extend(["--manifest", lib_json.as_str()]);
        library.extend(es);
        emitted(&library);
        let toy = at(&format!("{name}.shadertoy.glsl"));
        emitted(&["emit", file, "--entry", "shadertoy", "-q", "-o", &toy]);
        let source = std::fs::read_to_string(file).unwrap();
        let scene = compile(&source);
        let time = scene
            .params
            .iter()
            .find(|p| p.name == "time")
            .map_or(0.0, |p| p.default.x);
        for (k, &values) in settings.iter().enumerate() {
            let parsed: HashMap<String, Vec<f64>> = serde_json::from_str(values).unwrap();
            let v: serde_json::Value = serde_json::from_str(values).unwrap();
            let mut add = |json: serde_json::Value, flipped, hit_alpha| {
                jobs.push(Job {
                    json,
                    scene: source.clone(),
                    values: parsed.clone(),
                    flipped,
                    hit_alpha,
                })
            };
            let base = serde_json::json!({"width": w, "height": h, "values": v});
            let with = |extra: serde_json::Value| {
                let mut j = base.clone();
                j.as_object_mut()
                    .unwrap()
                    .extend(extra.as_object().unwrap().clone());
                j
            };
            add(
                with(serde_json::json!({"name": name, "target": "rgba8"})),
                false,
                false,
            );
            add(
                with(serde_json::json!({"name": name, "target": "srgb8"})),
                false,
                false,
            );
            add(
                with(serde_json::json!({"name": format!("{name}-lib"), "kind": "library"})),
                false,
                true,
            );
            if k == 0 {
                add(
                    with(serde_json::json!({"name": name, "yUp": false})),
                    true,
                    false,
                );
                add(
                    with(serde_json::json!({"name": name, "kind": "shadertoy", "time": time})),
                    false,
                    false,
                );
            }
        }
    }
    let list = serde_json::Value::Array(jobs.iter().map(|j| j.json.clone()).collect());
    let run = node(
        &chrome,
        &driver,
        &[
            "render",
            dir.to_str().unwrap(),
            &list.to_string(),
            dir.to_str().unwrap(),
        ],
    );
    assert!(
        run.status.success(),
        "the WebGL2 page failed: {}{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
    println!("{}", String::from_utf8_lossy(&run.stdout).trim());
    let gpu = gpu();
    let mut least: f64 = 1.0;
    for (i, job) in jobs.iter().enumerate() {
        let page = std::fs::read(dir.join(format!("{i}.rgba"))).unwrap();
        assert_eq!(page.len(), (4 * w * h) as usize);
        let here = compile(&job.scene).with_values(&job.values);
        let frame = render(&gpu, &here, &View::new(&here.camera, w, h));
        // Upside down when the page drew with the origin flag off: turned upright to compare.
        let row = 4 * w as usize;
        let page: Vec<u8> = match job.flipped {
            true => page.chunks_exact(row).rev().flatten().copied().collect(),
            false => page,
        };
        let (share, worst) = within_levels(&frame.color, &page, LEVELS);
        let masks = (page.chunks_exact(4).zip(&frame.depth))
            .filter(|(c, d)| !job.hit_alpha || (c[3] > 127) == (**d >= 0.0))
            .count();
        let mask = masks as f64 / frame.color.len() as f64;
        println!(
            "{}: within {LEVELS} levels of sdfc render on {:.2}% of pixels (worst {worst}), hit mask equal on {:.2}%",
            job.json,
            share * 100.0,
            mask * 100.0
        );
        least = least.min(share).min(mask);
        assert!(
            share >= SHARE && mask >= SHARE,
            "{}: {:.2}% / {:.2}%",
            job.json,
            share * 100.0,
            mask * 100.0
        );
    }
    crate::common::report(&format!(
        "Chrome's WebGL2 host: {} pictures (5 examples and a parametric scene; RGBA8, sRGB8, flipped, library, Shadertoy), each >= {:.2}% within {LEVELS} levels of sdfc render",
        jobs.len(),
        least * 100.0
    ));
}

/// Runs `sdfc` with `args`, which must succeed.
fn emitted(args: &[&str]) {
    let out = sdfc(args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "sdfc {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The WebGL2 driver (`examples/hosts/test/webgl2.mjs`) with `args`.
fn node(chrome: &str, driver: &Path, args: &[&str]) -> std::process::Output {
    Command::new("node")
        .arg(driver.join("webgl2.mjs"))
        .args(args)
        .env("CHROME", chrome)
        .output()
        .unwrap()
}
