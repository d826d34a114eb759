//! What the runtime's test files share: the example scenes, compiling, the GPU.
#![allow(dead_code)]

use sdfc::gpu::{BackendChoice, Gpu};
use sdfc_compiler::check::tracer::TRACE_METHODS;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::scene::{Method, Scene, Trace};
use std::path::PathBuf;

/// The example scene files, sorted.
pub fn examples() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "sdf"))
        .collect();
    v.sort();
    v
}

/// A checked scene, or a panic with the diagnostics.
pub fn compile(source: &str) -> Scene {
    let checked = sdfc_compiler::check::compile(source);
    checked.scene.unwrap_or_else(|| {
        panic!(
            "{}",
            sdfc_compiler::diag::render(&checked.diagnostics, "test", source)
        )
    })
}

/// The Vulkan device (lavapipe in CI).
pub fn gpu() -> Gpu {
    Gpu::new(BackendChoice::Vulkan)
        .unwrap_or_else(|e| panic!("{e}\n(CI installs Mesa's drivers in .ci/run)"))
}

/// Traces rays with the scene's `Entry::Rays` module: (t, steps, flags) per ray.
pub fn gpu_trace(
    gpu: &Gpu,
    scene: &Scene,
    rays: &[([f32; 3], [f32; 3], f32)],
) -> Vec<(f32, u32, u32)> {
    let (module, _) = emit::module(scene, Entry::Rays, &Options::from_scene(scene))
        .unwrap_or_else(|e| panic!("{}", e.0));
    gpu.trace_rays(&module, rays).unwrap()
}

/// The scene's tracer settings switched to `method` (its defaults for the rest).
pub fn with_method(scene: &Scene, method: Method) -> Trace {
    let name = TRACE_METHODS.iter().find(|m| m.1 == method).unwrap().0;
    sdfc_compiler::check::tracer::with_overrides(scene.trace, Some(name), &[]).unwrap()
}

/// The camera rays through image points, as the GPU's ray list takes them.
pub fn camera_rays(
    view: &sdfc_compiler::view::View,
    pts: &[(f64, f64)],
) -> Vec<([f32; 3], [f32; 3], f32)> {
    pts.iter()
        .map(|&(x, y)| {
            let d = view.ray(x, y);
            (
                view.eye.to_array().map(|v| v as f32),
                d.to_array().map(|v| v as f32),
                view.pixel as f32,
            )
        })
        .collect()
}
