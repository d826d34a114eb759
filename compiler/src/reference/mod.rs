//! The CPU reference, in f64: the scene's field, materials and blends, textures, shading, every
//! tracer, and the ground truth the GPU output and the benchmarks are checked against.
//!
//! These are the lowering's twins: each mirrors what the emitted shader computes, from the same
//! scene graph, so that tests compare the two.

pub mod blend;
pub mod eval;
pub mod pixel;
pub mod shading;
pub mod texture;
pub mod trace;
pub mod truth;
