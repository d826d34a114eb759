//! `sdfc render`: a scene file in, a PNG (or `.npy` depth) out, through the wgpu runtime; or
//! with `--frames`, an animation (`animate`).

mod animate;

use super::common::{progress_bar, write_output};
use crate::cli::driver::{driver_module, seconds};
use crate::cli::input::{exit_code, load_scene_with, param_values};
use crate::cli::values::parse_size;
use crate::cli::{Error, RenderArgs, messages::done};
use crate::view::watch::watching;
use sdfc::gpu::Gpu;
use sdfc::images::{self, Channel};
use sdfc_compiler::passes::{self, Pass};
use sdfc_compiler::scene::Scene;
use sdfc_compiler::view::View;
use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

/// Runs `sdfc render` (again on every save with `--watch`); returns the exit code.
pub fn run(args: &RenderArgs) -> i32 {
    watching(&args.file, args.watch, || match render(args) {
        // An invalid module is a bug in sdfc: exit 2, as `emit` does.
        Err(e @ Error::Compiler(_)) => {
            say!("{e}");
            say!(
                "note: this is a bug in sdfc, not in the scene; please report it with the scene file"
            );
            2
        }
        result => exit_code(result),
    })
}

/// The predicted compile (seconds, `sdfc_compiler::cost::predict`) from which `render` says
/// that the driver is compiling.
const SLOW_COMPILE: f64 = 2.0;

/// What the flags ask for, checked before the scene is read.
struct Request {
    /// With `--frames`: the frames and where they go.
    animation: Option<(std::ops::Range<u32>, animate::Sink)>,
    /// Raw depth to `.npy`.
    wants_npy: bool,
}

/// A scene compiled and its device ready: what the still picture and the animation share.
struct Job {
    gpu: Gpu,
    module: naga::Module,
    scene: Scene,
    /// The parameters at the values asked for (`--param`, `--time`).
    valued: Scene,
    view: View,
    plan: Option<Vec<Pass>>,
    /// Samples per pixel, and where in its pixel each passes.
    samples: u32,
    points: Vec<[f64; 2]>,
    started: Instant,
}

fn render(args: &RenderArgs) -> Result<(), Error> {
    let request = check_request(args)?;
    let started = Instant::now();
    let (w, h) = parse_size(&args.size)?;
    check_samples(args, request.wants_npy)?;
    let job = prepare(args, (w, h), started)?;
    match request.animation {
        Some((range, sink)) => animate::render(args, &job, range, sink),
        None => still(args, &job, request.wants_npy),
    }
}

/// Refuses what the flags cannot do together, before anything is read.
fn check_request(args: &RenderArgs) -> Result<Request, Error> {
    let output = args.output.as_path();
    // `--output` names the file (as for every command); the channel was `--output` before.
    let word = output.to_str().unwrap_or("");
    if ["color", "depth", "normal", "steps", "material"].contains(&word) {
        return Err(format!(
            "error: `--output {word}` names the file to write; the channel is `--channel {word}`\nhelp: sdfc render FILE -o OUT.png --channel {word}"
        )
        .into());
    }
    let animation = match args.frames.as_deref() {
        Some(text) => {
            let range = animate::parse_frames(text)?;
            if args.fps == 0 || args.fps > 240 {
                return Err(format!("error: `--fps {}` must be from 1 to 240", args.fps).into());
            }
            if args.kind != Channel::Color {
                return Err("error: `--frames` renders colour (`--channel color`)".into());
            }
            Some((range, animate::sink(output)?))
        }
        None => {
            check_extension(output)?;
            None
        }
    };
    if output == Path::new("-") && std::io::stdout().is_terminal() {
        return Err(
            "error: a PNG is binary; write it to a file with `-o FILE` (or pipe it)".into(),
        );
    }
    let wants_npy = output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    Ok(Request {
        animation,
        wants_npy,
    })
}

/// `--samples`: a square number up to 64, and one for `.npy`.
fn check_samples(args: &RenderArgs, wants_npy: bool) -> Result<(), Error> {
    if let Some(n) = args.samples {
        let s = (n as f64).sqrt().round() as u32;
        if n == 0 || s * s != n || s > 8 {
            return Err(format!(
                "error: `--samples {n}` must be a square number from 1 to 64 (1, 4, 9, 16, ...)"
            )
            .into());
        }
    }
    if wants_npy && (args.kind != Channel::Depth || args.samples.is_some_and(|n| n > 1)) {
        return Err(
            "error: `.npy` output is for `--channel depth` with one sample per pixel".into(),
        );
    }
    Ok(())
}

/// Reads, checks and compiles the scene, and opens the device with its parameters set.
fn prepare(args: &RenderArgs, (w, h): (u32, u32), started: Instant) -> Result<Job, Error> {
    let mut values = param_values(&args.params, args.time)?;
    values.bake_res = args.bake.bake_res;
    let Some((sources, mut scene)) = load_scene_with(&args.file, &values) else {
        return Err(Error::Reported);
    };
    let mut options = args.tracer.settle(&mut scene)?;
    let (module, predicted) =
        driver_module(&scene, &sources, &mut options, args.allow_slow_compile)?;
    let gpu = Gpu::new(args.backend.into())?;
    // The defaults' module, the values in its uniform only (as a host sets them).
    let valued = scene.with_values(&values.values);
    gpu.set_params(&sdfc_compiler::lower::params::bytes(&valued.params));
    gpu.set_volumes(&scene.volumes());
    if options.form == sdfc_compiler::lower::tracer::Form::Data {
        let pruner = crate::cli::pruner(&gpu, &scene, &options)?;
        crate::cli::set_tape(&gpu, (&scene, &valued), options.cells, pruner.as_ref())?;
    }
    if predicted.seconds >= SLOW_COMPILE {
        // The driver compiles the shader at pipeline creation, silently.
        say!(
            "compiling the shader for {} (predicted {} on lavapipe, up to {})…",
            gpu.info.name,
            seconds(predicted.seconds),
            seconds(predicted.at_most)
        );
    }
    let view = View::new(&scene.camera, w, h);
    let plan = options.passes.then(|| {
        passes::plan(&scene, w, h, scene.trace.steps, args.tracer.passes as usize)
            .unwrap_or_default()
    });
    // Anti-aliasing: one frame per sample point, accumulated at the output's size.
    let samples = args
        .samples
        .unwrap_or_else(|| default_samples(args.kind, &options.trace));
    Ok(Job {
        gpu,
        module,
        scene,
        valued,
        view,
        plan,
        samples,
        points: images::sample_points(samples),
        started,
    })
}

/// Renders the still picture, writes it and says so.
fn still(args: &RenderArgs, job: &Job, wants_npy: bool) -> Result<(), Error> {
    let (w, h) = (job.view.width, job.view.height);
    let mut sum = images::Accumulator::new((w * h) as usize, args.kind == Channel::Color);
    let mut depth = Vec::new();
    let budget = job.scene.trace.steps;
    let (mut exhausted, mut rays) = (0usize, 0usize);
    let bar = progress_bar("rendering tiles");
    job.gpu.render_samples(
        &job.module,
        &job.view,
        job.plan.as_deref(),
        &job.points,
        |done, total| {
            if let Some(b) = &bar {
                b.set_length(total as u64);
                b.set_position(done as u64);
            }
        },
        |frame| {
            // Camera rays that spent the whole budget and hit nothing: measured, not guessed.
            rays += frame.steps.len();
            exhausted += (frame.steps.iter().zip(&frame.depth))
                .filter(|&(&s, &d)| s >= budget && d < 0.0)
                .count();
            if wants_npy {
                depth = frame.depth;
            } else {
                sum.add(&images::rgba(&frame, args.kind, job.scene.trace.steps));
            }
            Ok(())
        },
    )?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let bytes = if wants_npy {
        images::npy(&depth, w, h)
    } else {
        images::png(sum.finish(), w, h)?
    };
    if write_output(Some(&args.output), &bytes, true) != 0 {
        return Err(Error::Reported);
    }
    let place = match args.output.to_str() {
        Some("-") => "standard output".to_string(),
        _ => args.output.display().to_string(),
    };
    let samples = job.samples;
    let per = if samples == 1 { "sample" } else { "samples" };
    done(&format!(
        "wrote {place} — {w}×{h}, {samples} {per} per pixel, {:.1} s, {} ({})",
        job.started.elapsed().as_secs_f64(),
        job.gpu.info.name,
        job.gpu.backend()
    ));
    if job.plan.is_none() {
        warn_exhausted(exhausted, rays, budget);
    }
    Ok(())
}

/// The share of camera rays ending on their step budget above which `render` warns: there the
/// picture is likely missing surfaces (every example stays under it: `runtime/tests/bounded.rs`).
pub const EXHAUSTED_SHARE: f64 = 0.01;

/// Warns when more than [`EXHAUSTED_SHARE`] of the camera rays spent all `budget` steps
/// without reaching a surface or the far distance, with the numbers and what to change.
fn warn_exhausted(exhausted: usize, rays: usize, budget: u32) {
    let share = exhausted as f64 / rays.max(1) as f64;
    if share <= EXHAUSTED_SHARE {
        return;
    }
    say!(
        "warning: {:.1}% of the camera rays ({exhausted} of {rays}) spent all {budget} steps without reaching a surface or `max_distance`: surfaces may be missing there\nhelp: raise the budget (`--steps {}`), loosen ε (`--epsilon`), lower `max_distance`, or check for a `@lipschitz` bound far larger than the field needs (`sdfc check --lipschitz`)",
        share * 100.0,
        budget.saturating_mul(4)
    );
}

/// What `render` writes, by the output file's extension (`-`: a PNG to standard output).
const IMAGE_EXTENSIONS: &[&str] = &["png", "npy"];

/// Refuses an output file whose extension names a format `render` does not write (a PNG in
/// `out.jpg` would be a lie).
fn check_extension(output: &Path) -> Result<(), Error> {
    if output == Path::new("-") {
        return Ok(());
    }
    match output.extension().and_then(|e| e.to_str()) {
        Some(e) if IMAGE_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()) => Ok(()),
        found => Err(format!(
            "error: `{}`: render writes PNG images (`.png`) and raw f32 depth (`.npy`){}",
            output.display(),
            match found {
                Some(e) => format!(", not `.{e}`"),
                None => "; give the file one of these extensions".into(),
            }
        )
        .into()),
    }
}

/// Samples per pixel without `--samples`: 4 for colour, so that edges are smooth by default
/// (about 1.7× the time of one sample for the README's jewel at 1280×720), but 1 when the
/// tracer already does Hart's cone anti-aliasing, and 1 for depth, normals, steps and
/// materials, whose values an average would blur into values no surface has.
fn default_samples(channel: Channel, trace: &sdfc_compiler::scene::Trace) -> u32 {
    if channel == Channel::Color && !trace.antialias {
        4
    } else {
        1
    }
}
