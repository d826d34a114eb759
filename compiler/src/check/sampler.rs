//! Where a bake's samples may come from besides the CPU: a host's sampler (the runtime's
//! evaluates the part's `map` on the GPU with the field-list entry of the same lowering).

use crate::bake::Grid;
use crate::scene::Scene;
use std::sync::RwLock;

/// Evaluates a part's field at many points at once.
pub trait Sampler: Send + Sync {
    /// The field of `part` (its root's `map`: divided by its λ, which keeps every sign and
    /// every crossing's place) at every point of `grid` in index order (x fastest), or `None`
    /// when it cannot (the CPU samples then).
    fn sample(&self, part: &Scene, grid: &Grid) -> Option<Vec<f64>>;
}

/// The host's sampler, if it set one.
static SAMPLER: RwLock<Option<Box<dyn Sampler>>> = RwLock::new(None);

/// Sets (or clears) the sampler bakes use for grids of at least [`MIN_WORK`].
pub fn set_sampler(sampler: Option<Box<dyn Sampler>>) {
    *SAMPLER.write().unwrap_or_else(|e| e.into_inner()) = sampler;
}

/// Fewest primitive evaluations (points × the part's evaluations per point) for which the
/// host's sampler is used: below it the CPU's near-surface sampling is as fast (a device to
/// open and a shader to compile cost more than the work; `docs/bake.md`).
pub const MIN_WORK: f64 = 2e7;

/// The part's field on `grid` from the host's sampler when `work` is worth it, else `None`.
pub fn sample(part: &Scene, grid: &Grid, work: f64) -> Option<Vec<f64>> {
    if work < MIN_WORK {
        return None;
    }
    let sampler = SAMPLER.read().unwrap_or_else(|e| e.into_inner());
    let values = sampler.as_ref()?.sample(part, grid)?;
    (values.len() == grid.len() && values.iter().all(|v| !v.is_nan())).then_some(values)
}
