//! The playground (`web/`, assembled in `target/web` by `scripts/build_web.sh`) in headless
//! Chromium: a scene typed into it key by key is compiled in the page by the WebAssembly
//! compiler and drawn with WebGPU as `sdfc render` draws it; its slider changes the picture
//! without compiling; the share link reopens the same text; a typo lists the diagnostic
//! `sdfc check` gives — on WebGPU, and again in pages without WebGPU, where it falls back to
//! WebGL2 (GLSL ES). Needs what `browser.rs` and `web.rs` need (`.ci/run` installs it).

use crate::common::{compile, gpu, render, report, root, scratch, sdfc, within_levels};
use sdfc_compiler::view::View;
use std::collections::HashMap;
use std::process::Command;

/// The scene typed: a parameter for the slider, a material, a smooth blend, a floor.
const SCENE: &str = "// Typed into the playground, key by key.
param lift = 0.8 in 0.4..1.4
camera { eye (3, 2.5, -5)  target (0, 0.6, 0) }
material red { color #d04038 }
smooth_union(0.3) {
  sphere(0.8) at (0, lift, 0) : red
  box((1.6, 0.4, 1.6))
}
plane(y, -0.2)
";

#[test]
fn the_playground_compiles_as_you_type_and_draws_what_sdfc_renders() {
    let Some((chrome, driver)) = crate::browser::browser() else {
        return;
    };
    if crate::web::wasm().is_none() {
        return;
    }
    for (mode, renderer) in [("webgpu", "webgpu"), ("no-webgpu", "webgl2")] {
        playground(&chrome, &driver, mode, renderer);
    }
}

/// The playground's session in Chromium (`mode`: `no-webgpu` takes WebGPU away), which must
/// draw with `renderer`.
fn playground(chrome: &str, driver: &std::path::Path, mode: &str, renderer: &str) {
    let dir = scratch(&format!("playground-{mode}"));
    let typo_text = SCENE.replace("sphere(0.8) at", "sphere(0.8 at");
    let (scene, typo) = (dir.join("scene.sdf"), dir.join("typo.sdf"));
    std::fs::write(&scene, SCENE).unwrap();
    std::fs::write(&typo, &typo_text).unwrap();
    let (w, h) = (160u32, 90u32);
    let run = Command::new("node")
        .arg(driver.join("playground.mjs"))
        .arg(root().join("target/web"))
        .args([&scene, &typo, &dir])
        .args([w.to_string(), h.to_string(), mode.to_string()])
        .env("CHROME", chrome)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stdout).to_string();
    assert!(
        run.status.success(),
        "the playground failed: {said}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let got: serde_json::Value = serde_json::from_str(said.trim()).expect("one JSON object");
    println!("{got}");
    assert_eq!(got["first"]["ok"], true, "the page's first scene: {got}");
    assert_eq!(got["first"]["renderer"], renderer, "{got}");
    assert_eq!(got["typed"]["ok"], true, "the typed scene: {got}");
    assert_eq!(got["errors"], serde_json::json!([]), "{got}");

    // The typed scene as `sdfc render` draws it, and after the slider moved to its maximum.
    let gpu = gpu();
    let picture = |name: &str, values: &HashMap<String, Vec<f64>>| {
        let page = std::fs::read(dir.join(format!("{name}.rgba"))).unwrap();
        let here = compile(SCENE).with_values(values);
        let frame = render(&gpu, &here, &View::new(&here.camera, w, h));
        (within_levels(&frame.color, &page, 2), page)
    };
    let ((typed, worst), page) = picture("typed", &HashMap::new());
    let lift = HashMap::from([("lift".to_string(), vec![1.4])]);
    let ((slid, slid_worst), moved) = picture("slid", &lift);
    let changed = page
        .chunks_exact(4)
        .zip(moved.chunks_exact(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 2))
        .count() as f64
        / f64::from(w * h);
    assert!(
        typed >= 0.995,
        "typed: only {:.2}% within 2 levels",
        100.0 * typed
    );
    assert!(slid >= 0.995, "after the slider: only {:.2}%", 100.0 * slid);
    assert_eq!(got["sliders"], 1, "{got}");
    assert_eq!(
        got["compilesAfter"], got["compilesBefore"],
        "a slider compiled: {got}"
    );
    assert!(
        changed > 0.01,
        "the slider changed {:.2}% of the picture",
        100.0 * changed
    );
    assert_eq!(got["shared"], true, "the share link: {got}");

    // The typo: the diagnostic `sdfc check --message-format json` gives, listed.
    let cli = sdfc(&["check", typo.to_str().unwrap(), "--message-format", "json"]);
    let first: serde_json::Value = String::from_utf8_lossy(&cli.stderr)
        .lines()
        .find_map(|l| serde_json::from_str(l).ok())
        .expect("a diagnostic");
    let broken = &got["broken"];
    assert_eq!(broken["ok"], false, "{got}");
    let page_first = &broken["diagnostics"][0];
    for key in ["message", "label", "span", "severity"] {
        assert_eq!(page_first[key], first[key], "the typo's {key}: {got}");
    }
    assert!(
        broken["shown"]
            .as_str()
            .unwrap()
            .contains(first["message"].as_str().unwrap()),
        "{got}"
    );
    report(&format!(
        "playground in Chrome ({renderer}): a scene typed key by key ({} compiles, {} ms) drawn within 2 \
         levels of sdfc render on {:.2}% of pixels (worst {worst}); its slider redrew without a \
         compile ({:.1}% of pixels changed, {:.2}% within 2 levels of sdfc render at that value, \
         worst {slid_worst}); the share link ({} characters) reopened the same text; a typo \
         listed `{}` at {}:{} as sdfc check does; measured: keystroke to its first frame {} ms \
         (3 edits), {:.1} frames a second while orbiting at 640×360; GL errors on the live canvas \
         (frame, code): {}",
        got["typed"]["compiles"],
        got["typedMs"],
        100.0 * typed,
        100.0 * changed,
        100.0 * slid,
        got["addressLength"],
        first["message"].as_str().unwrap(),
        first["span"]["line"],
        first["span"]["column"],
        got["latencies"],
        got["orbitFps"].as_f64().unwrap_or(f64::NAN),
        got["glErrors"]
    ));
}
