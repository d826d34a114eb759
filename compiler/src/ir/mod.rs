//! naga IR built by hand: a typed builder of modules and functions, and short names for math.
//!
//! The lowest layer of the compiler that knows naga: it knows nothing of scenes, shapes or
//! tracers, so the catalog's shader bodies and the lowering both build on it.

pub mod builder;
pub mod control;
mod math;

pub use builder::{Ex, FnBuilder, ModuleBuilder};
pub use control::Arm;

/// A distance farther than any a scene can have, where IR needs a "nothing yet" (a union's
/// running minimum before its first part). Not `f32::MAX`: naga's WGSL and GLSL writers print
/// that as `340282350000000000000000000000000000000f` / `3.4028235e38`, a decimal above f32's
/// largest value, which Chrome's WGSL compiler (Tint) refuses and some GL drivers read as
/// infinity. 1e30 prints as itself, is exactly a decimal within f32's range, lies far beyond
/// `catalog::GPU_RANGE` (every number of a scene is at most 1e18), and its square still
/// overflows f32 to +∞, as `f32::MAX`'s did (the box tests compare squared distances).
pub const FAR: f64 = 1e30;
