//! One cell of the benchmark: the trace-only module, the full frame and a hand-written
//! reference prepared before anything is timed, run in turn, and compared with the truth.

use super::{Cell, Error, Job, Reference};
use crate::gpu::{Gpu, Layout, Prepared, Ray, Source, Timing};
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::passes::{self, Pass};
use sdfc_compiler::scene::Trace;

/// Compiles the scene with `trace` for `entry`, with passes if more than one is asked; and
/// the schedule of passes (`None` for one).
fn compile(
    job: &Job,
    trace: Trace,
    (entry, count_primitives): (Entry, bool),
) -> Result<(naga::Module, Option<Vec<Pass>>), Error> {
    let (passes, view) = (job.passes, job.view);
    let mut s = job.scene.clone();
    s.trace = trace;
    let mut options = Options::from_scene(&s);
    options.passes = passes > 1;
    options.bounding_volumes = job.bvh;
    options.fixed_offset = job.fixed_offset;
    options.form = job.form;
    options.count_primitives = count_primitives;
    let (module, _) = emit::module(&s, entry, &options).map_err(|e| Error::Compile(e.0))?;
    let plan = match passes {
        0 | 1 => None,
        n => Some(
            passes::plan(&s, view.width, view.height, trace.steps, n as usize)
                .ok_or(Error::NoSchedule(n))?,
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
pub fn measure(gpu: &Gpu, job: &Job) -> Result<Cell, Error> {
    let (name, trace) = job.trace;
    let (tracing, full, reference) = prepare(gpu, job, trace)?;
    let all: Vec<&Prepared> = [Some(&tracing), Some(&full), reference.as_ref()]
        .into_iter()
        .flatten()
        .collect();
    let times = time(&all, job.repeat)?;
    let rays = tracing.rays()?;
    let (mut mse, mut mismatch) = errors(&rays, job.truth, trace.max_distance);
    let mut hit_depth_error = hit_depth_error(&rays, job.truth);
    if job.no_truth {
        (mse, mismatch, hit_depth_error) = (f64::NAN, f64::NAN, [f64::NAN; 3]);
    }
    let n = job.truth.len().max(1) as f64;
    // What shading evaluated, counted by the full frame's module itself.
    let shaded = full.frame(0.0)?.shading;
    let shading_evals_mean = shaded.iter().map(|&e| e as f64).sum::<f64>() / n;
    let seconds = median(&times[0]);
    let reference = match &reference {
        Some(r) => Some(compare(r, &rays, &times[2], seconds, n)?),
        None => None,
    };
    let primitives = match job.count_primitives {
        true => Some(count_primitives(gpu, job, trace)?),
        false => None,
    };
    Ok(Cell {
        tracer: name.to_string(),
        steps: trace.steps,
        passes: job.passes.max(1),
        seconds,
        seconds_each: times[0].clone(),
        frame_seconds: median(&times[1]),
        frame_seconds_each: times[1].clone(),
        evals_mean: mean_steps(&rays),
        evals_max: rays.iter().map(|r| r.steps).max().unwrap_or(0),
        shading_evals_mean,
        mse,
        mismatch,
        hit_depth_error,
        error_x_time: mse * seconds,
        reference,
        primitives,
    })
}

/// Mean primitive evaluations per pixel of the trace and of shading after it, from the trace
/// and frame modules compiled once more with counters (run once, untimed).
fn count_primitives(gpu: &Gpu, job: &Job, trace: Trace) -> Result<[f64; 2], Error> {
    let (tracing, full) = prepare_pair(gpu, job, trace, true)?;
    tracing.run()?;
    full.run()?;
    let shaded = full.frame(0.0)?.shading;
    let shaded = shaded.iter().map(|&e| f64::from(e)).sum::<f64>() / shaded.len().max(1) as f64;
    Ok([mean_steps(&tracing.rays()?), shaded])
}

/// The cell's trace-only module and its full frame (`count`: compiled to count primitive
/// evaluations), prepared whole (one dispatch per pass).
fn prepare_pair(
    gpu: &Gpu,
    job: &Job,
    trace: Trace,
    count: bool,
) -> Result<(Prepared, Prepared), Error> {
    let passes = job.passes > 1;
    let (trace_module, plan) = compile(job, trace, (Entry::Trace, count))?;
    let (full_module, _) = compile(job, trace, (Entry::Compute, count))?;
    let whole = u32::MAX;
    let tracing = gpu.prepare(
        Source::Module(&trace_module),
        Layout::TraceOnly { passes },
        job.view,
        plan.as_deref(),
        whole,
    )?;
    let full = gpu.prepare(
        Source::Module(&full_module),
        Layout::Full { passes },
        job.view,
        plan.as_deref(),
        whole,
    )?;
    Ok((tracing, full))
}

/// The cell's trace-only module, its full frame and the reference (if any), prepared whole
/// (one dispatch per pass).
fn prepare(
    gpu: &Gpu,
    job: &Job,
    trace: Trace,
) -> Result<(Prepared, Prepared, Option<Prepared>), Error> {
    let (tracing, full) = prepare_pair(gpu, job, trace, false)?;
    let reference = match job.reference {
        Some((text, path)) => Some(gpu.prepare(
            Source::Wgsl(text, path),
            Layout::TraceOnly { passes: false },
            job.view,
            None,
            u32::MAX,
        )?),
        None => None,
    };
    Ok((tracing, full, reference))
}

/// Each prepared module's times: one untimed run each, then `repeat` rounds of one run each.
fn time(all: &[&Prepared], repeat: u32) -> Result<Vec<Vec<f64>>, Error> {
    // Untimed first runs: whatever the driver does lazily at a first dispatch is not the
    // tracer's cost.
    for p in all {
        p.run()?;
    }
    let mut times = vec![Vec::new(); all.len()];
    for _ in 0..repeat.max(1) {
        for (k, p) in all.iter().enumerate() {
            times[k].push(seconds(p.run()?));
        }
    }
    Ok(times)
}

/// |t − truth| over the pixels both the ray and the truth hit: median, 99th percentile and
/// largest (zeros when none do).
fn hit_depth_error(rays: &[Ray], truth: &[Option<f64>]) -> [f64; 3] {
    let mut e: Vec<f64> = rays
        .iter()
        .zip(truth)
        .filter(|(r, _)| r.hit)
        .filter_map(|(r, gt)| gt.map(|t| (f64::from(r.t) - t).abs()))
        .collect();
    if e.is_empty() {
        return [0.0; 3];
    }
    e.sort_by(f64::total_cmp);
    let at = |q: f64| e[((e.len() - 1) as f64 * q).round() as usize];
    [at(0.5), at(0.99), e[e.len() - 1]]
}

/// The mean squared depth error over the pixels the truth hits, and the share of pixels
/// whose hit/miss differs from it.
fn errors(rays: &[Ray], truth: &[Option<f64>], max_distance: f64) -> (f64, f64) {
    let (mut sum, mut counted, mut mismatch) = (0.0, 0usize, 0usize);
    for (ray, gt) in rays.iter().zip(truth) {
        if gt.is_some() != ray.hit {
            mismatch += 1;
        }
        if let Some(t) = gt {
            // Where the ray stopped, hit or not (Bálint & Valasek: the depth each algorithm
            // reached), at most the far limit.
            let reached = (ray.t as f64).min(max_distance);
            sum += (reached - t).powi(2);
            counted += 1;
        }
    }
    let mse = if counted > 0 {
        sum / counted as f64
    } else {
        0.0
    };
    (mse, mismatch as f64 / truth.len().max(1) as f64)
}

/// The reference's measurement beside sdfc's trace (`ours` seconds, `rays`, `n` pixels).
fn compare(
    reference: &Prepared,
    rays: &[Ray],
    times: &[f64],
    ours: f64,
    n: f64,
) -> Result<Reference, Error> {
    let theirs = reference.rays()?;
    let agree = theirs
        .iter()
        .zip(rays)
        .filter(|(a, b)| a.hit == b.hit)
        .count() as f64;
    let their_seconds = median(times);
    Ok(Reference {
        seconds: their_seconds,
        seconds_each: times.to_vec(),
        evals_mean: mean_steps(&theirs),
        mask_agreement: agree / n,
        ratio: ours / their_seconds,
    })
}

fn mean_steps(rays: &[Ray]) -> f64 {
    rays.iter().map(|r| r.steps as f64).sum::<f64>() / rays.len().max(1) as f64
}
