//! The WebGPU host page (`examples/hosts/webgpu`: plain HTML and JavaScript loading the
//! library's WGSL and its manifest) in headless Chromium, WebGPU on SwiftShader, draws what
//! `sdfc render` draws on lavapipe, at the defaults and at other parameter values.
//!
//! Needs `chromium-headless-shell` and the page's test driver (`npm ci` in
//! `examples/hosts/test`), which `.ci/run` installs; without them the test says
//! SKIPPED loudly, and fails instead when `SDFC_REQUIRE_BROWSER=1` (as `.ci/run` sets).

use crate::common::{compile, examples, gpu, render, root, scratch, succeeded, within_levels};
use sdfc_compiler::scene::Scene;
use sdfc_compiler::view::View;
use std::collections::HashMap;
use std::process::Command;

/// Chromium and the page's test driver, or `None` (said loudly) when they are missing and
/// `SDFC_REQUIRE_BROWSER` is not set.
pub(crate) fn browser() -> Option<(String, std::path::PathBuf)> {
    let chrome = std::env::var("CHROME").unwrap_or("/usr/bin/chromium-headless-shell".into());
    let driver = root().join("examples/hosts/test");
    let ready = std::path::Path::new(&chrome).exists()
        && driver.join("node_modules/puppeteer-core").exists()
        && Command::new("node").arg("--version").output().is_ok();
    if !ready {
        assert!(
            std::env::var("SDFC_REQUIRE_BROWSER").is_err(),
            "SDFC_REQUIRE_BROWSER is set but {chrome} or the page's test driver (npm ci in {}) is missing",
            driver.display()
        );
        eprintln!(
            "\n*** chromium-headless-shell or the WebGPU page's test driver is missing: the browser test is SKIPPED (`.ci/run` installs them) ***\n"
        );
        return None;
    }
    Some((chrome, driver))
}

/// The scenes both browser hosts draw (`webgl2.rs` too): five examples (the lamp with
/// parameters; unions of five parts and more) and `params::SCENE`, written into `dir` (its
/// materials, lights and shapes read parameters); each with the settings it is drawn at, as
/// JSON (angles in radians): `{}` for the defaults, and other values for the parametric ones.
pub(crate) fn drawn_scenes(
    dir: &std::path::Path,
) -> Vec<(String, std::path::PathBuf, Vec<&'static str>)> {
    std::fs::write(dir.join("parametric.sdf"), crate::params::SCENE).unwrap();
    let example = |n: &str| root().join(format!("examples/{n}.sdf"));
    let mut scenes: Vec<(String, std::path::PathBuf, Vec<&'static str>)> =
        ["composition", "primitives", "shapes", "village"]
            .iter()
            .map(|n| (n.to_string(), example(n), vec!["{}"]))
            .collect();
    scenes.insert(
        0,
        (
            "lamp".into(),
            example("lamp"),
            vec!["{}", r#"{"reach": [1.0], "height": [1.7], "time": [2.0]}"#],
        ),
    );
    scenes.push((
        "parametric".into(),
        dir.join("parametric.sdf"),
        vec![
            "{}",
            r#"{"tint": [0.2, 0.5, 0.9], "shine": [0.9], "power": [1.4], "sun": [0.6, 0.8, -0.4], "tilt": [0.5], "r": [1.1], "time": [1.5]}"#,
        ],
    ));
    scenes
}

/// The page draws five examples (the lamp with parameters, unions of five parts and more) and
/// a scene whose materials, lights and shapes read parameters, at the defaults and (the
/// parametric ones) at other values, and the example that bakes two parts (its maps loaded from
/// the volume files `emit` wrote beside the shader, as the manifest names them): each within 2
/// levels of `sdfc render` on 99.5% of pixels. The live page on the lamp makes its five
/// sliders, draws, and turns with a drag.
#[test]
fn the_webgpu_page_draws_what_render_draws() {
    let Some((chrome, driver)) = browser() else {
        return;
    };
    let dir = scratch("browser");
    let (w, h) = (96u32, 64u32);
    let mut jobs = Vec::new();
    let mut scenes = drawn_scenes(&dir);
    scenes.push((
        "baked".into(),
        root().join("examples/baked.sdf"),
        vec!["{}"],
    ));
    // The data form (`--form data`): its buffers loaded from the files beside the shader; a
    // value of the parameter that moves its plane, held in those buffers, is refused.
    scenes.push((DATA.into(), data_scene(&dir), vec!["{}", DATA_MOVED]));
    for (name, file, settings) in &scenes {
        let (wgsl, json) = (
            dir.join(format!("{name}.wgsl")),
            dir.join(format!("{name}.json")),
        );
        let form = if name == DATA { "data" } else { "inline" };
        succeeded(&[
            "emit",
            file.to_str().unwrap(),
            "--entry",
            "library",
            "--form",
            form,
            "-q",
            "-o",
            wgsl.to_str().unwrap(),
            "--manifest",
            json.to_str().unwrap(),
        ]);
        let source = std::fs::read_to_string(file).unwrap();
        for values in settings {
            jobs.push((name.clone(), source.clone(), *values));
        }
    }
    let list: Vec<serde_json::Value> = jobs
        .iter()
        .map(|(name, _, values)| {
            let v: serde_json::Value = serde_json::from_str(values).unwrap();
            let refused = *values == DATA_MOVED;
            serde_json::json!({"name": name, "width": w, "height": h, "values": v, "refused": refused})
        })
        .collect();
    let run = Command::new("node")
        .arg(driver.join("webgpu-render.mjs"))
        .arg(&dir)
        .arg(serde_json::Value::Array(list).to_string())
        .arg(&dir)
        .arg("lamp")
        .env("CHROME", &chrome)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "the page failed: {}{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
    let said = String::from_utf8_lossy(&run.stdout).to_string();
    println!("{}", said.trim());
    // The live page: a slider for each of the lamp's five parameters (`time` runs with the
    // clock), no error shown, and a drag turns the camera.
    assert!(
        said.contains("page: sliders=5 status=\"\" dragged=true errors=[]"),
        "the interactive page: {said}"
    );
    let gpu = gpu();
    let mut least: f64 = 1.0;
    assert!(
        said.contains(&format!(
            "refused {DATA}: lift moves parts of the data form"
        )),
        "the page drew the data form at a value its buffers do not hold: {said}"
    );
    for (i, (name, source, json)) in jobs.iter().enumerate() {
        if *json == DATA_MOVED {
            continue;
        }
        let values: HashMap<String, Vec<f64>> = serde_json::from_str(json).unwrap();
        let page = std::fs::read(dir.join(format!("{i}.rgba"))).unwrap();
        assert_eq!(page.len(), (4 * w * h) as usize);
        let here = compile(source).with_values(&values);
        let view = View::new(&here.camera, w, h);
        let frame = if name == DATA {
            render_data(&gpu, &here, &view)
        } else {
            render(&gpu, &here, &view)
        };
        let (share, worst) = within_levels(&frame.color, &page, 2);
        println!(
            "{name} {json}: the WebGPU page within 2 levels of sdfc render on {:.2}% of pixels (worst {worst})",
            share * 100.0
        );
        assert!(share >= 0.995, "{name} {json}: only {:.2}%", share * 100.0);
        least = least.min(share);
    }
    crate::common::report(&format!(
        "Chrome's WebGPU page: {} pictures (6 examples, one with 2 baked maps read from their files, a parametric scene, defaults and other values, and 200 balls emitted as data, its buffers read from their files), each >= {:.2}% within 2 levels of sdfc render; a value the data's buffers do not hold refused",
        jobs.len() - 1,
        least * 100.0
    ));
}

/// The browser's data-form scene's name, and the values the page must refuse to draw it at.
const DATA: &str = "balls";
const DATA_MOVED: &str = r#"{"lift": [-0.9]}"#;

/// A scene for the data form, written into `dir`: 200 balls of three materials over a plane
/// whose height is a parameter (so the buffers follow it).
fn data_scene(dir: &std::path::Path) -> std::path::PathBuf {
    let text = format!(
        "param lift = -1.2 in -1.5..0\nmaterial red {{ color #d04038 }}\nmaterial blue {{ color #3050d0 }}\ncamera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nunion {{\n{}\nplane(y, lift)\n}}",
        crate::data_form::balls(200, true)
    );
    let path = dir.join("balls.sdf");
    std::fs::write(&path, text).unwrap();
    path
}

/// `scene` rendered on `gpu` by the compute entry in the data form, its buffers made at the
/// scene's values.
pub(crate) fn render_data(gpu: &sdfc::gpu::Gpu, scene: &Scene, view: &View) -> sdfc::gpu::Frame {
    use sdfc_compiler::lower::tracer::{Form, Options};
    let options = Options {
        form: Form::Data,
        ..Options::from_scene(scene)
    };
    let (module, _) =
        sdfc_compiler::emit::module(scene, sdfc_compiler::lower::Entry::Compute, &options)
            .unwrap_or_else(|e| panic!("{}", e.0));
    let (tree, layout) = sdfc_compiler::tape::data::layout(scene, None).expect("a data form");
    let data = sdfc_compiler::tape::data::data(scene, &tree, &layout).expect("its buffers");
    gpu.set_scene(scene);
    gpu.set_tape(Some(&data)).unwrap();
    let frame = gpu.render(&module, view, None, |_, _| {}).unwrap();
    gpu.set_tape(None).unwrap();
    frame
}

/// Every example's WGSL, for each of the compute, fragment, library and trace entries, with
/// the default bounding volumes and with every union's tree (`--bvh`), compiled by Chrome's
/// own WebGPU (Tint's front end, then a compute or render pipeline made of each entry on
/// SwiftShader; `examples/hosts/test/webgpu-compile.mjs`): none refused. naga's validator
/// had passed modules Chrome refuses (`f32::MAX` printed above f32's range, issue 30).
#[test]
fn every_example_compiles_in_chromes_webgpu() {
    use sdfc_compiler::emit::{self, Output, Target};
    use sdfc_compiler::lower::{Entry, tracer::BoundingVolumes, tracer::Options};
    let Some((chrome, driver)) = browser() else {
        return;
    };
    let dir = scratch("chrome-compile");
    let mut written = 0;
    for path in &examples() {
        let scene = compile(&std::fs::read_to_string(path).unwrap());
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        for (trees, tag) in [(BoundingVolumes::Large, ""), (BoundingVolumes::All, "-bvh")] {
            let mut options = Options::from_scene(&scene);
            options.bounding_volumes = trees;
            for (entry, name) in [
                (Entry::Compute, "compute"),
                (Entry::Fragment, "fragment"),
                (Entry::Library, "library"),
                (Entry::Trace, "trace"),
            ] {
                let (m, info) = emit::module(&scene, entry, &options).unwrap();
                let Output::Text(code) = emit::write(&m, &info, Target::Wgsl, entry).unwrap()
                else {
                    unreachable!("WGSL is text")
                };
                std::fs::write(dir.join(format!("{stem}{tag}.{name}.wgsl")), code).unwrap();
                written += 1;
            }
        }
    }
    // And the scenes the suites aim at the edges: the compute and fragment entries.
    for (stem, scene) in crate::common::edge_scenes() {
        let options = Options::from_scene(&scene);
        for (entry, name) in [(Entry::Compute, "compute"), (Entry::Fragment, "fragment")] {
            let (m, info) = emit::module(&scene, entry, &options).unwrap();
            let Output::Text(code) = emit::write(&m, &info, Target::Wgsl, entry).unwrap() else {
                unreachable!("WGSL is text")
            };
            std::fs::write(dir.join(format!("{stem}.{name}.wgsl")), code).unwrap();
            written += 1;
        }
    }
    let run = Command::new("node")
        .arg(driver.join("webgpu-compile.mjs"))
        .arg(&dir)
        .env("CHROME", &chrome)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stdout).to_string();
    let refused: Vec<&str> = said.lines().filter(|l| l.starts_with("error")).collect();
    println!("{}", said.lines().last().unwrap_or(""));
    assert!(
        run.status.success() && refused.is_empty(),
        "Chrome refused {} of {written} modules:\n{}{}",
        refused.len(),
        refused.join("\n"),
        String::from_utf8_lossy(&run.stderr)
    );
    let ok = said.lines().filter(|l| l.starts_with("ok ")).count();
    assert_eq!(ok, written, "{said}");
    crate::common::report(&format!(
        "Chrome's WebGPU (Tint + SwiftShader pipelines): {ok} of {written} WGSL modules (every example x compute/fragment/library/trace x default/--bvh; hostile and extremes scenes x compute/fragment), 0 refused"
    ));
    assert!(written >= 16 * 8 + 2 * 20, "{written}");
}
