//! Measuring the speed/accuracy trade of the tracers (Bálint & Valasek §5): every tracer ×
//! step budget traced on the GPU and compared with the f64 ground truth (`measure`), and the
//! plots of the results (`plot`).

use sdfc_compiler::scene::{Scene, Trace};
use sdfc_compiler::view::View;
use serde::Serialize;

mod measure;
pub mod plot;

pub use measure::measure;

/// Why a cell could not be measured.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The compiler failed on the scene (a bug in sdfc).
    #[error("internal compiler error: {0}")]
    Compile(String),
    /// No schedule of so many passes.
    #[error("error: there is no schedule of {0} passes")]
    NoSchedule(u32),
    /// The GPU failed.
    #[error(transparent)]
    Gpu(#[from] crate::gpu::Error),
}

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
    /// |t − truth| where both the ray and the truth hit: median, 99th percentile, largest
    /// (scene units): the error of the surface found, without the pixels whose hit differs.
    pub hit_depth_error: [f64; 3],
    /// `mse × seconds` (Bálint's error × time).
    pub error_x_time: f64,
    /// A hand-written reference traced alternately with the trace-only module.
    pub reference: Option<Reference>,
    /// With `--count-primitives`: mean primitive evaluations per pixel by the trace, and by
    /// shading after it (Barbier, Sanchez et al. 2025's measure), counted by modules compiled
    /// once more with counters in every primitive's function (not timed).
    pub primitives: Option<[f64; 2]>,
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
    /// How `map` holds the scene (the data form's buffers are set on the GPU beforehand).
    pub form: sdfc_compiler::lower::tracer::Form,
    /// Also count primitive evaluations per pixel ([`Cell::primitives`]).
    pub count_primitives: bool,
    /// No ground truth (`--no-truth`): the errors are NaN (`null` in JSON).
    pub no_truth: bool,
}
