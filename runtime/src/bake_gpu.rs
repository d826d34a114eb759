//! Bakes sampled on the GPU: the compiler's `check::sampler::Sampler` evaluating a part's `map`
//! with the mesher's `GpuField` (the field-list entry of the same lowering), slab by slab, on a
//! device of its own opened at the first bake that needs it.

use crate::gpu::{BackendChoice, Gpu};
use crate::mesh_gpu::{GpuField, POINTS_PER_DISPATCH};
use sdfc_compiler::bake::Grid;
use sdfc_compiler::check::sampler::Sampler;
use sdfc_compiler::mesh::field::Evaluator;
use sdfc_compiler::scene::Scene;
use std::sync::Mutex;

/// The GPU sampler; its device is opened when first needed (`None` inside once that failed:
/// the CPU samples from then on).
pub struct GpuSampler {
    gpu: Mutex<Option<Option<Gpu>>>,
}

impl GpuSampler {
    /// A sampler that has not opened its device yet.
    pub fn new() -> GpuSampler {
        GpuSampler {
            gpu: Mutex::new(None),
        }
    }
}

impl Default for GpuSampler {
    fn default() -> Self {
        GpuSampler::new()
    }
}

impl Sampler for GpuSampler {
    fn sample(&self, part: &Scene, grid: &Grid) -> Option<Vec<f64>> {
        let mut slot = self.gpu.lock().unwrap_or_else(|e| e.into_inner());
        let gpu = slot
            .get_or_insert_with(|| Gpu::new(BackendChoice::Auto).ok())
            .as_ref()?;
        // The part's field, its pipeline compiled once for every slab.
        let field = GpuField::on(gpu.clone(), part, (grid.lo, grid.hi)).ok()?;
        let [nx, ny, nz] = grid.n;
        // Whole z-slices at a time.
        let slices = (POINTS_PER_DISPATCH / (nx * ny)).max(1);
        let mut out = Vec::with_capacity(grid.len());
        for k0 in (0..nz).step_by(slices) {
            let points: Vec<glam::DVec3> = (k0..(k0 + slices).min(nz))
                .flat_map(|k| (0..ny).flat_map(move |j| (0..nx).map(move |i| [i, j, k])))
                .map(|[i, j, k]| grid.point(i, j, k))
                .collect();
            out.extend(field.values(&points)?);
        }
        Some(out)
    }
}
