//! Meshes evaluated on the GPU: the compiler's `mesh::field::Evaluator` running the scene's
//! `map` from the field-list entry (`Entry::Field`) of the same lowering as the pictures, a
//! batch of the mesher's points per dispatch, in f32.

use crate::gpu::{BackendChoice, Gpu, ListProgram};
use glam::DVec3;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::mesh::field::Evaluator;
use sdfc_compiler::scene::Scene;

/// Most points per dispatch (16 bytes in and out each).
pub const POINTS_PER_DISPATCH: usize = 1 << 20;

/// The scene's field on a device of its own, its pipeline compiled once.
pub struct GpuField {
    gpu: Gpu,
    program: ListProgram,
    /// f32's rounding at the largest coordinate the mesher asks about.
    resolution: f64,
}

impl GpuField {
    /// Compiles the scene's field entry and opens a device for it; `bounds` is the box being
    /// meshed (its largest coordinate sets the resolution).
    pub fn new(
        scene: &Scene,
        choice: BackendChoice,
        bounds: (DVec3, DVec3),
    ) -> Result<GpuField, String> {
        let gpu = Gpu::new(choice).map_err(|e| e.to_string())?;
        GpuField::on(gpu, scene, bounds)
    }

    /// [`GpuField::new`] on a device already open (its scene parameters and volumes are set
    /// to the scene's).
    pub fn on(gpu: Gpu, scene: &Scene, bounds: (DVec3, DVec3)) -> Result<GpuField, String> {
        let (module, _) = emit::module(scene, Entry::Field, &Options::from_scene(scene))
            .map_err(|e| format!("{e:?}"))?;
        gpu.set_scene(scene);
        let program = gpu.list_program(&module);
        // A cell beyond the box reaches a little past it: twice its largest coordinate.
        let largest = bounds.0.abs().max(bounds.1.abs()).max_element().max(1e-30);
        Ok(GpuField {
            program,
            resolution: 2.0 * f64::from(f32::EPSILON) * largest,
            gpu,
        })
    }

    /// What the device is (for the success line).
    pub fn device_name(&self) -> &str {
        &self.gpu.info.name
    }
}

impl Evaluator for GpuField {
    fn values(&self, points: &[DVec3]) -> Option<Vec<f64>> {
        let mut out = Vec::with_capacity(points.len());
        for chunk in points.chunks(POINTS_PER_DISPATCH) {
            let list: Vec<[f32; 3]> = chunk.iter().map(|p| p.as_vec3().to_array()).collect();
            let values = self.gpu.eval_points_with(&self.program, &list).ok()?;
            out.extend(values.into_iter().map(f64::from));
        }
        Some(out)
    }

    fn resolution(&self) -> f64 {
        self.resolution
    }
}
