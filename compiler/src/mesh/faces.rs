//! The surface's trace on one face of the grid: marching squares with the face's own centre
//! deciding an ambiguous face, so that both cells sharing it draw the same segments, and a
//! sharp point where the two tangent lines of a crease meet inside the face (Ho et al.,
//! *Cubical Marching Squares*, 2005, §3–4).

use super::field::{Field, Grid, inside};
use super::search::{self, Search};
use glam::{DVec3, IVec3};

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

/// A face of the grid: its lowest corner and the axis it is normal to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Face {
    /// The lowest corner.
    pub base: IVec3,
    /// The axis the face is normal to (0, 1, 2).
    pub axis: usize,
}

/// A path across a face from one crossing to another, through a sharp point or not.
#[derive(Clone, Debug)]
pub struct Segment {
    /// The crossing it starts at.
    pub from: u32,
    /// The sharp points in between, in order (positions; their indices are given later).
    pub sharp: Vec<DVec3>,
    /// The crossing it ends at.
    pub to: u32,
    /// The search for its sharp point, where one runs in the next batches (its result, kept
    /// [`MIN_GAP`] off the ends, becomes `sharp`).
    pub pending: Option<Bisect>,
}

/// The smallest sine of the angle between the tangent lines of a face's two crossings at
/// which their meeting point is taken as a crease (about 3°).
const CREASE_SINE: f64 = 0.05;

/// How close to the surface (in cells) a face's sharp point must come to be kept.
const ON_SURFACE: f64 = 1e-7;

impl Face {
    /// The two axes spanning the face, in the order that makes them right-handed with its
    /// normal (u × v = the normal).
    pub fn span(self) -> (usize, usize) {
        ((self.axis + 1) % 3, (self.axis + 2) % 3)
    }

    /// The face's four corners, counter-clockwise seen from the normal's positive side.
    pub fn corners(self) -> [IVec3; 4] {
        let (u, v) = self.span();
        let (eu, ev) = (IVec3::AXES[u], IVec3::AXES[v]);
        [
            self.base,
            self.base + eu,
            self.base + eu + ev,
            self.base + ev,
        ]
    }

    /// Face `i` (0..6) of cell `c`, and whether it is the cell's far side along its axis (its
    /// outward normal is then the axis; else the opposite).
    pub fn of_cell(c: IVec3, i: i32) -> (Face, bool) {
        let axis = (i / 2) as usize;
        let far = i % 2 == 1;
        let base = if far { c + IVec3::AXES[axis] } else { c };
        (Face { base, axis }, far)
    }

    /// Its four edges in the same order (edge i from corner i to corner i + 1), each as the
    /// grid edge's lowest end and axis.
    pub fn edges(self) -> [(IVec3, usize); 4] {
        let (u, v) = self.span();
        let c = self.corners();
        [(c[0], u), (c[1], v), (c[3], u), (c[0], v)]
    }
}

/// The segments the surface draws on `face`, oriented so that, seen from the normal's positive
/// side, the inside lies to their left. `value` gives the field at a grid point and `crossing`
/// the crossing on a grid edge. An ambiguous face (inside corners on a diagonal) joins its
/// inside corners where the field at its centre (`centre`, from [`centre`]'s point) is inside,
/// else keeps them apart; with `sharp`, a face of two crossings whose tangent lines meet at an
/// angle, inside the face and on the surface, gets that point (a [`Bisect`] left pending in the
/// segment; where they meet outside, the trace's bends are searched here on the CPU). Returns
/// the segments and the evaluations spent.
pub fn segments(
    field: &Field,
    grid: &Grid,
    (face, centre): (Face, f64),
    value: impl Fn(IVec3) -> f64,
    crossing: impl Fn((IVec3, usize)) -> Option<Crossing>,
    sharp: bool,
) -> (Vec<Segment>, usize) {
    let s = face.corners().map(|c| inside(value(c)));
    let x = face.edges().map(&crossing);
    let on: Vec<usize> = (0..4).filter(|&i| s[i] != s[(i + 1) % 4]).collect();
    let vertex = |i: usize| x[i].map_or(0, |c| c.vertex);
    let mut evaluations = 0;
    let pairs: Vec<(usize, usize)> = match on.len() {
        2 => {
            let (exit, entry) = if s[on[0]] {
                (on[0], on[1])
            } else {
                (on[1], on[0])
            };
            vec![(exit, entry)]
        }
        4 => {
            let joined = inside(centre);
            // Exits are the edges leaving an inside corner.
            let exits = (0..4).filter(|&i| s[i]);
            exits
                .map(|i| (i, if joined { (i + 1) % 4 } else { (i + 3) % 4 }))
                .collect()
        }
        _ => Vec::new(),
    };
    let mut out = Vec::with_capacity(pairs.len());

    for (exit, entry) in pairs {
        let mut segment = Segment {
            from: vertex(exit),
            sharp: Vec::new(),
            to: vertex(entry),
            pending: None,
        };
        if sharp
            && on.len() == 2
            && let (Some(a), Some(b)) = (x[exit], x[entry])
        {
            let ends = ((a.position, a.normal), (b.position, b.normal));
            match bends(field, grid, face, ends, &mut evaluations) {
                Bends::Found(found) => {
                    segment.sharp = apart(a.position, found, b.position, grid.h);
                }
                Bends::Pending(search) => segment.pending = Some(search),
            }
        }
        out.push(segment);
    }
    (out, evaluations)
}

/// Whether the face is ambiguous (its inside corners on a diagonal, by `value` at grid points)
/// and so needs the field at its [`centre`].
pub fn ambiguous(face: Face, value: impl Fn(IVec3) -> f64) -> bool {
    let s = face.corners().map(|c| inside(value(c)));
    s[0] == s[2] && s[1] == s[3] && s[0] != s[1]
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
pub fn apart(a: DVec3, found: Vec<DVec3>, b: DVec3, h: f64) -> Vec<DVec3> {
    let mut last = a;
    let mut out = Vec::with_capacity(found.len());
    for p in found {
        if (p - last).length() >= MIN_GAP * h && (p - b).length() >= MIN_GAP * h {
            out.push(p);
            last = p;
        }
    }
    out
}

/// Where a face's trace bends more than once, the points across its chord at which it is
/// sampled.
const STATIONS: usize = 6;

/// The cosine of the smallest angle between the normals at a face's two crossings for which a
/// trace bending more than once is sampled (45°: a box's faces meet at 90°, a hexagonal
/// prism's two apart at 120°, a dodecahedron's at 63°).
const CORNER_COSINE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// A surface point and its normal.
type Point = (DVec3, DVec3);

/// The points where the surface's trace on `face` bends between the surface points `a` and
/// `b`: where their tangent lines meet, settled on the surface. Where the lines meet outside
/// the face, the trace bends more than once (across a corner's three faces): it is sampled
/// across the chord at [`STATIONS`] points and each pair of neighbours searched the same way;
/// the samples are kept too (on the CPU, point by point: corners are few). Where they meet
/// inside, the search for the one bend is left to the batches.
fn bends(
    field: &Field,
    grid: &Grid,
    face: Face,
    (a, b): (Point, Point),
    evaluations: &mut usize,
) -> Bends {
    match meet(face, grid, a, b) {
        None => return Bends::Found(Vec::new()),
        Some(Meet::Inside(p)) => {
            return Bends::Pending(Bisect::new(field, grid, p, 0.5 * (a.0 + b.0), (a.0, b.0)));
        }
        // Two faces of a corner meet at a wide angle; a rough surface (a fractal) bends between
        // every two crossings by less, and sampling each of its faces would cost a dozen
        // evaluations and six vertices for nothing a chord does not do.
        Some(Meet::Outside) if a.1.dot(b.1) > CORNER_COSINE => return Bends::Found(Vec::new()),
        Some(Meet::Outside) => {}
    }
    let field = &field.on_cpu();
    let (u, v) = face.span();
    let mut across = DVec3::ZERO;
    across[u] = -(b.0 - a.0)[v];
    across[v] = (b.0 - a.0)[u];
    let mut samples = vec![a];
    for k in 1..=STATIONS {
        let station = a.0 + (b.0 - a.0) * (k as f64 / (STATIONS + 1) as f64);
        let nearest = [across, -across]
            .into_iter()
            .filter_map(|dir| {
                let reach = to_edge(grid, face, station, dir)?;
                march(field, grid, station, station + dir * reach, evaluations)
            })
            .min_by(|p, q| (*p - station).length().total_cmp(&(*q - station).length()));
        if let Some(p) = nearest {
            *evaluations += 4;
            samples.push((p, field.normal(p, field.gradient_step(grid.h))));
        }
    }
    samples.push(b);
    let mut out = Vec::new();
    for (k, pair) in samples.windows(2).enumerate() {
        let (p, q) = (pair[0], pair[1]);
        if let Some(Meet::Inside(m)) = meet(face, grid, p, q) {
            out.extend(between(field, grid, m, 0.5 * (p.0 + q.0), evaluations));
        }
        if k + 2 < samples.len() {
            out.push(q.0);
        }
    }
    Bends::Found(out)
}

/// What [`bends`] finds.
enum Bends {
    /// The bends, in order from `a` to `b`.
    Found(Vec<DVec3>),
    /// The one bend, once this search has run.
    Pending(Bisect),
}

/// Where two tangent lines meet.
enum Meet {
    /// Inside the face, here.
    Inside(DVec3),
    /// Outside the face.
    Outside,
}

/// Where the tangent lines at surface points `a` and `b` within the plane of `face` meet, if
/// they cross at an angle.
fn meet(face: Face, grid: &Grid, a: Point, b: Point) -> Option<Meet> {
    let (u, v) = face.span();
    let flat = |n: DVec3| glam::DVec2::new(n[u], n[v]).try_normalize();
    let (na, nb) = (flat(a.1)?, flat(b.1)?);
    let det = na.perp_dot(nb);
    if det.abs() < CREASE_SINE {
        return None;
    }
    let pa = glam::DVec2::new(a.0[u], a.0[v]);
    let pb = glam::DVec2::new(b.0[u], b.0[v]);
    let (ca, cb) = (na.dot(pa), nb.dot(pb));
    // Cramer's rule for na·x = ca, nb·x = cb.
    let m = glam::DVec2::new(ca * nb.y - cb * na.y, na.x * cb - nb.x * ca) / det;
    let lo = grid.point(face.base);
    let within = |k: usize, x: f64| x > lo[k] && x < lo[k] + grid.h;
    if !(within(u, m.x) && within(v, m.y)) {
        return Some(Meet::Outside);
    }
    let mut p = lo;
    p[u] = m.x;
    p[v] = m.y;
    Some(Meet::Inside(p))
}

/// The surface point on the segment from `p` to `q`, where the field changes side between
/// them (or `p` itself, on the surface), by bisection, on the CPU.
fn between(field: &Field, grid: &Grid, p: DVec3, q: DVec3, spent: &mut usize) -> Option<DVec3> {
    let mut search = [Bisect::new(field, grid, p, q, (p, q))];
    *spent += search::run(field, &mut search);
    let [search] = search;
    search.found
}

/// The search for the surface point on the segment from `p` to `q` (see [`between`]), for a
/// segment of a face's trace from `ends.0` to `ends.1`.
#[derive(Clone, Debug)]
pub struct Bisect {
    lo: DVec3,
    hi: DVec3,
    /// The field at `p` (NaN until told).
    fp: f64,
    /// Done below these: |f| and the bracket's length.
    tol_f: f64,
    tol_len: f64,
    /// The values of both ends are asked for first.
    started: bool,
    done: bool,
    /// The point found.
    pub found: Option<DVec3>,
    /// The trace's segment this point lies on.
    pub ends: (DVec3, DVec3),
}

impl Bisect {
    fn new(field: &Field, grid: &Grid, p: DVec3, q: DVec3, ends: (DVec3, DVec3)) -> Bisect {
        let res = field.resolution();
        Bisect {
            lo: p,
            hi: q,
            fp: f64::NAN,
            tol_f: (ON_SURFACE * grid.h).max(res),
            tol_len: (1e-7 * grid.h).max(res),
            started: false,
            done: false,
            found: None,
            ends,
        }
    }

    /// Done where the bracket is short enough: its middle.
    fn settle(&mut self) {
        if (self.hi - self.lo).length() <= self.tol_len {
            self.found = Some(0.5 * (self.lo + self.hi));
            self.done = true;
        }
    }
}

impl Search for Bisect {
    fn ask(&self, points: &mut Vec<DVec3>) {
        match (self.done, self.started) {
            (true, _) => {}
            (false, false) => points.extend([self.lo, self.hi]),
            (false, true) => points.push(0.5 * (self.lo + self.hi)),
        }
    }

    fn tell(&mut self, values: &[f64]) {
        if !self.started {
            self.started = true;
            let (fp, fq) = (values[0], values[1]);
            self.fp = fp;
            if fp.abs() <= self.tol_f {
                (self.found, self.done) = (Some(self.lo), true);
            } else if inside(fp) == inside(fq) {
                self.done = true;
            } else {
                self.settle();
            }
            return;
        }
        let (f, mid) = (values[0], 0.5 * (self.lo + self.hi));
        if f.abs() <= self.tol_f {
            (self.found, self.done) = (Some(mid), true);
            return;
        }
        if inside(f) == inside(self.fp) {
            self.lo = mid;
        } else {
            self.hi = mid;
        }
        self.settle();
    }
}

/// The first surface point from `p` toward `q`: eight even steps, then [`between`].
fn march(field: &Field, grid: &Grid, p: DVec3, q: DVec3, spent: &mut usize) -> Option<DVec3> {
    const STEPS: usize = 8;
    let side = inside(field.at(p));
    *spent += 1;
    let mut last = p;
    for k in 1..=STEPS {
        let x = p + (q - p) * (k as f64 / STEPS as f64);
        *spent += 1;
        if inside(field.at(x)) != side {
            return between(field, grid, last, x, spent);
        }
        last = x;
    }
    None
}

/// How far from `p` along `dir` (in the face's plane) the face's square ends.
fn to_edge(grid: &Grid, face: Face, p: DVec3, dir: DVec3) -> Option<f64> {
    let (u, v) = face.span();
    let lo = grid.point(face.base);
    let mut reach = f64::INFINITY;
    for k in [u, v] {
        if dir[k] > 0.0 {
            reach = reach.min((lo[k] + grid.h - p[k]) / dir[k]);
        } else if dir[k] < 0.0 {
            reach = reach.min((lo[k] - p[k]) / dir[k]);
        }
    }
    (reach.is_finite() && reach > 0.0).then_some(reach)
}
