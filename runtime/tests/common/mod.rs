//! What the runtime's test files share: the example scenes, compiling, the GPU devices.

use sdfc::gpu::{BackendChoice, Gpu};
use sdfc_compiler::check::tracer::TRACE_METHODS;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::reference::trace::{self, Traced};
use sdfc_compiler::scene::{Method, Scene, Trace};
use std::path::PathBuf;
use std::process::{Command, Output};
use std::sync::Mutex;

/// The example scene files, sorted.
pub fn examples() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "sdf"))
        .collect();
    v.sort();
    v
}

/// A checked scene, or a panic with the diagnostics.
pub fn compile(source: &str) -> Scene {
    let checked = sdfc_compiler::check::compile(source);
    checked.scene.unwrap_or_else(|| {
        panic!(
            "{}",
            sdfc_compiler::diag::render(&checked.diagnostics, "test", source)
        )
    })
}

/// The Vulkan devices the tests have finished with, for the next ones: the tests share one
/// binary, and a device is opened once per test thread rather than once per test.
static IDLE: Mutex<Vec<Gpu>> = Mutex::new(Vec::new());

/// A Vulkan device (lavapipe in CI) for one test alone while it holds it: one another test has
/// given back, else a new one. Tests running at the same time never share a device (its
/// parameters and error state are per device), so at most one is opened per test thread.
pub fn gpu() -> Lease {
    let idle = IDLE.lock().unwrap_or_else(|e| e.into_inner()).pop();
    Lease(Some(idle.unwrap_or_else(|| own_gpu(BackendChoice::Vulkan))))
}

/// A device of the test's own, never shared: for a test that loses it, or wants another
/// backend.
pub fn own_gpu(choice: BackendChoice) -> Gpu {
    Gpu::new(choice).unwrap_or_else(|e| panic!("{e}\n(CI installs Mesa's drivers in .ci/run)"))
}

/// A device lent to one test ([`gpu`]), given back when dropped as a new one would be (no scene
/// parameters set); not given back if the test panicked, as the device may be in a bad state.
pub struct Lease(Option<Gpu>);

impl std::ops::Deref for Lease {
    type Target = Gpu;
    fn deref(&self) -> &Gpu {
        self.0.as_ref().expect("lent")
    }
}

impl Drop for Lease {
    fn drop(&mut self) {
        if let Some(gpu) = self.0.take()
            && !std::thread::panicking()
        {
            gpu.set_params(&[]);
            IDLE.lock().unwrap_or_else(|e| e.into_inner()).push(gpu);
        }
    }
}

/// Traces rays with the scene's `Entry::Rays` module: (t, steps, flags) per ray.
pub fn gpu_trace(
    gpu: &Gpu,
    scene: &Scene,
    rays: &[([f32; 3], [f32; 3], f32)],
) -> Vec<(f32, u32, u32)> {
    let (module, _) = emit::module(scene, Entry::Rays, &Options::from_scene(scene))
        .unwrap_or_else(|e| panic!("{}", e.0));
    gpu.set_scene(scene);
    gpu.trace_rays(&module, rays).unwrap()
}

/// The scene's tracer settings switched to `method` (its defaults for the rest).
pub fn with_method(scene: &Scene, method: Method) -> Trace {
    let name = TRACE_METHODS.iter().find(|m| m.1 == method).unwrap().0;
    sdfc_compiler::check::tracer::with_overrides(scene.trace, Some(name), &[]).unwrap()
}

/// The camera rays through image points, as the GPU's ray list takes them.
pub fn camera_rays(
    view: &sdfc_compiler::view::View,
    pts: &[(f64, f64)],
) -> Vec<([f32; 3], [f32; 3], f32)> {
    pts.iter()
        .map(|&(x, y)| {
            let d = view.ray(x, y);
            (
                view.eye.to_array().map(|v| v as f32),
                d.to_array().map(|v| v as f32),
                view.pixel as f32,
            )
        })
        .collect()
}

/// The safety check shared by the tracer tests: the ground truth (basic tracing, 10 000 steps,
/// the scene's ε, every ray from the camera whatever bound the scene declares) and a far finer
/// threshold (1e-7·|eye − target|, f64, no floor) that tells a ray really reaching a surface
/// from one only passing within the scene's ε of it.
pub struct Safety {
    truth: Scene,
    fine_epsilon: f64,
}

/// What a tracer did on the rays the ground truth hits.
#[derive(Debug, Default)]
pub struct Tally {
    /// Missed a surface the ray really reaches.
    pub missed: u32,
    /// Missed a surface the ray only passes within ε of.
    pub grazed: u32,
    /// Ran out of budget (counted, not judged).
    pub exhausted: u32,
    /// Hybrid only: stepped through a stretch inside the scene shorter than its linear step,
    /// as its fixed steps do by construction (Liktor §5.4; docs/stability.md).
    pub slivers: u32,
}

impl Safety {
    /// The references for a scene.
    pub fn new(base: &Scene) -> Safety {
        let mut truth = base.clone();
        truth.bound = None;
        truth.trace.method = Method::Basic;
        truth.trace.steps = 10_000;
        truth.trace.discontinuity = 0;
        Safety {
            fine_epsilon: 1e-7 * (base.camera.eye - base.camera.target).length(),
            truth,
        }
    }

    /// The ground truth of the ray `rd` from the camera of `view`.
    pub fn truth(&self, view: &sdfc_compiler::view::View, rd: glam::DVec3) -> Traced {
        trace::ray(&self.truth, &self.truth.trace, view.eye, rd, view.pixel)
    }

    /// Counts the result `r` of tracer settings `trace` on the ray `rd` whose ground truth is
    /// `truth`; `footprint` is the largest pixel footprint (per unit of t) the tracer used (a
    /// coarse pass's).
    pub fn judge(
        &self,
        tally: &mut Tally,
        (view, rd, trace, footprint): (&sdfc_compiler::view::View, glam::DVec3, &Trace, f64),
        r: &Traced,
        truth: &Traced,
    ) {
        if r.exhausted {
            tally.exhausted += 1;
        } else if truth.hit && !r.hit {
            let t = &self.truth;
            let f = trace::ray_exact(t, &t.trace, self.fine_epsilon, view.eye, rd);
            if trace.method == Method::Hybrid && f.hit {
                let step = trace.linear * trace::Threshold::new(t, trace, footprint).at(f.t);
                if inside_length(t, view.eye, rd, f.t, step) < step {
                    tally.slivers += 1;
                    return;
                }
            }
            if f.hit || f.exhausted {
                tally.missed += 1;
            } else {
                tally.grazed += 1;
            }
        }
    }
}

/// How far the ray `eye + t·rd` runs inside the scene once it enters it after `t` (where a
/// fine trace stopped, just before the surface; within `around` of it), walked in steps of
/// `around`/1024; `f64::INFINITY` if it does not enter there.
fn inside_length(scene: &Scene, eye: glam::DVec3, rd: glam::DVec3, t: f64, around: f64) -> f64 {
    let step = around / 1024.0;
    let inside = |s: f64| sdfc_compiler::reference::eval::distance(scene, eye + rd * s) <= 0.0;
    let Some(entry) = (0..1024).map(|k| t + step * k as f64).find(|&s| inside(s)) else {
        return f64::INFINITY;
    };
    let mut s = entry;
    while inside(s + step) && s - entry < 2.0 * around {
        s += step;
    }
    s + step - entry
}

/// Seconds any `sdfc` command of the tests may run before it is called a hang (`timeout` ends
/// it).
pub const TIME_CAP: u64 = 300;

/// Most memory any `sdfc` command of the tests may hold at once (KiB, GNU time's maximum
/// resident set): 2 GiB, issue 32's bound for a first frame.
pub const PEAK_CAP_KIB: u64 = 2 << 20;

/// Peak files named so far.
static PEAKS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Runs the `sdfc` binary with `args` under [`TIME_CAP`] and [`PEAK_CAP_KIB`]: a command past
/// either fails the test, so every command line the tests run is bounded work.
pub fn sdfc(args: &[&str]) -> Output {
    bounded(&[], TIME_CAP, args)
}

/// Runs `sdfc args` and checks that it succeeded (exit 0; its standard error shown if not).
pub fn succeeded(args: &[&str]) -> Output {
    let run = sdfc(args);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{args:?}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    run
}

/// Runs `sdfc args` and checks that it refused them as a user error (exit 1) saying `says`,
/// without a panic, and left no file at `out`.
pub fn refused(args: &[&str], says: &str, out: &std::path::Path) {
    let run = sdfc(args);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.contains(says), "{args:?} should say {says:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(!out.exists(), "{args:?} left {} behind", out.display());
}

/// Runs `sdfc args` (behind `wrapper`, e.g. `prlimit --as=…`) under `timeout` at `seconds` and
/// GNU time, and fails the test if it ran past them or held more than [`PEAK_CAP_KIB`].
pub fn bounded(wrapper: &[String], seconds: u64, args: &[&str]) -> Output {
    let peak = std::env::temp_dir().join(format!(
        "sdfc-test-peak-{}-{}",
        std::process::id(),
        PEAKS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
    ));
    let out = Command::new("timeout")
        .arg(format!("{seconds}s"))
        .arg("/usr/bin/time")
        .args(["-f", "%M", "-o"])
        .arg(&peak)
        .args(wrapper)
        .arg(env!("CARGO_BIN_EXE_sdfc"))
        .args(args)
        .output()
        .expect("run sdfc under timeout and GNU time (.ci/run installs them)");
    let text = std::fs::read_to_string(&peak).unwrap_or_default();
    let _ = std::fs::remove_file(&peak);
    assert_ne!(
        out.status.code(),
        Some(124),
        "`sdfc {}` ran past {seconds} s",
        args.join(" ")
    );
    // (The last line: GNU time writes a note first when the command died by a signal.)
    let kib: u64 = text
        .lines()
        .last()
        .and_then(|l| l.trim().parse().ok())
        .unwrap_or(0);
    assert!(
        kib <= PEAK_CAP_KIB,
        "`sdfc {}` held {} MiB at its peak",
        args.join(" "),
        kib / 1024
    );
    out
}

/// Scenes the suites aim at the edges, for the real clients: every hostile scene that checks
/// (`tests/hostile/`) and is within the compile limit, and every case of the extremes suite (scales from 1e-4 to 1e4, tiny ε,
/// huge budgets…), by name.
pub fn edge_scenes() -> Vec<(String, Scene)> {
    let dir = root().join("runtime/tests/hostile");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "sdf"))
        .collect();
    files.sort();
    let hostile = files.into_iter().filter_map(|p| {
        let text = String::from_utf8(std::fs::read(&p).ok()?).ok()?;
        let scene = sdfc_compiler::check::compile(&text).scene?;
        Some((
            format!("hostile-{}", p.file_stem()?.to_string_lossy()),
            scene,
        ))
    });
    let extremes = crate::extremes::cases::cases()
        .into_iter()
        .enumerate()
        .filter_map(|(i, c)| {
            let scene = sdfc_compiler::check::compile(&c.source).scene?;
            Some((format!("extremes-{i:02}"), scene))
        });
    // A scene whose shader sdfc itself would not hand a driver as it is (the compile limit's
    // cases: `render` refuses it or drops its box trees) is for those tests, not the clients':
    // SwiftShader took minutes on the 2 434-sphere union.
    let drivable = |(_, scene): &(String, Scene)| {
        let options = Options::from_scene(scene);
        emit::module(scene, Entry::Compute, &options)
            .is_ok_and(|(m, _)| !sdfc_compiler::cost::predict_module(&m).too_slow())
    };
    hostile.chain(extremes).filter(drivable).collect()
}

/// Appends `line` to `target/real-clients.log`, the tally of what each real client (Chrome's
/// WebGPU and WebGL2, the Vulkan driver) accepted and drew, which `.ci/run` prints after the
/// tests (the harness hides a passing test's output).
pub fn report(line: &str) {
    use std::io::Write;
    println!("{line}");
    let path = root().join("target/real-clients.log");
    if let Ok(mut f) = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
    {
        let _ = writeln!(f, "{line}");
    }
}

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// A fresh folder under the system's temporary one, by test name: the tests share one process,
/// so `name` must differ across all the test files.
pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sdfc-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `text` to `dir/name`; its path.
pub fn write(dir: &std::path::Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// The compute entry's 8-bit sRGB for the CPU reference shader's linear colour `c`.
pub fn srgb8(c: glam::DVec3) -> [i32; 3] {
    use sdfc_compiler::color::to_srgb;
    [c.x, c.y, c.z].map(|v| (to_srgb(v.clamp(0.0, 1.0)) * 255.0).round() as i32)
}

/// The largest difference over the three channels between a frame's packed pixel and `want`.
pub fn off_by(px: u32, want: [i32; 3]) -> i32 {
    let got = px.to_le_bytes();
    (0..3)
        .map(|k| (got[k] as i32 - want[k]).abs())
        .max()
        .unwrap()
}

/// How closely RGBA8 pixels from another client (`rgba`, row-major, 4 bytes each) match a
/// frame's packed colours: the share of pixels within `levels` on every channel, and the
/// largest difference.
pub fn within_levels(color: &[u32], rgba: &[u8], levels: i32) -> (f64, i32) {
    let (mut within, mut worst) = (0u32, 0);
    for (px, c) in color.iter().zip(rgba.chunks_exact(4)) {
        let d = off_by(*px, [c[0].into(), c[1].into(), c[2].into()]);
        worst = worst.max(d);
        within += u32::from(d <= levels);
    }
    (f64::from(within) / color.len().max(1) as f64, worst)
}

/// `scene` rendered on `gpu` by the compute entry with the scene's own settings.
pub fn render(gpu: &Gpu, scene: &Scene, view: &sdfc_compiler::view::View) -> sdfc::gpu::Frame {
    let (module, _) = emit::module(scene, Entry::Compute, &Options::from_scene(scene))
        .unwrap_or_else(|e| panic!("{}", e.0));
    gpu.set_scene(scene);
    gpu.render(&module, view, None, |_, _| {}).unwrap()
}

/// The extremes suite's scene: a sphere, a rotated box and a torus on a ground plane.
pub const EXTREMES_BASE: &str = "sphere(1) at (0, 1, 0)\nbox((1.5, 1, 1)) |> rotate(y, 30deg) at (2, 0.5, 1)\ntorus(0.8, 0.2) at (-2, 0.2, 0.5)\nplane(y, 0)";

/// Every shading feature at once — soft and hard shadows, occlusion, fog, a mirror ball and a
/// glass ball — with `shapes` (and the `materials` they use), the whole scaled by `s` with its
/// camera, lights and distances, as the extremes suite scales its scene.
pub fn every_feature_scene(s: f64, materials: &str, shapes: &str) -> String {
    format!(
        "camera {{ eye (0, {}, {})  target (0, {}, 0) }}\n\
         trace basic {{ max_distance {} }}\n\
         light {{ direction (-0.4, 1, -0.5)  shadow soft }}\n\
         light point {{ position ({}, {}, {})  shadow hard }}\n\
         occlusion {{ distance {} }}\n\
         fog {{ density {} }}\n\
         material chrome {{ reflect 0.7 }}\n\
         material glass {{ transparent 0.9  ior 1.5 }}\n\
         {materials}\n\
         scale({s}) {{ union {{\n{shapes}\n\
           sphere(0.6) at (1.5, 0.6, -1.5) : chrome\n\
           sphere(0.6) at (-1.5, 0.6, -1.5) : glass\n\
         }} }}",
        3.0 * s,
        -7.0 * s,
        0.5 * s,
        100.0 * s,
        2.0 * s,
        4.0 * s,
        -3.0 * s,
        0.5 * s,
        0.02 / s,
    )
}
