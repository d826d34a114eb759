//! Checking `@lipschitz(L)` annotations where rays go: the slope of each annotated node is
//! sampled at the points the camera's rays make it evaluate (up to `max_distance`, in the node's
//! own coordinates, through every transform and copy above it), refined around the steepest
//! samples, and for `implicit` bodies searched by subdividing the region with interval bounds,
//! which finds features too thin for samples. A slope above the annotation is a warning with
//! the place, the slope seen (a lower bound of the true one) and a safe bound where one is known.

use super::reach::{self, Ray};
use super::{Rng, bound_in};
use crate::diag::Diagnostic;
use crate::interval::Interval;
use crate::reference::eval;
use crate::scene::{NodeId, NodeKind, Scene};
use glam::DVec3;

/// How hard to look.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effort {
    /// What `render` and `emit` run on every compile: a few thousand evaluations.
    Fast,
    /// `sdfc check --lipschitz`: ten times the samples and boxes.
    Thorough,
}

/// Samples and search sizes for an effort.
struct Budget {
    /// Points in the camera's frustum (each evaluates the whole scene once).
    world: usize,
    /// Points in the node's own bounding box (or around its origin).
    local: usize,
    /// Steepest samples refined by local search, and the search's steps for each.
    refine: (usize, usize),
    /// Boxes of the interval search (`implicit` only).
    boxes: usize,
    /// Camera rays traced to a surface, whence secondary rays are sampled (scenes with
    /// shadows, occlusion, mirrors or transparent solids).
    hits: usize,
    /// Points sampled on each secondary ray.
    per_ray: usize,
}

impl Effort {
    fn budget(self) -> Budget {
        match self {
            Effort::Fast => Budget {
                world: 1500,
                local: 500,
                refine: (6, 24),
                boxes: 2000,
                hits: 96,
                per_ray: 8,
            },
            Effort::Thorough => Budget {
                world: 15_000,
                local: 5_000,
                refine: (24, 60),
                boxes: 2000,
                hits: 960,
                per_ray: 16,
            },
        }
    }
}

/// A slope above the annotation by more than this factor is reported (sampling noise and f64
/// rounding stay far below it; the smallest planted error in the tests is ×1.05).
const MARGIN: f64 = 1.01;

/// Most scene-node evaluations the frustum sampling may spend (large scenes get fewer points).
const WORK: usize = 20_000_000;

/// Warnings for every annotation the sampling shows to be too small, and for every one so
/// far above the steepest slope sampled that rays cannot arrive within their step budget
/// (`converge.rs`).
pub fn verify_annotations(scene: &Scene, effort: Effort) -> Vec<Diagnostic> {
    let budget = effort.budget();
    let reachable = scene.reachable();
    // (Annotations above the catalog's rule have the checker's own warning, "looser than the
    // inferred bound".)
    let mut out: Vec<Diagnostic> = Vec::new();
    // Annotations at or above the catalog's rule need no check: the rule is a proven bound.
    let annotated: Vec<NodeId> = reachable
        .iter()
        .copied()
        .filter(|&id| scene.nodes[id].lambda < scene.nodes[id].inferred_lambda)
        .collect();
    if annotated.is_empty() {
        return out;
    }
    // Shared `let`s and `repeat` copies multiply what one point costs.
    let cost = scene.root_node().evaluations.max(1.0) as usize + scene.nodes.len();
    let world = budget.world.min(WORK / cost).max(64);
    // A traced camera ray costs up to `SECONDARY_STEPS` evaluations, its secondary rays more.
    let hits = budget.hits.min(WORK / (cost * 192));
    let seen = reach::where_rays_evaluate(scene, &annotated, world, (hits, budget.per_ray));
    for (k, &id) in annotated.iter().enumerate() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ (k as u64 + 1));
        match check_node(scene, id, &seen[&id], &budget, &mut rng) {
            Err(d) => out.push(d),
            Ok(slope) => out.extend(super::converge::too_loose(scene, id, slope)),
        }
    }
    out
}

/// The check of one annotated node given the points rays evaluate it at.
fn check_node(
    scene: &Scene,
    id: NodeId,
    from_rays: &[(DVec3, Ray)],
    budget: &Budget,
    rng: &mut Rng,
) -> Result<f64, Diagnostic> {
    let node = &scene.nodes[id];
    let lambda = node.lambda;
    let field = |p: DVec3| eval::node(scene, id, p).d;
    // The region: the points rays reach, and the node's own box (grown), or around its origin.
    let mut points: Vec<(DVec3, Ray)> = from_rays.to_vec();
    let (lo, hi) = if node.bound.is_finite() {
        let grow = ((node.bound.hi - node.bound.lo) * 0.25).max(DVec3::splat(1e-3));
        (node.bound.lo - grow, node.bound.hi + grow)
    } else {
        (DVec3::splat(-4.0), DVec3::splat(4.0))
    };
    let framed = (scene.camera.eye - scene.camera.target).length().max(1e-6);
    points.extend(stratified(lo, hi, budget.local, framed, rng).map(|p| (p, Ray::Region)));
    let (mut rlo, mut rhi) = (lo, hi);
    for (p, _) in &points {
        rlo = rlo.min(*p);
        rhi = rhi.max(*p);
    }
    let size = (rhi - rlo).max_element().max(1e-6);
    let slope = |p: DVec3| slope_at(&field, p, size * 1e-6);
    // Sample, keep the steepest, refine them by local search.
    let mut scored: Vec<(f64, DVec3, Ray)> =
        points.iter().map(|&(p, r)| (slope(p), p, r)).collect();
    scored.sort_by(|a, b| b.0.total_cmp(&a.0));
    let (keep, steps) = budget.refine;
    let mut best = scored.first().copied().unwrap_or((0.0, rlo, Ray::Region));
    for &(s, p, r) in scored.iter().take(keep) {
        let found = climb(&slope, p, s, size, steps, rng);
        if found.0 > best.0 {
            best = (found.0, found.1, r);
        }
    }
    // An expression: search the region box by box, guided by interval bounds.
    let mut proven = None;
    if let NodeKind::Implicit { field: body } = &node.kind {
        let region = [0, 1, 2].map(|i| Interval::new(rlo[i], rhi[i]));
        proven = Some(bound_in(body, &region));
        if best.0 <= lambda * MARGIN {
            let found = search(body, &slope, region, lambda, budget.boxes, rng);
            if found.0 > best.0 {
                let (s, at) = climb(&slope, found.1, found.0, size, steps, rng);
                best = (s, at, nearest_kind(&points, at));
            }
        }
    }
    if best.0 <= lambda * MARGIN {
        return Ok(best.0);
    }
    Err(too_small(scene, id, best, proven))
}

/// The kind of ray of the sampled point nearest `at` (what reaches a point the search found).
fn nearest_kind(points: &[(DVec3, Ray)], at: DVec3) -> Ray {
    points
        .iter()
        .min_by(|a, b| {
            a.0.distance_squared(at)
                .total_cmp(&b.0.distance_squared(at))
        })
        .map_or(Ray::Region, |p| p.1)
}

/// About `n` points of the box [lo, hi] on a jittered grid (every cell holds one, so no part
/// of the box goes unsampled), more for a box larger than the distance `framed` the camera
/// frames: up to 8× for one 8× that size.
fn stratified(
    lo: DVec3,
    hi: DVec3,
    n: usize,
    framed: f64,
    rng: &mut Rng,
) -> impl Iterator<Item = DVec3> {
    let scale = ((hi - lo).length() / framed).clamp(1.0, 8.0);
    let k = ((n as f64 * scale).cbrt().ceil() as usize).max(1);
    let cell = (hi - lo) / k as f64;
    let points: Vec<DVec3> = (0..k * k * k)
        .map(|i| {
            let c = DVec3::new((i % k) as f64, (i / k % k) as f64, (i / (k * k)) as f64);
            lo + (c + rng.vec()) * cell
        })
        .collect();
    points.into_iter()
}

/// The warning for a slope `seen` at `at` (reached by `ray`) above the node's annotation;
/// `proven` an interval bound over the region (an `implicit`).
fn too_small(
    scene: &Scene,
    id: NodeId,
    (seen, at, ray): (f64, DVec3, Ray),
    proven: Option<f64>,
) -> Diagnostic {
    let node = &scene.nodes[id];
    let safe = proven
        .filter(|b| b.is_finite())
        .or(Some(node.inferred_lambda).filter(|b| b.is_finite()));
    let mut d = Diagnostic::warning(node.span, "the annotated Lipschitz bound is too small")
        .label(format!(
            "the slope reaches at least {} at ({}, {}, {}), above the annotated {}",
            short(seen),
            short(at.x),
            short(at.y),
            short(at.z),
            node.lambda
        ))
        .note("steps of f/λ may pass through the surface there");
    d = match safe {
        Some(b) => d.help(format!(
            "a safe bound where rays go is {}: annotate `@lipschitz({})`",
            short(b),
            short_up(b)
        )),
        None => d.help(format!("raise the annotation above {}", short_up(seen))),
    };
    super::with_call(node, d).note(format!(
        "the point is in the annotated shape's own coordinates; {}",
        ray.say()
    ))
}

/// |∇f| at `p` by central differences with step `h`; 0 where the field is not finite.
fn slope_at(f: &impl Fn(DVec3) -> f64, p: DVec3, h: f64) -> f64 {
    let g = DVec3::new(
        f(p + DVec3::X * h) - f(p - DVec3::X * h),
        f(p + DVec3::Y * h) - f(p - DVec3::Y * h),
        f(p + DVec3::Z * h) - f(p - DVec3::Z * h),
    ) / (2.0 * h);
    if g.is_finite() { g.length() } else { 0.0 }
}

/// Local search for a steeper point around `p`: random moves at shrinking radii.
fn climb(
    slope: &impl Fn(DVec3) -> f64,
    p: DVec3,
    s: f64,
    size: f64,
    steps: usize,
    rng: &mut Rng,
) -> (f64, DVec3) {
    let (mut best, mut at) = (s, p);
    let mut radius = size * 0.02;
    for _ in 0..steps {
        let q = at + (rng.vec() * 2.0 - DVec3::ONE) * radius;
        let sq = slope(q);
        if sq > best {
            (best, at) = (sq, q);
        } else {
            radius *= 0.8;
        }
    }
    (best, at)
}

/// Branch and bound over the region: the box with the largest interval bound on |∇f| is
/// sampled (centre and two random points) and split along its longest side, until a point
/// steeper than the annotation turns up, every box is proven within it, or the budget ends.
fn search(
    body: &crate::scene::Field,
    slope: &impl Fn(DVec3) -> f64,
    region: [Interval; 3],
    lambda: f64,
    budget: usize,
    rng: &mut Rng,
) -> (f64, DVec3) {
    let mut best = (0.0, DVec3::ZERO);
    let mut boxes = vec![(bound_in(body, &region), region)];
    for _ in 0..budget {
        // The box with the largest bound (a linear scan: the list stays small).
        let Some(i) = (0..boxes.len()).max_by(|&a, &b| boxes[a].0.total_cmp(&boxes[b].0)) else {
            break;
        };
        let (bound, b) = boxes.swap_remove(i);
        if bound <= lambda * MARGIN {
            break;
        }
        let lo = DVec3::new(b[0].lo, b[1].lo, b[2].lo);
        let hi = DVec3::new(b[0].hi, b[1].hi, b[2].hi);
        for p in [
            (lo + hi) / 2.0,
            lo + (hi - lo) * rng.vec(),
            lo + (hi - lo) * rng.vec(),
        ] {
            let s = slope(p);
            if s > best.0 {
                best = (s, p);
            }
        }
        if best.0 > lambda * MARGIN {
            break;
        }
        let axis = (hi - lo).max_position();
        let mid = (lo[axis] + hi[axis]) / 2.0;
        for half in [Interval::new(lo[axis], mid), Interval::new(mid, hi[axis])] {
            let mut c = b;
            c[axis] = half;
            boxes.push((bound_in(body, &c), c));
        }
    }
    best
}

/// A number printed with four significant digits.
fn short(x: f64) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// A number rounded up to three significant digits (for a suggested annotation).
fn short_up(x: f64) -> String {
    if x <= 0.0 || !x.is_finite() {
        return short(x);
    }
    let e = 10f64.powi(x.log10().floor() as i32 - 2);
    short((x / e).ceil() * e)
}
