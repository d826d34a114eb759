//! The compiler as WebAssembly (`web/`, built by `scripts/build_web.sh`) run by Node — V8, the
//! engine of Chromium's pages — gives what the CLI gives: every example's WGSL and GLSL ES
//! fragment shader and manifest byte for byte as `sdfc emit`, and every file of the error
//! corpus the diagnostics of `sdfc check --message-format json`. Issue 36's first step.
//!
//! Needs the `wasm32-unknown-unknown` target and Node (`.ci/run` installs both); without them
//! the test says SKIPPED loudly, and fails instead when `SDFC_REQUIRE_WASM=1` (as `.ci/run`
//! sets).

use crate::common::{examples, report, root, scratch, sdfc};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Builds the module and the page (`target/web`; once per run: the playground's test uses it
/// too); the module's path, or `None` (said loudly) without the target or Node.
pub(crate) fn wasm() -> Option<PathBuf> {
    static BUILT: std::sync::OnceLock<(bool, bool)> = std::sync::OnceLock::new();
    let (node, built) = *BUILT.get_or_init(build);
    if !built {
        assert!(
            std::env::var("SDFC_REQUIRE_WASM").is_err(),
            "SDFC_REQUIRE_WASM is set but Node ({node}) or the wasm build is missing"
        );
        eprintln!(
            "\n*** Node or the wasm32-unknown-unknown target is missing: the WebAssembly test is SKIPPED (`.ci/run` installs them) ***\n"
        );
        return None;
    }
    Some(root().join("target/web/sdfc.wasm"))
}

/// Runs `scripts/build_web.sh`: whether Node is here, and whether the build succeeded.
fn build() -> (bool, bool) {
    let node = Command::new("node").arg("--version").output().is_ok();
    let built = node
        && Command::new("bash")
            .arg(root().join("scripts/build_web.sh"))
            .output()
            .map(|o| {
                if !o.status.success() {
                    eprintln!("build_web.sh: {}", String::from_utf8_lossy(&o.stderr));
                } else {
                    report(String::from_utf8_lossy(&o.stdout).trim());
                }
                o.status.success()
            })
            .unwrap_or(false);
    (node, built)
}

/// The module's responses for `files`, one JSON object per file (`file`, `ms`, `response`).
fn in_node(wasm: &Path, target: &str, entry: &str, files: &[PathBuf]) -> Vec<serde_json::Value> {
    let out = Command::new("node")
        .arg(root().join("web/test/compile.mjs"))
        .args([wasm.to_str().unwrap(), target, entry])
        .args(files)
        .output()
        .expect("node");
    assert!(
        out.status.success(),
        "node: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<serde_json::Value> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect();
    assert_eq!(lines.len(), files.len());
    lines
}

#[test]
fn the_wasm_compiler_emits_and_reports_what_the_cli_does() {
    let Some(wasm) = wasm() else {
        return;
    };
    let dir = scratch("web");
    let files = examples();
    for (target, ext, extra) in [("wgsl", "wgsl", None), ("glsl", "frag", Some("300es"))] {
        let mut slowest = (0.0, String::new());
        for got in in_node(&wasm, target, "fragment", &files) {
            let file = got["file"].as_str().unwrap();
            let r = &got["response"];
            assert_eq!(r["ok"], true, "{file}: {r}");
            let stem = Path::new(file).file_stem().unwrap().to_string_lossy();
            let (code, manifest) = (
                dir.join(format!("{stem}.{ext}")),
                dir.join(format!("{stem}.json")),
            );
            let mut args = vec![
                "emit",
                file,
                "--target",
                target,
                "--entry",
                "fragment",
                "-o",
                code.to_str().unwrap(),
                "--manifest",
                manifest.to_str().unwrap(),
            ];
            if let Some(v) = extra {
                args.extend(["--glsl-version", v]);
            }
            let run = sdfc(&args);
            assert!(
                run.status.success(),
                "{}",
                String::from_utf8_lossy(&run.stderr)
            );
            let cli_code = std::fs::read_to_string(&code).unwrap();
            assert!(
                r["code"] == cli_code.as_str(),
                "{file} {target}: the shaders differ"
            );
            let cli_manifest: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(&manifest).unwrap()).unwrap();
            assert_eq!(
                r["manifest"], cli_manifest,
                "{file} {target}: the manifests differ"
            );
            let ms = got["first_ms"].as_f64().unwrap();
            if ms > slowest.0 {
                slowest = (ms, stem.into_owned());
            }
        }
        report(&format!(
            "wasm compiler in Node: {} examples' {target} fragment shaders and manifests equal \
             `sdfc emit`'s; slowest first compile {:.1} ms ({})",
            files.len(),
            slowest.0,
            slowest.1
        ));
    }
    // The error corpus: the same diagnostics as `sdfc check --message-format json` (files that
    // import other files are left out: the page has none).
    let corpus: Vec<PathBuf> = std::fs::read_dir(root().join("tests/errors"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "sdf"))
        .filter(|p| {
            let text = std::fs::read_to_string(p).unwrap_or_default();
            !text
                .lines()
                .any(|l| l.trim_start().starts_with("import") && !l.contains("\"std/"))
        })
        .collect();
    let mut compared = 0;
    for got in in_node(&wasm, "wgsl", "fragment", &corpus) {
        let file = got["file"].as_str().unwrap();
        let run = sdfc(&["check", file, "--message-format", "json"]);
        let said: Vec<serde_json::Value> = String::from_utf8_lossy(&run.stderr)
            .lines()
            .filter_map(|l| serde_json::from_str(l).ok())
            .collect();
        let (cli_summary, cli): (Vec<_>, Vec<_>) =
            said.into_iter().partition(|v| v.get("summary").is_some());
        let r = &got["response"];
        assert_eq!(r["diagnostics"], serde_json::Value::from(cli), "{file}");
        if let Some(s) = cli_summary.first() {
            assert_eq!(r["summary"], s["summary"], "{file}");
        }
        assert_eq!(r["ok"], run.status.success(), "{file}: {r}");
        compared += 1;
    }
    report(&format!(
        "wasm compiler in Node: {compared} files of the error corpus give `sdfc check`'s \
         diagnostics"
    ));
}

/// Bad input never traps the module nor hangs the page: every file of the hostile suite
/// (`runtime/tests/hostile`: huge counts, values past f32, a NUL byte, exponential sharing, 2 434
/// spheres…) compiled in Node gives what `sdfc check` gives — compiled or refused, with the same
/// first message. (`invalid_utf8.sdf` is bytes a page cannot hold as text: it only must not trap.)
#[test]
fn hostile_scenes_in_the_wasm_compiler_get_the_clis_answers() {
    let Some(wasm) = wasm() else {
        return;
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("runtime/tests/hostile"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "sdf"))
        .collect();
    files.extend(deepest(&scratch("web-deepest")));
    let mut slowest = (0.0, String::new());
    for got in in_node(&wasm, "wgsl", "fragment", &files) {
        let file = got["file"].as_str().unwrap();
        let r = &got["response"];
        let ms = got["first_ms"].as_f64().unwrap();
        if ms > slowest.0 {
            slowest = (ms, file.rsplit('/').next().unwrap().to_string());
        }
        if file.ends_with("invalid_utf8.sdf") {
            continue;
        }
        if file.contains("deepest_") {
            let refused = file.contains("too_deep");
            assert_eq!(
                r["ok"], !refused,
                "{file}: {}",
                r["diagnostics"][0]["message"]
            );
        }
        let run = sdfc(&["check", file, "--message-format", "json"]);
        let first: Option<serde_json::Value> = String::from_utf8_lossy(&run.stderr)
            .lines()
            .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
            .find(|v| v.get("message").is_some());
        assert_eq!(r["ok"], run.status.success(), "{file}: {r}");
        if let Some(first) = first {
            assert_eq!(r["diagnostics"][0]["message"], first["message"], "{file}");
        }
    }
    report(&format!(
        "wasm compiler in Node: {} hostile scenes (nesting to the limits among them) answered as \
         `sdfc check` answers them, none trapped (a 32 MiB stack); slowest first compile {:.0} ms \
         ({})",
        files.len(),
        slowest.0,
        slowest.1
    ));
}

/// Scenes nested as deep as the compiler takes them, and one level deeper, written into `dir`:
/// brackets, calls, unions and negations to `syntax::MAX_NESTING` (the parser's bound), and
/// functions calling functions to `check::MAX_DEPTH` (the checker's): the module's 32 MiB stack
/// must hold every pass over them, through the WGSL writer. (That the deepest are accepted
/// and one more is refused is asserted, so the limits cannot drift from these scenes.)
fn deepest(dir: &Path) -> Vec<PathBuf> {
    let n = sdfc_compiler::syntax::MAX_NESTING - 2;
    let calls = |depth: usize| {
        let mut text = String::from("fn f0(r) = sphere(r)\n");
        for k in 1..depth {
            text += &format!("fn f{k}(r) = f{}(r) at (0.001, 0, 0)\n", k - 1);
        }
        text + &format!("f{}(1)\n", depth - 1)
    };
    let scenes = [
        (
            "parens",
            format!("sphere({}1{})", "(".repeat(n), ")".repeat(n)),
        ),
        (
            "sqrt",
            format!("sphere({}1{})", "sqrt(".repeat(n), ")".repeat(n)),
        ),
        (
            "unions",
            format!("{}sphere(1){}", "union { ".repeat(n), " }".repeat(n)),
        ),
        (
            "negations",
            format!("sphere(1 + {}1{})", "-(".repeat(n / 2), ")".repeat(n / 2)),
        ),
        (
            "too_deep",
            format!("sphere({}1{})", "(".repeat(n + 3), ")".repeat(n + 3)),
        ),
        // A call and its body take two of the checker's levels.
        ("calls", calls(sdfc_compiler::check::MAX_DEPTH / 2 - 1)),
        ("calls_too_deep", calls(sdfc_compiler::check::MAX_DEPTH / 2)),
    ];
    scenes
        .iter()
        .map(|(name, text)| {
            let path = dir.join(format!("deepest_{name}.sdf"));
            std::fs::write(&path, text).unwrap();
            path
        })
        .collect()
}
