//! How a face's trace bends between two crossings: where their tangent lines meet (a crease,
//! Ho et al., *Cubical Marching Squares*, 2005, §3–4), sampled across the chord where it bends
//! more than once (a corner), and where it dips in from an edge crossed twice.

use super::edges::Crossing;
use super::field::{Face, Field, Grid, inside};
use super::search::{self, Search};
use glam::DVec3;

/// The smallest sine of the angle between the tangent lines of a face's two crossings at
/// which their meeting point is taken as a crease (about 3°).
const CREASE_SINE: f64 = 0.05;

/// The normals of the two planes whose crease a sharp point lies on.
pub type Planes = (DVec3, DVec3);

/// A point where a face's trace bends, or one it passes through.
#[derive(Clone, Copy, Debug)]
pub struct Sharp {
    /// Where.
    pub at: DVec3,
    /// Where the tangent lines of two surface points with these normals met there (a crease),
    /// those normals; `None` for a point sampled on the trace.
    pub planes: Option<Planes>,
}

/// How close to the surface (in cells) a face's sharp point must come to be kept.
const ON_SURFACE: f64 = 1e-7;

/// Where the trace of a face dips in from its edge `edge` (0..4, as [`Face::edges`]) between
/// that edge's two crossings `x` and `y`: where their tangent lines meet inside the face (a
/// crease), settled on the surface; else the first surface point from the middle of the chord
/// straight into the face. Without such a point, the polygons of the cells at the edge would
/// close on the chord alone, and it would be shared by more than two triangles.
pub fn apex(
    field: &Field,
    grid: &Grid,
    (face, edge): (Face, usize),
    (x, y): (Crossing, Crossing),
    spent: &mut usize,
) -> Option<Sharp> {
    let mid = 0.5 * (x.position + y.position);
    if let Some(Meet::Inside(p)) = meet(face, grid, (x.position, x.normal), (y.position, y.normal))
        && let Some(at) = between(field, grid, p, mid, spent)
    {
        let planes = Some((x.normal, y.normal));
        return Some(Sharp { at, planes });
    }
    let at = march(
        field,
        grid,
        mid,
        mid + into_face(face, edge) * grid.h,
        spent,
    )?;
    Some(Sharp { at, planes: None })
}

/// The direction from `face`'s edge `edge` (0..4, as [`Face::edges`]) into the face.
pub fn into_face(face: Face, edge: usize) -> DVec3 {
    // Edges 0 and 2 run along u and lie at v's low and high side; 1 and 3 along v, at u's high
    // and low side.
    let (u, v) = face.span();
    let mut into = DVec3::ZERO;
    match edge {
        0 => into[v] = 1.0,
        1 => into[u] = -1.0,
        2 => into[v] = -1.0,
        _ => into[u] = 1.0,
    }
    into
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
pub fn bends(
    field: &Field,
    grid: &Grid,
    face: Face,
    (a, b): (Point, Point),
    evaluations: &mut usize,
) -> Bends {
    let found = meet(face, grid, a, b);
    match found {
        Some(Meet::Inside(p)) => {
            let mut search = Bisect::new(field, grid, p, 0.5 * (a.0 + b.0), (a.0, b.0));
            search.planes = Some((a.1, b.1));
            return Bends::Pending(search);
        }
        // Two faces of a corner meet at a wide angle; a rough surface (a fractal) bends between
        // every two crossings by less, and sampling each of its faces would cost a dozen
        // evaluations and six vertices for nothing a chord does not do. Tangent lines that do
        // not meet (parallel in the face) with normals that far apart and opposite in the face
        // turn back: the trace crosses a third plane between them (a box's corner, its crease
        // parallel to the face) and is sampled too.
        _ if a.1.dot(b.1) > CORNER_COSINE => return Bends::Found(Vec::new()),
        None if !opposite(face, a.1, b.1) => return Bends::Found(Vec::new()),
        _ => {}
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
        if let Some(Meet::Inside(m)) = meet(face, grid, p, q)
            && let Some(at) = between(field, grid, m, 0.5 * (p.0 + q.0), evaluations)
        {
            let planes = Some((p.1, q.1));
            out.push(Sharp { at, planes });
        }
        if k + 2 < samples.len() {
            out.push(Sharp {
                at: q.0,
                planes: None,
            });
        }
    }
    Bends::Found(out)
}

/// Whether the normals `a` and `b`, seen within `face`'s plane, point about opposite ways (a
/// trace that turns back between them; a rough surface's traces, parallel by chance, do not).
fn opposite(face: Face, a: DVec3, b: DVec3) -> bool {
    let (u, v) = face.span();
    let flat = |n: DVec3| glam::DVec2::new(n[u], n[v]).try_normalize();
    matches!((flat(a), flat(b)), (Some(p), Some(q)) if p.dot(q) < -0.9)
}

/// What [`bends`] finds.
pub enum Bends {
    /// The bends, in order from `a` to `b`.
    Found(Vec<Sharp>),
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
    /// The planes whose crease it is sought on, if a crease's.
    pub planes: Option<Planes>,
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
            planes: None,
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
