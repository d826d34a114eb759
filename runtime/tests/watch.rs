//! `sdfc render … --watch` and `sdfc emit … --watch`: every save of the scene, or of a file it
//! imports, writes the output again with one line; a broken save prints its diagnostics and
//! leaves the output and the watch as they were. (No window: the viewer's own following of
//! its file is in `view.rs`.)

use crate::common::scratch;
use crate::view::{BASE, wait_until};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// Starts `sdfc WHAT SCENE -o OUT --watch ARGS` with its standard error in `log`, and waits
/// for its first output ("watching").
fn start_watch(what: &str, scene: &Path, out: &Path, args: &[&str], log: &Path) -> Child {
    let mut child = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args([
            what,
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--watch",
        ])
        .args(args)
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(log).unwrap())
        .spawn()
        .unwrap();
    wait_until(
        "the first output",
        &mut child,
        log,
        Duration::from_secs(60),
        || {
            std::fs::read_to_string(log)
                .unwrap_or_default()
                .contains("watching")
        },
    );
    child
}

/// `render --watch` and `emit --watch` write again on every save, one line each; a broken save
/// prints its diagnostics and leaves the output and the watch as they were.
#[test]
fn watch_rebuilds_on_every_save() {
    let dir = scratch("watch");
    let scene = dir.join("scene.sdf");
    std::fs::write(&scene, BASE).unwrap();
    for (what, out, args) in [
        (
            "render",
            dir.join("out.png"),
            vec!["--size", "64x48", "--samples", "1"],
        ),
        ("emit", dir.join("out.wgsl"), vec![]),
    ] {
        std::fs::write(&scene, BASE).unwrap();
        let log = dir.join(format!("{what}.log"));
        let mut child = start_watch(what, &scene, &out, &args, &log);
        let said = || std::fs::read_to_string(&log).unwrap_or_default();
        let first = std::fs::read(&out).unwrap();
        std::fs::write(&scene, BASE.replace("sphere(0.8)", "torus(0.7, 0.25)")).unwrap();
        wait_until(
            "a rebuild",
            &mut child,
            &log,
            Duration::from_secs(60),
            || std::fs::read(&out).is_ok_and(|b| b != first),
        );
        let second = std::fs::read(&out).unwrap();
        if what == "emit" {
            assert!(String::from_utf8_lossy(&second).contains("fn sd_torus("));
        }
        std::fs::write(&scene, "sphere(1\n").unwrap();
        wait_until(
            "the diagnostics",
            &mut child,
            &log,
            Duration::from_secs(60),
            || said().contains("error: unclosed"),
        );
        std::thread::sleep(Duration::from_millis(300));
        assert!(
            child.try_wait().unwrap().is_none(),
            "{what} --watch ended on a broken save"
        );
        assert!(
            std::fs::read(&out).unwrap() == second,
            "a broken save changed the output"
        );
        assert_eq!(said().matches("wrote ").count(), 2, "{}", said());
        child.kill().unwrap();
        let _ = child.wait();
    }
}

/// `--watch` follows the files a scene imports too: a save of a library in another directory
/// rebuilds, and so does a library imported only after a reload.
#[test]
fn watch_follows_imported_files() {
    let dir = scratch("watch-imports");
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    let scene = dir.join("scene.sdf");
    let lib = dir.join("lib/parts.sdf");
    let later = dir.join("lib/later.sdf");
    std::fs::write(&lib, "fn part() = sphere(0.8)\n").unwrap();
    std::fs::write(&later, "fn other() = box((1, 1, 1))\n").unwrap();
    std::fs::write(&scene, "import \"lib/parts.sdf\"\npart()\n").unwrap();
    let out = dir.join("out.wgsl");
    let log = dir.join("emit.log");
    let mut child = start_watch("emit", &scene, &out, &[], &log);
    let said = || std::fs::read_to_string(&log).unwrap_or_default();
    let wrote = |n: usize| move || said().matches("wrote ").count() >= n;
    // Waits for the n-th output.
    let rebuilt = |child: &mut std::process::Child, what: &str, n: usize| {
        wait_until(what, child, &log, Duration::from_secs(60), wrote(n));
    };
    std::fs::write(&lib, "fn part() = torus(0.7, 0.25)\n").unwrap();
    rebuilt(&mut child, "a rebuild for the library", 2);
    assert!(
        std::fs::read_to_string(&out)
            .unwrap()
            .contains("fn sd_torus(")
    );
    std::fs::write(
        &scene,
        "import \"lib/parts.sdf\"\nimport \"lib/later.sdf\"\nunion { part() other() }\n",
    )
    .unwrap();
    rebuilt(&mut child, "a rebuild for the scene", 3);
    std::fs::write(&later, "fn other() = capsule(1, 0.2)\n").unwrap();
    rebuilt(&mut child, "a rebuild for the new import", 4);
    assert!(
        std::fs::read_to_string(&out)
            .unwrap()
            .contains("fn sd_capsule(")
    );
    let _ = child.kill();
    let _ = child.wait();
}
