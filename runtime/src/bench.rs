//! Measuring the speed/accuracy trade of the tracers (Bálint & Valasek §5): every tracer ×
//! step budget traced on the GPU and compared with the f64 ground truth; the trace alone and
//! the whole frame timed separately, with modules prepared before anything is timed.

use crate::frames::{Layout, Prepared, Ray, Source, Timing};
use crate::gpu::Gpu;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::passes::{self, Pass};
use sdfc_compiler::scene::{Scene, Trace};
use sdfc_compiler::view::View;
use serde::Serialize;

/// One tracer at one step budget (and number of multi-resolution passes).
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// Tracer name.
    pub tracer: String,
    /// Step budget per pixel.
    pub steps: u32,
    /// Multi-resolution passes (Bálint §4); 1 is the single pass `render` uses.
    pub passes: u32,
    /// Median time of a trace-only frame (the module writes t and the step count per pixel,
    /// as a hand-written tracer does), seconds.
    pub seconds: f64,
    /// Every repetition's trace-only time, seconds.
    pub seconds_each: Vec<f64>,
    /// Median time of a full frame (trace, normals, materials, shading, five outputs),
    /// seconds.
    pub frame_seconds: f64,
    /// Every repetition's full-frame time, seconds.
    pub frame_seconds_each: Vec<f64>,
    /// Mean evaluations of the field per pixel by the tracer.
    pub evals_mean: f64,
    /// Most evaluations any pixel's ray made.
    pub evals_max: u32,
    /// Mean evaluations per pixel that a full frame adds after the trace, as counted by the
    /// compute entry (`out_shading`): the normal's and the material's at every hit, shadow
    /// rays, occlusion, reflected and refracted rays, and cone anti-aliasing's shading of
    /// near misses.
    pub shading_evals_mean: f64,
    /// Mean squared difference to the ground truth's depth of the t where each ray stopped
    /// (hit, best candidate, budget out, or escaped: at most `max_distance`), over the pixels
    /// the ground truth hits.
    pub mse: f64,
    /// Share of pixels whose hit/miss differs from the ground truth.
    pub mismatch: f64,
    /// `mse × seconds` (Bálint's error × time).
    pub error_x_time: f64,
    /// A hand-written reference traced alternately with the trace-only module.
    pub reference: Option<Reference>,
}

/// A hand-written reference shader measured next to a cell's trace-only module.
#[derive(Clone, Debug, Serialize)]
pub struct Reference {
    /// Median time of its frame, seconds.
    pub seconds: f64,
    /// Every repetition's time, seconds.
    pub seconds_each: Vec<f64>,
    /// Mean evaluations per pixel it reports.
    pub evals_mean: f64,
    /// Share of pixels whose hit/miss agrees with sdfc's trace.
    pub mask_agreement: f64,
    /// sdfc's trace-only time over the reference's.
    pub ratio: f64,
}

/// The ground truth of a view.
#[derive(Clone, Debug, Serialize)]
pub struct Truth {
    /// Steps of its basic tracing.
    pub steps: u32,
    /// Its hit threshold relative to |eye − target|.
    pub epsilon: f64,
    /// Bisection iterations at the hit.
    pub bisections: u32,
    /// Pixels.
    pub pixels: usize,
    /// Pixels whose ray escapes (or exhausts the 10 000 steps): no depth to compare.
    pub escaped: usize,
    /// Seconds the CPU took.
    pub seconds: f64,
}

/// What one cell measures.
pub struct Job<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// Tracer name and settings.
    pub trace: (&'a str, Trace),
    /// Multi-resolution passes (1: one).
    pub passes: u32,
    /// The view.
    pub view: &'a View,
    /// The ground truth's depth per pixel.
    pub truth: &'a [Option<f64>],
    /// Timed frames of each kind.
    pub repeat: u32,
    /// A hand-written reference (WGSL text, its file name) to time alternately with the
    /// trace.
    pub reference: Option<(&'a str, &'a str)>,
    /// Which unions' bounding-volume trees `map` tests.
    pub bvh: sdfc_compiler::lower::tracer::BoundingVolumes,
    /// Start secondary rays a fixed 2·ε_floor off the surface.
    pub fixed_offset: bool,
}

/// Compiles the scene with `trace` for `entry`, with passes if more than one is asked; and
/// the schedule of passes (`None` for one).
fn compile(
    job: &Job,
    trace: Trace,
    entry: Entry,
) -> Result<(naga::Module, Option<Vec<Pass>>), String> {
    let (passes, view) = (job.passes, job.view);
    let mut s = job.scene.clone();
    s.trace = trace;
    let mut options = Options::from_scene(&s);
    options.passes = passes > 1;
    options.bounding_volumes = job.bvh;
    options.fixed_offset = job.fixed_offset;
    let (module, _) = emit::module(&s, entry, &options)
        .map_err(|e| format!("internal compiler error: {}", e.0))?;
    let plan = match passes {
        0 | 1 => None,
        n => Some(
            passes::plan(&s, view.width, view.height, trace.steps, n as usize)
                .ok_or_else(|| format!("error: there is no schedule of {n} passes"))?,
        ),
    };
    Ok((module, plan))
}

/// The median of some times.
fn median(times: &[f64]) -> f64 {
    let mut sorted = times.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted[sorted.len() / 2]
}

/// GPU time where the adapter has timestamps, wall time otherwise.
fn seconds(t: Timing) -> f64 {
    t.gpu.unwrap_or(t.wall)
}

/// Measures one cell: the trace-only module, the full frame and the reference (if any)
/// prepared first, run once untimed, then `repeat` times each in turn; the median times, and
/// the errors of the trace against `truth`.
pub fn measure(gpu: &Gpu, job: &Job) -> Result<Cell, String> {
    let (name, trace) = job.trace;
    let with_passes = job.passes > 1;
    let (trace_module, plan) = compile(job, trace, Entry::Trace)?;
    let (full_module, _) = compile(job, trace, Entry::Compute)?;
    let whole = u32::MAX;
    let tracing = gpu.prepare(
        Source::Module(&trace_module),
        Layout::TraceOnly {
            passes: with_passes,
        },
        job.view,
        plan.as_deref(),
        whole,
    )?;
    let full = gpu.prepare(
        Source::Module(&full_module),
        Layout::Full {
            passes: with_passes,
        },
        job.view,
        plan.as_deref(),
        whole,
    )?;
    let reference = match job.reference {
        Some((text, path)) => Some(gpu.prepare(
            Source::Wgsl(text, path),
            Layout::TraceOnly { passes: false },
            job.view,
            None,
            whole,
        )?),
        None => None,
    };
    // Untimed first runs: whatever the driver does lazily at a first dispatch is not the
    // tracer's cost.
    let all: Vec<&Prepared> = [Some(&tracing), Some(&full), reference.as_ref()]
        .into_iter()
        .flatten()
        .collect();
    for p in &all {
        p.run()?;
    }
    let mut times = vec![Vec::new(); all.len()];
    for _ in 0..job.repeat.max(1) {
        for (k, p) in all.iter().enumerate() {
            times[k].push(seconds(p.run()?));
        }
    }
    let rays = tracing.rays()?;
    let (mut sum, mut counted, mut mismatch) = (0.0, 0usize, 0usize);
    for (ray, gt) in rays.iter().zip(job.truth) {
        if gt.is_some() != ray.hit {
            mismatch += 1;
        }
        if let Some(t) = gt {
            // Where the ray stopped, hit or not (Bálint & Valasek: the depth each algorithm
            // reached), at most the far limit.
            let reached = (ray.t as f64).min(trace.max_distance);
            sum += (reached - t).powi(2);
            counted += 1;
        }
    }
    let n = job.truth.len().max(1) as f64;
    let evals_mean = mean_steps(&rays);
    // What shading evaluated, counted by the full frame's module itself.
    let shaded = full.frame(0.0)?.shading;
    let shading_evals_mean = shaded.iter().map(|&e| e as f64).sum::<f64>() / n;
    let mse = if counted > 0 {
        sum / counted as f64
    } else {
        0.0
    };
    let seconds = median(&times[0]);
    let reference = match &reference {
        Some(r) => {
            let theirs = r.rays()?;
            let agree = theirs
                .iter()
                .zip(&rays)
                .filter(|(a, b)| a.hit == b.hit)
                .count() as f64;
            let their_seconds = median(&times[2]);
            Some(Reference {
                seconds: their_seconds,
                seconds_each: times[2].clone(),
                evals_mean: mean_steps(&theirs),
                mask_agreement: agree / n,
                ratio: seconds / their_seconds,
            })
        }
        None => None,
    };
    Ok(Cell {
        tracer: name.to_string(),
        steps: trace.steps,
        passes: job.passes.max(1),
        seconds,
        seconds_each: times[0].clone(),
        frame_seconds: median(&times[1]),
        frame_seconds_each: times[1].clone(),
        evals_mean,
        evals_max: rays.iter().map(|r| r.steps).max().unwrap_or(0),
        shading_evals_mean,
        mse,
        mismatch: mismatch as f64 / n,
        error_x_time: mse * seconds,
        reference,
    })
}

fn mean_steps(rays: &[Ray]) -> f64 {
    rays.iter().map(|r| r.steps as f64).sum::<f64>() / rays.len().max(1) as f64
}
