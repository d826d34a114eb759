//! Following the surface's trace on a face of the grid: where two tangent lines meet, the
//! surface point between two points by regula falsi (batched, or one at a time on the CPU), a
//! march along a line to the first surface point.

use super::field::{Face, Field, Grid, inside};
use super::search::{self, Illinois, Search};
use glam::DVec3;

/// A point where a face's trace bends, or one it passes through.
#[derive(Clone, Copy, Debug)]
pub struct Sharp {
    /// Where.
    pub at: DVec3,
    /// Where the tangent lines of two surface points with these normals met there (a crease),
    /// those normals; `None` for a point sampled on the trace.
    pub planes: Option<Planes>,
}

/// The smallest sine of the angle between the tangent lines of a face's two crossings at
/// which their meeting point is taken as a crease (about 3°).
const CREASE_SINE: f64 = 0.05;

/// The normals of the two planes whose crease a sharp point lies on.
pub type Planes = (DVec3, DVec3);

/// How close to the surface (in cells) a face's sharp point must come to be kept.
const ON_SURFACE: f64 = 1e-7;

/// The steps a [`Bracket`] takes at most after its two ends (halving alone reaches 1e-7 of a
/// cell in about 23).
const BRACKET_STEPS: usize = 48;

/// A surface point and its normal.
pub type Point = (DVec3, DVec3);

/// How far (in cells) the surface point found from where two tangent lines meet may lie from
/// that point for it to be their crease's: the normals come from differences a ten-thousandth
/// of a cell apart, so the meeting point is a little off; a third plane that cuts the meeting
/// point off (a corner) leaves the point found much farther.
const AT_MEET: f64 = 1e-3;

/// Whether `at`, found from `meet` where two tangent lines meet, is that crease's point.
pub fn at_meet(at: DVec3, meet: DVec3, grid: &Grid) -> bool {
    (at - meet).length() <= AT_MEET * grid.h
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

/// The direction within `face` of the tangent line of a surface point of normal `n` (unit, or
/// zero where `n` is normal to the face).
pub fn along_trace(face: Face, n: DVec3) -> DVec3 {
    let (u, v) = face.span();
    let mut along = DVec3::ZERO;
    (along[u], along[v]) = (-n[v], n[u]);
    along.normalize_or_zero()
}

/// Whether the normals `a` and `b`, seen within `face`'s plane, point about opposite ways (a
/// trace that turns back between them; a rough surface's traces, parallel by chance, do not).
pub fn opposite(face: Face, a: DVec3, b: DVec3) -> bool {
    let (u, v) = face.span();
    let flat = |n: DVec3| glam::DVec2::new(n[u], n[v]).try_normalize();
    matches!((flat(a), flat(b)), (Some(p), Some(q)) if p.dot(q) < -0.9)
}

/// Where two tangent lines meet.
pub enum Meet {
    /// Inside the face, here.
    Inside(DVec3),
    /// Outside the face.
    Outside,
}

/// Where the tangent lines at surface points `a` and `b` within the plane of `face` meet, if
/// they cross at an angle.
pub fn meet(face: Face, grid: &Grid, a: Point, b: Point) -> Option<Meet> {
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
/// them (or `p` itself, on the surface), by Illinois regula falsi (halving where the secant's
/// root falls outside the bracket), on the CPU.
pub fn between(field: &Field, grid: &Grid, p: DVec3, q: DVec3, spent: &mut usize) -> Option<DVec3> {
    let mut search = [Bracket::new(field, grid, p, q, (p, q))];
    *spent += search::run(field, &mut search);
    let [search] = search;
    search.found
}

/// The search for the surface point on the segment from `p` to `q` (see [`between`]), for a
/// segment of a face's trace from `ends.0` to `ends.1`.
#[derive(Clone, Debug)]
pub struct Bracket {
    /// The bracket from `p` to `q` (the field there NaN until told).
    bracket: Illinois<DVec3>,
    steps: usize,
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
    /// Where the search starts (the tangent lines' meeting point, for a crease's).
    pub from: DVec3,
    /// Whether only `from` itself is wanted (a crease's point on a face shared by two
    /// segments), not another point of the trace.
    pub only_crease: bool,
}

impl Bracket {
    pub fn new(field: &Field, grid: &Grid, p: DVec3, q: DVec3, ends: (DVec3, DVec3)) -> Bracket {
        let res = field.resolution();
        Bracket {
            bracket: Illinois::new((p, f64::NAN), (q, f64::NAN)),
            steps: 0,
            tol_f: (ON_SURFACE * grid.h).max(res),
            tol_len: (1e-7 * grid.h).max(res),
            started: false,
            done: false,
            found: None,
            planes: None,
            ends,
            from: p,
            only_crease: false,
        }
    }

    /// The point asked for next: the secant's root inside the bracket (Illinois regula falsi:
    /// on a smooth field a few steps reach [`ON_SURFACE`], where halving took about 23), else
    /// its middle.
    fn next(&self) -> DVec3 {
        let ((lo, flo), (hi, fhi)) = (self.bracket.lo, self.bracket.hi);
        let t = flo / (flo - fhi);
        let t = if t.is_finite() && t > 0.0 && t < 1.0 {
            t
        } else {
            0.5
        };
        lo + (hi - lo) * t
    }

    /// Done where the bracket is short enough (or the steps are spent): its middle.
    fn settle(&mut self) {
        let (lo, hi) = (self.bracket.lo.0, self.bracket.hi.0);
        if (hi - lo).length() <= self.tol_len || self.steps >= BRACKET_STEPS {
            self.found = Some(0.5 * (lo + hi));
            self.done = true;
        }
    }
}

impl Search for Bracket {
    fn ask(&self, points: &mut Vec<DVec3>) {
        match (self.done, self.started) {
            (true, _) => {}
            (false, false) => points.extend([self.bracket.lo.0, self.bracket.hi.0]),
            (false, true) => points.push(self.next()),
        }
    }

    fn tell(&mut self, values: &[f64]) {
        if !self.started {
            self.started = true;
            let (fp, fq) = (values[0], values[1]);
            (self.bracket.lo.1, self.bracket.hi.1) = (fp, fq);
            if fp.abs() <= self.tol_f {
                (self.found, self.done) = (Some(self.bracket.lo.0), true);
            } else if inside(fp) == inside(fq) {
                self.done = true;
            } else {
                self.settle();
            }
            return;
        }
        let (f, x) = (values[0], self.next());
        self.steps += 1;
        if f.abs() <= self.tol_f {
            (self.found, self.done) = (Some(x), true);
            return;
        }
        self.bracket.narrow(x, f);
        self.settle();
    }
}

/// The first surface point from `p` toward `q`: eight even steps, then [`between`].
pub fn march(field: &Field, grid: &Grid, p: DVec3, q: DVec3, spent: &mut usize) -> Option<DVec3> {
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
pub fn to_edge(grid: &Grid, face: Face, p: DVec3, dir: DVec3) -> Option<f64> {
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

/// Whether the path through `points` (in `face`'s plane) is simple: no two of its segments
/// cross or overlap, and none turns straight back on the one before.
pub fn simple(face: Face, points: &[DVec3]) -> bool {
    let (u, v) = face.span();
    let p: Vec<glam::DVec2> = points
        .iter()
        .map(|p| glam::DVec2::new(p[u], p[v]))
        .collect();
    let n = p.len().saturating_sub(1);
    let side = |a: glam::DVec2, b: glam::DVec2, c: glam::DVec2| (b - a).perp_dot(c - a);
    for i in 0..n {
        let (a, b) = (p[i], p[i + 1]);
        if i + 2 <= n {
            // Straight back: the next segment runs along this one the other way.
            let c = p[i + 2];
            let (d1, d2) = (b - a, c - b);
            if d1.perp_dot(d2).abs() <= 1e-9 * d1.length() * d2.length() && d1.dot(d2) < 0.0 {
                return false;
            }
        }
        for j in i + 2..n {
            let (c, d) = (p[j], p[j + 1]);
            let crosses =
                side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0;
            if crosses {
                return false;
            }
        }
    }
    true
}
