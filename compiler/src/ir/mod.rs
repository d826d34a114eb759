//! naga IR built by hand: a typed builder of modules and functions, and short names for math.
//!
//! The lowest layer of the compiler that knows naga: it knows nothing of scenes, shapes or
//! tracers, so the catalog's shader bodies and the lowering both build on it.

pub mod builder;
mod math;

pub use builder::{Ex, FnBuilder, ModuleBuilder};
