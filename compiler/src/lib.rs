//! sdfc's compiler: the scene language's syntax, checker, catalog, Lipschitz bounds and CPU
//! reference evaluator, lowering to naga IR and emitting code.

// pest_derive without its `std` feature (see the workspace's Cargo.toml) names `::alloc`.
extern crate alloc;

pub mod bake;
pub mod catalog;
pub mod check;
pub mod color;
pub mod cost;
pub mod diag;
pub mod docs;
pub mod emit;
pub mod interval;
pub mod ir;
pub mod layout;
pub mod lipschitz;
pub mod lower;
pub mod manifest;
pub mod mesh;
pub mod parallel;
pub mod passes;
pub mod reference;
pub mod scene;
pub mod shadertoy;
pub mod source;
pub mod syntax;
pub mod tape;
pub mod view;
