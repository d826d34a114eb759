//! Walking a face's trace across a corner's planes: from one end along its tangent line to
//! where the field leaves that line (a crease), onto the next plane, until the other end's
//! line is met — each bend found on its crease, however short the plane between.

use super::field::{Face, Field, Grid, inside};
use super::trace::{Meet, Point, Sharp, along_trace, between, meet, to_edge};
use glam::DVec3;

/// How far (in cells) the field may be from zero on a tangent line for the line to lie on
/// the surface (the normals come from differences a ten-thousandth of a cell apart).
const ON_LINE: f64 = 1e-6;

/// How far from a bend (in cells) the next plane's surface point is sought.
const BEYOND: f64 = 1e-3;

/// The points on the circle around a bend at which the field is asked.
const AROUND: usize = 16;

/// The shortest stretch (in cells) of a plane's line a walk follows.
const MIN_RUN: f64 = 1e-2;

/// The most bends a walk takes before it gives up (a trace that curves, not bends).
const MAX_BENDS: usize = 6;

/// The cosine above which two normals are one plane's.
const SAME_PLANE: f64 = 0.9999;

/// The bends of `face`'s trace from `a` to `b`, where it runs along planes (a corner's, or a
/// crease's parallel to the face): from `a` along its tangent line to the last point where the
/// field stays zero on it (bisection: the field leaves a plane's line at its crease), then
/// from a surface point just past that bend along the next plane's line, until a line meets
/// `b`'s inside the face on the surface or is `b`'s own. Every bend is a crease point (its two
/// planes given). `None` where the walk leaves the face, finds no next plane, follows a line
/// less than [`MIN_RUN`] or bends more than [`MAX_BENDS`] times (a curved trace: `bends`
/// samples it instead).
pub fn walk(
    field: &Field,
    grid: &Grid,
    face: Face,
    (a, b): (Point, Point),
    spent: &mut usize,
) -> Option<Vec<Sharp>> {
    let field = &field.on_cpu();
    let (h, tol) = (grid.h, ON_LINE * grid.h);
    let mut out = Vec::new();
    let mut cur = a;
    let mut dir = start(grid, face, a, b)?;
    for _ in 0..MAX_BENDS {
        if let Some(Meet::Inside(c)) = meet(face, grid, cur, b) {
            *spent += 1;
            if (c - cur.0).dot(dir) > 0.0 && field.at(c).abs() <= tol {
                out.push(Sharp {
                    at: c,
                    planes: Some((cur.1, b.1)),
                });
                return Some(out);
            }
        }
        if cur.1.dot(b.1) > SAME_PLANE && cur.1.dot(b.0 - cur.0).abs() <= tol {
            return Some(out);
        }
        let reach = to_edge(grid, face, cur.0, dir)?;
        let on = |t: f64, spent: &mut usize| {
            *spent += 1;
            field.at(cur.0 + dir * t).abs() <= tol
        };
        // (A trace that leaves its tangent line within a hundredth of a cell curves: a rough
        // surface's, which the stations sample for less.)
        if on(reach, spent) || !on(reach.min(MIN_RUN * h), spent) {
            return None;
        }
        let (mut lo, mut hi) = (0.0, reach);
        while hi - lo > 1e-9 * h {
            let mid = 0.5 * (lo + hi);
            match on(mid, spent) {
                true => lo = mid,
                false => hi = mid,
            }
        }
        let bend = cur.0 + dir * lo;
        let q = next_plane(field, grid, face, (bend, dir), spent)?;
        *spent += 6;
        let n = field.normal(q, field.gradient_step(h));
        if n.dot(cur.1) > SAME_PLANE {
            return None;
        }
        // (Where the two planes' lines meet is more precise than the bisection's end.)
        let bend = match meet(face, grid, cur, (q, n)) {
            Some(Meet::Inside(c)) if (c - bend).length() <= BEYOND * h => c,
            _ => bend,
        };
        out.push(Sharp {
            at: bend,
            planes: Some((cur.1, n)),
        });
        let next = along(face, n)?;
        dir = next * (q - bend).dot(next).signum();
        cur = (bend, n);
    }
    None
}

/// A surface point of the plane the trace turns onto at `bend`, having come along `dir`: of
/// the two points where the trace crosses a circle of radius [`BEYOND`] around the bend (sampled
/// at [`AROUND`] points, each sign change bisected), the one farther from where it came from.
fn next_plane(
    field: &Field,
    grid: &Grid,
    face: Face,
    (bend, dir): (DVec3, DVec3),
    spent: &mut usize,
) -> Option<DVec3> {
    let (u, v) = face.span();
    let ring: Vec<DVec3> = (0..AROUND)
        .map(|k| {
            let (s, c) = (std::f64::consts::TAU * k as f64 / AROUND as f64).sin_cos();
            let mut p = bend;
            p[u] += c * BEYOND * grid.h;
            p[v] += s * BEYOND * grid.h;
            p
        })
        .collect();
    *spent += AROUND;
    let values: Vec<f64> = ring.iter().map(|&p| field.at(p)).collect();
    let crossed: Vec<DVec3> = (0..AROUND)
        .filter(|&k| inside(values[k]) != inside(values[(k + 1) % AROUND]))
        .filter_map(|k| between(field, grid, ring[k], ring[(k + 1) % AROUND], spent))
        .collect();
    match crossed[..] {
        [p, q] => Some(match (p - bend).dot(dir) > (q - bend).dot(dir) {
            true => p,
            false => q,
        }),
        _ => None,
    }
}

/// The direction along `a`'s tangent line in which the trace leaves it: into the face from
/// an edge, else toward `b`.
fn start(grid: &Grid, face: Face, a: Point, b: Point) -> Option<DVec3> {
    let d = along(face, a.1)?;
    let reach = |d: DVec3| to_edge(grid, face, a.0, d).unwrap_or(0.0);
    let edge = 1e-9 * grid.h;
    Some(match (reach(d) > edge, reach(-d) > edge) {
        (true, false) => d,
        (false, true) => -d,
        (false, false) => return None,
        (true, true) => d * (b.0 - a.0).dot(d).signum(),
    })
}

/// The unit direction within `face` of the tangent line of a surface point of normal `n`
/// ([`along_trace`]), if `n` is not normal to the face.
fn along(face: Face, n: DVec3) -> Option<DVec3> {
    Some(along_trace(face, n)).filter(|d| *d != DVec3::ZERO)
}
