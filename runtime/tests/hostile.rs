//! Hostile inputs, data-driven: each `runtime/tests/hostile/*.sdf` goes through `check` (its
//! diagnostics snapshotted), and, when it checks, through `emit` and `render`, each under a time
//! cap and a cap on its peak memory. Nothing may panic, die by a signal or answer with exit 2 (an internal
//! compiler error) on user input, and a failed command leaves no output file.

use std::path::{Path, PathBuf};
use std::process::Output;

/// Seconds a command may take before the test calls it a hang.
const TIME_CAP: u64 = 60;
/// Address space a command may use (KiB), a backstop: Vulkan and LLVM reserve far more than
/// they touch, so the real bound is the resident peak `common::bounded` checks (2 GiB, issue
/// 32's bound for a first frame: the let-sharing render's 7 GB and the 4.2 GB of a 2 434-sphere
/// compile would fail there).
const MEMORY_CAP_KIB: u64 = 6 << 20;

/// Runs `sdfc args` under the caps; the output, or a panic naming a hang or the peak memory
/// past its cap.
fn capped(args: &[&str]) -> Output {
    let wrapper = [
        "prlimit".to_string(),
        format!("--as={}", MEMORY_CAP_KIB * 1024),
    ];
    crate::common::bounded(&wrapper, TIME_CAP, args)
}

/// Exit 0 or 1, no signal, no panic.
fn sane(what: &str, out: &Output) -> i32 {
    let err = String::from_utf8_lossy(&out.stderr);
    let code = out.status.code();
    assert!(
        matches!(code, Some(0 | 1)),
        "{what}: exit {code:?} (a signal or an internal error)\n{err}"
    );
    assert!(!err.contains("panicked"), "{what}: panicked\n{err}");
    code.unwrap()
}

fn inputs() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/hostile");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("hostile folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "sdf"))
        .collect();
    v.sort();
    v
}

fn scratch() -> PathBuf {
    let d = std::env::temp_dir().join(format!("sdfc-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn hostile_inputs_end_in_a_scene_or_a_diagnostic() {
    let dir = scratch();
    let mut accepted = 0;
    for path in inputs() {
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let file = path.to_str().unwrap();
        let out = capped(&["check", file]);
        let code = sane(&format!("check {name}"), &out);
        // The report as the user sees it, with the folder taken out of the paths.
        let report = String::from_utf8_lossy(&out.stderr)
            .replace(path.parent().unwrap().to_str().unwrap(), "hostile");
        insta::assert_snapshot!(format!("hostile@{name}"), format!("exit {code}\n{report}"));
        if code != 0 {
            continue;
        }
        accepted += 1;
        for (what, out_path, extra) in [
            ("emit", dir.join(format!("{name}.wgsl")), vec![]),
            (
                "render",
                dir.join(format!("{name}.png")),
                vec!["--size", "32x18"],
            ),
        ] {
            let _ = std::fs::remove_file(&out_path);
            let mut args = vec![what, file, "-o", out_path.to_str().unwrap()];
            args.extend(extra);
            let out = capped(&args);
            let code = sane(&format!("{what} {name}"), &out);
            assert_eq!(
                code != 0,
                !Path::new(&out_path).exists(),
                "{what} {name}: exit {code} but the output file {} there",
                if out_path.exists() { "is" } else { "is not" }
            );
        }
    }
    assert!(
        accepted >= 3,
        "only {accepted} inputs were accepted: the emit/render half tests little"
    );
}
