//! How a face's trace bends between two crossings: where their tangent lines meet (a crease,
//! Ho et al., *Cubical Marching Squares*, 2005, §3–4), followed further where it bends more
//! than once (across a corner's faces), and where it dips in from an edge crossed twice.

use super::edges::Crossing;
use super::field::{Face, Field, Grid};
use super::trace::{
    Bracket, Meet, Point, along_trace, at_meet, between, into_face, march, meet, opposite, simple,
    to_edge,
};
pub use super::trace::{Planes, Sharp};
use super::walk::walk;
use glam::DVec3;

/// What [`bends`] finds.
pub enum Bends {
    /// The bends, in order from `a` to `b`.
    Found(Vec<Sharp>),
    /// The one bend, once this search has run.
    Pending(Box<Bracket>),
}

/// Where a face's trace bends more than once, the points across its chord at which it is
/// sampled.
const STATIONS: usize = 6;

/// The cosine of the smallest angle between the normals at two points of a face's trace for
/// which the trace between them is followed past one bend (45°: a box's faces meet at 90°, a
/// hexagonal prism's two apart at 120°, a dodecahedron's at 63°). A rough surface (a fractal)
/// bends between every two crossings by less, and following each of its faces would cost a
/// dozen evaluations and six vertices for nothing a chord does not do.
pub const CORNER_COSINE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// How many times the trace between two points is followed further: sampled across, or split
/// at a point found between ([`pair`]).
pub const DEPTH: usize = 3;

/// The points where the surface's trace on `face` bends between the surface points `a` and
/// `b`. Where their tangent lines meet inside the face, the search for that one bend is left
/// to the batches (a [`Bracket`]: what it finds short of the meeting point is followed with
/// [`either_side`]); elsewhere the trace is followed here on the CPU ([`pair`]: corners are
/// few). On a face that `shares` with another segment (four crossings), only the lines'
/// meeting point, found on the surface, is taken: a search across the face could reach the
/// other segment's trace.
pub fn bends(
    field: &Field,
    grid: &Grid,
    (face, shares): (Face, bool),
    (a, b): (Point, Point),
    evaluations: &mut usize,
) -> Bends {
    match meet(face, grid, a, b) {
        Some(Meet::Inside(p)) => {
            let mut search = Bracket::new(field, grid, p, 0.5 * (a.0 + b.0), (a.0, b.0));
            search.planes = Some((a.1, b.1));
            search.only_crease = shares;
            Bends::Pending(Box::new(search))
        }
        _ if shares => Bends::Found(Vec::new()),
        _ => {
            let found = pair(field, grid, face, (a, b), DEPTH, evaluations);
            Bends::Found(untangled(face, a.0, found, b.0))
        }
    }
}

/// The trace from `a` through `found` to `b` if it does not cross or fold back on itself
/// within the face; else its crease points alone if they do not, else nothing. A bend just
/// past the face's edge (a crease's wedge poking through it by less than the edge's search
/// finds) makes the trace turn outside the face, and the points followed toward it from both
/// sides overlap.
pub fn untangled(face: Face, a: DVec3, found: Vec<Sharp>, b: DVec3) -> Vec<Sharp> {
    let path = |points: &[Sharp]| {
        let mut path = vec![a];
        path.extend(points.iter().map(|s| s.at));
        path.push(b);
        path
    };
    if simple(face, &path(&found)) {
        return found;
    }
    let creases: Vec<Sharp> = found.into_iter().filter(|s| s.planes.is_some()).collect();
    match simple(face, &path(&creases)) {
        true => creases,
        false => Vec::new(),
    }
}

/// Where the trace of a face dips in from its edge `edge` (0..4, as [`Face::edges`]) between
/// that edge's two crossings `x` and `y`, in order from `x`: where their tangent lines meet
/// inside the face and on the surface (a crease); else a surface point between (from the
/// meeting point toward the chord's middle, or from the middle into the face: [`dip`]) and the
/// bends on either side of it (a corner just past the face cuts it in a small triangle, whose
/// two bends inside the face are two of its creases). Without such a point, the polygons of
/// the cells at the edge would close on the chord alone, and it would be shared by more than
/// two triangles.
pub fn apex(
    field: &Field,
    grid: &Grid,
    (face, edge): (Face, usize),
    (x, y): (Crossing, Crossing),
    spent: &mut usize,
) -> Vec<Sharp> {
    let mid = 0.5 * (x.position + y.position);
    let (x, y) = ((x.position, x.normal), (y.position, y.normal));
    let found = match meet(face, grid, x, y) {
        Some(Meet::Inside(p)) => match between(field, grid, p, mid, spent) {
            Some(at) if at_meet(at, p, grid) => {
                let planes = Some((x.1, y.1));
                return vec![Sharp { at, planes }];
            }
            found => found,
        },
        _ => None,
    };
    let dir = dip(face, edge, x.1, y.1);
    let into = mid + dir * to_edge(grid, face, mid, dir).unwrap_or(grid.h);
    match found.or_else(|| march(field, grid, mid, into, spent)) {
        Some(at) => {
            let found = either_side(field, grid, face, (x, at, y), DEPTH - 1, spent);
            match untangled(face, x.0, found, y.0) {
                // (The dip's one point, rather than none: the chord needs one.)
                found if found.is_empty() => vec![Sharp { at, planes: None }],
                found => found,
            }
        }
        None => Vec::new(),
    }
}

/// The path of a face's trace from `a` through `at` (a surface point between, not a crease's)
/// to `b`: where it bends between `a` and `at` ([`pair`], `depth` levels), `at`, and where it
/// bends between `at` and `b`.
pub fn either_side(
    field: &Field,
    grid: &Grid,
    face: Face,
    (a, at, b): (Point, DVec3, Point),
    depth: usize,
    spent: &mut usize,
) -> Vec<Sharp> {
    let field = &field.on_cpu();
    *spent += 4;
    let m = (at, field.normal(at, field.gradient_step(grid.h)));
    let mut out = pair(field, grid, face, (a, m), depth, spent);
    out.push(Sharp { at, planes: None });
    out.extend(pair(field, grid, face, (m, b), depth, spent));
    out
}

/// Where the trace of `face` bends strictly between its surface points `p` and `q`, in order:
/// - tangent lines meeting inside the face: their meeting point, settled on the surface (a
///   crease); a surface point short of it (a third plane cuts the meeting point off) is
///   followed on either side;
/// - meeting outside: the trace bends more than once (across a corner's three faces), and is
///   sampled across the chord at [`STATIONS`] points, each two neighbours followed the same way;
/// - parallel and facing opposite ways: the trace turns back through a third plane (a U: a
///   box's corner whose crease runs along the face); its bottom, the first surface point from
///   the chord's middle along the lines, is followed on either side (sampled if not found).
///
/// All but the first only where the normals lie more than 45° apart ([`CORNER_COSINE`]), and
/// `depth` levels deep.
fn pair(
    field: &Field,
    grid: &Grid,
    face: Face,
    (p, q): (Point, Point),
    depth: usize,
    spent: &mut usize,
) -> Vec<Sharp> {
    let field = &field.on_cpu();
    let follow = depth > 0 && p.1.dot(q.1) <= CORNER_COSINE;
    let mid = 0.5 * (p.0 + q.0);
    match meet(face, grid, p, q) {
        Some(Meet::Inside(c)) => match between(field, grid, c, mid, spent) {
            Some(at) if at_meet(at, c, grid) => vec![Sharp {
                at,
                planes: Some((p.1, q.1)),
            }],
            Some(at) if follow => either_side(field, grid, face, (p, at, q), depth - 1, spent),
            Some(at) => vec![Sharp { at, planes: None }],
            None => Vec::new(),
        },
        Some(Meet::Outside) if follow => walk(field, grid, face, (p, q), spent)
            .unwrap_or_else(|| sampled(field, grid, face, (p, q), depth - 1, spent)),
        None if follow && opposite(face, p.1, q.1) => {
            if let Some(found) = walk(field, grid, face, (p, q), spent) {
                return found;
            }
            match bottom(field, grid, face, (p, q), spent) {
                Some(at) => either_side(field, grid, face, (p, at, q), depth - 1, spent),
                None => sampled(field, grid, face, (p, q), depth - 1, spent),
            }
        }
        _ => Vec::new(),
    }
}

/// The bottom of a U-turn between `p` and `q`, whose tangent lines run parallel: the nearest
/// surface point from the middle of their chord along the lines, either way, within the face.
fn bottom(
    field: &Field,
    grid: &Grid,
    face: Face,
    (p, q): (Point, Point),
    spent: &mut usize,
) -> Option<DVec3> {
    let mid = 0.5 * (p.0 + q.0);
    nearest_along(field, grid, face, (mid, along_trace(face, p.1)), spent)
}

/// The surface point nearest `from` along the line through it in direction `dir` (either way),
/// within `face`: the first point of a march each way to the face's edge.
fn nearest_along(
    field: &Field,
    grid: &Grid,
    face: Face,
    (from, dir): (DVec3, DVec3),
    spent: &mut usize,
) -> Option<DVec3> {
    [dir, -dir]
        .into_iter()
        .filter_map(|d| {
            let reach = to_edge(grid, face, from, d)?;
            march(field, grid, from, from + d * reach, spent)
        })
        .min_by(|a, b| (*a - from).length().total_cmp(&(*b - from).length()))
}

/// The trace from `a` to `b` sampled at [`STATIONS`] points across the chord (the nearest
/// surface point to each, either way across), each two neighbours followed with [`pair`]
/// (`depth` levels) and the stations kept as points of the trace.
fn sampled(
    field: &Field,
    grid: &Grid,
    face: Face,
    (a, b): (Point, Point),
    depth: usize,
    evaluations: &mut usize,
) -> Vec<Sharp> {
    let field = &field.on_cpu();
    let (u, v) = face.span();
    let mut across = DVec3::ZERO;
    across[u] = -(b.0 - a.0)[v];
    across[v] = (b.0 - a.0)[u];
    let mut samples = vec![a];
    for k in 1..=STATIONS {
        let station = a.0 + (b.0 - a.0) * (k as f64 / (STATIONS + 1) as f64);
        if let Some(p) = nearest_along(field, grid, face, (station, across), evaluations) {
            *evaluations += 4;
            samples.push((p, field.normal(p, field.gradient_step(grid.h))));
        }
    }
    samples.push(b);
    let mut out = Vec::new();
    for (k, w) in samples.windows(2).enumerate() {
        out.extend(pair(field, grid, face, (w[0], w[1]), depth, evaluations));
        if k + 2 < samples.len() {
            out.push(Sharp {
                at: w[1].0,
                planes: None,
            });
        }
    }
    out
}

/// The direction in which a trace dipping in from `face`'s edge `edge` between crossings of
/// normals `a` and `b` goes deepest: along its two sides where they run parallel, opposite ways
/// (a U whose bottom is a third plane: a box's corner whose crease runs along the face), else
/// straight into the face.
fn dip(face: Face, edge: usize, a: DVec3, b: DVec3) -> DVec3 {
    let into = into_face(face, edge);
    if !opposite(face, a, b) {
        return into;
    }
    let side = along_trace(face, a);
    let side = side * into.dot(side).signum();
    // (Sides nearly along the edge: no deeper direction than straight in.)
    match side.dot(into) > 0.5 {
        true => side,
        false => into,
    }
}
