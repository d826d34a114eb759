//! A cell's polygon that is flat between its crease points drawn as the faces it passes
//! through, meeting at their corners inside the cell.
//!
//! One vertex per polygon keeps one corner. Where a cell holds two or more — the box's cap
//! cutting a small triangle off a turned box's corner at a coarse grid, so that the cap and
//! three faces meet in two or three corners within one cell — the fan around one vertex cuts
//! across the creases between them (3.7e-3 of the box's size on the capped turned box at 16 to
//! 54 cells). Where the ring is flat between its k crease points (k stretches, each on one
//! plane), the surface in the cell is taken to be those planes meeting at corners of three each:
//! which ones meet is a triangulation of the polygon of the k planes (two for k = 4, five for 5,
//! fourteen for 6), each tried in turn; where the vertex lies on none of them, the plane the
//! gradient gives there is a face hidden inside the cell, and each crease ends on it. The ring is
//! drawn as one polygon per plane (its stretch of the ring, then back through its corners) where
//! every corner lies in the cell, every polygon is convex and turns as the ring does, and the
//! field is zero at the corners and at the polygons' centres; else as before.

use super::bends::Planes;
use super::creases::{CREASE, SAME_PLANE};
use super::field::{Field, Grid};
use super::plans::{Plan, around, meeting, triangulations};
use super::search;
use glam::{DMat3, DVec3, IVec3};

/// A polygon to fan: its cell, its vertices (clockwise seen from outside) and the point it is
/// fanned around.
pub struct Polygon {
    /// The cell.
    pub cell: IVec3,
    /// Vertex indices.
    pub ring: Vec<u32>,
    /// The fan's centre.
    pub centre: DVec3,
}

/// How far (in cells) a polygon's centre must lie off every plane of its ring for a hidden face
/// to be sought.
const OFF: f64 = 1e-3;

/// How far (in cells) a flat stretch's vertices may lie off its plane, and the field's value at
/// the new corners and at the new polygons' centres may be off zero.
const ON: f64 = 1e-5;

/// The least distance (in cells) between two new corners, and from each to the ring's crease
/// points: nearer, the face between is too small to matter (and `separate` would move them).
const APART: f64 = 2e-4;

/// The most planes a flat ring may pass through (14 triangulations of 6).
const MOST_PLANES: usize = 6;

/// Replaces each of `polygons` that is flat between three or more crease points and holds two
/// or more corners, or a hidden face (see the module's comment), by one polygon per plane,
/// their new corners appended to `positions`; `normals` are the crossings' normals (vertex
/// `v < normals.len()` is a crossing) and `planes` the sharp points' after them. Returns the
/// field evaluations spent.
pub fn reveal(
    field: &Field,
    grid: &Grid,
    polygons: &mut Vec<Polygon>,
    positions: &mut Vec<DVec3>,
    (normals, planes): (&[DVec3], &[Option<Planes>]),
) -> usize {
    let flats: Vec<Flat> = (0..polygons.len())
        .filter_map(|i| flat(i, &polygons[i], positions, (normals, planes), grid.h))
        .collect();
    if flats.is_empty() {
        return 0;
    }
    // The gradient at the centres off every plane: the hidden face's plane.
    let mut points = Vec::new();
    for f in flats.iter().filter(|f| f.off) {
        search::gradient_points(
            polygons[f.index].centre,
            field.gradient_step(grid.h),
            &mut points,
        );
    }
    let values = field.many(&points);
    let mut evaluations = points.len();
    let mut hidden = values.chunks(4).map(search::unit_gradient);
    let mut tries: Vec<Drawn> = Vec::new();
    for f in &flats {
        let polygon = &polygons[f.index];
        let k = f.planes.len();
        if f.off {
            let n = hidden.next().unwrap_or(DVec3::ZERO);
            if n == DVec3::ZERO || f.planes.iter().any(|&(m, _)| m.dot(n) > SAME_PLANE) {
                continue;
            }
            let mut planes = f.planes.clone();
            planes.push((n, polygon.centre));
            tries.extend(draw(f, polygon, &planes, &around(k), positions, grid));
        } else if (4..=MOST_PLANES).contains(&k) {
            for plan in triangulations(&(0..k).collect::<Vec<_>>()) {
                let plan = meeting(k, plan);
                tries.extend(draw(f, polygon, &f.planes, &plan, positions, grid));
            }
        }
    }
    // The field at every new corner and every new polygon's centre, each zero to keep it.
    let points: Vec<DVec3> = tries
        .iter()
        .flat_map(|d| d.corners.iter().copied().chain(d.centres()))
        .collect();
    let values = field.many(&points);
    evaluations += points.len();
    let mut values = values.into_iter();
    let mut replaced: Vec<Option<Vec<Polygon>>> = (0..polygons.len()).map(|_| None).collect();
    for d in tries {
        let n = d.corners.len() + d.parts.len();
        // (Every one of the n values taken, so that the next try reads its own.)
        let tol = (ON * grid.h).max(field.resolution());
        let on = values
            .by_ref()
            .take(n)
            .filter(|v| v.is_nan() || v.abs() > tol)
            .count()
            == 0;
        if !on || replaced[d.index].is_some() {
            continue;
        }
        let first = positions.len() as u32;
        positions.extend(&d.corners);
        let cell = polygons[d.index].cell;
        let parts = d.parts.iter().zip(d.centres()).map(|(part, centre)| {
            let ring = part
                .iter()
                .map(|&v| match v {
                    Vertex::Old(v) => v,
                    Vertex::Corner(j) => first + j as u32,
                })
                .collect();
            Polygon { cell, ring, centre }
        });
        replaced[d.index] = Some(parts.collect());
    }
    if replaced.iter().any(Option::is_some) {
        let old = std::mem::take(polygons);
        for (p, r) in old.into_iter().zip(replaced) {
            match r {
                Some(parts) => polygons.extend(parts),
                None => polygons.push(p),
            }
        }
    }
    evaluations
}

/// A polygon whose ring is flat between its crease points.
struct Flat {
    /// Which polygon.
    index: usize,
    /// Where its crease points are in its ring, in order.
    at: Vec<usize>,
    /// The plane of the stretch after each crease point: its unit normal and a point on it.
    planes: Vec<(DVec3, DVec3)>,
    /// Whether the polygon's centre lies off every one of them by more than [`OFF`] cells (a
    /// face hidden inside the cell is sought).
    off: bool,
}

/// `polygon` (the `index`-th) as a [`Flat`], if it is one: three to [`MOST_PLANES`] crease
/// points (sharp points between planes at least [`CREASE`] apart), each stretch between two of
/// them on the one plane the two share — its crossings' normals that plane's, all its vertices
/// on it.
fn flat(
    index: usize,
    polygon: &Polygon,
    positions: &[DVec3],
    (normals, planes): (&[DVec3], &[Option<Planes>]),
    h: f64,
) -> Option<Flat> {
    let ring = &polygon.ring;
    // A crease point's two planes.
    let crease = |v: u32| {
        let k = (v as usize).checked_sub(normals.len())?;
        let (a, b) = planes.get(k).copied().flatten()?;
        (a.dot(b) < CREASE).then_some((a, b))
    };
    let at: Vec<usize> = (0..ring.len())
        .filter(|&k| crease(ring[k]).is_some())
        .collect();
    if !(3..=MOST_PLANES).contains(&at.len()) {
        return None;
    }
    let mut stretches = Vec::with_capacity(at.len());
    for j in 0..at.len() {
        let (s, e) = (at[j], at[(j + 1) % at.len()]);
        let ((a, b), (c, d)) = (crease(ring[s])?, crease(ring[e])?);
        let one = |n: DVec3| n.dot(c) > SAME_PLANE || n.dot(d) > SAME_PLANE;
        let n = match (one(a), one(b)) {
            (true, false) => a,
            (false, true) => b,
            _ => return None,
        };
        let p = positions[ring[s] as usize];
        let mut k = s;
        while k != e {
            k = (k + 1) % ring.len();
            let v = ring[k] as usize;
            let facing = normals.get(v).is_none_or(|&m| m.dot(n) > SAME_PLANE);
            if !facing || n.dot(positions[v] - p).abs() > ON * h {
                return None;
            }
        }
        stretches.push((n, p));
    }
    // Each crease point between two different planes.
    let turns = (0..at.len()).all(|j| {
        let before = stretches[(j + at.len() - 1) % at.len()].0;
        before.dot(stretches[j].0) < SAME_PLANE
    });
    let off = (stretches.iter()).all(|&(n, p)| n.dot(polygon.centre - p).abs() > OFF * h);
    turns.then_some(Flat {
        index,
        at,
        planes: stretches,
        off,
    })
}

/// A vertex of a new polygon: one already placed, or the j-th new corner.
#[derive(Clone, Copy)]
enum Vertex {
    Old(u32),
    Corner(usize),
}

/// A flat polygon drawn by a [`Plan`].
struct Drawn {
    /// Which polygon.
    index: usize,
    /// The corners.
    corners: Vec<DVec3>,
    /// The new polygons, one per plane.
    parts: Vec<Vec<Vertex>>,
    /// Their vertices' positions.
    at: Vec<Vec<DVec3>>,
}

impl Drawn {
    /// The new polygons' centres (the means of their vertices).
    fn centres(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.at
            .iter()
            .map(|ps| ps.iter().sum::<DVec3>() / ps.len() as f64)
    }
}

/// `flat`'s polygon drawn by `plan` over `planes` (the stretches' and a hidden one after them):
/// `None` unless every corner is well defined, lies in the cell and [`APART`] from the others
/// and from the crease points, and every new polygon is convex and turns as the ring does
/// (clockwise seen from outside).
fn draw(
    flat: &Flat,
    polygon: &Polygon,
    planes: &[(DVec3, DVec3)],
    plan: &Plan,
    positions: &[DVec3],
    grid: &Grid,
) -> Option<Drawn> {
    let (ring, k) = (&polygon.ring, flat.at.len());
    let lo = grid.point(polygon.cell);
    let (lo, hi) = (lo - 1e-9 * grid.h, lo + (1.0 + 1e-9) * grid.h);
    let mut corners: Vec<DVec3> = Vec::with_capacity(plan.corners.len());
    for t in &plan.corners {
        let [a, b, c] = t.map(|i| planes[i]);
        let m = DMat3::from_cols(a.0, b.0, c.0).transpose();
        if m.determinant().abs() < 0.01 {
            return None;
        }
        let x = m.inverse() * DVec3::new(a.0.dot(a.1), b.0.dot(b.1), c.0.dot(c.1));
        let near = |q: DVec3| (q - x).length() < APART * grid.h;
        let creases = flat.at.iter().map(|&i| positions[ring[i] as usize]);
        if x.cmplt(lo).any() || x.cmpgt(hi).any() || corners.iter().copied().any(near) {
            return None;
        }
        if creases.clone().any(near) {
            return None;
        }
        corners.push(x);
    }
    let mut parts = Vec::with_capacity(plan.back.len());
    for (j, back) in plan.back.iter().enumerate() {
        let mut part = Vec::new();
        if j < k {
            let (s, e) = (flat.at[j], flat.at[(j + 1) % k]);
            let mut i = s;
            part.push(Vertex::Old(ring[i]));
            while i != e {
                i = (i + 1) % ring.len();
                part.push(Vertex::Old(ring[i]));
            }
        }
        part.extend(back.iter().map(|&c| Vertex::Corner(c)));
        parts.push(part);
    }
    let at: Vec<Vec<DVec3>> = parts
        .iter()
        .map(|part| {
            part.iter()
                .map(|&v| match v {
                    Vertex::Old(v) => positions[v as usize],
                    Vertex::Corner(j) => corners[j],
                })
                .collect()
        })
        .collect();
    let convex = (at.iter().zip(planes)).all(|(ps, &(n, _))| clockwise(ps, n, grid.h));
    convex.then_some(Drawn {
        index: flat.index,
        corners,
        parts,
        at,
    })
}

/// Whether the polygon `ps` is convex and runs clockwise seen from the side `n` points to
/// (straight runs allowed: a face's crossings along a cell's side).
fn clockwise(ps: &[DVec3], n: DVec3, h: f64) -> bool {
    let m = ps.len();
    let turns = (0..m).all(|i| {
        let (a, b, c) = (ps[(i + m - 1) % m], ps[i], ps[(i + 1) % m]);
        (b - a).cross(c - b).dot(n) <= 1e-9 * h * h
    });
    let area: DVec3 = (0..m).map(|i| ps[i].cross(ps[(i + 1) % m])).sum();
    turns && area.dot(n) < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square seen from +z runs clockwise when its vertices go −y first; a dent is refused.
    #[test]
    fn clockwise_and_convex() {
        let square = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
        ];
        assert!(clockwise(&square, DVec3::Z, 1.0));
        assert!(!clockwise(&square, -DVec3::Z, 1.0));
        let mut dented = square.to_vec();
        dented.insert(3, DVec3::new(0.5, 0.8, 0.0));
        assert!(!clockwise(&dented, DVec3::Z, 1.0));
        let mut straight = square.to_vec();
        straight.insert(1, DVec3::new(0.0, 0.5, 0.0));
        assert!(clockwise(&straight, DVec3::Z, 1.0));
    }
}
