//! Corners just outside the cell whose ring draws them: the ring's vertex goes to the corner
//! itself when the cell holding the corner draws nothing.
//!
//! A corner of the shape a little past a cell's face pokes through that face as a small
//! closed trace that crosses none of the face's edges: marching squares cannot see it, so the
//! cell beyond holds no ring and the cell below draws the corner's three faces as one ring
//! around it. Its vertex, kept in its cell, would cut the corner's tip off (up to the tip's
//! height: a tenth of a cell on the turned box, 2.5e-3 of its size at 64 cells). The QEF of
//! the ring's tangent planes (its crossings' and its sharp points' two each) finds the corner
//! exactly; where every plane passes through that point, the cell holding it (a neighbour)
//! draws no ring, no other ring claims it and the field is zero there, the fan goes from the
//! corner. Each of its triangles then lies in one of the corner's planes (two consecutive
//! vertices of the ring share a plane, a sharp point standing where the plane changes), so
//! the fan is the surface itself; and the mesh's connectivity is the same as with the vertex
//! in its cell, so it stays closed and 2-manifold.

use super::field::{Field, Grid};
use super::qef::Solution;
use glam::{DVec3, IVec3};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// How far (in cells) any of the ring's tangent planes may pass from the corner.
const ON_PLANES: f64 = 1e-3;

/// A corner outside the cell of the ring it would be the vertex of.
#[derive(Clone, Copy, Debug)]
pub struct Corner {
    /// Where.
    pub at: DVec3,
    /// The cell holding it: a neighbour of the ring's (across a face, an edge or a corner).
    pub cell: IVec3,
}

/// The corner the QEF found for a ring of cell `c`, when it lies in a neighbouring cell and on
/// every plane of `sheet` (surface points and unit normals), to a thousandth of a cell.
pub fn outside(
    found: &Solution,
    sheet: &[(DVec3, DVec3)],
    grid: &Grid,
    c: IVec3,
) -> Option<Corner> {
    if !found.corner || !found.point.is_finite() {
        return None;
    }
    let at = found.point;
    let cell = ((at - grid.origin) / grid.h).floor().as_ivec3();
    let step = (cell - c).abs().max_element();
    if step != 1 {
        return None;
    }
    let on = sheet
        .iter()
        .all(|&(p, n)| n.dot(at - p).abs() <= ON_PLANES * grid.h);
    on.then_some(Corner { at, cell })
}

/// Keeps of the `claims` (a ring's cell and its corner, if any) the corners whose cell holds
/// no ring (`drawn`), that one ring alone claims and where the field is zero (to `tol`); the
/// rest are dropped (those rings' vertices stay in their cells). Returns the evaluations spent.
pub fn keep(
    field: &Field,
    claims: &mut [&mut Option<Corner>],
    drawn: &HashSet<IVec3>,
    tol: f64,
) -> usize {
    let mut claimed: HashMap<IVec3, usize> = HashMap::default();
    for corner in claims.iter().filter_map(|c| c.as_ref()) {
        *claimed.entry(corner.cell).or_default() += 1;
    }
    let free = |c: &Corner| claimed[&c.cell] == 1 && !drawn.contains(&c.cell);
    for claim in claims.iter_mut() {
        if claim.as_ref().is_some_and(|c| !free(c)) {
            **claim = None;
        }
    }
    let points: Vec<DVec3> = claims.iter().filter_map(|c| c.map(|c| c.at)).collect();
    if points.is_empty() {
        return 0;
    }
    let values = field.many(&points);
    let mut values = values.into_iter();
    for claim in claims.iter_mut().filter(|c| c.is_some()) {
        if values.next().is_none_or(|d| d.is_nan() || d.abs() > tol) {
            **claim = None;
        }
    }
    points.len()
}
