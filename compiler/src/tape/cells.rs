//! Lipschitz pruning (Barbier, Sanchez et al. 2025, §4): the part tree that decides the field
//! inside a cell of space. Every proven child of a fold is bounded over the cell by its value at
//! the cell's centre ± the cell's half-diagonal in the fold's own units (its value is
//! 1-Lipschitz there), and the children are walked in the fold's order with bounds of the
//! running result:
//!
//! - a child that stays `k` beyond the running result (above it for a minimum, below for a
//!   maximum) is dropped: the smooth blend's kernel is zero at a gap of `k` (a sharp one's at
//!   any gap), so the result is the running one, bit for bit;
//! - a child that stays `k` beyond on the other side replaces everything before it: the result
//!   is the child's own value;
//! - otherwise it is kept, and the running result's bounds follow it: for IQ's quadratic
//!   smooth minimum of radius k, min(a, b) − k/4 ≤ smin(a, b) ≤ min(a, b), and a whole chain of
//!   them stays above the smallest operand − k (see [`keep`]).
//!
//! Inside the cell the pruned tree's value and material equal the whole tree's (the property
//! `tests/tape.rs` checks on random trees and cells); outside it they need not.

use super::eval::value;
use super::{Part, PartKind, Way};
use crate::scene::Scene;
use glam::DVec3;

/// Relative margin on every bound, for the rounding of the values they are made of.
const MARGIN: f64 = 1e-9;

/// `part` pruned to the cell around `center` of half-diagonal `radius` (world units).
pub fn prune(scene: &Scene, part: &Part, center: DVec3, radius: f64) -> Part {
    prune_bounded(scene, part, center, radius).0
}

/// [`prune`], with a lower bound of the whole part's value over the cell where it is a proven
/// fold: its result's bounds as the walk of [`keep_bounded`] ends with them, times its factor
/// — what far-field culling marks a cell by (`data::far_count`; the device's pre-pass takes the
/// same from its frame, `lower/data/prune/first.rs`).
pub fn prune_bounded(
    scene: &Scene,
    part: &Part,
    center: DVec3,
    radius: f64,
) -> (Part, Option<f64>) {
    let PartKind::Fold { way, k, children } = &part.kind else {
        return (part.clone(), None);
    };
    let bounds = child_bounds(scene, part, center, radius);
    let (kept, (lo, hi)) = keep_bounded(*way, *k, &bounds);
    let lower = part.proven.then(|| {
        let raw = match way {
            Way::Min => lo,
            Way::Max => -hi,
        };
        raw * part.factor
    });
    let children = kept
        .into_iter()
        .map(|i| {
            let (c, negate) = &children[i];
            (prune(scene, c, center, radius), *negate)
        })
        .collect();
    // (Field by field: `..part.clone()` would copy the whole subtree only to drop it.)
    let pruned = Part {
        kind: PartKind::Fold {
            way: *way,
            k: *k,
            children,
        },
        node: part.node,
        id: part.id,
        frame: part.frame,
        zoom: part.zoom,
        factor: part.factor,
        material: part.material,
        proven: part.proven,
        loose: part.loose,
    };
    (pruned, lower)
}

/// The bounds of fold `part`'s children's values (negated where it negates them) over the cell
/// around `center` of half-diagonal `radius`: their parent's point moves by zoom × radius.
fn child_bounds(scene: &Scene, part: &Part, center: DVec3, radius: f64) -> Vec<(f64, f64)> {
    let PartKind::Fold { children, .. } = &part.kind else {
        return Vec::new();
    };
    let reach = part.zoom * radius * (1.0 + MARGIN) + MARGIN;
    children
        .iter()
        .map(|(c, negate)| {
            if !c.proven {
                return (f64::NEG_INFINITY, f64::INFINITY);
            }
            let v = value(scene, c, center);
            let v = if *negate { -v } else { v };
            let slack = reach + MARGIN * v.abs();
            (v - slack, v + slack)
        })
        .collect()
}

/// Which of a fold's children, with values within `bounds` (already negated where the fold
/// negates), can change its result: their indices in order.
///
/// For a minimum with k > 0, the running result r after keeping operands a₁…aₙ satisfies
/// r > min(aᵢ) − k: each smooth step subtracts h²k/4 with h = (k − |r − a|)/k, and with
/// δ = (min − r)/k a step gives at most δ + (1 − δ)²/4 < 1 whenever δ < 1. A maximum mirrors it.
pub fn keep(way: Way, k: f64, bounds: &[(f64, f64)]) -> Vec<usize> {
    keep_bounded(way, k, bounds).0
}

/// [`keep`], with the bounds of the fold's result over the cell that the walk ends with (as a
/// minimum sees them: a maximum's negated): what the pre-pass marks a far cell by.
pub fn keep_bounded(way: Way, k: f64, bounds: &[(f64, f64)]) -> (Vec<usize>, (f64, f64)) {
    // Work on minima: a maximum's bounds are negated (max(a, b) = −min(−a, −b), smoothly too).
    let flip = |(lo, hi): (f64, f64)| match way {
        Way::Min => (lo, hi),
        Way::Max => (-hi, -lo),
    };
    let mut kept: Vec<usize> = Vec::new();
    let (mut lo, mut hi) = (f64::INFINITY, f64::INFINITY);
    let mut lowest = f64::INFINITY;
    for (i, &b) in bounds.iter().enumerate() {
        let (blo, bhi) = flip(b);
        if kept.is_empty() {
            kept.push(i);
            (lo, hi, lowest) = (blo, bhi, blo);
        } else if blo > hi + k {
            // Always k above the running result: it never blends in, never is the smallest.
        } else if bhi + k < lo {
            // Always k below: the result is this child's value from here.
            kept.clear();
            kept.push(i);
            (lo, hi, lowest) = (blo, bhi, blo);
        } else {
            kept.push(i);
            hi = hi.min(bhi);
            lowest = lowest.min(blo);
            let dip = if k > 0.0 { k / 4.0 } else { 0.0 };
            lo = (lo.min(blo) - dip).max(lowest - k);
        }
    }
    (kept, (lo, hi))
}

/// Cells a side of the coarser grid a fine one is pruned from (see [`map_grid`]). Measured on
/// 1000 blended spheres at 64 cells a side: 298 ms for the whole pre-pass with 2 (levels of
/// 64, 32, 16, 8, 4), 326 ms with 4 (64, 16, 4).
pub const SPLIT: usize = 2;

/// `made` of each cell's tree (with the cell's centre and the tree's lower bound over the
/// cell, [`prune_bounded`]) for the grid from `lo` of `n` cells of edge `size`, x fastest
/// (the fine cells' trees are not kept: a grid of millions of cells holds only what `made`
/// makes of them). Pruned hierarchically, as the paper does (§4.2): where the grid is larger
/// than `2 · SPLIT` cells a side, each cell is pruned from the tree of the coarser cell,
/// `SPLIT` cells a side, that holds it — that tree equals the whole one inside the coarse
/// cell, so inside the fine one too, and its children's values there are the whole
/// children's — so the work per fine cell is the parts its coarse cell kept, not all of them.
pub fn map_grid<R: Send>(
    scene: &Scene,
    part: &Part,
    (lo, size, n): (DVec3, f64, [usize; 3]),
    made: impl Fn(Part, DVec3, Option<f64>) -> R + Sync,
) -> Vec<R> {
    let radius = size * 3f64.sqrt() / 2.0;
    let cells: Vec<usize> = (0..n[0] * n[1] * n[2]).collect();
    let at = |i: usize| [i % n[0], (i / n[0]) % n[1], i / (n[0] * n[1])];
    let center =
        |[x, y, z]: [usize; 3]| lo + (DVec3::new(x as f64, y as f64, z as f64) + 0.5) * size;
    let Some(up) = coarser(n) else {
        return crate::parallel::par_map(&cells, |&i| {
            let c = center(at(i));
            let (pruned, lower) = prune_bounded(scene, part, c, radius);
            made(pruned, c, lower)
        });
    };
    let coarse = map_grid(scene, part, (lo, size * SPLIT as f64, up), the_tree);
    crate::parallel::par_map(&cells, |&i| {
        let [x, y, z] = at(i);
        let parent = &coarse[x / SPLIT + up[0] * (y / SPLIT + up[1] * (z / SPLIT))];
        let c = center([x, y, z]);
        let (pruned, lower) = prune_bounded(scene, parent, c, radius);
        made(pruned, c, lower)
    })
}

/// A cell's tree as [`map_grid`] makes it.
fn the_tree(part: Part, _centre: DVec3, _lower: Option<f64>) -> Part {
    part
}

/// The coarser grid a grid of `n` cells a side is pruned from ([`map_grid`]): `SPLIT` times
/// fewer cells a side, rounded up; none where the grid is pruned from the whole tree.
pub fn coarser(n: [usize; 3]) -> Option<[usize; 3]> {
    (!n.iter().all(|&k| k <= 2 * SPLIT)).then(|| n.map(|k| k.div_ceil(SPLIT)))
}

/// The grids [`map_grid`] prunes for a grid of `n` cells a side, coarsest first (it last), each
/// from the one before and the first from the whole tree; grid `i` of `m` has cells
/// `SPLIT^(m − 1 − i)` times as large, from the same lowest corner.
pub fn levels(n: [usize; 3]) -> Vec<[usize; 3]> {
    let mut levels = vec![n];
    while let Some(up) = coarser(levels[levels.len() - 1]) {
        levels.push(up);
    }
    levels.reverse();
    levels
}

/// A grid of cells over a box, each with its pruned tree.
pub struct Cells {
    /// The box's lowest corner.
    pub lo: DVec3,
    /// The cells' edge length.
    pub size: f64,
    /// Cells along x, y and z.
    pub n: [usize; 3],
    /// Each cell's tree, x fastest, then y, then z.
    pub parts: Vec<Part>,
}

impl Cells {
    /// The scene's tree pruned for each cube of edge `size` of the grid from `lo` with `n`
    /// cells along each axis.
    pub fn new(scene: &Scene, part: &Part, lo: DVec3, size: f64, n: [usize; 3]) -> Cells {
        let parts = map_grid(scene, part, (lo, size, n), the_tree);
        Cells { lo, size, n, parts }
    }

    /// The cell holding `p`, if the grid covers it.
    pub fn at(&self, p: DVec3) -> Option<&Part> {
        let c = ((p - self.lo) / self.size).floor();
        let inside = (0..3).all(|a| c[a] >= 0.0 && (c[a] as usize) < self.n[a]);
        inside.then(|| {
            let [x, y, z] = [c.x as usize, c.y as usize, c.z as usize];
            &self.parts[x + self.n[0] * (y + self.n[1] * z)]
        })
    }

    /// The mean number of leaves a cell's tree evaluates.
    pub fn mean_leaves(&self) -> f64 {
        let total: usize = self.parts.iter().map(Part::leaves).sum();
        total as f64 / self.parts.len().max(1) as f64
    }
}
