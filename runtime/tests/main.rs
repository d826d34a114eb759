//! The runtime's integration tests as one binary (as naga's `tests/naga/main.rs`): each file of
//! this folder is a module, its tests named `<file>::<test>`, and `common` (what they share, the
//! pooled GPU devices among it) is compiled once.

mod common;

mod bake;
mod bench;
mod blends;
mod bounded;
mod browser;
mod budget;
mod cli;
mod compile_cost;
mod data_form;
mod device;
mod diagnostics;
mod extremes;
mod f32_limits;
mod field;
mod fragment;
mod fuzz_render;
mod golden;
mod host;
mod hostile;
mod lipschitz;
mod mesh;
mod nan;
mod options;
mod outputs;
mod params;
mod playground;
mod prepass;
mod render;
mod shading;
mod shadows;
mod streams;
mod textures;
mod tracers;
mod view;
mod view_params;
mod watch;
mod web;
mod webgl2;
