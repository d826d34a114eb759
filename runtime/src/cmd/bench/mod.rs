//! `sdfc bench`: the speed/accuracy table of the tracers on a scene, as text, JSON, CSV and a
//! plot.

use super::common::progress_bar;
use crate::cli::driver::driver_module;
use crate::cli::input::{exit_code, load_scene, print_out};
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
    seconds: f64,
    bytes: usize,
    cells: usize,
    mean_leaves: f64,
}

/// The data form's buffers made on the CPU, timed, and set on `gpu`.
fn prepass(gpu: &Gpu, scene: &Scene) -> Result<Prepass, Error> {
    let clock = std::time::Instant::now();
    let tape = crate::cli::tape_data(scene, scene)?;
    let seconds = clock.elapsed().as_secs_f64();
    gpu.set_tape(Some(&tape));
    Ok(Prepass {
        seconds,
        bytes: tape.bytes(),
        cells: tape.cells(),
        mean_leaves: tape.mean_leaves,
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
        true => Some(prepass(&gpu, &scene)?),
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
    print(args, &report)
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

/// Draws the plot (if asked for) and prints the report as asked: JSON, CSV or the table.
fn print(args: &BenchArgs, report: &Report) -> Result<(), Error> {
    if let Some(p) = args.plot.as_deref() {
        let title = format!(
            "{}: {}×{} on {}",
            report.scene, report.width, report.height, report.adapter
        );
        sdfc::bench::plot::write(p, &title, &report.cells)?;
    }
    let text = if args.json {
        let text = serde_json::to_string_pretty(report)
            .map_err(|e| Error::Usage(format!("error: {e}")))?;
        format!("{text}\n")
    } else if args.csv {
        csv(&report.cells)
    } else {
        table(report)
    };
    // A closed pipe ends quietly; a full device was reported already.
    match print_out(&text) {
        Ok(()) | Err(0) => Ok(()),
        Err(_) => Err(Error::Reported),
    }
}

fn split(s: &str) -> Vec<&str> {
    s.split(',')
        .map(str::trim)
        .filter(|x| !x.is_empty())
        .collect()
}

fn csv(cells: &[Cell]) -> String {
    let mut out = String::from(
        "tracer,steps,passes,seconds,frame_seconds,evals_mean,evals_max,shading_evals_mean,mse,mismatch,error_x_time,reference_seconds,reference_evals_mean\n",
    );
    for c in cells {
        let (rs, re) = match &c.reference {
            Some(r) => (r.seconds.to_string(), r.evals_mean.to_string()),
            None => (String::new(), String::new()),
        };
        out += &format!(
            "{},{},{},{},{},{},{},{},{},{},{},{rs},{re}\n",
            c.tracer,
            c.steps,
            c.passes,
            c.seconds,
            c.frame_seconds,
            c.evals_mean,
            c.evals_max,
            c.shading_evals_mean,
            c.mse,
            c.mismatch,
            c.error_x_time
        );
    }
    out
}

/// The table's lines about the scene's parts: each baked part, the data form's pre-pass.
fn parts(r: &Report) -> String {
    let mut out = String::new();
    for (i, v) in r.volumes.iter().enumerate() {
        let [x, y, z] = v.points;
        let took = v
            .bake_seconds
            .map_or("read from the cache".to_string(), |s| {
                format!("baked in {s:.2} s")
            });
        out += &format!(
            "baked part {i}: {x}×{y}×{z} points, spacing {:.4}, {:.1} MiB, λ {:.3}, {took}\n",
            v.spacing,
            v.bytes as f64 / f64::from(1u32 << 20),
            v.lambda
        );
    }
    if let Some(p) = &r.prepass {
        out += &format!(
            "form: data — pre-pass on the CPU {:.1} ms, {} cells, {:.1} leaves a cell, {:.1} MiB of buffers\n",
            p.seconds * 1e3,
            p.cells,
            p.mean_leaves,
            p.bytes as f64 / f64::from(1u32 << 20)
        );
    }
    if r.truth_scene.is_some() || !r.volumes.is_empty() || r.prepass.is_some() {
        out += "\n";
    }
    out
}

fn table(r: &Report) -> String {
    let truth = match r.truth.steps {
        0 => "ground truth: none (`--no-truth`), so no errors".to_string(),
        _ => format!(
            "ground truth: basic, {} steps, ε {}·|eye − target|, {} bisections; {} of {} pixels escape (CPU {:.1} s)",
            r.truth.steps,
            r.truth.epsilon,
            r.truth.bisections,
            r.truth.escaped,
            r.truth.pixels,
            r.truth.seconds
        ),
    };
    let mut out = format!(
        "{}: {}×{} on {} ({})\n{truth}\ntime: {}\n\n",
        r.scene, r.width, r.height, r.adapter, r.backend, r.timing
    );
    if let Some(t) = &r.truth_scene {
        out += &format!("truth: the f64 field of {t}\n");
    }
    if !r.sweep.is_empty() {
        return out + &sweep::table(&r.sweep);
    }
    out += &parts(r);
    out += &format!(
        "{:<9} {:>6} {:>6} {:>9} {:>9} {:>10} {:>9} {:>9} {:>11} {:>9} {:>11}\n",
        "tracer",
        "steps",
        "passes",
        "trace ms",
        "frame ms",
        "evals/px",
        "max",
        "+shading",
        "depth MSE",
        "hit/miss",
        "err×time"
    );
    for c in &r.cells {
        out += &format!(
            "{:<9} {:>6} {:>6} {:>9.3} {:>9.3} {:>10.2} {:>9} {:>9.2} {:>11.3e} {:>8.2}% {:>11.3e}\n",
            c.tracer,
            c.steps,
            c.passes,
            c.seconds * 1e3,
            c.frame_seconds * 1e3,
            c.evals_mean,
            c.evals_max,
            c.shading_evals_mean,
            c.mse,
            c.mismatch * 100.0,
            c.error_x_time
        );
        if let Some([traced, shaded]) = c.primitives {
            out += &format!(
                "{:<9} {:>6} {:>6}   primitive evaluations per pixel: {traced:.1} by the trace, +{shaded:.1} by shading\n",
                "", "", ""
            );
        }
        if let Some(x) = &c.reference {
            out += &format!(
                "{:<9} {:>6} {:>6} {:>9.3} {:>9} {:>10.2}   hit/miss agree with sdfc's on {:.2}%; sdfc / reference = {:.3}×\n",
                "  ref",
                "",
                "",
                x.seconds * 1e3,
                "",
                x.evals_mean,
                x.mask_agreement * 100.0,
                x.ratio
            );
        }
    }
    if let Some(e) = r.target_error {
        out += &match &r.fastest {
            Some(c) => format!(
                "\nfastest with depth MSE ≤ {e:e} and hit/miss differing on ≤ {:.1}% of pixels: {} with {} steps, {:.3} ms ({:.2} evaluations per pixel)\n",
                r.max_mismatch * 100.0,
                c.tracer,
                c.steps,
                c.seconds * 1e3,
                c.evals_mean
            ),
            None => format!(
                "\nno tracer and budget measured reaches depth MSE ≤ {e:e} with hit/miss differing on ≤ {:.1}% of pixels; try larger budgets\n",
                r.max_mismatch * 100.0
            ),
        };
    }
    out
}
