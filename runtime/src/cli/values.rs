//! The command line's values (`--spirv-version`, `--glsl-version`, `--backend`, `--target`,
//! `--entry`, `--size`, `sdfc mesh`'s `--format` and `--method`) and what they stand for in the
//! runtime and the compiler.

use super::Error;
use sdfc_compiler::emit::{self, Target};
use sdfc_compiler::lower::Entry;

/// A SPIR-V version.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum SpirvVersion {
    #[value(name = "1.0")]
    V10,
    #[value(name = "1.1")]
    V11,
    #[value(name = "1.2")]
    V12,
    #[value(name = "1.3")]
    V13,
    #[value(name = "1.4")]
    V14,
    #[value(name = "1.5")]
    V15,
    #[value(name = "1.6")]
    V16,
}

impl SpirvVersion {
    pub fn pair(self) -> (u8, u8) {
        (1, self as u8)
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub enum BackendArg {
    Auto,
    Vulkan,
    Gl,
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub enum TargetArg {
    Wgsl,
    Spirv,
    Glsl,
    Msl,
    Hlsl,
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub enum EntryArg {
    Compute,
    Fragment,
    Library,
    /// The trace-only compute entry `sdfc bench` times (t and steps per pixel).
    Trace,
    /// A Shadertoy Image shader: GLSL ES 3.00 with `mainImage`, `iTime` for `time`, an orbit
    /// camera on `iMouse` (target glsl).
    Shadertoy,
}

impl From<BackendArg> for sdfc::gpu::BackendChoice {
    fn from(b: BackendArg) -> Self {
        match b {
            BackendArg::Auto => sdfc::gpu::BackendChoice::Auto,
            BackendArg::Vulkan => sdfc::gpu::BackendChoice::Vulkan,
            BackendArg::Gl => sdfc::gpu::BackendChoice::Gl,
        }
    }
}

impl From<TargetArg> for Target {
    fn from(t: TargetArg) -> Target {
        match t {
            TargetArg::Wgsl => Target::Wgsl,
            TargetArg::Spirv => Target::Spirv,
            TargetArg::Glsl => Target::Glsl,
            TargetArg::Msl => Target::Msl,
            TargetArg::Hlsl => Target::Hlsl,
        }
    }
}

impl From<EntryArg> for Entry {
    fn from(e: EntryArg) -> Entry {
        match e {
            EntryArg::Compute => Entry::Compute,
            EntryArg::Fragment => Entry::Fragment,
            EntryArg::Library => Entry::Library,
            EntryArg::Trace => Entry::Trace,
            EntryArg::Shadertoy => Entry::Library,
        }
    }
}

/// `--glsl-version`.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum GlslVersionArg {
    /// Desktop GLSL 4.50 core.
    #[value(name = "450")]
    Core450,
    /// GLSL ES 3.10.
    #[value(name = "310es")]
    Es310,
    /// GLSL ES 3.00.
    #[value(name = "300es")]
    Es300,
}

impl From<GlslVersionArg> for emit::GlslVersion {
    fn from(v: GlslVersionArg) -> Self {
        match v {
            GlslVersionArg::Core450 => emit::GlslVersion::Core450,
            GlslVersionArg::Es310 => emit::GlslVersion::Es310,
            GlslVersionArg::Es300 => emit::GlslVersion::Es300,
        }
    }
}

/// Parses `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32), Error> {
    let bad = || format!("error: `--size {s}` is not WIDTHxHEIGHT, e.g. `--size 1280x720`");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (
        w.trim().parse().map_err(|_| bad())?,
        h.trim().parse().map_err(|_| bad())?,
    );
    if w == 0 || h == 0 {
        return Err(format!("error: the image size {w}x{h} is empty").into());
    }
    if w > sdfc::gpu::MAX_SIDE || h > sdfc::gpu::MAX_SIDE {
        return Err(format!(
            "error: the image size {w}x{h} is too large (at most {} per side)",
            sdfc::gpu::MAX_SIDE
        )
        .into());
    }
    Ok((w, h))
}

/// `sdfc mesh --format`.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum MeshFormatArg {
    Stl,
    Obj,
    Ply,
    Glb,
}

impl From<MeshFormatArg> for sdfc_compiler::mesh::formats::Format {
    fn from(f: MeshFormatArg) -> Self {
        use sdfc_compiler::mesh::formats::Format;
        match f {
            MeshFormatArg::Stl => Format::Stl,
            MeshFormatArg::Obj => Format::Obj,
            MeshFormatArg::Ply => Format::Ply,
            MeshFormatArg::Glb => Format::Glb,
        }
    }
}

/// `sdfc mesh --backend`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MeshBackendArg {
    /// The GPU (Vulkan, then GL) for a scene whose evaluation is costly, else the CPU.
    Auto,
    /// The CPU in f64 (the reference).
    Cpu,
    /// Vulkan only (lavapipe on machines without a GPU).
    Vulkan,
    /// GL only (llvmpipe over EGL on machines without a GPU).
    Gl,
}

/// `sdfc mesh --method`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MeshMethodArg {
    Sharp,
    Plain,
}
