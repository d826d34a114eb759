//! The command line's definition (clap): the global flags and each subcommand's arguments.

use super::tracer::TracerArgs;
use super::values::{BackendArg, EntryArg, GlslVersionArg, SpirvVersion, TargetArg};
use clap::{Args, Parser, Subcommand};
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
    /// The subcommand.
    #[command(subcommand)]
    pub command: Command,
    /// Print nothing on success (errors and warnings still go to standard error).
    #[arg(short, long, global = true)]
    pub quiet: bool,
    /// Diagnostics as a report with the source and a caret, or one JSON object per line.
    #[arg(long, value_enum, global = true, default_value = "human")]
    pub message_format: super::messages::Format,
    /// Colour the report: on a terminal unless `NO_COLOR` is set, always, or never.
    #[arg(long, value_enum, global = true, default_value = "auto")]
    pub color: super::messages::Color,
}

#[derive(Subcommand)]
pub enum Command {
    /// Parse and check a scene; print a summary or the diagnostics.
    Check(CheckArgs),
    /// Compile a scene to shader code.
    Emit(EmitArgs),
    /// Render a scene to a PNG (or depth to `.npy`) on the GPU, headless.
    Render(RenderArgs),
    /// Show a scene in a window, live: drag to orbit, right-drag to pan, wheel to zoom; the
    /// picture follows the file on every save. Keys: 1–5 colour/normal/depth/steps/material,
    /// t tracer, a anti-aliasing, [ ] pick a parameter, - = change it, space pauses `time`,
    /// r back to the scene's camera, s screenshot, q quit.
    View(ViewArgs),
    /// Measure every tracer × step budget on the GPU against an f64 ground truth: time,
    /// evaluations per pixel, depth error, hit/miss agreement.
    Bench(BenchArgs),
    /// Mesh a scene's surface into triangles for printers, engines and modelling tools:
    /// closed, 2-manifold, sharp corners kept (STL, OBJ, PLY with colours, glTF).
    Mesh(MeshArgs),
    /// Serve the playground (the compiler in the page, WebGPU or WebGL2) on this machine:
    /// build it first with `bash scripts/build_web.sh`, then open the address printed.
    Serve(ServeArgs),
    /// Print shell completions for `sdfc` (bash, zsh, fish, elvish, powershell).
    Completions(CompletionsArgs),
    /// Print the man page of `sdfc` (roff; `man -l sdfc.1` shows it).
    Man(ManArgs),
}

/// `--bake-res`: one resolution for every `bake` of the scene.
#[derive(Args, Debug, Default, Clone, Copy)]
pub struct BakeArgs {
    /// Bake every `bake { … }` of the scene at N points along its box's longest side instead
    /// of its own `res` (7 to 512; docs/bake.md).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(sdfc_compiler::bake::MIN_RES as i64..=sdfc_compiler::bake::MAX_RES as i64))]
    pub bake_res: Option<u32>,
}

/// `sdfc check`'s arguments.
#[derive(Args)]
pub struct CheckArgs {
    /// The scene file (`-` for standard input).
    pub file: Option<PathBuf>,
    /// Print the catalog of primitives, operators and functions instead.
    #[arg(long)]
    pub list: bool,
    /// Check `@lipschitz` annotations thoroughly (ten times the samples of the quick check
    /// that `check`, `render` and `emit` always run).
    #[arg(long)]
    pub lipschitz: bool,
    #[command(flatten)]
    pub bake: BakeArgs,
}

/// `sdfc emit`'s arguments.
#[derive(Args)]
pub struct EmitArgs {
    /// The scene file (`-` for standard input).
    pub file: PathBuf,
    /// Output language [default: wgsl; glsl for `--entry shadertoy`].
    #[arg(long, value_enum)]
    pub target: Option<TargetArg>,
    /// The interface: the runtime's compute pass, a full-screen fragment pass, or a library of functions.
    #[arg(long, value_enum, default_value = "compute")]
    pub entry: EntryArg,
    /// Output file (default, or `-`: standard output; SPIR-V only when it is not a terminal).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// SPIR-V version to write: 1.0 (Vulkan 1.0; the compute entry's storage buffers then need
    /// the VK_KHR_storage_buffer_storage_class device extension) to 1.6. 1.3 by default: Vulkan
    /// 1.1, where storage buffers need no extension.
    #[arg(long, value_enum, default_value = "1.3")]
    pub spirv_version: SpirvVersion,
    /// GLSL dialect: 450 (desktop core, Vulkan-style bindings), 310es (OpenGL ES 3.1) or
    /// 300es (WebGL 2 / OpenGL ES 3.0: fragment and library entries only).
    #[arg(long, value_enum, default_value = "450")]
    pub glsl_version: GlslVersionArg,
    #[command(flatten)]
    pub tracer: TracerArgs,
    /// Prefix the shader's own names (functions, structs, globals, constants) with `NAME_`
    /// so that they cannot collide with the host's: `NAME_map`, `NAME_trace`, `NAME_Params`.
    #[arg(long, value_name = "NAME")]
    pub prefix: Option<String>,
    /// Also write the manifest a host needs (bindings, uniform layouts, parameters, entry
    /// points, functions, materials, camera, lights) as JSON to this file
    /// (docs/interface.md).
    #[arg(long, value_name = "FILE")]
    pub manifest: Option<PathBuf>,
    /// Write the output again on every save of the scene file, until interrupted.
    #[arg(long)]
    pub watch: bool,
    /// The binding (in group 0) of the scene's `Params` uniform: another than the default
    /// 9 lets two scenes' libraries (with `--prefix`) share a shader.
    #[arg(long, value_name = "N", default_value_t = 9)]
    pub params_binding: u32,
    #[command(flatten)]
    pub bake: BakeArgs,
}

/// `sdfc render`'s arguments.
#[derive(Args)]
pub struct RenderArgs {
    /// The scene file (`-` for standard input).
    pub file: PathBuf,
    /// Output file: `.png`, or `.npy` for raw f32 depth (`-`: a PNG to standard output).
    #[arg(
        short = 'o',
        long = "output",
        visible_alias = "out",
        value_name = "OUT"
    )]
    pub output: PathBuf,
    /// Image size.
    #[arg(long, default_value = "1280x720", value_name = "WxH")]
    pub size: String,
    #[command(flatten)]
    pub tracer: TracerArgs,
    /// Graphics API: Vulkan, then GL, or one of them.
    #[arg(long, value_enum, default_value = "auto")]
    pub backend: BackendArg,
    /// What to write.
    #[arg(long = "channel", value_enum, default_value = "color")]
    pub kind: sdfc::images::Channel,
    /// Samples per pixel for anti-aliasing: a square number (a stratified grid), accumulated
    /// at the output's size. Default: 4 for `--channel color` (1 when the scene's tracer
    /// does Hart's cone anti-aliasing), 1 for the other channels.
    #[arg(long, value_name = "N")]
    pub samples: Option<u32>,
    /// Render a shader the driver is predicted to take longer than 30 s to compile (the model
    /// of lavapipe's compile time in docs/stability.md; `check` prints the prediction). Compiled
    /// shaders are kept in the pipeline cache: `$SDFC_CACHE_DIR`, else `$XDG_CACHE_HOME/sdfc`,
    /// else `~/.cache/sdfc` (Vulkan; `SDFC_CACHE_DIR=off` for none).
    #[arg(long)]
    pub allow_slow_compile: bool,
    /// Set a scene parameter: `NAME=VALUE` (a number; an angle with its unit, `30deg` or
    /// `0.5rad`; `x,y,z`; a colour as `#rrggbb` or `r,g,b`); repeat for several. It must be
    /// within the parameter's range.
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// The scene's `time`, in seconds (default 0); with `--frames`, added to each frame
    /// k's k/fps.
    #[arg(long, allow_hyphen_values = true, value_name = "T")]
    pub time: Option<f64>,
    /// Render an animation of `time`: frames START to END (excluded), each `1/fps` s
    /// after the one before, to an animated GIF (`-o anim.gif`) or numbered PNGs
    /// (`-o out_###.png`); the shader is compiled once.
    #[arg(long, value_name = "START..END")]
    pub frames: Option<String>,
    /// Frames per second of `--frames`.
    #[arg(long, default_value_t = 30, requires = "frames", value_name = "N")]
    pub fps: u32,
    /// Render again on every save of the scene file, until interrupted.
    #[arg(long)]
    pub watch: bool,
    #[command(flatten)]
    pub bake: BakeArgs,
}

/// `sdfc view`'s arguments.
#[derive(Args)]
pub struct ViewArgs {
    /// The scene file.
    pub file: PathBuf,
    /// The window's size.
    #[arg(long, default_value = "960x600")]
    pub size: String,
    #[command(flatten)]
    pub tracer: TracerArgs,
    /// Graphics API: Vulkan, then GL, or one of them.
    #[arg(long, value_enum, default_value = "auto")]
    pub backend: BackendArg,
    /// Write each finished picture (and the one kept after a failed reload) to this
    /// directory as 000.png, 001.png, … (for tests and recordings).
    #[arg(long, value_name = "DIR")]
    pub screenshots: Option<PathBuf>,
    /// Input to replay, one step per finished picture: `drag DX DY; pan DX DY; zoom N; key K;
    /// orbit S` (a steady drag for S seconds, then the frames shown and their rate).
    #[arg(long)]
    pub script: Option<String>,
    /// Close after this many finished pictures, saved or not (a still scene makes one, then one
    /// per script step and per save of its file; a running `time` makes one per frame).
    #[arg(long, value_name = "N")]
    pub quit_after: Option<u32>,
    /// Hold the scene's `time` at T seconds (space lets it run); it runs with the clock
    /// otherwise.
    #[arg(long, allow_hyphen_values = true)]
    pub time: Option<f64>,
    /// Open a scene whose shader the driver is predicted to take longer than 30 s to compile
    /// (as `render`).
    #[arg(long)]
    pub allow_slow_compile: bool,
    #[command(flatten)]
    pub bake: BakeArgs,
}

/// `sdfc bench`'s arguments.
#[derive(Args)]
pub struct BenchArgs {
    /// The scene file (`-` for standard input).
    pub file: PathBuf,
    /// Tracers to measure, comma-separated.
    #[arg(long, default_value = "basic,relaxed,enhanced,hybrid,auto")]
    pub tracers: String,
    /// Step budgets, comma-separated.
    #[arg(long, default_value = "8,16,32,64,128,256")]
    pub steps: String,
    /// Hit threshold for every tracer instead of the scene's: a distance, or `pixel`.
    #[arg(long, allow_hyphen_values = true)]
    pub epsilon: Option<String>,
    /// Image size.
    #[arg(long, default_value = "320x180")]
    pub size: String,
    /// Renders per cell; the median time is reported.
    #[arg(long, default_value_t = 3)]
    pub repeat: u32,
    /// Report the fastest tracer and budget whose mean squared depth error is at most this.
    #[arg(long, allow_hyphen_values = true)]
    pub target_error: Option<f64>,
    /// With `--target-error`: the largest share of pixels whose hit/miss may differ.
    #[arg(long, default_value_t = 0.01)]
    pub max_mismatch: f64,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Print CSV instead of the table.
    #[arg(long, conflicts_with = "json")]
    pub csv: bool,
    /// Also draw error against time and against evaluations per pixel to this `.svg` or `.png`.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Graphics API: Vulkan, then GL, or one of them.
    #[arg(long, value_enum, default_value = "auto")]
    pub backend: BackendArg,
    /// Also measure every cell with this many multi-resolution passes (Bálint §4): 2, 4 or 6.
    #[arg(long, default_value_t = 1)]
    pub passes: u32,
    /// A hand-written WGSL tracer (runtime/benches/reference/README.md gives its interface)
    /// timed alternately with each cell's trace, same view and size.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Measure the error against this scene's f64 ground truth instead of the benchmarked
    /// scene's own (the same camera): e.g. the analytic form of a scene whose parts are baked
    /// (docs/bake.md).
    #[arg(long, value_name = "FILE")]
    pub truth: Option<PathBuf>,
    /// Measure the scene once per resolution, every `bake` at N (comma-separated, e.g.
    /// `32,64,128,256`), and the `--truth` scene itself, all against its one f64 truth:
    /// Liktor's Table 1 with the error beside the time, plus bake time and memory per part.
    #[arg(long, value_name = "N,N,…", requires = "truth", conflicts_with_all = ["bake_res", "csv", "plot", "target_error", "reference"])]
    pub bake_sweep: Option<String>,
    /// Test every union's bounding boxes in `map` (as `render --bvh`).
    #[arg(long, conflicts_with = "no_bvh")]
    pub bvh: bool,
    /// No bounding-box tests in `map` (as `render --no-bvh`).
    #[arg(long)]
    pub no_bvh: bool,
    /// Start secondary rays a fixed 2·ε_floor off the surface (as `render --fixed-offset`).
    #[arg(long)]
    pub fixed_offset: bool,
    /// Measure a shader larger than the driver compiles in reasonable time (as `render`).
    #[arg(long)]
    pub allow_slow_compile: bool,
    /// How `map` holds the scene (as `render --form`): `data` measures the scene as data,
    /// pruned per cell, and reports the pre-pass's time.
    #[arg(long, value_enum, default_value = "auto")]
    pub form: super::tracer::FormArg,
    /// The data form's grid: cells along its longest side, 1 to 128 (as `render --cells`).
    #[arg(long, value_name = "N")]
    pub cells: Option<usize>,
    /// Where the data form's cells are pruned (as `render --prepass`): `auto` (the default),
    /// `gpu` or `cpu`.
    #[arg(long, value_enum, value_name = "WHERE")]
    pub prepass: Option<super::tracer::PrepassArg>,
    /// Also count primitive evaluations per pixel, of the trace and of shading (compiles the
    /// trace and the frame once more with a counter in every primitive's function; not timed).
    #[arg(long)]
    pub count_primitives: bool,
    /// Skip the f64 ground truth (its CPU time grows with the parts: thousands of them take
    /// hours): the errors are then reported as absent (`null` in JSON).
    #[arg(long, conflicts_with_all = ["truth", "target_error", "bake_sweep"])]
    pub no_truth: bool,
    #[command(flatten)]
    pub bake: BakeArgs,
}

/// `sdfc completions`'s arguments.
#[derive(Args)]
pub struct CompletionsArgs {
    /// The shell.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
    /// Output file (default, or `-`: standard output).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// `sdfc man`'s arguments.
#[derive(Args)]
pub struct ManArgs {
    /// A subcommand's page (`sdfc man render`: sdfc-render(1)) instead of sdfc(1).
    pub subcommand: Option<String>,
    /// Write every page — sdfc.1 and one per subcommand, sdfc-render.1… — into this folder
    /// (created if missing), for `man -M` or a MANPATH entry.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["subcommand", "output"])]
    pub dir: Option<PathBuf>,
    /// The subcommand's synopsis as plain text (the README's is this), not a page.
    #[arg(long, requires = "subcommand")]
    pub synopsis: bool,
    /// Output file (default, or `-`: standard output).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// `sdfc mesh`'s arguments.
#[derive(Args)]
pub struct MeshArgs {
    /// The scene file (`-` for standard input).
    pub file: PathBuf,
    /// Output file: `.stl`, `.obj` (with its `.mtl` beside it), `.ply` (colour per vertex) or
    /// `.glb` (binary glTF); `-` with `--format` for standard output.
    #[arg(short = 'o', long = "output", value_name = "OUT")]
    pub output: PathBuf,
    /// The file format, when the output's extension does not say it.
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub format: Option<super::values::MeshFormatArg>,
    /// Cells along the box's longest side.
    #[arg(long, default_value_t = 128, value_name = "N", conflicts_with = "cell")]
    pub resolution: u32,
    /// The cells' edge length in scene units (instead of `--resolution`).
    #[arg(long, value_name = "SIZE")]
    pub cell: Option<f64>,
    /// About this many triangles (instead of `--resolution` or `--cell`): the resolution is
    /// chosen from a coarse mesh's count (triangles grow with its square), then corrected once;
    /// the success line says what it chose and how near the count came.
    #[arg(long, value_name = "N", conflicts_with_all = ["resolution", "cell"])]
    pub triangles: Option<u64>,
    /// The box to mesh, `X0,Y0,Z0,X1,Y1,Z1`: the surface is cut there and capped, so the
    /// mesh stays closed. Default: the scene's own finite box, grown by 1%.
    #[arg(long, value_name = "X0,Y0,Z0,X1,Y1,Z1", allow_hyphen_values = true)]
    pub bounds: Option<String>,
    /// `sharp`: each cell's vertex where the surface's tangent planes meet, and the creases'
    /// points on the cells' faces (corners and edges kept); `plain`: the mean of the edge
    /// crossings, as marching cubes places them (chamfered edges; the baseline).
    #[arg(long, value_enum, default_value = "sharp")]
    pub method: super::values::MeshMethodArg,
    /// Where the field is evaluated: the octree's blocks, the corners, the edge crossings, the
    /// vertices' Newton steps and the measuring, in batches — on the GPU in f32 (the scene's
    /// `map` as the pictures compile it) or on all cores in f64. `auto`: the GPU when the
    /// scene costs at least 16 primitive evaluations a point (below that the CPU is as fast
    /// as opening a device), the CPU if no device opens.
    #[arg(long, value_enum, default_value = "auto")]
    pub backend: super::values::MeshBackendArg,
    /// Contour every cell of the grid instead of only those the field's bound cannot rule out
    /// (the brute-force baseline the pruning is measured against; memory grows with the cube
    /// of the resolution).
    #[arg(long)]
    pub no_prune: bool,
    /// Refuse, before the fine work, a mesh estimated to need more memory than this (GiB).
    #[arg(long, default_value_t = 8.0, value_name = "GIB")]
    pub max_memory: f64,
    /// Set a scene parameter: `NAME=VALUE`, as `sdfc render --param`.
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// The scene's `time`, in seconds (default 0).
    #[arg(long, allow_hyphen_values = true, value_name = "T")]
    pub time: Option<f64>,
    /// Print when each step starts and what the mesh cost (cells, field evaluations).
    #[arg(long)]
    pub stats: bool,
    #[command(flatten)]
    pub bake: BakeArgs,
}

/// `sdfc serve`'s arguments.
#[derive(Args)]
pub struct ServeArgs {
    /// The folder to serve: by default the playground as `scripts/build_web.sh` assembles it
    /// (`target/web`, relative to the current folder).
    pub dir: Option<PathBuf>,
    /// The port; 0 takes a free one (the address printed says which).
    #[arg(long, default_value_t = 8000, value_name = "PORT")]
    pub port: u16,
    /// The address to listen on: this machine only by default; `0.0.0.0` for every network.
    #[arg(long, default_value = "127.0.0.1", value_name = "ADDRESS")]
    pub host: std::net::IpAddr,
}
