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

/// A `@lipschitz` claim below the sphere's slope: `sdfc check` warns (the page's worker too).
const CLAIM: &str = "camera { eye (0, 1, -4)  target (0, 0, 0) }
sphere(1) @lipschitz(0.5)
plane(y, -1)
";

/// A colour parameter, for the page's colour picker.
const TINT: &str = "param tint = #d04038
camera { eye (0, 1, -4)  target (0, 0, 0) }
material paint { color tint }
sphere(1) : paint
plane(y, -1)
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

/// 150 balls of three materials blended together over a plane whose height is a parameter:
/// drawn as data in the page (WebGPU), its cells pruned by the page's device. (The plane is
/// beside the blend, not in it: a plane blended in would make every ray beyond the grid run the
/// whole tree, which SwiftShader takes minutes over at the page's size.)
fn data_scene() -> String {
    format!(
        "param lift = -1.2 in -1.5..0\nmaterial red {{ color #d04038 }}\nmaterial blue {{ color #3050d0 }}\ncamera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nsmooth_union(0.1) {{\n{}\n}}\nplane(y, lift)",
        crate::data_form::balls(150, true)
    )
}

/// The page drew the data scene as data — at its defaults and with the plane's slider at its
/// maximum, the buffers made again by the page's compiler without a new compile — as `sdfc
/// render --form data` draws it there.
fn data_form(got: &serde_json::Value, dir: &std::path::Path, (w, h): (u32, u32), text: &str) {
    let data = &got["data"];
    assert_eq!(data["form"], true, "drawn as data: {got}");
    assert_eq!(data["follows"], serde_json::json!(["lift"]), "{got}");
    assert_eq!(data["compiled"], 0, "the slider compiled: {got}");
    // Pruned by the page's device (its pre-pass from the compile), every cell with room.
    let prune = &data["prune"];
    assert!(
        prune["prunes"].as_u64().unwrap_or(0) >= 2,
        "not pruned on the device: {got}"
    );
    assert_eq!(prune["fellBack"], 0, "a pre-pass found no room: {got}");
    let gpu = gpu();
    let mut said = Vec::new();
    for (name, lift) in [("data0", -1.2), ("data1", 0.0)] {
        let values = HashMap::from([("lift".to_string(), vec![lift])]);
        let here = compile(text).with_values(&values);
        let frame = crate::browser::render_data(&gpu, &here, &View::new(&here.camera, w, h));
        let page = std::fs::read(dir.join(format!("{name}.rgba"))).unwrap();
        let (share, worst) = within_levels(&frame.color, &page, 2);
        assert!(
            share >= 0.995,
            "{name} (lift {lift}): only {:.2}% within 2 levels",
            100.0 * share
        );
        said.push(format!(
            "lift {lift}: {:.2}% (worst {worst})",
            100.0 * share
        ));
    }
    report(&format!(
        "playground in Chrome (webgpu): 150 blended balls over a plane drawn as data, its cells pruned by the page's device at the slider's values ({} pre-passes, the last {:.0} ms; no compile), within 2 levels of sdfc render --form data: {}",
        prune["prunes"],
        prune["ms"].as_f64().unwrap_or(f64::NAN),
        said.join(", ")
    ));
}

/// The playground's session in Chromium (`mode`: `no-webgpu` takes WebGPU away), which must
/// draw with `renderer`.
fn playground(chrome: &str, driver: &std::path::Path, mode: &str, renderer: &str) {
    let dir = scratch(&format!("playground-{mode}"));
    let typo_text = SCENE.replace("sphere(0.8) at", "sphere(0.8 at");
    let (scene, typo, claim) = (
        dir.join("scene.sdf"),
        dir.join("typo.sdf"),
        dir.join("claim.sdf"),
    );
    std::fs::write(&claim, CLAIM).unwrap();
    let tint = dir.join("tint.sdf");
    std::fs::write(&tint, TINT).unwrap();
    std::fs::write(&scene, SCENE).unwrap();
    std::fs::write(&typo, &typo_text).unwrap();
    // A scene of many parts (the page draws it as data where it has WebGPU).
    let data_text = data_scene();
    std::fs::write(dir.join("data.sdf"), &data_text).unwrap();
    let (w, h) = (160u32, 90u32);
    let server = Serve::start();
    let run = Command::new("node")
        .arg(driver.join("playground.mjs"))
        .arg(&server.address)
        .args([&scene, &typo, &claim, &tint, &dir])
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
    let picture = |name: &str, values: &HashMap<String, Vec<f64>>, steps: Option<u32>| {
        let page = std::fs::read(dir.join(format!("{name}.rgba"))).unwrap();
        let mut here = compile(SCENE).with_values(values);
        if let Some(n) = steps {
            here.trace.steps = n;
        }
        let frame = render(&gpu, &here, &View::new(&here.camera, w, h));
        (within_levels(&frame.color, &page, 2), page)
    };
    let ((typed, worst), page) = picture("typed", &HashMap::new(), None);
    let lift = HashMap::from([("lift".to_string(), vec![1.4])]);
    let ((slid, slid_worst), moved) = picture("slid", &lift, None);
    let ((tuned, tuned_worst), coarse) = picture("tuned", &lift, Some(12));
    let differ = |a: &[u8], b: &[u8]| {
        a.chunks_exact(4)
            .zip(b.chunks_exact(4))
            .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 2))
            .count() as f64
            / f64::from(w * h)
    };
    let changed = differ(&page, &moved);
    let stepped = differ(&moved, &coarse);
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
    assert_eq!(got["indented"], true, "the editor's indentation: {got}");
    // Progressive refinement: coarse frames while orbiting, the full size once still.
    assert!(
        got["whileMoving"]["coarseFrames"].as_u64() > Some(0),
        "{got}"
    );
    assert_eq!(got["refined"], serde_json::json!([640, 360]), "{got}");
    assert_eq!(got["fullOrbitScale"], 1, "?full drew coarse frames: {got}");
    // The tracer panel: its 12 steps are `sdfc render`'s with 12 steps; 0 is refused.
    assert!(
        tuned >= 0.995,
        "with 12 steps: only {:.2}% within 2 levels",
        100.0 * tuned
    );
    assert!(stepped > 0.01, "12 steps changed {stepped} of the picture");
    let settings = &got["tracer"]["settings"];
    assert!(
        settings
            .as_array()
            .unwrap()
            .contains(&serde_json::json!(["steps", "12"])),
        "{got}"
    );
    assert!(
        got["refused"]
            .as_str()
            .unwrap()
            .contains("`--steps` must be"),
        "{got}"
    );
    downloads(&dir, &scene, &got);
    // The PNG: the canvas at full size, from the scene's camera, the slider at its maximum.
    let png = image::open(dir.join("scene.png"))
        .expect("the PNG decodes")
        .to_rgba8();
    assert_eq!(png.dimensions(), (640, 360));
    let here = compile(SCENE).with_values(&lift);
    let frame = render(&gpu, &here, &View::new(&here.camera, 640, 360));
    let (saved, saved_worst) = within_levels(&frame.color, png.as_raw(), 2);
    assert!(
        saved >= 0.995,
        "the PNG: only {:.2}% within 2 levels of sdfc render",
        100.0 * saved
    );

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
    // Underlined in the editor where the CLI's caret is, its message on hover.
    let span = &first["span"];
    let (start, end) = (
        span["start"].as_u64().unwrap() as usize,
        span["end"].as_u64().unwrap() as usize,
    );
    let under = if end > start {
        &typo_text[start..end]
    } else {
        &typo_text[start..=start]
    };
    assert_eq!(got["underlined"], under, "{got}");
    assert!(
        got["tooltip"]
            .as_str()
            .is_some_and(|t| t.contains(first["message"].as_str().unwrap())),
        "the hover: {got}"
    );
    // The claim's warning: the worker's check gives what `sdfc check` gives, underlined.
    let cli = sdfc(&["check", claim.to_str().unwrap(), "--message-format", "json"]);
    let warnings: Vec<serde_json::Value> = String::from_utf8_lossy(&cli.stderr)
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter(|d| d.get("severity").is_some())
        .collect();
    assert_eq!(warnings.len(), 1, "sdfc check of the claim: {warnings:?}");
    let claimed = &got["claimed"];
    let page_warnings = claimed["diagnostics"].as_array().unwrap();
    assert_eq!(page_warnings.len(), 1, "{got}");
    for key in ["message", "label", "span", "severity", "notes"] {
        assert_eq!(
            page_warnings[0][key], warnings[0][key],
            "the claim's {key}: {got}"
        );
    }
    assert!(claimed["marks"].as_u64() >= Some(1), "no underline: {got}");

    // The colour picker set to #20c040: `sdfc render` with that colour, and no compile.
    assert_eq!(
        got["tint"],
        serde_json::json!({"pickers": 1, "compiled": 0}),
        "{got}"
    );
    let green = HashMap::from([(
        "tint".to_string(),
        vec![32.0 / 255.0, 192.0 / 255.0, 64.0 / 255.0],
    )]);
    let page_tinted = std::fs::read(dir.join("tinted.rgba")).unwrap();
    let tinted_scene = compile(TINT).with_values(&green);
    let frame = render(&gpu, &tinted_scene, &View::new(&tinted_scene.camera, w, h));
    let (tinted, tinted_worst) = within_levels(&frame.color, &page_tinted, 2);
    let untinted = compile(TINT);
    let default = render(&gpu, &untinted, &View::new(&untinted.camera, w, h));
    assert!(
        tinted >= 0.995 && within_levels(&default.color, &page_tinted, 2).0 < 0.95,
        "the colour picker: {:.2}% within 2 levels of sdfc render (worst {tinted_worst})",
        100.0 * tinted
    );

    // The `baked` example from the menu: its maps' bytes from the compiler in the page.
    let baked_source = std::fs::read_to_string(root().join("examples/baked.sdf")).unwrap();
    let baked_scene = compile(&baked_source);
    let sizes: Vec<u64> = baked_scene
        .volumes()
        .iter()
        .map(|v| sdfc_compiler::bake::file::raw(v).len() as u64)
        .collect();
    assert_eq!(got["baked"]["volumes"], serde_json::json!(sizes), "{got}");
    let page_baked = std::fs::read(dir.join("baked.rgba")).unwrap();
    let frame = render(&gpu, &baked_scene, &View::new(&baked_scene.camera, w, h));
    let (baked, baked_worst) = within_levels(&frame.color, &page_baked, 2);
    assert!(
        baked >= 0.995,
        "the baked example: only {:.2}% within 2 levels",
        100.0 * baked
    );
    if renderer == "webgpu" {
        data_form(&got, &dir, (w, h), &data_text);
    }
    report(&format!(
        "playground in Chrome ({renderer}): a scene typed key by key ({} compiles, {} ms) drawn within 2 \
         levels of sdfc render on {:.2}% of pixels (worst {worst}); its slider redrew without a \
         compile ({:.1}% of pixels changed, {:.2}% within 2 levels of sdfc render at that value, \
         worst {slid_worst}); the share link ({} characters) reopened the same text; a typo \
         listed and underlined `{}` at {}:{} as sdfc check does; the tracer panel's 12 steps \
         drawn as sdfc render --steps 12 on {:.2}% (worst {tuned_worst}); coarse frames while \
         orbiting, full once still; the PNG downloaded within 2 levels of sdfc render on {:.2}% (worst \
         {saved_worst}), WGSL and GLSL as sdfc emit writes them, the manifest; the baked example \
         from the menu ({} volumes from the page's compiler, compiled in {:.0} ms) within 2 levels \
         on {:.2}% (worst {baked_worst}); the colour picker drawn as sdfc render with that colour on {:.2}% (worst {tinted_worst}); \
         a too small `@lipschitz` warned by the worker as by sdfc \
         check ({:.0} ms off the page's thread); measured: compile in the page per example (ms, 3 \
         runs) {};  keystroke to its first frame {} ms \
         (3 edits), orbiting: {:.1} frames a second (coarse frames at 320×180), {:.1} with every \
         frame at 640×360 (?full); GL errors on the live canvas \
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
        100.0 * tuned,
        100.0 * saved,
        sizes.len(),
        got["baked"]["ms"].as_f64().unwrap_or(f64::NAN),
        100.0 * baked,
        100.0 * tinted,
        claimed["ms"].as_f64().unwrap_or(f64::NAN),
        got["examples"],
        got["latencies"],
        got["orbitFps"].as_f64().unwrap_or(f64::NAN),
        got["fullOrbitFps"].as_f64().unwrap_or(f64::NAN),
        got["glErrors"]
    ));
}

/// `sdfc serve target/web --port 0`, the page's server for the test, stopped when dropped.
struct Serve {
    child: std::process::Child,
    address: String,
}

impl Serve {
    fn start() -> Serve {
        use std::io::BufRead;
        let web = root().join("target/web");
        let mut child = Command::new(env!("CARGO_BIN_EXE_sdfc"))
            .args(["serve", web.to_str().unwrap(), "--port", "0"])
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("sdfc serve");
        let mut line = String::new();
        let stderr = child.stderr.take().unwrap();
        std::io::BufReader::new(stderr)
            .read_line(&mut line)
            .unwrap();
        // "serving DIR at http://127.0.0.1:PORT/ (Ctrl-C stops)"
        let address = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap_or_else(|| panic!("sdfc serve said: {line}"))
            .to_string();
        Serve { child, address }
    }
}

impl Drop for Serve {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The page's downloads of the scene: all four came; the shaders are those `sdfc emit` writes
/// for its fragment entry, the manifest is one.
fn downloads(dir: &std::path::Path, scene: &std::path::Path, got: &serde_json::Value) {
    let names = ["scene.png", "scene.wgsl", "scene.frag", "scene.json"];
    assert_eq!(got["downloaded"], serde_json::json!(names), "{got}");
    for (target, file, extra) in [
        ("wgsl", "scene.wgsl", None),
        ("glsl", "scene.frag", Some("300es")),
    ] {
        let mut args = vec![
            "emit",
            scene.to_str().unwrap(),
            "--target",
            target,
            "--entry",
            "fragment",
        ];
        if let Some(v) = extra {
            args.extend(["--glsl-version", v]);
        }
        let cli = sdfc(&[&args[..], &["-o", "-"]].concat());
        let page = std::fs::read_to_string(dir.join(file)).unwrap();
        assert!(
            page == String::from_utf8_lossy(&cli.stdout),
            "{file} differs from sdfc emit"
        );
    }
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("scene.json")).unwrap()).unwrap();
    assert_eq!(manifest["format"], "sdfc-manifest 1");
}
