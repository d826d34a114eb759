//! The data form's buffers for the runtime: made on the CPU (`tape::data::data`) or pruned on
//! the device (`Gpu::prune`), at parameter values, for a shader compiled at the defaults.

use super::Error;
use sdfc::gpu::{Gpu, Pruner};
use sdfc_compiler::lower::tracer::{Options, Prepass};
use sdfc_compiler::scene::Scene;
use sdfc_compiler::tape::data;

/// The data form's buffers for a scene compiled at its defaults (`scene`: the kinds, the
/// stack's depth and whether there is a grid and a proxy are compiled into the shader) drawn
/// at other values (`valued`: the grid, the cells' programs and the parts' arguments).
/// The grid has `cells` along its longest side (by default as many as the parts call for,
/// `tape::data::cells_for`): the grid is data, so any count runs on the same shader — fewer
/// cells make the buffers faster, the trace slower.
pub fn tape_data(scene: &Scene, valued: &Scene, cells: Option<usize>) -> Result<data::Data, Error> {
    let (tree, layout) = layout_at(scene, valued, cells)?;
    data::data(valued, &tree, &layout).map_err(|why| fail(scene, why))
}

/// The error for a scene whose data form cannot be made.
fn fail(scene: &Scene, why: data::Why) -> Error {
    Error::Usage(format!("error: `--form data`: {}", data::say(scene, &why)))
}

/// The tree and layout of `valued`, checked to run on the shader compiled for `scene` (see
/// [`tape_data`]).
fn layout_at(
    scene: &Scene,
    valued: &Scene,
    cells: Option<usize>,
) -> Result<(sdfc_compiler::tape::Part, data::Layout), Error> {
    let fail = |why| fail(scene, why);
    let (_, compiled) = data::layout(scene, None).map_err(fail)?;
    let (tree, layout) = data::layout(valued, cells).map_err(fail)?;
    if !compiled.holds(&layout) {
        return Err(Error::Usage(
            "error: `--form data`: at these parameter values the scene's parts need another \
             shader (their kinds, nesting or bounds changed): draw it with `--form inline`"
                .into(),
        ));
    }
    Ok((tree, layout))
}

/// The data form's buffers as made and set (for `bench`).
#[derive(Clone, Copy, Debug)]
pub struct TapeMade {
    /// Seconds from the scene to the buffers set (the pre-pass included).
    pub seconds: f64,
    /// The bytes of the three buffers.
    pub bytes: usize,
    /// The grid's cells.
    pub cells: usize,
    /// The mean leaves a cell's program evaluates.
    pub mean_leaves: f64,
    /// Whether the device pruned them.
    pub on_gpu: bool,
    /// How many times the device ran the pre-pass again with more room.
    pub retries: u32,
}

/// The pre-pass's pipeline for `scene` where `options` prune on the device — `--prepass gpu`,
/// or `auto` for a tree of at least `tape::data::GPU_PREPASS_FROM` leaves — (`None` for the
/// CPU, or where the scene has no data form).
pub fn pruner(gpu: &Gpu, scene: &Scene, options: &Options) -> Result<Option<Pruner>, Error> {
    // (The form first: an inline scene's tree is not built to count its leaves.)
    let device = options.form == sdfc_compiler::lower::tracer::Form::Data
        && match options.prepass {
            Prepass::Gpu => true,
            Prepass::Cpu => false,
            Prepass::Auto => sdfc_compiler::tape::build(scene)
                .is_ok_and(|tree| tree.leaves() >= data::GPU_PREPASS_FROM),
        };
    if !device {
        return Ok(None);
    }
    Ok(gpu.pruner(scene)?)
}

/// Makes the data form's buffers of `valued` (for the shader compiled for `scene`; see
/// [`tape_data`]) and sets them on `gpu`: pruned on the device by `pruner` where given and
/// the device can hold the programs, else on the CPU.
pub fn set_tape(
    gpu: &Gpu,
    (scene, valued): (&Scene, &Scene),
    cells: Option<usize>,
    pruner: Option<&Pruner>,
) -> Result<TapeMade, Error> {
    let clock = std::time::Instant::now();
    let (tree, layout) = layout_at(scene, valued, cells)?;
    if let Some(pruner) = pruner
        && let Some(seed) =
            sdfc_compiler::tape::seed::seed(valued, &tree, &layout).map_err(|w| fail(scene, w))?
        && let Some(made) = gpu.prune(pruner, &seed)?
    {
        return Ok(TapeMade {
            seconds: clock.elapsed().as_secs_f64(),
            bytes: made.bytes,
            cells: made.cells,
            mean_leaves: made.mean_leaves,
            on_gpu: true,
            retries: made.retries,
        });
    }
    let data = data::data(valued, &tree, &layout).map_err(|w| fail(scene, w))?;
    gpu.set_tape(Some(&data))?;
    Ok(TapeMade {
        seconds: clock.elapsed().as_secs_f64(),
        bytes: data.bytes(),
        cells: data.cells(),
        mean_leaves: data.mean_leaves,
        on_gpu: false,
        retries: 0,
    })
}
