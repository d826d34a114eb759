//! The options that choose what a module has besides `map` (its interface, the tracer's
//! settings, the bounding-volume trees), and where a multi-resolution pass starts a ray; the
//! module is assembled from them in `assemble.rs`.

use crate::ir::builder::Ex;
use crate::scene::Scene;

/// Which interface the module has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entry {
    /// `main` compute entry point writing colour, depth, normal, material and steps to storage
    /// buffers (what the runtime uses).
    Compute,
    /// `main` full-screen fragment entry point: `@builtin(position)` in, colour out.
    Fragment,
    /// No entry point: `map`, `trace`, `normal` (and `shade`) for other shaders.
    Library,
    /// `main` compute entry point tracing a list of rays (for tests and benchmarks): binding 0
    /// holds two vec4 per ray (origin and pixel footprint; direction and the t to start at),
    /// binding 1 receives `vec4(t, steps, flags, cover)` per ray (cover: the anti-aliasing
    /// coverage, 0 without). Not offered on the command line.
    Rays,
    /// `main` compute entry point evaluating the scene's field at a list of points (for
    /// tests): binding 0 holds one `vec4<f32>` per point (xyz, w unused), binding 1 receives
    /// `vec4(map(p), raw, 0, 0)` per point, `raw` being the root's field before the division by
    /// its λ (`map(p)·λ`); 64 points per workgroup. The module has no tracer, `normal` or
    /// `shade`. Not offered on the command line.
    Field,
    /// `main` compute entry point that only traces (what `sdfc bench` times as "trace only",
    /// as a hand-written tracer would): binding 0 the `View` uniform, binding 1 receives
    /// `vec2<u32>(bitcast<u32>(t), steps | hit << 31)` per pixel, t where the ray stopped.
    /// No normal, material or shading. With `Options::passes`, the hand-over buffers of the
    /// compute entry at bindings 6 and 7.
    Trace,
}

/// Tracer settings after command-line overrides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The tracer settings used.
    pub trace: crate::scene::Trace,
    /// Compile the compute entry for multi-resolution passes (Bálint §4): a `pass` field in
    /// the view and two buffers handing each pixel's t and step count to the next pass.
    pub passes: bool,
    /// Which unions test their bounding-volume tree in `map` (`catalog::prune`): the same
    /// field with groups of far parts skipped.
    pub bounding_volumes: BoundingVolumes,
    /// Start shadow, reflected and refracted rays a fixed 2·ε_floor from the surface instead
    /// of Keinert's ε_dynamic = 2·max(h, |f(p)|) (§3.3): only to measure what ε_dynamic
    /// prevents (`--fixed-offset`).
    pub fixed_offset: bool,
    /// Keep the parameters in a private global the shader itself sets (`params = Params(…)`)
    /// instead of the `Params` uniform: for hosts without uniforms of their own (Shadertoy).
    pub private_params: bool,
    /// The `Params` uniform's binding in group 0 (`emit --params-binding`, so that two
    /// scenes' libraries can share a shader).
    pub params_binding: u32,
    /// How `map` holds the scene: as code, or as data a generic evaluator runs (issue 33).
    pub form: Form,
    /// Count primitive evaluations instead of field evaluations (`sdfc bench
    /// --count-primitives`): the trace-only entry writes the camera ray's where it writes its
    /// steps, the compute entry's shading count (binding 8) is shading's.
    pub count_primitives: bool,
    /// The data form's grid: cells along its longest side (`None`: as many as the parts call
    /// for, `tape::data::cells_for`). Data only: the shader reads the grid from its buffers.
    pub cells: Option<usize>,
    /// Where the data form's cells are pruned: on the device by the pre-pass entry
    /// (`lower::prune`), or on the CPU (`tape::data::data`, the reference). Data only: the
    /// shader is the same.
    pub prepass: Prepass,
}

/// Where the data form's pre-pass runs (`--prepass`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Prepass {
    /// On the device for a tree of at least `tape::data::GPU_PREPASS_FROM` leaves, else on
    /// the CPU (where each measured faster on lavapipe).
    #[default]
    Auto,
    /// On the device, where it can hold the programs (else on the CPU).
    Gpu,
    /// On the CPU.
    Cpu,
}

/// How `map` holds the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Form {
    /// Every part's code inline in `map` (the default).
    #[default]
    Inline,
    /// The scene as data: each grid cell's pruned program in storage buffers
    /// (`crate::tape::data`), run by `tape_eval`; the code has one arm per primitive kind.
    /// Where the scene has no data form, the lowering keeps the inline one (the command line
    /// refuses first, saying why).
    Data,
}

/// Which unions' bounding-volume trees (`catalog::prune::Tree`) the shader tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BoundingVolumes {
    /// None: every child of every union is evaluated each time (`--no-bvh`).
    Off,
    /// Unions whose tree groups at least `prune::GPU_MIN_GROUPED` children: where the tests
    /// measured faster than the plain union (the default).
    #[default]
    Large,
    /// Every union that has a tree (`--bvh`).
    All,
}

impl BoundingVolumes {
    /// Whether the shader tests `tree`.
    pub fn uses(self, tree: &crate::catalog::prune::Tree) -> bool {
        match self {
            BoundingVolumes::Off => false,
            BoundingVolumes::Large => tree.grouped() >= crate::catalog::prune::GPU_MIN_GROUPED,
            BoundingVolumes::All => true,
        }
    }
}

impl Options {
    /// The scene's own settings, one pass.
    pub fn from_scene(scene: &Scene) -> Options {
        Options {
            trace: scene.trace,
            passes: false,
            bounding_volumes: BoundingVolumes::default(),
            fixed_offset: false,
            private_params: false,
            params_binding: crate::layout::PARAMS_BINDING,
            form: Form::Inline,
            count_primitives: false,
            cells: None,
            prepass: Prepass::Auto,
        }
    }
}

/// Where a multi-resolution pass starts a ray and with what budget and cone slope.
#[derive(Clone, Copy)]
pub(super) struct Pass {
    pub start: Ex,
    pub budget: Ex,
    pub cone: Ex,
}
