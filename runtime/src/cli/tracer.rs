//! The tracer flags `emit` and `render` share (`--tracer`, `--steps`, …, `--passes`, `--bvh`,
//! `--no-bvh`), and how they settle a scene's settings.

use super::Error;
use clap::Args;
use sdfc_compiler::check;
use sdfc_compiler::lower::tracer::BoundingVolumes;

/// Tracer settings that override the scene's `trace` block (emit and render).
#[derive(Args, Debug, Default)]
pub struct TracerArgs {
    /// Tracer to use instead of the scene's: basic, relaxed, enhanced, hybrid, auto.
    #[arg(long, value_name = "NAME")]
    pub tracer: Option<String>,
    /// Step budget (evaluations of the field per ray).
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub steps: Option<String>,
    /// Hit threshold: a distance, or `pixel` for the pixel footprint.
    #[arg(long, allow_hyphen_values = true, value_name = "E|pixel")]
    pub epsilon: Option<String>,
    /// Rays stop beyond this distance.
    #[arg(long, allow_hyphen_values = true, value_name = "D")]
    pub max_distance: Option<String>,
    /// Relaxation ω (relaxed: [1, 2); enhanced: [0.5, 2)).
    #[arg(long, allow_hyphen_values = true, value_name = "W")]
    pub omega: Option<String>,
    /// Weight of the slope average (auto).
    #[arg(long, allow_hyphen_values = true, value_name = "B")]
    pub beta: Option<String>,
    /// Linear-search step in units of ε (hybrid).
    #[arg(long, allow_hyphen_values = true, value_name = "K")]
    pub linear: Option<String>,
    /// Regula falsi iterations (hybrid).
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub refine: Option<String>,
    /// Discontinuity-reduction iterations after a hit (Keinert §3.4).
    #[arg(long, allow_hyphen_values = true, value_name = "N")]
    pub discontinuity: Option<String>,
    /// Hart's cone anti-aliasing (`cone`, basic tracer) or `none`.
    #[arg(long, allow_hyphen_values = true, value_name = "cone|none")]
    pub antialias: Option<String>,
    /// After a failed relaxed step: `keep` ω (Bálint & Valasek Alg. 2) or `reset` it to 1
    /// (Keinert Listing 2); relaxed tracer.
    #[arg(long, allow_hyphen_values = true, value_name = "reset|keep")]
    pub fallback: Option<String>,
    /// Multi-resolution passes (Bálint §4): 2 (1/2 then full resolution), 4 or 6; 1 is a
    /// single pass. Compute entry only.
    #[arg(long, default_value_t = 1, value_name = "1|2|4|6")]
    pub passes: u32,
    /// Ignore the scene's `bound` block (trace every ray from the camera).
    #[arg(long)]
    pub no_bound: bool,
    /// Test the bounding boxes of every union's groups of parts in `map`, skipping far groups
    /// (the same field). By default only unions whose tree groups 5 or more parts (with
    /// finite boxes and exact distances) test them, where that measured faster on Mesa 25's
    /// lavapipe (docs/benchmarks.md).
    #[arg(long, conflicts_with = "no_bvh")]
    pub bvh: bool,
    /// Evaluate every part of every union each time: no bounding-box tests in `map`.
    #[arg(long)]
    pub no_bvh: bool,
    /// How `map` holds the scene: `inline` code, or `data`: the scene's parts in storage
    /// buffers, each cell of a grid over it with only the parts that can matter there
    /// (Lipschitz pruning), run by a generic evaluator whose code does not grow with the parts
    /// (primitives under moves, turns and scales, folded by unions, intersections and
    /// subtractions, hard or smooth); `auto` (the default): `data` for a scene of many parts
    /// it can hold (docs/data-form.md gives the measured threshold), else `inline`. `emit`
    /// writes the inline form unless given `data`: then the buffers are files beside the
    /// shader, for the host to bind (the manifest's `data`).
    #[arg(long, value_enum, default_value = "auto")]
    pub form: FormArg,
    /// The data form's grid: cells along its longest side, 1 to 128 (by default about 256
    /// cells a part, 8 to 128). Fewer make smaller buffers and a faster pre-pass, more keep
    /// fewer parts a cell and trace faster.
    #[arg(long, value_name = "N")]
    pub cells: Option<usize>,
    /// Where the data form's cells are pruned: `gpu` by a compute pre-pass on the device (on
    /// the CPU where the device cannot hold the programs), `cpu`, or `auto` (the default): the
    /// device from 1000 parts, where it measured faster. The same programs either way
    /// (docs/data-form.md); `emit` makes its buffer files on the CPU.
    #[arg(long, value_enum, value_name = "WHERE")]
    pub prepass: Option<PrepassArg>,
    /// Start shadow, reflected and refracted rays a fixed 2·ε_floor off the surface instead of
    /// Keinert's ε_dynamic = 2·max(ε, |f(p)|): only to see and measure what ε_dynamic prevents
    /// (shadow acne, self-intersecting refraction).
    #[arg(long)]
    pub fixed_offset: bool,
}

impl TracerArgs {
    /// The scene's tracer settings with these overrides, or an error for the user.
    pub fn apply(
        &self,
        scene: sdfc_compiler::scene::Trace,
    ) -> Result<sdfc_compiler::scene::Trace, Error> {
        let values: Vec<(&str, &str)> = [
            ("steps", &self.steps),
            ("epsilon", &self.epsilon),
            ("max_distance", &self.max_distance),
            ("omega", &self.omega),
            ("beta", &self.beta),
            ("linear", &self.linear),
            ("refine", &self.refine),
            ("discontinuity", &self.discontinuity),
            ("antialias", &self.antialias),
            ("fallback", &self.fallback),
        ]
        .iter()
        .filter_map(|(k, v)| v.as_deref().map(|v| (*k, v)))
        .collect();
        check::tracer::with_overrides(scene, self.tracer.as_deref(), &values)
            .map_err(|e| Error::Usage(format!("error: {e}")))
    }

    /// [`TracerArgs::settle`] for code a host runs (`emit`): `--form auto` is the inline form
    /// there (the data form's buffers are files the host must load and bind, so it is asked for
    /// by name), `--form data` the data form where the scene has one.
    pub fn settle_emitted(
        &self,
        scene: &mut sdfc_compiler::scene::Scene,
    ) -> Result<sdfc_compiler::lower::tracer::Options, Error> {
        let mut options = self.settle(scene)?;
        if self.form != FormArg::Data {
            options.form = sdfc_compiler::lower::tracer::Form::Inline;
        }
        Ok(options)
    }

    /// Applies the overrides to a scene and returns the lowering options, or an error for the
    /// user.
    pub fn settle(
        &self,
        scene: &mut sdfc_compiler::scene::Scene,
    ) -> Result<sdfc_compiler::lower::tracer::Options, Error> {
        scene.trace = self.apply(scene.trace)?;
        if self.no_bound {
            scene.bound = None;
        }
        check_passes(self.passes)?;
        let mut options = sdfc_compiler::lower::tracer::Options::from_scene(scene);
        options.passes = self.passes > 1;
        options.bounding_volumes = bounding_volumes(self.bvh, self.no_bvh);
        options.fixed_offset = self.fixed_offset;
        options.form = self.form.choose(self.passes, scene)?;
        options.cells = check_cells(self.cells, options.form)?;
        options.prepass = check_prepass(self.prepass, options.form)?;
        Ok(options)
    }
}

/// Refuses what the data form cannot do yet: several passes, and nodes it has no data for
/// (`tape::data::layout` says which). Parameters and `time` in shapes' arguments are
/// followed: the host makes the buffers at their values (`tape_data`; the window at every new
/// moment while `time` runs), the shader stays.
pub fn data_form_allowed(passes: u32, scene: &sdfc_compiler::scene::Scene) -> Result<(), Error> {
    if passes > 1 {
        return Err(Error::Usage(
            "error: `--form data` takes one pass (`--passes 1`) so far".into(),
        ));
    }
    if let Err(why) = sdfc_compiler::tape::data::layout(scene, None) {
        return Err(Error::Usage(format!(
            "error: `--form data` cannot hold this scene: {}",
            sdfc_compiler::tape::data::say(scene, &why)
        )));
    }
    Ok(())
}

/// `--form`: how `map` holds the scene.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FormArg {
    /// The data form for a scene of many parts that has one (`tape::data::prefer`), else
    /// inline.
    #[default]
    Auto,
    /// Every part's code in `map`.
    Inline,
    /// The scene as data, pruned per cell.
    Data,
}

impl FormArg {
    /// The form for `scene` drawn in `passes` passes: `auto` takes the data form where the
    /// scene has enough parts and nothing the data form refuses, else the inline one;
    /// `data` is an error where the data form cannot draw the scene.
    pub fn choose(
        self,
        passes: u32,
        scene: &sdfc_compiler::scene::Scene,
    ) -> Result<sdfc_compiler::lower::tracer::Form, Error> {
        use sdfc_compiler::lower::tracer::Form;
        Ok(match self {
            FormArg::Inline => Form::Inline,
            FormArg::Data => {
                data_form_allowed(passes, scene)?;
                Form::Data
            }
            FormArg::Auto => {
                let data = sdfc_compiler::tape::data::prefer(scene)
                    && data_form_allowed(passes, scene).is_ok();
                if data { Form::Data } else { Form::Inline }
            }
        })
    }
}

/// `--cells` checked: within 1 to `tape::data::CELLS`' most, and only for the data form.
pub fn check_cells(
    cells: Option<usize>,
    form: sdfc_compiler::lower::tracer::Form,
) -> Result<Option<usize>, Error> {
    let Some(n) = cells else {
        return Ok(None);
    };
    let most = sdfc_compiler::tape::data::CELLS.1;
    if !(1..=most).contains(&n) {
        return Err(Error::Usage(format!(
            "error: `--cells {n}`: the grid has 1 to {most} cells along its longest side"
        )));
    }
    if form != sdfc_compiler::lower::tracer::Form::Data {
        return Err(Error::Usage(format!(
            "error: `--cells {n}` is for the data form, and this scene is drawn inline\nhelp: `--form data`"
        )));
    }
    Ok(Some(n))
}

/// `--prepass`: where the data form's cells are pruned.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrepassArg {
    /// On the device from 1000 parts, else on the CPU (the default).
    Auto,
    /// On the device.
    Gpu,
    /// On the CPU.
    Cpu,
}

/// `--prepass` checked: only for the data form; by default `auto`.
pub fn check_prepass(
    prepass: Option<PrepassArg>,
    form: sdfc_compiler::lower::tracer::Form,
) -> Result<sdfc_compiler::lower::tracer::Prepass, Error> {
    use sdfc_compiler::lower::tracer::{Form, Prepass};
    match (prepass, form) {
        (Some(p), Form::Inline) => Err(Error::Usage(format!(
            "error: `--prepass {}` is for the data form, and this scene is drawn inline\nhelp: `--form data`",
            match p {
                PrepassArg::Auto => "auto",
                PrepassArg::Gpu => "gpu",
                PrepassArg::Cpu => "cpu",
            }
        ))),
        (Some(PrepassArg::Cpu), _) => Ok(Prepass::Cpu),
        (Some(PrepassArg::Gpu), _) => Ok(Prepass::Gpu),
        _ => Ok(Prepass::Auto),
    }
}

/// `--passes N` of `render`, `emit` and `bench`: a number of passes there is a schedule for.
pub fn check_passes(passes: u32) -> Result<(), Error> {
    let counts = sdfc_compiler::passes::counts();
    if counts.contains(&(passes as usize)) {
        return Ok(());
    }
    let list: Vec<String> = counts.iter().map(|c| c.to_string()).collect();
    Err(Error::Usage(format!(
        "error: `--passes {passes}`: there are schedules for {} passes",
        list.join(", ")
    )))
}

/// The trees `--bvh` (every union's) or `--no-bvh` (none) ask for; by default those of large
/// unions (`BoundingVolumes::Large`).
pub fn bounding_volumes(bvh: bool, no_bvh: bool) -> BoundingVolumes {
    match (bvh, no_bvh) {
        (true, _) => BoundingVolumes::All,
        (_, true) => BoundingVolumes::Off,
        _ => BoundingVolumes::Large,
    }
}
