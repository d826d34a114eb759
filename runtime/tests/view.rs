//! `sdfc view` in a real window under Xvfb (lavapipe presenting to X11): its picture is
//! `sdfc render`'s, scripted input moves the camera as documented, a saved file shows at once,
//! a broken one leaves the window and its last good picture with the diagnostics printed, and
//! a deleted file is watched until it comes back. Without a display it is a clear error.
//!
//! Needs `xvfb-run` (Debian's `xvfb`), which `.ci/run` installs; without it the window tests
//! say SKIPPED loudly, and fail instead when `SDFC_REQUIRE_DISPLAY=1` (as `.ci/run` sets).

use crate::common::{root, scratch, succeeded};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

pub(crate) fn xvfb() -> bool {
    let ok = Command::new("xvfb-run").arg("--help").output().is_ok();
    if !ok {
        assert!(
            std::env::var("SDFC_REQUIRE_DISPLAY").is_err(),
            "SDFC_REQUIRE_DISPLAY is set but xvfb-run is missing"
        );
        eprintln!(
            "\n*** xvfb-run is missing: the window tests are SKIPPED (`.ci/run` installs xvfb) ***\n"
        );
    }
    ok
}

/// `sdfc view` under a fresh Xvfb display, its standard error in `log`; while it runs, the X
/// server's window titles are read from outside (`xwininfo`, five times a second) into
/// `log` + `.titles`.
fn view(args: &[&str], log: &Path) -> Child {
    // (xvfb-run runs one command: a shell that starts the viewer, polls the titles, and exits
    // with the viewer's status.)
    let script = format!(
        "\"$@\" & pid=$!; while kill -0 $pid 2>/dev/null; do xwininfo -root -tree 2>/dev/null | grep -o '\"[^\"]*\"' >> '{}'; sleep 0.2; done; wait $pid",
        titles(log).display()
    );
    // Each viewer searches for a free display from its own number: the tests start their Xvfb
    // servers at once, and two `xvfb-run -a` searching from the same number may pick the same.
    static NEXT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let start = 200 + 10 * NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    Command::new("xvfb-run")
        .args([
            "-a",
            "-n",
            &start.to_string(),
            "-s",
            // (-noreset: the title poller connects and leaves; without it the server resets when
            // its last client goes, and a viewer connecting then fails — seen in CI.)
            "-screen 0 1280x1024x24 -noreset",
            "sh",
            "-c",
            &script,
            "sh",
        ])
        .arg(env!("CARGO_BIN_EXE_sdfc"))
        .arg("view")
        .args(args)
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(log).unwrap())
        .spawn()
        .unwrap()
}

/// Where [`view`] keeps the window titles it saw.
fn titles(log: &Path) -> std::path::PathBuf {
    log.with_extension("titles")
}

/// Waits for `file` to appear (whole: a rename) or the child to end.
pub(crate) fn wait_for(file: &Path, child: &mut Child, log: &Path) {
    let what = file.display().to_string();
    wait_until(&what, child, log, Duration::from_secs(90), || file.exists());
}

/// Waits until `ready` holds, the child still running, at most `limit`.
pub(crate) fn wait_until(
    what: &str,
    child: &mut Child,
    log: &Path,
    limit: Duration,
    mut ready: impl FnMut() -> bool,
) {
    let start = Instant::now();
    while !ready() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!(
                "ended ({status}) before {what}:\n{}",
                std::fs::read_to_string(log).unwrap_or_default()
            );
        }
        assert!(
            start.elapsed() < limit,
            "no {what} after {} s:\n{}",
            limit.as_secs(),
            std::fs::read_to_string(log).unwrap_or_default()
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A `sdfc view` under way: its process, scene file, screenshot directory and log.
pub(crate) struct Viewer {
    pub(crate) child: Child,
    pub(crate) scene: PathBuf,
    pub(crate) shots: PathBuf,
    pub(crate) log: PathBuf,
}

/// `sdfc view` of `source` (written to `dir/scene.sdf`) at 128×96, screenshots in
/// `dir/shots`, with `extra` arguments.
pub(crate) fn start_view(dir: &Path, source: &str, extra: &[&str]) -> Viewer {
    let (scene, shots, log) = (
        dir.join("scene.sdf"),
        dir.join("shots"),
        dir.join("view.log"),
    );
    std::fs::write(&scene, source).unwrap();
    let mut args = vec![
        scene.to_str().unwrap(),
        "--size",
        "128x96",
        "--screenshots",
        shots.to_str().unwrap(),
    ];
    args.extend(extra);
    let child = view(&args, &log);
    Viewer {
        child,
        scene,
        shots,
        log,
    }
}

/// `sdfc render` of `scene` at `size` (4 samples, as the viewer at rest).
fn rendered(dir: &Path, scene: &str, name: &str) -> PathBuf {
    rendered_with(dir, scene, name, &[])
}

/// [`rendered`] with more flags for `sdfc render`.
pub(crate) fn rendered_with(dir: &Path, scene: &str, name: &str, extra: &[&str]) -> PathBuf {
    let file = dir.join(format!("{name}.sdf"));
    std::fs::write(&file, scene).unwrap();
    let out = dir.join(format!("{name}.png"));
    let mut args = vec![
        "render",
        file.to_str().unwrap(),
        "--size",
        "128x96",
        "-o",
        out.to_str().unwrap(),
        "-q",
    ];
    args.extend(extra);
    succeeded(&args);
    out
}

/// The share of pixels within 2 levels per channel.
pub(crate) fn agreement(a: &Path, b: &Path) -> f64 {
    let (a, b) = (
        image::open(a).unwrap().to_rgba8(),
        image::open(b).unwrap().to_rgba8(),
    );
    assert_eq!(a.dimensions(), b.dimensions());
    let same = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..3).all(|k| p[k].abs_diff(q[k]) <= 2))
        .count();
    same as f64 / a.pixels().len() as f64
}

pub(crate) const BASE: &str = "camera { eye (0, 1.5, -5)  target (0, 1, 0) }\n\
                    sphere(0.8) at (0, 1, 0)\nbox((0.6, 0.6, 0.6)) at (1.4, 0.3, -0.4)\nplane(y, 0)\n";

/// The first picture is `sdfc render`'s; `drag 180 0` turns the camera 90° about the target's
/// vertical (0.5° a pixel) to world +x here, `zoom 2` brings it to 0.81 of the distance: each
/// picture is `sdfc render` with that camera written in the scene.
#[test]
fn the_window_shows_render_and_scripted_input_moves_the_camera() {
    if !xvfb() {
        return;
    }
    let dir = scratch("view-input");
    let extra = ["--script", "drag 180 0; zoom 2", "--quit-after", "3"];
    let Viewer {
        mut child,
        shots,
        log,
        ..
    } = start_view(&dir, BASE, &extra);
    wait_for(&shots.join("002.png"), &mut child, &log);
    let status = child.wait().unwrap();
    assert!(
        status.success(),
        "{}",
        std::fs::read_to_string(&log).unwrap()
    );
    let body = BASE.lines().skip(1).collect::<Vec<_>>().join("\n");
    let expected = [
        rendered(&dir, BASE, "start"),
        rendered(
            &dir,
            &format!("camera {{ eye (5, 1.5, 0)  target (0, 1, 0) }}\n{body}"),
            "turned",
        ),
        rendered(
            &dir,
            &format!("camera {{ eye (4.05, 1.405, 0)  target (0, 1, 0) }}\n{body}"),
            "zoomed",
        ),
    ];
    for (k, want) in expected.iter().enumerate() {
        let got = shots.join(format!("{k:03}.png"));
        let share = agreement(&got, want);
        println!(
            "screenshot {k}: {:.2}% of pixels within 2 levels of sdfc render",
            share * 100.0
        );
        assert!(share >= 0.995, "screenshot {k}: only {:.2}%", share * 100.0);
    }
}

/// A save shows at once; a broken save keeps the window and its picture and prints the
/// diagnostics; a deleted file is watched until it comes back.
#[test]
fn the_window_follows_the_file() {
    if !xvfb() {
        return;
    }
    let dir = scratch("view-reload");
    let Viewer {
        mut child,
        scene,
        shots,
        log,
    } = start_view(&dir, BASE, &["--quit-after", "4"]);
    let shot = |k: u32| shots.join(format!("{k:03}.png"));
    wait_for(&shot(0), &mut child, &log);
    assert!(agreement(&shot(0), &rendered(&dir, BASE, "first")) >= 0.995);
    let second = BASE.replace("sphere(0.8)", "torus(0.7, 0.25)");
    std::fs::write(&scene, &second).unwrap();
    wait_for(&shot(1), &mut child, &log);
    let share = agreement(&shot(1), &rendered(&dir, &second, "second"));
    assert!(share >= 0.995, "after the save: {:.2}%", share * 100.0);
    std::fs::write(&scene, "sphere(1\n").unwrap();
    wait_for(&shot(2), &mut child, &log);
    assert!(
        std::fs::read(shot(2)).unwrap() == std::fs::read(shot(1)).unwrap(),
        "the picture after a broken save is not the last good one"
    );
    assert!(
        child.try_wait().unwrap().is_none(),
        "the window closed on a broken save"
    );
    std::fs::remove_file(&scene).unwrap();
    // The title says the viewer waits for the file (read from the X server, from outside).
    let name = scene.display().to_string();
    wait_until(
        "a title that waits",
        &mut child,
        &log,
        Duration::from_secs(20),
        || {
            std::fs::read_to_string(titles(&log))
                .is_ok_and(|t| t.contains(&format!("waiting for {name}")))
        },
    );
    let third = BASE.replace("sphere(0.8)", "capsule(1, 0.4)");
    std::fs::write(&scene, &third).unwrap();
    wait_for(&shot(3), &mut child, &log);
    let status = child.wait().unwrap();
    let said = std::fs::read_to_string(&log).unwrap();
    assert!(status.success(), "{said}");
    let share = agreement(&shot(3), &rendered(&dir, &third, "third"));
    assert!(
        share >= 0.995,
        "after the file came back: {:.2}%\n{said}",
        share * 100.0
    );
    for needle in ["error: unclosed", "scene.sdf:1:7", "deleted", "reloaded"] {
        assert!(said.contains(needle), "`{needle}` not said:\n{said}");
    }
    let seen = std::fs::read_to_string(titles(&log)).unwrap();
    let last = seen.lines().rfind(|l| l.contains("evals/px")).unwrap();
    assert!(
        last.contains(" ms, ") && !last.contains("waiting"),
        "the title once the file is back: {last}"
    );
    println!("{said}");
}

/// Without a display: an error that says what to do, exit 1, no panic.
#[test]
fn without_a_display_view_says_so() {
    let scene = root().join("examples/gem.sdf");
    let o = Command::new(env!("CARGO_BIN_EXE_sdfc"))
        .args(["view", scene.to_str().unwrap()])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.starts_with("error: `sdfc view` needs a display") && err.contains("xvfb-run"),
        "{err}"
    );
}

/// `--quit-after` counts finished pictures whether or not they are saved: a still scene with a
/// one-step script makes two and closes by itself at `--quit-after 2`; asked for three, it
/// says it will wait for a save of the file to make the third.
#[test]
fn quit_after_counts_pictures_without_screenshots() {
    if !xvfb() {
        return;
    }
    let dir = scratch("view-quit");
    let (scene, log) = (dir.join("scene.sdf"), dir.join("view.log"));
    std::fs::write(&scene, BASE).unwrap();
    let file = scene.to_str().unwrap();
    let common = [
        file,
        "--size",
        "64x48",
        "--script",
        "zoom 2",
        "--quit-after",
    ];
    let mut child = view(&[&common[..], &["2"]].concat(), &log);
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        assert!(
            start.elapsed() < Duration::from_secs(90),
            "`--quit-after 2` did not close the window:\n{}",
            std::fs::read_to_string(&log).unwrap_or_default()
        );
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(
        status.success(),
        "{}",
        std::fs::read_to_string(&log).unwrap()
    );
    let mut child = view(&[&common[..], &["3"]].concat(), &log);
    let note = "note: `--quit-after 3`: this still scene makes 2 pictures";
    wait_until(note, &mut child, &log, Duration::from_secs(90), || {
        std::fs::read_to_string(&log).is_ok_and(|s| s.contains(note))
    });
    child.kill().unwrap();
    let _ = child.wait();
}

/// A scene with a baked part: the window's first picture is `sdfc render`'s (the map uploaded
/// to the viewer's device as to the renderer's).
#[test]
fn the_window_shows_a_baked_part() {
    if !xvfb() {
        return;
    }
    let dir = scratch("view-baked");
    let scene = "camera { eye (0, 1.5, -5)  target (0, 1, 0) }\n\
                 bake(res = 32) { union { sphere(0.8)  box((0.5, 0.5, 0.5)) at (0.7, -0.4, 0) } } at (0, 1, 0)\n\
                 plane(y, 0)\n";
    let Viewer {
        mut child,
        shots,
        log,
        ..
    } = start_view(&dir, scene, &["--quit-after", "1"]);
    wait_for(&shots.join("000.png"), &mut child, &log);
    let status = child.wait().unwrap();
    assert!(
        status.success(),
        "{}",
        std::fs::read_to_string(&log).unwrap()
    );
    let share = agreement(&shots.join("000.png"), &rendered(&dir, scene, "baked"));
    println!(
        "baked: {:.2}% of pixels within 2 levels of sdfc render",
        share * 100.0
    );
    assert!(share >= 0.995, "only {:.2}%", share * 100.0);
}
