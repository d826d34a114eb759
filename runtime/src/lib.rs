//! sdfc's runtime: the headless wgpu renderer and the pictures it writes.

pub mod bench;
pub mod files;
pub mod frames;
pub mod gpu;
pub mod images;
pub mod orbit;
pub mod plot;
pub mod present;
