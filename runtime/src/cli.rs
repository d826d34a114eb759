//! Command-line parsing and the subcommands' drivers.

use crate::cli_values::{BackendArg, EntryArg, SpirvVersion, TargetArg};
use crate::input::check_command;
pub use crate::input::{exit_code, load_scene, print_out};
pub use crate::tracer_args::TracerArgs;
use crate::view_events::watching;
use clap::{Parser, Subcommand};
use sdfc_compiler::lipschitz::Effort;
use std::path::PathBuf;

/// The version `--version` prints: the package's, and the commit it was built from when the
/// build could ask git (`build.rs`).
const VERSION: &str = match option_env!("SDFC_COMMIT") {
    Some(_) => concat!(
        env!("CARGO_PKG_VERSION"),
        " (commit ",
        env!("SDFC_COMMIT"),
        ")"
    ),
    None => env!("CARGO_PKG_VERSION"),
};

/// The command line.
#[derive(Parser)]
#[command(
    name = "sdfc",
    version = VERSION,
    about = "A compiler for scenes of signed distance functions"
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Print nothing on success (errors and warnings still go to standard error).
    #[arg(short, long, global = true)]
    quiet: bool,
    /// Diagnostics as a report with the source and a caret, or one JSON object per line.
    #[arg(long, value_enum, global = true, default_value = "human")]
    message_format: crate::messages::Format,
    /// Colour the report: on a terminal unless `NO_COLOR` is set, always, or never.
    #[arg(long, value_enum, global = true, default_value = "auto")]
    color: crate::messages::Color,
}

/// Whether `-q/--quiet` was given.
static QUIET: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Prints a command's one line of success to standard error, unless `--quiet`.
pub fn done(line: &str) {
    if !QUIET.load(std::sync::atomic::Ordering::Relaxed) {
        say!("{line}");
    }
}

#[derive(Subcommand)]
enum Command {
    /// Parse and check a scene; print a summary or the diagnostics.
    Check {
        /// The scene file (`-` for standard input).
        file: Option<PathBuf>,
        /// Print the catalog of primitives, operators and functions instead.
        #[arg(long)]
        list: bool,
        /// Check `@lipschitz` annotations thoroughly (ten times the samples of the quick check
        /// that `check`, `render` and `emit` always run).
        #[arg(long)]
        lipschitz: bool,
    },
    /// Compile a scene to shader code.
    Emit {
        /// The scene file (`-` for standard input).
        file: PathBuf,
        /// Output language [default: wgsl; glsl for `--entry shadertoy`].
        #[arg(long, value_enum)]
        target: Option<TargetArg>,
        /// The interface: the runtime's compute pass, a full-screen fragment pass, or a library of functions.
        #[arg(long, value_enum, default_value = "compute")]
        entry: EntryArg,
        /// Output file (default, or `-`: standard output; SPIR-V only when it is not a terminal).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// SPIR-V version to write: 1.0 (Vulkan 1.0; the compute entry's storage buffers through
        /// the SPV_KHR_storage_buffer_storage_class extension) to 1.6.
        #[arg(long, value_enum, default_value = "1.3")]
        spirv_version: SpirvVersion,
        /// GLSL dialect: 450 (desktop core, Vulkan-style bindings), 310es (OpenGL ES 3.1) or
        /// 300es (WebGL 2 / OpenGL ES 3.0: fragment and library entries only).
        #[arg(long, value_enum, default_value = "450")]
        glsl_version: crate::emit_cmd::GlslVersionArg,
        #[command(flatten)]
        tracer: TracerArgs,
        /// Prefix the shader's own names (functions, structs, globals, constants) with `NAME_`
        /// so that they cannot collide with the host's: `NAME_map`, `NAME_trace`, `NAME_Params`.
        #[arg(long, value_name = "NAME")]
        prefix: Option<String>,
        /// Also write the manifest a host needs (bindings, uniform layouts, parameters, entry
        /// points, functions, materials, camera, lights) as JSON to this file
        /// (docs/interface.md).
        #[arg(long, value_name = "FILE")]
        manifest: Option<PathBuf>,
        /// Write the output again on every save of the scene file, until interrupted.
        #[arg(long)]
        watch: bool,
        /// The binding (in group 0) of the scene's `Params` uniform: another than the default
        /// 9 lets two scenes' libraries (with `--prefix`) share a shader.
        #[arg(long, value_name = "N", default_value_t = 9)]
        params_binding: u32,
    },
    /// Render a scene to a PNG (or depth to `.npy`) on the GPU, headless.
    Render {
        /// The scene file (`-` for standard input).
        file: PathBuf,
        /// Output file: `.png`, or `.npy` for raw f32 depth (`-`: a PNG to standard output).
        #[arg(short = 'o', long = "output", visible_alias = "out")]
        output: PathBuf,
        /// Image size.
        #[arg(long, default_value = "1280x720")]
        size: String,
        #[command(flatten)]
        tracer: TracerArgs,
        /// Graphics API: Vulkan, then GL, or one of them.
        #[arg(long, value_enum, default_value = "auto")]
        backend: BackendArg,
        /// What to write.
        #[arg(long = "channel", value_enum, default_value = "color")]
        kind: sdfc::images::Channel,
        /// Samples per pixel for anti-aliasing: a square number (a stratified grid), accumulated
        /// at the output's size. Default: 4 for `--channel color` (1 when the scene's tracer
        /// does Hart's cone anti-aliasing), 1 for the other channels.
        #[arg(long)]
        samples: Option<u32>,
        /// Render a shader larger than the driver compiles in reasonable time (more than
        /// 4 096 calls of distance functions; docs/stability.md).
        #[arg(long)]
        allow_slow_compile: bool,
        /// Set a scene parameter: `NAME=VALUE` (a number, an angle with `deg`, `x,y,z` or
        /// `#rrggbb`); repeat for several. It must be within the parameter's range.
        #[arg(long = "param", value_name = "NAME=VALUE")]
        params: Vec<String>,
        /// The scene's `time`, in seconds (default 0); with `--frames`, added to each frame
        /// k's k/fps.
        #[arg(long, allow_hyphen_values = true)]
        time: Option<f64>,
        /// Render an animation of `time`: frames START to END (excluded), each `1/fps` s
        /// after the one before, to an animated GIF (`-o anim.gif`) or numbered PNGs
        /// (`-o out_###.png`); the shader is compiled once.
        #[arg(long, value_name = "START..END")]
        frames: Option<String>,
        /// Frames per second of `--frames`.
        #[arg(long, default_value_t = 30, requires = "frames")]
        fps: u32,
        /// Render again on every save of the scene file, until interrupted.
        #[arg(long)]
        watch: bool,
    },
    /// Show a scene in a window, live: drag to orbit, right-drag to pan, wheel to zoom; the
    /// picture follows the file on every save. Keys: 1–5 colour/normal/depth/steps/material,
    /// t tracer, a anti-aliasing, [ ] pick a parameter, - = change it, space pauses `time`,
    /// r back to the scene's camera, s screenshot, q quit.
    View {
        /// The scene file.
        file: PathBuf,
        /// The window's size.
        #[arg(long, default_value = "960x600")]
        size: String,
        #[command(flatten)]
        tracer: TracerArgs,
        /// Graphics API: Vulkan, then GL, or one of them.
        #[arg(long, value_enum, default_value = "auto")]
        backend: BackendArg,
        /// Write each finished picture (and the one kept after a failed reload) to this
        /// directory as 000.png, 001.png, … (for tests and recordings).
        #[arg(long, value_name = "DIR")]
        screenshots: Option<PathBuf>,
        /// Input to replay, one step per finished picture: `drag DX DY; pan DX DY; zoom N; key K`.
        #[arg(long)]
        script: Option<String>,
        /// Close after this many screenshots.
        #[arg(long, value_name = "N")]
        quit_after: Option<u32>,
        /// Hold the scene's `time` at T seconds (space lets it run); it runs with the clock
        /// otherwise.
        #[arg(long, allow_hyphen_values = true)]
        time: Option<f64>,
    },
    /// Measure every tracer × step budget on the GPU against an f64 ground truth: time,
    /// evaluations per pixel, depth error, hit/miss agreement.
    Bench {
        /// The scene file (`-` for standard input).
        file: PathBuf,
        /// Tracers to measure, comma-separated.
        #[arg(long, default_value = "basic,relaxed,enhanced,hybrid,auto")]
        tracers: String,
        /// Step budgets, comma-separated.
        #[arg(long, default_value = "8,16,32,64,128,256")]
        steps: String,
        /// Hit threshold for every tracer instead of the scene's: a distance, or `pixel`.
        #[arg(long, allow_hyphen_values = true)]
        epsilon: Option<String>,
        /// Image size.
        #[arg(long, default_value = "320x180")]
        size: String,
        /// Renders per cell; the median time is reported.
        #[arg(long, default_value_t = 3)]
        repeat: u32,
        /// Report the fastest tracer and budget whose mean squared depth error is at most this.
        #[arg(long, allow_hyphen_values = true)]
        target_error: Option<f64>,
        /// With `--target-error`: the largest share of pixels whose hit/miss may differ.
        #[arg(long, default_value_t = 0.01)]
        max_mismatch: f64,
        /// Print JSON instead of the table.
        #[arg(long)]
        json: bool,
        /// Print CSV instead of the table.
        #[arg(long, conflicts_with = "json")]
        csv: bool,
        /// Also draw error against time and against evaluations per pixel to this `.svg` or `.png`.
        #[arg(long)]
        plot: Option<PathBuf>,
        /// Graphics API: Vulkan, then GL, or one of them.
        #[arg(long, value_enum, default_value = "auto")]
        backend: BackendArg,
        /// Also measure every cell with this many multi-resolution passes (Bálint §4): 2, 4 or 6.
        #[arg(long, default_value_t = 1)]
        passes: u32,
        /// A hand-written WGSL tracer (runtime/benches/reference/README.md gives its interface)
        /// timed alternately with each cell's trace, same view and size.
        #[arg(long)]
        reference: Option<PathBuf>,
        /// Test every union's bounding boxes in `map` (as `render --bvh`).
        #[arg(long, conflicts_with = "no_bvh")]
        bvh: bool,
        /// No bounding-box tests in `map` (as `render --no-bvh`).
        #[arg(long)]
        no_bvh: bool,
        /// Start secondary rays a fixed 2·ε_floor off the surface (as `render --fixed-offset`).
        #[arg(long)]
        fixed_offset: bool,
        /// Measure a shader larger than the driver compiles in reasonable time (as `render`).
        #[arg(long)]
        allow_slow_compile: bool,
    },
    /// Print shell completions for `sdfc` (bash, zsh, fish, elvish, powershell).
    Completions {
        /// The shell.
        #[arg(value_enum)]
        shell: clap_complete::Shell,
        /// Output file (default, or `-`: standard output).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Print the man page of `sdfc` (roff; `man -l sdfc.1` shows it).
    Man {
        /// Output file (default, or `-`: standard output).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
}

/// Runs the command line; returns the exit code (0 ok, 1 user error).
pub fn run() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 1 } else { 0 };
            let _ = e.print();
            return code;
        }
    };
    QUIET.store(cli.quiet, std::sync::atomic::Ordering::Relaxed);
    crate::messages::configure(cli.message_format, cli.color);
    match cli.command {
        Command::Completions { shell, output } => {
            crate::shell::completions(shell, output.as_deref())
        }
        Command::Man { output } => crate::shell::man(output.as_deref()),
        Command::Check { list: true, .. } => print_out(&sdfc_compiler::docs::catalog_table())
            .err()
            .unwrap_or(0),
        Command::Check { file: None, .. } => {
            say!("error: give a scene file to check (or `-` for standard input)");
            1
        }
        Command::Check {
            file: Some(file),
            lipschitz,
            ..
        } => check_command(
            &file,
            if lipschitz {
                Effort::Thorough
            } else {
                Effort::Fast
            },
        ),
        Command::Emit {
            file,
            target,
            entry,
            output,
            spirv_version,
            glsl_version,
            tracer,
            prefix,
            manifest,
            watch,
            params_binding,
        } => {
            let shadertoy = matches!(entry, EntryArg::Shadertoy);
            let target = match (target, shadertoy) {
                (Some(t), _) => t,
                (None, true) => TargetArg::Glsl,
                (None, false) => TargetArg::Wgsl,
            };
            let once = || {
                crate::emit_cmd::run(
                    &file,
                    (target.into(), entry.into()),
                    (output.as_deref(), manifest.as_deref()),
                    &sdfc_compiler::emit::Settings {
                        spirv_version: spirv_version.pair(),
                        glsl_version: glsl_version.into(),
                    },
                    crate::emit_cmd::Extras {
                        tracer: &tracer,
                        prefix: prefix.as_deref(),
                        shadertoy,
                        params_binding,
                    },
                )
            };
            watching(&file, watch, once)
        }
        Command::Render {
            file,
            output,
            size,
            tracer,
            backend,
            kind,
            samples,
            allow_slow_compile,
            params,
            time,
            frames,
            fps,
            watch,
        } => watching(&file, watch, || {
            crate::render_cmd::run(&crate::render_cmd::RenderArgs {
                file: &file,
                output: &output,
                size: &size,
                tracer: &tracer,
                backend: backend.into(),
                channel: kind,
                samples,
                allow_slow_compile,
                params: &params,
                time,
                frames: frames.as_deref(),
                fps,
            })
        }),
        Command::View {
            file,
            size,
            tracer,
            backend,
            screenshots,
            script,
            quit_after,
            time,
        } => crate::view_cmd::run(crate::view_cmd::ViewArgs {
            file,
            size,
            backend: backend.into(),
            tracer,
            screenshots,
            script,
            quit_after,
            time,
        }),
        Command::Bench {
            file,
            tracers,
            steps,
            epsilon,
            size,
            repeat,
            target_error,
            max_mismatch,
            json,
            csv,
            plot,
            backend,
            passes,
            reference,
            bvh,
            no_bvh,
            fixed_offset,
            allow_slow_compile,
        } => crate::bench_cmd::run(&crate::bench_cmd::BenchArgs {
            file: &file,
            tracers: &tracers,
            steps: &steps,
            epsilon: epsilon.as_deref(),
            size: &size,
            repeat,
            target_error,
            max_mismatch,
            json,
            csv,
            plot: plot.as_deref(),
            backend: backend.into(),
            passes,
            reference: reference.as_deref(),
            bvh: crate::tracer_args::bounding_volumes(bvh, no_bvh),
            fixed_offset,
            allow_slow_compile,
        }),
    }
}
