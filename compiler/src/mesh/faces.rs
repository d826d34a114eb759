//! The surface's trace on one face of the grid: marching squares with the face's own centre
//! deciding an ambiguous face, so that both cells sharing it draw the same segments, and a
//! sharp point where the two tangent lines of a crease meet inside the face (`bends`).

use super::bends::{self, Bends, Sharp};
use super::creases::SAME_PLANE;
use super::edges::{Crossed, Crossing};
use super::field::{Face, Field, Grid, inside};
use super::trace::{self, Bracket};
use glam::{DVec3, IVec3};
use rustc_hash::FxHashMap as HashMap;

/// A path across a face from one crossing to another, through a sharp point or not.
#[derive(Clone, Debug)]
pub struct Segment {
    /// The crossing it starts at.
    pub from: u32,
    /// The sharp points in between, in order (their indices are given later).
    pub sharp: Vec<Sharp>,
    /// The crossing it ends at.
    pub to: u32,
    /// The search for its sharp point, where one runs in the next batches (its result, kept
    /// [`MIN_GAP`] off the ends, becomes `sharp`). Boxed: few segments have one, and a
    /// search is about 250 bytes that every segment allocated (the box less a ball at 215
    /// cells: 1.04 → 0.89 s to the measuring step, median of 6; its peak memory, reached
    /// later, unchanged).
    pub pending: Option<Box<Bracket>>,
}

/// The segments the surface draws on `face`, oriented so that, seen from the normal's positive
/// side, the inside lies to their left. `value` gives the field at a grid point and `crossing`
/// the crossings on a grid edge. Going round the face's border counter-clockwise, each crossing
/// that leaves the inside (an exit) is joined to the next crossing where the inside regions
/// meet across the face, else to the one before (a face of more than two crossings decides by
/// the field at its centre, `centre`, from [`centre`]'s point). With `sharp`, a segment whose
/// crossings' tangent lines meet at an angle, inside the face and on the surface, gets that
/// point (a [`Bracket`] left pending in the segment; on a face of two crossings, where they
/// meet outside or off the surface, the trace's bends are searched: [`bends::bends`]).
/// Returns the segments and the evaluations spent.
pub fn segments(
    field: &Field,
    grid: &Grid,
    (face, centre): (Face, f64),
    value: impl Fn(IVec3) -> f64,
    crossing: impl Fn((IVec3, usize)) -> Option<Crossed>,
    sharp: bool,
) -> (Vec<Segment>, usize) {
    let border = border(face, value, crossing);
    let n = border.len();
    let mut evaluations = 0;
    let dipped = (0..n.saturating_sub(1)).any(|k| border[k].2 == border[k + 1].2);
    let joined = match (n, dipped) {
        (2, _) => true,
        // Four crossings, two of them on an edge crossed twice: the pairing whose segments join
        // crossings of the most alike normals (a crease or a thin part's two sides cross the
        // face as two traces, each along one sheet; the face's centre can lie either side of a
        // thin dip, and a straight search from the dip can meet the other trace).
        (4, true) => alike(&border, 1) >= alike(&border, n - 1),
        // Six or more: only where one pairing joins crossings of one plane each, as a rough
        // surface's traces join crossings of normals alike by chance (a corner's tip through a
        // face near the face's corner crosses it as three straight traces, one per plane, and
        // the face's centre can lie just outside all of them).
        (_, true) if planar(&border, 1) => true,
        (_, true) if planar(&border, n - 1) => false,
        _ => inside(centre),
    };
    let mut out = Vec::with_capacity(n / 2);
    for (k, &(x, exit, edge)) in border.iter().enumerate() {
        if !exit {
            continue;
        }
        let (y, _, other) = border[if joined { (k + 1) % n } else { (k + n - 1) % n }];
        let mut segment = Segment {
            from: x.vertex,
            sharp: Vec::new(),
            to: y.vertex,
            pending: None,
        };
        if edge == other {
            // Both ends on one edge, crossed twice: the trace dips into the face between them.
            let field = &field.on_cpu();
            let found = bends::apex(field, grid, (face, edge), (x, y), &mut evaluations);
            segment.sharp = apart(x.position, found, y.position, grid.h);
            if segment.sharp.is_empty() {
                // No surface point found (a field that is no bound, a dip too shallow): a point
                // just inside the face, so that the chord is not shared by more than two
                // triangles.
                let mid = 0.5 * (x.position + y.position);
                segment.sharp = vec![Sharp {
                    at: mid + trace::into_face(face, edge) * (4.0 * MIN_GAP * grid.h),
                    planes: None,
                }];
            }
        } else if sharp {
            let ends = ((x.position, x.normal), (y.position, y.normal));
            match bends::bends(field, grid, (face, n > 2), ends, &mut evaluations) {
                Bends::Found(found) => {
                    segment.sharp = apart(x.position, found, y.position, grid.h);
                }
                Bends::Pending(search) => segment.pending = Some(search),
            }
        }
        out.push(segment);
    }
    (out, evaluations)
}

/// How alike the normals of the crossings each exit of `border` is joined to are, joining it
/// to the crossing `step` places on: the sum of their cosines.
fn alike(border: &[(Crossing, bool, usize)], step: usize) -> f64 {
    let n = border.len();
    (0..n)
        .filter(|&k| border[k].1)
        .map(|k| border[k].0.normal.dot(border[(k + step) % n].0.normal))
        .sum()
}

/// Whether joining each exit of `border` to the crossing `step` places on joins crossings of
/// one plane each (normals within about 2.5°).
fn planar(border: &[(Crossing, bool, usize)], step: usize) -> bool {
    let pairs = border.len() / 2;
    alike(border, step) > pairs as f64 * SAME_PLANE
}

/// The crossings on `face`'s border in counter-clockwise order, each with whether it leaves
/// the inside (the side changes at every crossing, starting from the first corner's) and the
/// edge it lies on (0..4, as [`Face::edges`]).
fn border(
    face: Face,
    value: impl Fn(IVec3) -> f64,
    crossing: impl Fn((IVec3, usize)) -> Option<Crossed>,
) -> Vec<(Crossing, bool, usize)> {
    let corners = face.corners();
    let mut side = inside(value(corners[0]));
    let mut out = Vec::with_capacity(4);
    for (i, edge) in face.edges().into_iter().enumerate() {
        let Some(crossed) = crossing(edge) else {
            continue;
        };
        // Edges 2 and 3 run against the counter-clockwise order.
        let along: Vec<Crossing> = match i {
            0 | 1 => crossed.iter().collect(),
            _ => crossed.iter().rev().collect(),
        };
        for x in along {
            out.push((x, side, i));
            side = !side;
        }
    }
    out
}

/// The crossings on the face's border: none, and it draws nothing; more than two (its inside
/// corners on a diagonal, or an edge crossed twice), and it needs the field at its [`centre`]
/// to pair them.
pub fn crossings_on(face: Face, crossing: impl Fn((IVec3, usize)) -> Option<Crossed>) -> usize {
    face.edges()
        .into_iter()
        .filter_map(&crossing)
        .map(|c| c.count())
        .sum()
}

/// The centre of `face`.
pub fn centre(grid: &Grid, face: Face) -> DVec3 {
    let (u, v) = face.span();
    grid.point(face.base) + 0.5 * grid.h * (DVec3::AXES[u] + DVec3::AXES[v])
}

/// How near (in cells) two vertices of a path may come: nearer ones would share a position
/// once written as f32, and tools that join vertices by position would see a pinched mesh.
pub const MIN_GAP: f64 = 1e-4;

/// The points of `found` (a path from `a` to `b`) at least [`MIN_GAP`] cells from the point
/// before them and from `b`.
pub fn apart(a: DVec3, found: Vec<Sharp>, b: DVec3, h: f64) -> Vec<Sharp> {
    let mut last = a;
    let mut out = Vec::with_capacity(found.len());
    for p in found {
        if (p.at - last).length() >= MIN_GAP * h && (p.at - b).length() >= MIN_GAP * h {
            out.push(p);
            last = p.at;
        }
    }
    out
}

/// Every face's segments as paths of mesh vertices (from, sharp points, to), stored flat: one
/// table entry per face drawn, no allocation per segment.
pub struct Paths {
    /// By face: the range of its paths in `paths`.
    by_face: HashMap<Face, (u32, u32)>,
    /// Each path's range in `vertices`.
    paths: Vec<(u32, u32)>,
    vertices: Vec<u32>,
    /// The paths before this one belong to faces already finished.
    finished: u32,
}

impl Paths {
    /// Room for `faces` faces.
    pub fn with_capacity(faces: usize) -> Paths {
        Paths {
            by_face: HashMap::with_capacity_and_hasher(faces, Default::default()),
            paths: Vec::with_capacity(faces),
            vertices: Vec::with_capacity(2 * faces),
            finished: 0,
        }
    }

    /// Adds a path (a list of vertices) to the face [`Paths::finish`] names next.
    pub fn push(&mut self, path: impl IntoIterator<Item = u32>) {
        let start = self.vertices.len() as u32;
        self.vertices.extend(path);
        self.paths.push((start, self.vertices.len() as u32));
    }

    /// The paths pushed since the last call are `face`'s.
    pub fn finish(&mut self, face: Face) {
        let end = self.paths.len() as u32;
        self.by_face.insert(face, (self.finished, end));
        self.finished = end;
    }

    /// `face`'s paths (none if it draws none).
    pub fn of(&self, face: Face) -> impl Iterator<Item = &[u32]> {
        let (a, b) = self.by_face.get(&face).copied().unwrap_or((0, 0));
        self.paths[a as usize..b as usize]
            .iter()
            .map(|&(s, e)| &self.vertices[s as usize..e as usize])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each face gets back the paths pushed before its `finish`, in order; a face never
    /// finished has none.
    #[test]
    fn paths_come_back_by_face() {
        let face = |x, axis| Face {
            base: IVec3::new(x, 0, 0),
            axis,
        };
        let mut paths = Paths::with_capacity(2);
        paths.push([1, 2]);
        paths.push([3, 9, 4]);
        paths.finish(face(0, 0));
        paths.push([5, 6]);
        paths.finish(face(1, 2));
        let of = |f| paths.of(f).map(<[u32]>::to_vec).collect::<Vec<_>>();
        assert_eq!(of(face(0, 0)), vec![vec![1, 2], vec![3, 9, 4]]);
        assert_eq!(of(face(1, 2)), vec![vec![5, 6]]);
        assert!(of(face(2, 1)).is_empty());
    }
}
