//! Measuring the speed/accuracy trade of the tracers (Bálint & Valasek §5): every tracer ×
//! step budget rendered on the GPU and compared with the f64 ground truth.

use crate::gpu::Gpu;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::passes::{self, Pass};
use sdfc_compiler::scene::{Scene, Trace};
use sdfc_compiler::view::View;
use serde::Serialize;

/// One tracer at one step budget.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// Tracer name.
    pub tracer: String,
    /// Step budget per pixel.
    pub steps: u32,
    /// Median wall time of the dispatches over the timed renders (after one untimed warm-up
    /// render), seconds.
    pub seconds: f64,
    /// Every repetition's time, seconds.
    pub seconds_each: Vec<f64>,
    /// Mean evaluations of the field per pixel (the tracer's; normals and shading excluded).
    pub evals_mean: f64,
    /// Most evaluations any pixel's ray made.
    pub evals_max: u32,
    /// Mean squared difference to the ground truth's depth of the t where each ray stopped
    /// (hit, best candidate, budget out, or escaped: at most `max_distance`), over the pixels
    /// the ground truth hits.
    pub mse: f64,
    /// Share of pixels whose hit/miss differs from the ground truth.
    pub mismatch: f64,
    /// `mse × seconds` (Bálint's error × time).
    pub error_x_time: f64,
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

/// The scene compiled with `trace` for one pass, with the hand-over buffer of multi-resolution
/// passes so that the t where every ray stopped, hit or not, is read back
/// ([`crate::gpu::Frame::reached`]); and that single pass.
fn compile(scene: &Scene, trace: Trace, view: &View) -> Result<(naga::Module, Vec<Pass>), String> {
    let mut s = scene.clone();
    s.trace = trace;
    let mut options = Options::from_scene(&s);
    options.passes = true;
    let (module, _) = emit::module(&s, Entry::Compute, &options)
        .map_err(|e| format!("internal compiler error: {}", e.0))?;
    let one = passes::plan(&s, view.width, view.height, trace.steps, 1).unwrap_or_default();
    Ok((module, one))
}

/// Measures one cell: `repeat` renders, the median time, and the errors against `truth`.
pub fn measure(
    gpu: &Gpu,
    scene: &Scene,
    (name, trace): (&str, Trace),
    view: &View,
    truth: &[Option<f64>],
    repeat: u32,
) -> Result<Cell, String> {
    // A first, untimed render: the driver compiles the shader at its first dispatch (lavapipe:
    // LLVM, ~0.2 s, then cached), which is not the tracer's cost.
    let (module, one) = compile(scene, trace, view)?;
    let render = || gpu.render(&module, view, Some(&one), |_, _| {});
    let frame = render()?;
    let mut times = Vec::new();
    for _ in 0..repeat.max(1) {
        times.push(render()?.seconds);
    }
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let seconds = sorted[sorted.len() / 2];
    let (mut sum, mut counted, mut mismatch) = (0.0, 0usize, 0usize);
    for (i, gt) in truth.iter().enumerate() {
        let hit = frame.depth[i] >= 0.0;
        if gt.is_some() != hit {
            mismatch += 1;
        }
        if let Some(t) = gt {
            // Where the ray stopped, hit or not (Bálint & Valasek: the depth each algorithm
            // reached), at most the far limit.
            let reached = (frame.reached[i] as f64).min(trace.max_distance);
            sum += (reached - t).powi(2);
            counted += 1;
        }
    }
    let n = truth.len().max(1) as f64;
    let evals_mean = frame.steps.iter().map(|&s| s as f64).sum::<f64>() / n;
    let mse = if counted > 0 {
        sum / counted as f64
    } else {
        0.0
    };
    Ok(Cell {
        tracer: name.to_string(),
        steps: trace.steps,
        seconds,
        seconds_each: times,
        evals_mean,
        evals_max: frame.steps.iter().copied().max().unwrap_or(0),
        mse,
        mismatch: mismatch as f64 / n,
        error_x_time: mse * seconds,
    })
}
