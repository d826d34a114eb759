//! `sdfc bench`: the speed/accuracy table of the tracers on a scene, as text, JSON, CSV and a
//! plot.

use super::common::progress_bar;
use crate::cli::driver::driver_module;
use crate::cli::input::{exit_code, load_scene};
use crate::cli::tracer::{bounding_volumes, check_passes};
use crate::cli::values::parse_size;
use crate::cli::{BenchArgs, Error};
use sdfc::bench::{self, Cell, Truth};
use sdfc::gpu::Gpu;
use sdfc_compiler::check::tracer::with_overrides;
use sdfc_compiler::lower::tracer::{BoundingVolumes, Form};
use sdfc_compiler::reference::truth;
use sdfc_compiler::scene::{Scene, Trace};
use sdfc_compiler::view::View;
use serde::Serialize;

mod report;
mod sweep;

/// Everything a run measured.
#[derive(Serialize)]
struct Report {
    scene: String,
    width: u32,
    height: u32,
    adapter: String,
    /// The driver's own version string (Mesa's, on lavapipe).
    driver: String,
    backend: String,
    timing: String,
    repeat: u32,
    truth: Truth,
    /// The scene whose f64 field is the truth, when another than the benchmarked one
    /// (`--truth`).
    truth_scene: Option<String>,
    /// The scene's baked parts, one row each.
    volumes: Vec<sweep::Baked>,
    cells: Vec<Cell>,
    /// `--bake-sweep`: the scene at each resolution, then the `--truth` scene ("analytic").
    sweep: Vec<sweep::Swept>,
    /// How `map` held the scene: `inline` or `data` (`--form`).
    form: &'static str,
    /// The data form: seconds the CPU took to build the scene's buffers (tree, pruning per
    /// cell, programs) — the pre-pass a parameter change reruns; their size in bytes.
    prepass: Option<Prepass>,
    target_error: Option<f64>,
    max_mismatch: f64,
    fastest: Option<Cell>,
}

/// The data form's pre-pass, as measured.
#[derive(Serialize)]
struct Prepass {
    /// Where it ran: "gpu" (the pre-pass entry on the device) or "cpu".
    ran_on: &'static str,
    /// Seconds from the scene to the buffers set.
    seconds: f64,
    /// Seconds the device's pre-pass pipeline took to compile (once per scene; 0 on the CPU).
    compile_seconds: f64,
    /// Times the device ran it again with more room for programs or scratch.
    retries: u32,
    bytes: usize,
    cells: usize,
    mean_leaves: f64,
}

/// The data form's buffers made (on `cells` a side, by default the parts'; on the device
/// where `options` say and it can, else on the CPU), timed, and set on `gpu`.
fn prepass(
    gpu: &Gpu,
    scene: &Scene,
    options: &sdfc_compiler::lower::tracer::Options,
) -> Result<Prepass, Error> {
    let clock = std::time::Instant::now();
    let pruner = crate::cli::pruner(gpu, scene, options)?;
    let compile_seconds = clock.elapsed().as_secs_f64();
    let made = crate::cli::set_tape(gpu, (scene, scene), options.cells, pruner.as_ref())?;
    Ok(Prepass {
        ran_on: if made.on_gpu { "gpu" } else { "cpu" },
        seconds: made.seconds,
        compile_seconds,
        retries: made.retries,
        bytes: made.bytes,
        cells: made.cells,
        mean_leaves: made.mean_leaves,
    })
}

/// How frames were timed on `gpu`.
fn timing(gpu: &Gpu) -> String {
    let how = if gpu.timestamps() {
        "GPU timestamp queries around each frame's passes"
    } else {
        "wall time from the frame's submission to its completion (the adapter has no timestamp queries)"
    };
    format!(
        "{how}; modules compiled and pipelines built before timing, one dispatch per pass, one submission per frame, one untimed frame first; median of the repetitions"
    )
}

/// Runs `sdfc bench`; returns the exit code.
pub fn run(args: &BenchArgs) -> i32 {
    exit_code(bench(args))
}

/// A cell to measure: tracer name, its settings, passes.
type Planned<'a> = (&'a str, Trace, u32);

fn bench(args: &BenchArgs) -> Result<(), Error> {
    let (w, h) = parse_size(&args.size)?;
    check_flags(args)?;
    let reference = match args.reference.as_deref() {
        Some(p) => Some((read_reference(p)?, p.display().to_string())),
        None => None,
    };
    check_passes(args.passes)?;
    let Some((sources, scene)) = load_scene(&args.file, args.bake.bake_res) else {
        return Err(Error::Reported);
    };
    let name = sources.main_name().to_string();
    let truth_scene = match args.truth.as_deref() {
        None => None,
        Some(path) => {
            let Some((_, other)) = load_scene(path, None) else {
                return Err(Error::Reported);
            };
            if other.camera != scene.camera {
                return Err(format!(
                    "error: `--truth {}` has another camera than `{name}`: its picture is not this one's truth",
                    path.display()
                )
                .into());
            }
            Some(other)
        }
    };
    let sweep = match args.bake_sweep.as_deref() {
        Some(list) => sweep::resolutions(list)?,
        None => Vec::new(),
    };
    let mut options = sdfc_compiler::lower::tracer::Options::from_scene(&scene);
    options.bounding_volumes = bvh(args);
    options.fixed_offset = args.fixed_offset;
    options.form = args.form.choose(args.passes, &scene)?;
    options.cells = crate::cli::tracer::check_cells(args.cells, options.form)?;
    options.prepass = crate::cli::tracer::check_prepass(args.prepass, options.form)?;
    let data = options.form == Form::Data;
    driver_module(&scene, &sources, &mut options, args.allow_slow_compile)?;
    let cells = plan(args, &scene)?;
    let gpu = Gpu::new(args.backend.into())?;
    let view = View::new(&scene.camera, w, h);
    let reference = reference.as_ref().map(|(t, p)| (t.as_str(), p.as_str()));
    let truth_of = truth_scene.as_ref().unwrap_or(&scene);
    let (truth, depth) = match args.no_truth {
        false => ground_truth(truth_of, &view),
        true => no_truth(&view),
    };
    let bvh_now = options.bounding_volumes;
    let mut measured = Vec::new();
    let mut swept = Vec::new();
    let prepass = match data {
        true => Some(prepass(&gpu, &scene, &options)?),
        false => None,
    };
    if sweep.is_empty() {
        // A scene with parameters is measured at their defaults, as its ground truth is.
        gpu.set_scene(&scene);
        measured = measure(
            (args, bvh_now),
            &gpu,
            (&scene, &view, &depth),
            &cells,
            reference,
        )?;
    } else {
        let forms = (&sweep[..], truth_of);
        swept = sweep::measure_all((args, bvh_now), &gpu, forms, (&view, &depth), reference)?;
    }
    let fastest = args.target_error.and_then(|e| {
        measured
            .iter()
            .filter(|c| c.mse <= e && c.mismatch <= args.max_mismatch)
            .min_by(|a, b| a.seconds.total_cmp(&b.seconds))
            .cloned()
    });
    let report = Report {
        scene: name,
        width: w,
        height: h,
        adapter: gpu.info.name.clone(),
        driver: gpu.info.driver_info.clone(),
        backend: gpu.backend(),
        timing: timing(&gpu),
        repeat: args.repeat,
        truth,
        truth_scene: args.truth.as_ref().map(|p| p.display().to_string()),
        volumes: scene.volumes().iter().map(sweep::Baked::of).collect(),
        cells: measured,
        sweep: swept,
        form: if data { "data" } else { "inline" },
        prepass,
        target_error: args.target_error,
        max_mismatch: args.max_mismatch,
        fastest,
    };
    report::print(args, &report)
}

/// The most bytes `--reference` reads: a bench's JSON is a few kilobytes (`/dev/zero` was read
/// for 3.6 GB before failing).
const MAX_REFERENCE_BYTES: u64 = 16 << 20;

/// The most rounds `--repeat` runs (each times every cell once; a billion ran until killed).
const MAX_REPEAT: u32 = 1000;

/// The `--reference` file's text, read at most [`MAX_REFERENCE_BYTES`].
fn read_reference(p: &std::path::Path) -> Result<String, Error> {
    use std::io::Read;
    let bad = |why: String| format!("error: cannot read the reference `{}`: {why}", p.display());
    let file = std::fs::File::open(p).map_err(|e| bad(e.to_string()))?;
    let mut bytes = Vec::new();
    file.take(MAX_REFERENCE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| bad(e.to_string()))?;
    if bytes.len() as u64 > MAX_REFERENCE_BYTES {
        return Err(bad(format!(
            "it is larger than {} MiB, and a `sdfc bench --json` output is a few kilobytes",
            MAX_REFERENCE_BYTES >> 20
        ))
        .into());
    }
    String::from_utf8(bytes).map_err(|_| bad("it is not UTF-8 text".into()).into())
}

/// Refuses flags out of their ranges.
fn check_flags(args: &BenchArgs) -> Result<(), Error> {
    if args.repeat == 0 || args.repeat > MAX_REPEAT {
        return Err(format!(
            "error: `--repeat {}`: give 1 to {MAX_REPEAT} rounds (each times every cell once)",
            args.repeat
        )
        .into());
    }
    if let Some(e) = args.target_error
        && !(e > 0.0 && e.is_finite())
    {
        return Err(format!("error: `--target-error {e}` must be a number > 0").into());
    }
    if !(0.0..=1.0).contains(&args.max_mismatch) {
        return Err("error: `--max-mismatch` must be a share in [0, 1]".into());
    }
    if let Some(p) = args.plot.as_deref()
        && p.extension().is_none_or(|e| e != "svg" && e != "png")
    {
        return Err(format!(
            "error: `--plot {}`: plots are written as SVG or PNG; give a `.svg` or `.png` file",
            p.display()
        )
        .into());
    }
    Ok(())
}

/// The trees `--bvh` or `--no-bvh` ask for.
fn bvh(args: &BenchArgs) -> BoundingVolumes {
    bounding_volumes(args.bvh, args.no_bvh)
}

/// Every tracer × budget (× passes), each checked before the long part.
fn plan<'a>(args: &'a BenchArgs, scene: &Scene) -> Result<Vec<Planned<'a>>, Error> {
    let tracers: Vec<&str> = split(&args.tracers);
    let budgets: Vec<&str> = split(&args.steps);
    if tracers.is_empty() || budgets.is_empty() {
        return Err("error: give at least one tracer and one step budget".into());
    }
    let mut cells = Vec::new();
    for t in &tracers {
        for s in &budgets {
            let mut values = vec![("steps", *s)];
            if let Some(e) = args.epsilon.as_deref() {
                values.push(("epsilon", e));
            }
            let trace = with_overrides(scene.trace, Some(t), &values)
                .map_err(|e| Error::Usage(format!("error: {e}")))?;
            cells.push((*t, trace, 1));
            if args.passes > 1 {
                cells.push((*t, trace, args.passes));
            }
        }
    }
    Ok(cells)
}

/// The ground truth of `scene` seen through `view`, on the CPU: its summary and its depths.
fn ground_truth(scene: &Scene, view: &View) -> (Truth, Vec<Option<f64>>) {
    let bar = progress_bar("ground truth (CPU)");
    let clock = std::time::Instant::now();
    let depth = truth::depth_map(scene, view);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let truth = Truth {
        steps: truth::STEPS,
        epsilon: truth::EPSILON,
        bisections: truth::BISECTIONS,
        pixels: depth.len(),
        escaped: depth.iter().filter(|d| d.is_none()).count(),
        seconds: clock.elapsed().as_secs_f64(),
    };
    (truth, depth)
}

/// `--no-truth`: no steps, every pixel without a depth.
fn no_truth(view: &View) -> (Truth, Vec<Option<f64>>) {
    let pixels = (view.width * view.height) as usize;
    let truth = Truth {
        steps: 0,
        epsilon: 0.0,
        bisections: 0,
        pixels,
        escaped: pixels,
        seconds: 0.0,
    };
    (truth, vec![None; pixels])
}

/// Every cell on the GPU against the truth's `depth`, with a progress bar.
fn measure(
    (args, bvh): (&BenchArgs, sdfc_compiler::lower::tracer::BoundingVolumes),
    gpu: &Gpu,
    (scene, view, depth): (&Scene, &View, &[Option<f64>]),
    cells: &[Planned],
    reference: Option<(&str, &str)>,
) -> Result<Vec<Cell>, Error> {
    let bar = progress_bar("measuring");
    if let Some(b) = &bar {
        b.set_length(cells.len() as u64);
    }
    let mut measured = Vec::new();
    for (i, (t, trace, passes)) in cells.iter().enumerate() {
        if let Some(b) = &bar {
            b.set_position(i as u64 + 1);
            b.set_message(format!("{t}, {} steps", trace.steps));
        }
        let job = bench::Job {
            scene,
            trace: (t, *trace),
            passes: *passes,
            view,
            truth: depth,
            repeat: args.repeat,
            reference,
            bvh,
            fixed_offset: args.fixed_offset,
            form: args.form.choose(args.passes, scene)?,
            count_primitives: args.count_primitives,
            no_truth: args.no_truth,
        };
        measured.push(bench::measure(gpu, &job)?);
    }
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    Ok(measured)
}

fn split(s: &str) -> Vec<&str> {
    s.split(',')
        .map(str::trim)
        .filter(|x| !x.is_empty())
        .collect()
}
