//! The command line's value enums (`--spirv-version`, `--backend`, `--target`, `--entry`) and
//! what they stand for in the runtime and the compiler.

use sdfc_compiler::emit::Target;
use sdfc_compiler::lower::Entry;

/// A SPIR-V version.
#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum SpirvVersion {
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
    pub(crate) fn pair(self) -> (u8, u8) {
        (1, self as u8)
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum BackendArg {
    Auto,
    Vulkan,
    Gl,
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum TargetArg {
    Wgsl,
    Spirv,
    Glsl,
    Msl,
    Hlsl,
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum EntryArg {
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
