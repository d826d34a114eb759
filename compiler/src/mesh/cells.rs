//! Which cells the surface may cross: an octree over the grid, a block dropped when the field's
//! bound proves the surface misses it (|d(centre)| > half-diagonal), so that the work grows with
//! the surface's area rather than the volume.

use super::field::{Field, Grid};
use super::par_map;
use glam::IVec3;

/// The cells a surface may cross, and what finding them cost.
pub struct Active {
    /// The cells (their lowest corners in grid units), in no particular order.
    pub cells: Vec<IVec3>,
    /// Field evaluations spent (one per octree block tested).
    pub evaluations: usize,
}

/// The octree's blocks at one level that the coarse pass stops at (8³ cells each) before the
/// memory estimate is made.
pub const COARSE: i32 = 8;

/// Finds the cells of `grid` that the surface of `field` may cross. `budget` is called once,
/// with the number of 8³-cell blocks the surface may cross, before the finer levels run; an
/// error from it stops the work.
pub fn active<E>(
    field: &Field,
    grid: &Grid,
    budget: impl FnOnce(usize) -> Result<(), E>,
) -> Result<Active, E> {
    let levels = (grid.n.max_element().max(1) as u32)
        .next_power_of_two()
        .trailing_zeros() as i32;
    let mut size = 1i32 << levels;
    let mut blocks = vec![IVec3::ZERO];
    let mut evaluations = 0;
    let mut budget = Some(budget);
    loop {
        let keep = par_map(&blocks, |&b| {
            let centre = grid.origin + (b.as_dvec3() + 0.5 * size as f64) * grid.h;
            let reach = 0.5 * 3f64.sqrt() * size as f64 * grid.h;
            // A margin for rounding: a block kept in doubt costs only time.
            let d = field.at(centre).abs();
            d.is_nan() || d <= reach * (1.0 + 1e-9)
        });
        evaluations += blocks.len();
        blocks = blocks
            .into_iter()
            .zip(keep)
            .filter_map(|(b, k)| k.then_some(b))
            .collect();
        if size == COARSE.min(1 << levels)
            && let Some(check) = budget.take()
        {
            check(blocks.len())?;
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
            .flat_map(|&b| (0..8).map(move |i| b + IVec3::new(i & 1, (i >> 1) & 1, i >> 2) * size))
            .filter(|c| c.cmplt(grid.n).all())
            .collect();
    }
}
