//! sdfc's runtime: the headless wgpu renderer (`gpu`), the pictures it writes (`images`,
//! `files`) and the tracers' benchmark (`bench`). The command line (`main.rs`: `cli`, `cmd`,
//! `view`) is built on it.

pub mod bake_gpu;
pub mod bake_store;
pub mod bench;
pub mod files;
pub mod gpu;
pub mod images;
pub mod mesh_gpu;
