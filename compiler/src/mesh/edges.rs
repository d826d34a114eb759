//! Where the surface crosses the grid's edges: once on an edge whose ends lie on different
//! sides (regula falsi), and — with sharp features asked for — twice on an edge whose ends lie
//! on the same side but between which the field's bound allows it to dip across (a crease
//! cutting the edge, a part thinner than a cell), found by a bound-guided search.

use super::field::{Face, Field, Grid, corner, inside, local};
use super::search::{self, Search};
use crate::parallel::{par_flat_map, par_map, par_sort_unstable_by_key};
use glam::{DVec3, IVec3};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// The iterations of the search for a crossing along an edge (Illinois regula falsi; f64
/// reaches its tolerance in far fewer on a smooth field).
const ROOT_STEPS: usize = 48;

/// A crossing is kept this fraction of the edge away from its ends, so that a corner exactly
/// on the surface does not give several crossings the same position.
const END_GAP: f64 = 1e-4;

/// Where the surface crosses a grid edge: the vertex's index, position and unit normal.
#[derive(Clone, Copy, Debug)]
pub struct Crossing {
    /// The vertex's index in the mesh.
    pub vertex: u32,
    /// On the surface, on the edge.
    pub position: DVec3,
    /// The field's gradient there.
    pub normal: DVec3,
}

/// The crossings of one grid edge, in order along its axis: one where its ends lie on
/// different sides, two where the field dips across between ends on the same side.
#[derive(Clone, Copy, Debug)]
pub struct Crossed {
    /// The first (or only) crossing.
    pub first: Crossing,
    /// The second, on an edge crossed twice.
    pub second: Option<Crossing>,
}

impl Crossed {
    /// The crossings in order from the edge's lowest end.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = Crossing> {
        std::iter::once(self.first).chain(self.second)
    }

    /// How many there are (1 or 2).
    pub fn count(&self) -> usize {
        1 + self.second.is_some() as usize
    }
}

/// What [`crossings`] finds.
pub struct Crossings {
    /// Vertex positions and normals: the crossings, numbered first.
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    /// The crossings by edge key ([`edge_key`]).
    pub by_edge: HashMap<u64, Crossed>,
    /// Edges crossed twice.
    pub dipped: usize,
    /// Field evaluations spent.
    pub evaluations: usize,
}

/// A grid edge: its [`edge_key`], and the cell (its index) and the cell's edge (0..12) it is.
type KeyedEdge = (u64, (u32, u8));

/// The crossings on every edge of `cells` (`at` gives the field at a grid point): once on each
/// edge that changes side; with `dips`, twice on each edge whose ends lie on the same side but
/// where the field dips across between them, if all four cells around it are in `listed` (so
/// every face at the edge is drawn, and sees both).
pub fn crossings(
    field: &Field,
    grid: &Grid,
    (cells, listed): (&[IVec3], &HashSet<IVec3>),
    at: &(impl Fn(IVec3) -> f64 + Sync),
    dips: bool,
) -> Crossings {
    let (changes, same) = cell_edges(grid, cells, at, dips);
    // The edges the field may dip across with all four cells around them there.
    let all_around = par_map(&same, |&(e, _)| {
        around(e).iter().all(|c| listed.contains(c))
    });
    let mut dipping: Vec<Dip> = (same.into_iter().zip(all_around))
        .filter_map(|(e, all)| all.then_some(e))
        .map(|((p, a), ends)| {
            let along = DVec3::AXES[a] * grid.h;
            Dip::new(field, grid.point(p), along, ends, (p, a))
        })
        .collect();
    let mut evaluations = search::run(field, &mut dipping);
    // One search per crossing: a changing edge's, and a dipped edge's two halves.
    let mut keys: Vec<u64> = Vec::with_capacity(changes.len());
    let mut searches: Vec<Root> = Vec::with_capacity(changes.len());
    for &((p, a), (fa, fb)) in &changes {
        let along = DVec3::AXES[a] * grid.h;
        searches.push(Root::new(field, grid.h, (grid.point(p), fa), along, fb));
        keys.push(edge_key(grid, p, a));
    }
    let mut dipped = 0;
    for dip in &dipping {
        let Some((t, fm)) = dip.found else { continue };
        let (p, a) = dip.edge;
        let key = edge_key(grid, p, a);
        let m = dip.a + dip.along * t;
        let (fa, fb) = dip.ends;
        searches.push(Root::new(field, grid.h, (dip.a, fa), dip.along * t, fm));
        searches.push(Root::new(field, grid.h, (m, fm), dip.along * (1.0 - t), fb));
        keys.extend([key, key]);
        dipped += 1;
    }
    evaluations += search::run(field, &mut searches);
    let mut positions = Vec::with_capacity(searches.len() * 2);
    let mut normals = Vec::with_capacity(searches.len());
    let mut by_edge: HashMap<u64, Crossed> =
        HashMap::with_capacity_and_hasher(searches.len(), Default::default());
    for (key, search) in keys.into_iter().zip(searches) {
        let Stage::Done(position, normal) = search.stage else {
            // (`run` ends every search.)
            unreachable!("a crossing's search ended unfinished");
        };
        let vertex = positions.len() as u32;
        positions.push(position);
        normals.push(normal);
        let c = Crossing {
            vertex,
            position,
            normal,
        };
        by_edge
            .entry(key)
            .and_modify(|x| x.second = Some(c))
            .or_insert(Crossed {
                first: c,
                second: None,
            });
    }
    Crossings {
        positions,
        normals,
        by_edge,
        dipped,
        evaluations,
    }
}

/// An edge (lowest end and axis) and the field at its ends.
type Ended = ((IVec3, usize), (f64, f64));

/// Each edge of `cells`, once, with the field at its ends (`at`): those that change side, and
/// with `dips` apart those on one side that the field may dip across, |d(a)| + |d(b)| < h (d is
/// 1-Lipschitz) — the rest dropped before sorting (most edges of a fine grid).
fn cell_edges(
    grid: &Grid,
    cells: &[IVec3],
    at: &(impl Fn(IVec3) -> f64 + Sync),
    dips: bool,
) -> (Vec<Ended>, Vec<Ended>) {
    let values: Vec<[f64; 8]> = par_map(cells, |&c| {
        std::array::from_fn(|i| at(c + corner(i as i32)))
    });
    let ends = |(cell, i): (u32, u8)| {
        let c = cells[cell as usize];
        let (p, a) = cell_edge(c, i as i32);
        let value = &values[cell as usize];
        (
            (p, a),
            (value[local(p - c)], value[local(p - c + IVec3::AXES[a])]),
        )
    };
    let index: Vec<u32> = (0..cells.len() as u32).collect();
    let mut edges: Vec<KeyedEdge> = par_flat_map(&index, |&cell| {
        (0..12u8).filter_map(move |i| {
            let ((p, a), (fa, fb)) = ends((cell, i));
            let keep = inside(fa) != inside(fb) || (dips && fa.abs() + fb.abs() < grid.h);
            keep.then_some((edge_key(grid, p, a), (cell, i)))
        })
    });
    par_sort_unstable_by_key(&mut edges, |e| e.0);
    edges.dedup_by_key(|e| e.0);
    edges
        .into_iter()
        .map(|(_, e)| ends(e))
        .partition(|&(_, (fa, fb))| inside(fa) != inside(fb))
}

/// The cosine of the angle between two crossings' normals on one face above which neither is
/// taken again by [`sharpen`] (20°: a curved sheet turns less within a cell at any resolution
/// worth meshing; a crease or a corner's faces turn more).
const SHARPEN_COSINE: f64 = 0.94;

/// On a field whose gradients are coarse (the GPU's f32, sampled a hundredth of a cell apart),
/// the normals of the crossings of `faces` that differ by more than 20° from another crossing's
/// on one face, taken again in f64 on the CPU a ten-thousandth of a cell apart: near a crease
/// the coarse gradient blends its two planes, and the faces' crease points and the cells' QEF
/// vertices are only as good as these normals. Returns the evaluations spent (none on the CPU).
pub fn sharpen(field: &Field, grid: &Grid, faces: &[Face], crossings: &mut Crossings) -> usize {
    let cpu = field.on_cpu();
    let step = cpu.gradient_step(grid.h);
    if field.gradient_step(grid.h) <= step {
        return 0;
    }
    let mut marked: HashSet<u32> = HashSet::default();
    for &f in faces {
        let on: Vec<Crossing> = f
            .edges()
            .into_iter()
            .filter_map(|(p, a)| crossings.by_edge.get(&edge_key(grid, p, a)))
            .flat_map(Crossed::iter)
            .collect();
        for (i, x) in on.iter().enumerate() {
            for y in &on[i + 1..] {
                if x.normal.dot(y.normal) < SHARPEN_COSINE {
                    marked.extend([x.vertex, y.vertex]);
                }
            }
        }
    }
    let list: Vec<u32> = marked.into_iter().collect();
    let positions = &crossings.positions;
    let fresh = crate::parallel::par_map(&list, |&v| cpu.normal(positions[v as usize], step));
    for (&v, n) in list.iter().zip(fresh) {
        crossings.normals[v as usize] = n;
    }
    let normals = &crossings.normals;
    for c in crossings.by_edge.values_mut() {
        c.first.normal = normals[c.first.vertex as usize];
        if let Some(s) = &mut c.second {
            s.normal = normals[s.vertex as usize];
        }
    }
    4 * list.len()
}

/// The four cells around the grid edge from `p` along `axis`.
fn around((p, axis): (IVec3, usize)) -> [IVec3; 4] {
    let (u, v) = (IVec3::AXES[(axis + 1) % 3], IVec3::AXES[(axis + 2) % 3]);
    [p, p - u, p - v, p - u - v]
}

/// A key for the grid edge from `p` along `axis` (or the face at `p` normal to it).
pub fn edge_key(grid: &Grid, p: IVec3, axis: usize) -> u64 {
    grid.key(p) * 3 + axis as u64
}

/// Edge `i` (0..12) of cell `c`: its lowest end and axis.
fn cell_edge(c: IVec3, i: i32) -> (IVec3, usize) {
    let axis = (i / 4) as usize;
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let p = c + IVec3::AXES[u] * (i & 1) + IVec3::AXES[v] * ((i >> 1) & 1);
    (p, axis)
}

/// The evaluations a [`Dip`] spends at most on one edge (8 missed a box's crease poking a
/// hundredth of a cell through an edge near its end, which 16 finds; 16 missed one 0.003 of a
/// cell through, which 32 finds; 64 found no more on the turned box at 168 placements).
const DIP_STEPS: usize = 32;

/// The search, along an edge whose ends lie on the same side, for a point on the other side:
/// the field being 1-Lipschitz, |d| over a stretch from s to t is at least the lower of the
/// two cones |d(s)| − (x − s) and |d(t)| − (t − x), lowest where they meet, at
/// (|d(s)| + |d(t)| − (t − s)) / 2. The stretch of the lowest such bound is sampled next where
/// its cones meet (Piyavskii's and Shubert's search for a Lipschitz function's minimum), the
/// stretches the bound keeps on the ends' side dropped, until a point on the other side is
/// found, none is left or [`DIP_STEPS`] are spent. (Halving the stretches instead missed the
/// dip of a crease passing 0.04 of a cell from an edge: the smaller end drew the search away.)
struct Dip {
    /// The edge's start, extent, and the field at its ends.
    a: DVec3,
    along: DVec3,
    ends: (f64, f64),
    /// The grid edge.
    edge: (IVec3, usize),
    /// The ends' side.
    side: bool,
    /// The stretches not yet ruled out: parameters and the field there.
    open: Vec<(f64, f64, f64, f64)>,
    steps: usize,
    /// The shortest stretch halved (f32's resolution on the GPU).
    shortest: f64,
    /// The point found on the other side: its parameter and the field there.
    found: Option<(f64, f64)>,
}

impl Dip {
    fn new(field: &Field, a: DVec3, along: DVec3, ends: (f64, f64), edge: (IVec3, usize)) -> Dip {
        Dip {
            a,
            along,
            ends,
            edge,
            side: inside(ends.0),
            open: vec![(0.0, ends.0, 1.0, ends.1)],
            steps: 0,
            shortest: (2.0 * field.resolution() / along.length()).max(1e-6),
            found: None,
        }
    }

    /// The open stretch nearest to holding a dip (its ends' distances least over its length).
    fn next(&self) -> Option<usize> {
        let len = self.along.length();
        let low = |&(t0, d0, t1, d1): &(f64, f64, f64, f64)| d0.abs() + d1.abs() - (t1 - t0) * len;
        (0..self.open.len()).min_by(|&i, &j| low(&self.open[i]).total_cmp(&low(&self.open[j])))
    }

    /// Where the cones of the stretch from `t0` to `t1` meet, kept a twentieth of it off its
    /// ends.
    fn apex(&self, (t0, d0, t1, d1): (f64, f64, f64, f64)) -> f64 {
        let meet = 0.5 * (t0 + t1) + (d0.abs() - d1.abs()) / (2.0 * self.along.length());
        let margin = 0.05 * (t1 - t0);
        meet.clamp(t0 + margin, t1 - margin)
    }
}

impl Search for Dip {
    fn ask(&self, points: &mut Vec<DVec3>) {
        if self.found.is_some() || self.steps == DIP_STEPS {
            return;
        }
        if let Some(i) = self.next() {
            points.push(self.a + self.along * self.apex(self.open[i]));
        }
    }

    fn tell(&mut self, values: &[f64]) {
        let Some(i) = self.next() else { return };
        let (t0, d0, t1, d1) = self.open.swap_remove(i);
        let (tm, dm) = (self.apex((t0, d0, t1, d1)), values[0]);
        self.steps += 1;
        if inside(dm) != self.side && !dm.is_nan() {
            self.found = Some((tm, dm));
            return;
        }
        let len = self.along.length();
        for (s0, e0, s1, e1) in [(t0, d0, tm, dm), (tm, dm, t1, d1)] {
            // (NaN fails the test and is dropped.)
            if e0.abs() + e1.abs() < (s1 - s0) * len && s1 - s0 > self.shortest {
                self.open.push((s0, e0, s1, e1));
            }
        }
    }
}

/// The search for where the surface crosses a grid edge (or a part of one) from `a` (field
/// `fa`) to the point of field `fb`: Illinois regula falsi on the side change, kept [`END_GAP`] off
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
    /// The search along `along` from `a` (field `fa`) to `a + along` (field `fb`), on a grid of
    /// cells `h`.
    fn new(field: &Field, h: f64, (a, fa): (DVec3, f64), along: DVec3, fb: f64) -> Root {
        let res = field.resolution();
        let mut root = Root {
            a,
            along,
            t0: 0.0,
            f0: fa,
            t1: 1.0,
            f1: fb,
            t: 0.5,
            last_side: 0,
            steps: 0,
            tol_f: (1e-9 * h).max(res),
            tol_t: 1e-9f64.max(res / along.length()),
            step: field.gradient_step(h),
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
