//! Triangles from the active cells: the field at their corners, the crossings on their edges,
//! the segments on their faces chained into one closed polygon per surface sheet in each cell,
//! and each polygon fanned around a vertex the QEF places (Cubical Marching Squares, Ho et al.
//! 2005: crossings and face segments shared by neighbours make the mesh closed and 2-manifold
//! by construction; the QEF vertex and the faces' sharp points keep corners and creases).

use super::faces::{self, Crossing, Face, Segment};
use super::field::{Field, Grid, corner, inside};
use super::polygons;
use super::search::{self, Search};
use crate::parallel::par_map;
use glam::{DVec3, IVec3};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// The mesh of the active cells.
pub struct Contour {
    /// Vertex positions: the crossings first, then the faces' sharp points, then the cells'.
    pub positions: Vec<DVec3>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Field evaluations spent.
    pub evaluations: usize,
    /// Cells the surface crosses that the pruning had dropped (a bound wrong there).
    pub added: usize,
    /// Cells whose segments did not close into polygons (0 unless the field is not a function:
    /// NaN flickering between calls; such cells are left out and the mesh has a hole there).
    pub broken: usize,
}

/// The iterations of the search for a crossing along an edge (Illinois regula falsi; f64
/// reaches its tolerance in far fewer on a smooth field).
const ROOT_STEPS: usize = 48;

/// A crossing is kept this fraction of the edge away from its ends, so that a corner exactly
/// on the surface does not give several crossings the same position.
const END_GAP: f64 = 1e-4;

/// Contours the surface of `field` through `cells` of `grid`.
pub fn contour(field: &Field, grid: &Grid, cells: &[IVec3], sharp: bool) -> Contour {
    let given = cells.len();
    let Closed {
        cells,
        listed,
        value,
        mut evaluations,
    } = closed(field, grid, cells);
    let added = cells.len() - given;
    let cells = &cells[..];
    let at = |p: IVec3| value.get(&grid.key(p)).copied().unwrap_or(f64::NAN);

    // Every edge of an active cell that changes side, and where the surface crosses it.
    let (mut positions, normals, crossings, spent) = crossings(field, grid, cells, &at);
    evaluations += spent;
    let crossing_at = |(p, a): (IVec3, usize)| crossings.get(&edge_key(grid, p, a)).copied();

    // The segments on every face of an active cell.
    // Each face once: a cell's near faces, and its far ones where no active cell lies beyond.
    let face_list: Vec<Face> = cells
        .iter()
        .flat_map(|&c| (0..6).map(move |i| (c, Face::of_cell(c, i))))
        .filter(|&(c, (f, far))| !far || !listed.contains(&(c + IVec3::AXES[f.axis])))
        .map(|(_, (f, _))| f)
        .collect();
    // The ambiguous faces' centres, in one batch.
    let mut centres: Vec<(Face, f64)> = face_list.iter().map(|&f| (f, f64::NAN)).collect();
    let ambiguous: Vec<usize> = (0..face_list.len())
        .filter(|&i| faces::ambiguous(face_list[i], at))
        .collect();
    let points: Vec<DVec3> = ambiguous
        .iter()
        .map(|&i| faces::centre(grid, face_list[i]))
        .collect();
    evaluations += points.len();
    for (&i, v) in ambiguous.iter().zip(field.many(&points)) {
        centres[i].1 = v;
    }
    let mut drawn = par_map(&centres, |&f| {
        faces::segments(field, grid, f, at, crossing_at, sharp)
    });
    // The faces' sharp points inside them, in lockstep batches.
    let mut owners = Vec::new();
    let mut pending: Vec<faces::Bisect> = Vec::new();
    for (i, (list, _)) in drawn.iter_mut().enumerate() {
        for (j, s) in list.iter_mut().enumerate() {
            if let Some(b) = s.pending.take() {
                owners.push((i, j));
                pending.push(b);
            }
        }
    }
    evaluations += search::run(field, &mut pending);
    for ((i, j), b) in owners.into_iter().zip(pending) {
        let (a, e) = b.ends;
        drawn[i].0[j].sharp = faces::apart(a, b.found.into_iter().collect(), e, grid.h);
    }
    let mut segments: HashMap<Face, Vec<Vec<u32>>> =
        HashMap::with_capacity_and_hasher(face_list.len(), Default::default());
    for (&f, (list, spent)) in face_list.iter().zip(drawn) {
        evaluations += spent;
        if list.is_empty() {
            continue;
        }
        let paths = list.iter().map(|s| path(s, &mut positions)).collect();
        segments.insert(f, paths);
    }
    // One polygon per sheet in each cell, fanned around its QEF vertex.
    let fans = polygons::fan(
        field,
        grid,
        cells,
        &segments,
        &normals,
        &mut positions,
        sharp,
    );
    evaluations += fans.evaluations;
    Contour {
        positions,
        triangles: fans.triangles,
        evaluations,
        added,
        broken: fans.broken,
    }
}

/// The crossings on every edge of `cells` that changes side (`at` gives the field at a grid
/// point): the vertex positions and normals (the crossings, numbered first), the crossings by
/// edge key, and the evaluations spent.
fn crossings(
    field: &Field,
    grid: &Grid,
    cells: &[IVec3],
    at: &(impl Fn(IVec3) -> f64 + Sync),
) -> (Vec<DVec3>, Vec<DVec3>, HashMap<u64, Crossing>, usize) {
    let mut evaluations = 0;
    let mut edges: Vec<(IVec3, usize)> = cells
        .iter()
        .flat_map(|&c| (0..12).map(move |i| cell_edge(c, i)))
        .filter(|&(p, a)| inside(at(p)) != inside(at(p + IVec3::AXES[a])))
        .collect();
    edges.sort_unstable_by_key(|&(p, a)| edge_key(grid, p, a));
    edges.dedup();
    let mut searches: Vec<Root> = edges
        .iter()
        .map(|&(p, a)| Root::new(field, grid, grid.point(p), at(p), a, at(p + IVec3::AXES[a])))
        .collect();
    evaluations += search::run(field, &mut searches);
    let found = searches.iter().map(|s| match s.stage {
        Stage::Done(p, normal) => (p, normal),
        // (`run` ends every search.)
        _ => unreachable!("a crossing's search ended unfinished"),
    });
    let mut positions = Vec::with_capacity(edges.len() * 2);
    let mut normals = Vec::with_capacity(edges.len());
    let mut crossings: HashMap<u64, Crossing> =
        HashMap::with_capacity_and_hasher(edges.len(), Default::default());
    for (&(p, a), (position, normal)) in edges.iter().zip(found) {
        let vertex = positions.len() as u32;
        positions.push(position);
        normals.push(normal);
        let c = Crossing {
            vertex,
            position,
            normal,
        };
        crossings.insert(edge_key(grid, p, a), c);
    }
    (positions, normals, crossings, evaluations)
}

/// The cells `cells` with every neighbour across a face the surface crosses, until no face
/// the surface crosses leads out of the set, and the field at all their corners; and the
/// evaluations spent. With a correct bound the pruning already keeps every such cell; a bound
/// that is wrong somewhere (an annotation too small, a fractal's estimate) would otherwise leave
/// a hole in the mesh where it pruned a cell the surface crosses.
fn closed(field: &Field, grid: &Grid, cells: &[IVec3]) -> Closed {
    let mut active: HashSet<IVec3> = cells.iter().copied().collect();
    // (Sized once: this machine's page faults made the tables' growth a third of the time.)
    let mut value: HashMap<u64, f64> =
        HashMap::with_capacity_and_hasher(cells.len() * 3 / 2, Default::default());
    let mut frontier = cells.to_vec();
    let mut evaluations = 0;
    while !frontier.is_empty() {
        // The corners not yet known, each once (NaN holds the place until it is evaluated).
        let mut points: Vec<IVec3> = Vec::new();
        for &c in &frontier {
            for i in 0..8 {
                let p = c + corner(i);
                if let std::collections::hash_map::Entry::Vacant(e) = value.entry(grid.key(p)) {
                    e.insert(f64::NAN);
                    points.push(p);
                }
            }
        }
        let at: Vec<DVec3> = points.iter().map(|&p| grid.point(p)).collect();
        let values = field.many(&at);
        evaluations += points.len();
        value.extend(points.iter().map(|&p| grid.key(p)).zip(values));
        let inside_at = |p: IVec3| inside(value[&grid.key(p)]);
        let mut next = Vec::new();
        for &c in &frontier {
            for i in 0..6 {
                let (face, far) = Face::of_cell(c, i);
                let sides = face.corners().map(inside_at);
                if sides.iter().all(|&s| s == sides[0]) {
                    continue;
                }
                let step = IVec3::AXES[face.axis];
                let across = if far { c + step } else { c - step };
                if across.cmpge(IVec3::ZERO).all()
                    && across.cmplt(grid.n).all()
                    && active.insert(across)
                {
                    next.push(across);
                }
            }
        }
        frontier = next;
    }
    let mut cells: Vec<IVec3> = active.iter().copied().collect();
    cells.sort_unstable_by_key(|&c| grid.key(c));
    Closed {
        cells,
        listed: active,
        value,
        evaluations,
    }
}

/// What [`closed`] finds.
struct Closed {
    /// The cells, in grid order.
    cells: Vec<IVec3>,
    /// The same cells, to ask whether one is among them.
    listed: HashSet<IVec3>,
    /// The field at every corner of them, by grid point key.
    value: HashMap<u64, f64>,
    /// Field evaluations spent.
    evaluations: usize,
}

/// A key for the grid edge from `p` along `axis` (or the face at `p` normal to it).
fn edge_key(grid: &Grid, p: IVec3, axis: usize) -> u64 {
    grid.key(p) * 3 + axis as u64
}

/// Edge `i` (0..12) of cell `c`: its lowest end and axis.
fn cell_edge(c: IVec3, i: i32) -> (IVec3, usize) {
    let axis = (i / 4) as usize;
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let p = c + IVec3::AXES[u] * (i & 1) + IVec3::AXES[v] * ((i >> 1) & 1);
    (p, axis)
}

/// A segment as a path of vertices (from, its sharp points given indices, to).
fn path(s: &Segment, positions: &mut Vec<DVec3>) -> Vec<u32> {
    let mut out = vec![s.from];
    for &p in &s.sharp {
        out.push(positions.len() as u32);
        positions.push(p);
    }
    out.push(s.to);
    out
}

/// The search for where the surface crosses the grid edge from `a` (field `fa`) along an axis
/// to the point of field `fb`: Illinois regula falsi on the side change, kept [`END_GAP`] off
/// the ends; then the unit normal there.
struct Root {
    /// The edge's start and its extent.
    a: DVec3,
    along: DVec3,
    /// The bracket: parameters along the edge and the field there (Illinois-scaled).
    t0: f64,
    f0: f64,
    t1: f64,
    f1: f64,
    /// The parameter evaluated next.
    t: f64,
    /// Which end the last step replaced (−1 the low, 1 the high, 0 none yet).
    last_side: i32,
    steps: usize,
    /// Stop once |f| or the bracket's length in scene units is below these.
    tol_f: f64,
    tol_t: f64,
    /// The gradient's sample distance.
    step: f64,
    stage: Stage,
}

/// Where a [`Root`] search is.
enum Stage {
    Root,
    Normal(DVec3),
    Done(DVec3, DVec3),
}

impl Root {
    fn new(field: &Field, grid: &Grid, a: DVec3, fa: f64, axis: usize, fb: f64) -> Root {
        let res = field.resolution();
        let mut root = Root {
            a,
            along: DVec3::AXES[axis] * grid.h,
            t0: 0.0,
            f0: fa,
            t1: 1.0,
            f1: fb,
            t: 0.5,
            last_side: 0,
            steps: 0,
            tol_f: (1e-9 * grid.h).max(res),
            tol_t: 1e-9f64.max(res / grid.h),
            step: field.gradient_step(grid.h),
            stage: Stage::Root,
        };
        root.guess();
        root
    }

    /// Takes the field `f` at the parameter asked for: the bracket narrowed (Illinois), or the
    /// root taken and its normal asked for next.
    fn step(&mut self, f: f64) {
        let t = self.t;
        self.steps += 1;
        if f.abs() < self.tol_f || self.t1 - self.t0 < self.tol_t || self.steps == ROOT_STEPS {
            let p = self.a + self.along * t.clamp(END_GAP, 1.0 - END_GAP);
            self.stage = Stage::Normal(p);
            return;
        }
        if inside(f) == inside(self.f0) {
            (self.t0, self.f0) = (t, f);
            if self.last_side == -1 {
                self.f1 *= 0.5;
            }
            self.last_side = -1;
        } else {
            (self.t1, self.f1) = (t, f);
            if self.last_side == 1 {
                self.f0 *= 0.5;
            }
            self.last_side = 1;
        }
        self.guess();
    }

    /// The next parameter: the secant's root inside the bracket, else its middle.
    fn guess(&mut self) {
        let (t0, f0, t1, f1) = (self.t0, self.f0, self.t1, self.f1);
        let guess = (t0 * f1 - t1 * f0) / (f1 - f0);
        self.t = if guess.is_finite() && guess > t0 && guess < t1 {
            guess
        } else {
            0.5 * (t0 + t1)
        };
    }
}

impl Search for Root {
    fn ask(&self, points: &mut Vec<DVec3>) {
        match self.stage {
            Stage::Root => points.push(self.a + self.along * self.t),
            Stage::Normal(p) => search::gradient_points(p, self.step, points),
            Stage::Done(..) => {}
        }
    }

    fn tell(&mut self, values: &[f64]) {
        match self.stage {
            Stage::Root => self.step(values[0]),
            Stage::Normal(p) => self.stage = Stage::Done(p, search::unit_gradient(values)),
            Stage::Done(..) => {}
        }
    }
}
