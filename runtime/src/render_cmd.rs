//! `sdfc render`: a scene file in, a PNG (or `.npy` depth) out, through the wgpu runtime.

use crate::cli::load_scene;
use crate::emit_cmd::write_whole;
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
    /// Samples per pixel (a square number).
    pub samples: u32,
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

/// Primitive evaluations per step from which `render` says that the driver is compiling.
const SLOW_COMPILE: f64 = 512.0;

/// How an internal compiler error's message starts.
const INTERNAL: &str = "internal compiler error";

fn render(args: &RenderArgs) -> Result<(), String> {
    let (w, h) = parse_size(args.size)?;
    let s = (args.samples as f64).sqrt().round() as u32;
    if args.samples == 0 || s * s != args.samples || s > 8 {
        return Err(format!(
            "error: `--samples {}` must be a square number from 1 to 64 (1, 4, 9, 16, ...)",
            args.samples
        ));
    }
    if (w * s) > sdfc::gpu::MAX_SIDE || (h * s) > sdfc::gpu::MAX_SIDE {
        return Err("error: the image is too large with this many samples".into());
    }
    let Some((_, _, mut scene)) = load_scene(args.file) else {
        return Err(String::new());
    };
    let options = args.tracer.settle(&mut scene)?;
    let (module, _) = emit::module(&scene, Entry::Compute, &options)
        .map_err(|e| format!("{INTERNAL}: {}", e.0))?;
    let gpu = Gpu::new(args.backend)?;
    let cost = scene.root_node().evaluations;
    if cost >= SLOW_COMPILE {
        // The driver compiles the shader at the first dispatch, silently; on a software
        // driver a large scene takes minutes (a flat union of 2 048 spheres: 21 s on lavapipe).
        say!(
            "compiling the shader for {} ({cost:.0} primitive evaluations per step: this can take a while)…",
            gpu.info.name
        );
    }
    let view = View::new(&scene.camera, w * s, h * s);
    let plan = options.passes.then(|| {
        passes::plan(
            &scene,
            w * s,
            h * s,
            scene.trace.steps,
            args.tracer.passes as usize,
        )
        .unwrap_or_default()
    });
    let bar = progress_bar("rendering tiles");
    let frame = gpu.render(&module, &view, plan.as_deref(), |done, total| {
        if let Some(b) = &bar {
            b.set_length(total as u64);
            b.set_position(done as u64);
        }
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let wants_npy = args.output.extension().is_some_and(|e| e == "npy");
    let bytes = if wants_npy {
        if args.channel != Channel::Depth || s != 1 {
            return Err(
                "error: `.npy` output is for `--output depth` with one sample per pixel".into(),
            );
        }
        images::npy(&frame.depth, w, h)
    } else {
        let px = images::rgba(&frame, args.channel, scene.trace.steps);
        images::png(images::downsample(&px, w * s, h * s, s), w, h)?
    };
    match write_whole(args.output, &bytes) {
        0 => Ok(()),
        _ => Err(String::new()),
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
