//! `sdfc render`: a scene file in, a PNG (or `.npy` depth) out, through the wgpu runtime.

use crate::emit_cmd::write_output;
use sdfc::gpu::{BackendChoice, Gpu};
use sdfc::images::{self, Channel};
use sdfc_compiler::emit;
use sdfc_compiler::lower::Entry;
use sdfc_compiler::passes;
use sdfc_compiler::view::View;
use std::io::IsTerminal;
use std::path::Path;

/// What `sdfc render` was asked for.
pub struct RenderArgs<'a> {
    /// Scene file.
    pub file: &'a Path,
    /// Output file.
    pub output: &'a Path,
    /// `WxH`.
    pub size: &'a str,
    /// Tracer overrides.
    pub tracer: &'a crate::cli::TracerArgs,
    /// Backend.
    pub backend: BackendChoice,
    /// Channel to write.
    pub channel: Channel,
    /// Samples per pixel (a square number); `None`: the default (see [`default_samples`]).
    pub samples: Option<u32>,
    /// Go on with a shader above [`MAX_DRIVER_CALLS`].
    pub allow_slow_compile: bool,
    /// `--param NAME=VALUE`s.
    pub params: &'a [String],
    /// `--time T`.
    pub time: Option<f64>,
    /// `--frames START..END`.
    pub frames: Option<&'a str>,
    /// `--fps N`.
    pub fps: u32,
}

/// Parses `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("error: `--size {s}` is not WIDTHxHEIGHT, e.g. `--size 1280x720`");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (
        w.trim().parse().map_err(|_| bad())?,
        h.trim().parse().map_err(|_| bad())?,
    );
    if w == 0 || h == 0 {
        return Err(format!("error: the image size {w}x{h} is empty"));
    }
    if w > sdfc::gpu::MAX_SIDE || h > sdfc::gpu::MAX_SIDE {
        return Err(format!(
            "error: the image size {w}x{h} is too large (at most {} per side)",
            sdfc::gpu::MAX_SIDE
        ));
    }
    Ok((w, h))
}

/// Runs `sdfc render`; returns the exit code.
pub fn run(args: &RenderArgs) -> i32 {
    match render(args) {
        // An invalid module is a bug in sdfc: exit 2, as `emit` does.
        Err(e) if e.starts_with(INTERNAL) => {
            say!("{e}");
            say!(
                "note: this is a bug in sdfc, not in the scene; please report it with the scene file"
            );
            2
        }
        result => crate::cli::exit_code(result),
    }
}

/// Calls of distance functions in the shader from which `render` says that the driver is
/// compiling (lavapipe: 256 took 0.7 s, 1 024 took 5.9 s).
const SLOW_COMPILE: usize = 512;

/// Most calls of distance functions in a shader `render` and `bench` hand to the driver
/// without `--allow-slow-compile`. Measured on lavapipe (a flat union of spheres at 32×18, the
/// driver's compile dominating): 256 calls 0.7 s, 1 024 5.9 s, 2 048 21.5 s, 4 096 113 s —
/// quadratic; 8 192 would take about 8 minutes. In `map` a shared `let` is one function and
/// costs little (4 096 evaluations through them: 2.4 s), but the material function writes its
/// body at each use; `sdfc emit` has no such limit.
pub const MAX_DRIVER_CALLS: usize = 4096;

/// Refuses, with the scene's span, a module too large for the driver to compile in
/// reasonable time (see [`MAX_DRIVER_CALLS`]); else its calls of distance functions.
pub fn check_driver_size(
    module: &naga::Module,
    (sources, scene): (
        &sdfc_compiler::source::Sources,
        &sdfc_compiler::scene::Scene,
    ),
    allow: bool,
) -> Result<usize, String> {
    let calls = emit::distance_calls(module);
    if calls > MAX_DRIVER_CALLS && !allow {
        let d = sdfc_compiler::diag::Diagnostic::error(
            scene.root_node().span,
            "this scene's shader is too large for the GPU driver to compile in reasonable time",
        )
        .label(format!("its code calls distance functions {calls} times"))
        .note(format!(
            "sdfc renders at most {MAX_DRIVER_CALLS} calls: on lavapipe a flat union of 2 048 shapes took 21 s to compile and 4 096 took 113 s, growing quadratically"
        ))
        .help("share repeated shapes with `let` or `repeat`, or pass `--allow-slow-compile` to wait; `sdfc emit` writes the shader for other engines");
        say_raw!("{}", crate::messages::report(&[d], sources));
        return Err(String::new());
    }
    Ok(calls)
}

/// How an internal compiler error's message starts.
const INTERNAL: &str = "internal compiler error";

fn render(args: &RenderArgs) -> Result<(), String> {
    // `--output` names the file (as for every command); the channel was `--output` before.
    let word = args.output.to_str().unwrap_or("");
    if ["color", "depth", "normal", "steps", "material"].contains(&word) {
        return Err(format!(
            "error: `--output {word}` names the file to write; the channel is `--channel {word}`\nhelp: sdfc render FILE -o OUT.png --channel {word}"
        ));
    }
    let animation = match args.frames {
        Some(text) => {
            let range = crate::animate::parse_frames(text)?;
            if args.fps == 0 || args.fps > 240 {
                return Err(format!("error: `--fps {}` must be from 1 to 240", args.fps));
            }
            if args.channel != Channel::Color {
                return Err("error: `--frames` renders colour (`--channel color`)".into());
            }
            Some((range, crate::animate::sink(args.output)?))
        }
        None => {
            check_extension(args.output)?;
            None
        }
    };
    if args.output == Path::new("-") && std::io::stdout().is_terminal() {
        return Err(
            "error: a PNG is binary; write it to a file with `-o FILE` (or pipe it)".into(),
        );
    }
    let started = std::time::Instant::now();
    let (w, h) = parse_size(args.size)?;
    if let Some(n) = args.samples {
        let s = (n as f64).sqrt().round() as u32;
        if n == 0 || s * s != n || s > 8 {
            return Err(format!(
                "error: `--samples {n}` must be a square number from 1 to 64 (1, 4, 9, 16, ...)"
            ));
        }
    }
    let wants_npy = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    if wants_npy && (args.channel != Channel::Depth || args.samples.is_some_and(|n| n > 1)) {
        return Err(
            "error: `.npy` output is for `--channel depth` with one sample per pixel".into(),
        );
    }
    let values = crate::input::param_values(args.params, args.time)?;
    let Some((sources, mut scene)) = crate::input::load_scene_with(args.file, &values) else {
        return Err(String::new());
    };
    let options = args.tracer.settle(&mut scene)?;
    let (module, _) = emit::module(&scene, Entry::Compute, &options)
        .map_err(|e| format!("{INTERNAL}: {}", e.0))?;
    let calls = check_driver_size(&module, (&sources, &scene), args.allow_slow_compile)?;
    let gpu = Gpu::new(args.backend)?;
    // The defaults' module, the values in its uniform only (as a host sets them).
    let valued = scene.with_values(&values);
    gpu.set_params(&sdfc_compiler::lower::params::bytes(&valued.params));
    if calls >= SLOW_COMPILE {
        // The driver compiles the shader at pipeline creation, silently.
        say!(
            "compiling the shader for {} ({calls} calls of distance functions: this can take a while)…",
            gpu.info.name
        );
    }
    let view = View::new(&scene.camera, w, h);
    let plan = options.passes.then(|| {
        passes::plan(&scene, w, h, scene.trace.steps, args.tracer.passes as usize)
            .unwrap_or_default()
    });
    // Anti-aliasing: one frame per sample point, accumulated at the output's size.
    let mut sum = images::Accumulator::new((w * h) as usize, args.channel == Channel::Color);
    let mut depth = Vec::new();
    let bar = progress_bar("rendering tiles");
    let samples = args
        .samples
        .unwrap_or_else(|| default_samples(args.channel, &options.trace));
    let points = images::sample_points(samples);
    if let Some((range, sink)) = animation {
        let first = range.start;
        let settings = crate::animate::settings(
            &valued.params,
            range,
            f64::from(args.fps),
            args.time.unwrap_or(0.0),
        )?;
        let count = settings.len();
        let mut writer = crate::animate::Writer::new(sink, first, f64::from(args.fps), (w, h))?;
        let mut sum = images::Accumulator::new((w * h) as usize, true);
        let mut taken = 0;
        gpu.render_sequence(
            &module,
            (&view, plan.as_deref()),
            &points,
            &settings,
            |done, total| {
                if let Some(b) = &bar {
                    b.set_length(total as u64);
                    b.set_position(done as u64);
                }
            },
            |_, frame| {
                sum.add(&images::rgba(&frame, Channel::Color, scene.trace.steps));
                taken += 1;
                if taken == points.len() {
                    let done = std::mem::replace(
                        &mut sum,
                        images::Accumulator::new((w * h) as usize, true),
                    );
                    taken = 0;
                    writer.add(done.finish())?;
                }
                Ok(())
            },
        )?;
        if let Some(b) = bar {
            b.finish_and_clear();
        }
        let place = writer.finish()?;
        let still = if scene
            .params
            .iter()
            .any(|p| p.name == sdfc_compiler::check::TIME)
        {
            ""
        } else {
            " (the scene does not read `time`: every frame is the same)"
        };
        crate::cli::done(&format!(
            "wrote {place} — {count} frames of {w}×{h} at {} fps, {samples} {} per pixel, {:.1} s, {} ({}){still}",
            args.fps,
            if samples == 1 { "sample" } else { "samples" },
            started.elapsed().as_secs_f64(),
            gpu.info.name,
            gpu.backend()
        ));
        return Ok(());
    }
    gpu.render_samples(
        &module,
        &view,
        plan.as_deref(),
        &points,
        |done, total| {
            if let Some(b) = &bar {
                b.set_length(total as u64);
                b.set_position(done as u64);
            }
        },
        |frame| {
            if wants_npy {
                depth = frame.depth;
            } else {
                sum.add(&images::rgba(&frame, args.channel, scene.trace.steps));
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
    if write_output(Some(args.output), &bytes, true) != 0 {
        return Err(String::new());
    }
    let place = match args.output.to_str() {
        Some("-") => "standard output".to_string(),
        _ => args.output.display().to_string(),
    };
    let per = if samples == 1 { "sample" } else { "samples" };
    crate::cli::done(&format!(
        "wrote {place} — {w}×{h}, {samples} {per} per pixel, {:.1} s, {} ({})",
        started.elapsed().as_secs_f64(),
        gpu.info.name,
        gpu.backend()
    ));
    Ok(())
}

/// What `render` writes, by the output file's extension (`-`: a PNG to standard output).
const IMAGE_EXTENSIONS: &[&str] = &["png", "npy"];

/// Refuses an output file whose extension names a format `render` does not write (a PNG in
/// `out.jpg` would be a lie).
fn check_extension(output: &Path) -> Result<(), String> {
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
        )),
    }
}

/// Samples per pixel without `--samples`: 4 for colour, so that edges are smooth by default
/// (about 1.7× the time of one sample for the README's jewel at 1280×720), but 1 when the
/// tracer already does Hart's cone anti-aliasing, and 1 for depth, normals, steps and
/// materials, whose values an average would blur into values no surface has.
pub fn default_samples(channel: Channel, trace: &sdfc_compiler::scene::Trace) -> u32 {
    if channel == Channel::Color && !trace.antialias {
        4
    } else {
        1
    }
}

/// A progress bar on standard error, only when it is a terminal.
pub fn progress_bar(what: &str) -> Option<indicatif::ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = indicatif::ProgressBar::new(1);
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{{spinner}} {what} {{pos}}/{{len}} {{wide_bar}} {{elapsed}} {{msg}}"
        ))
        .ok()?,
    );
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    Some(bar)
}
