//! Which cells the surface may cross: an octree over the grid, a block dropped when the field's
//! bound proves the surface misses it (|d(centre)| > half-diagonal), so that the work grows with
//! the surface's area rather than the volume.

use super::field::{Field, Grid, corner};
use glam::IVec3;

/// The cells a surface may cross, and what finding them cost.
pub struct Active {
    /// The cells (their lowest corners in grid units), in no particular order.
    pub cells: Vec<IVec3>,
    /// Field evaluations spent (one per octree block tested).
    pub evaluations: usize,
}

/// Every cell of `grid`, none pruned (the brute-force baseline).
pub fn every(grid: &Grid) -> Active {
    let n = grid.n;
    let cells = (0..n.z)
        .flat_map(|z| (0..n.y).flat_map(move |y| (0..n.x).map(move |x| IVec3::new(x, y, z))))
        .collect();
    Active {
        cells,
        evaluations: 0,
    }
}

/// The largest blocks (in cells along a side) whose count [`active`] reports to its budget:
/// a block this small that the surface may cross holds about its side² cells of the surface.
pub const ESTIMATED_FROM: i32 = 512;

/// Finds the cells of `grid` that the surface of `field` may cross. `budget` is called after
/// each level of blocks of at most [`ESTIMATED_FROM`] cells a side, with their count and side,
/// before the finer levels run; an error from it stops the work.
pub fn active<E>(
    field: &Field,
    grid: &Grid,
    budget: impl Fn(usize, i32) -> Result<(), E>,
) -> Result<Active, E> {
    let levels = (grid.n.max_element().max(1) as u32)
        .next_power_of_two()
        .trailing_zeros() as i32;
    let mut size = 1i32 << levels;
    let mut blocks = vec![IVec3::ZERO];
    let mut evaluations = 0;
    loop {
        let reach = 0.5 * 3f64.sqrt() * size as f64 * grid.h;
        let centres: Vec<_> = blocks
            .iter()
            .map(|&b| grid.origin + (b.as_dvec3() + 0.5 * size as f64) * grid.h)
            .collect();
        // A margin for rounding (f32's where the batches are): a block kept in doubt costs
        // only time.
        let limit = reach * (1.0 + 1e-9) + 64.0 * field.resolution();
        let keep: Vec<bool> = field
            .many(&centres)
            .into_iter()
            .map(|d| d.is_nan() || d.abs() <= limit)
            .collect();
        evaluations += blocks.len();
        blocks = blocks
            .into_iter()
            .zip(keep)
            .filter_map(|(b, k)| k.then_some(b))
            .collect();
        if size <= ESTIMATED_FROM {
            budget(blocks.len(), size)?;
        }
        if size == 1 {
            return Ok(Active {
                cells: blocks,
                evaluations,
            });
        }
        size /= 2;
        blocks = blocks
            .iter()
            .flat_map(|&b| (0..8).map(move |i| b + corner(i) * size))
            .filter(|c| c.cmplt(grid.n).all())
            .collect();
    }
}
