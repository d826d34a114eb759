//! Checking `@lipschitz(L)` annotations where rays go: the slope of each annotated node is
//! sampled at the points the camera's rays make it evaluate (up to `max_distance`, in the node's
//! own coordinates, through every transform and copy above it), refined around the steepest
//! samples, and for `implicit` bodies searched by subdividing the region with interval bounds,
//! which finds features too thin for samples. A slope above the annotation is a warning with
//! the place, the slope seen (a lower bound of the true one) and a safe bound where one is known.

use super::reach::{self, Ray};
use super::{Rng, bound_in};
use crate::catalog::traits::Motion;
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
    /// Node evaluations each phase may spend (camera rays, traced rays, a node's slopes).
    work: usize,
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
                work: WORK,
            },
            Effort::Thorough => Budget {
                world: 15_000,
                local: 5_000,
                refine: (24, 60),
                boxes: 2000,
                hits: 960,
                per_ray: 16,
                work: WORK,
            },
        }
    }
}

/// A slope above the annotation by more than this factor is reported (sampling noise and f64
/// rounding stay far below it; the smallest planted error in the tests is ×1.05).
const MARGIN: f64 = 1.01;

/// Most scene-node evaluations the frustum sampling may spend (large scenes get fewer points).
pub(super) const WORK: usize = 20_000_000;

/// Warnings for every annotation the sampling shows to be too small, and for every one so
/// far above the steepest slope sampled that rays cannot arrive within their step budget
/// (`converge.rs`).
pub fn verify_annotations(scene: &Scene, effort: Effort) -> Vec<Diagnostic> {
    verify_where(scene, effort, &|_| true, WORK)
}

/// [`verify_annotations`] of the annotated nodes `keep` picks (at other parameter values, only
/// those that read the parameters changed: `ranges.rs`), spending at most about `work` node
/// evaluations on each of the camera's rays, the traced rays and each node's slopes.
pub(super) fn verify_where(
    scene: &Scene,
    effort: Effort,
    keep: &dyn Fn(NodeId) -> bool,
    work: usize,
) -> Vec<Diagnostic> {
    let budget = Budget {
        work,
        ..effort.budget()
    };
    let mut out: Vec<Diagnostic> = Vec::new();
    let mut annotated = super::annotated(scene);
    annotated.retain(|&id| keep(id));
    if annotated.is_empty() {
        return out;
    }
    // Shared `let`s and `repeat` copies multiply what one point costs.
    let cost = scene.root_node().evaluations.max(1.0) as usize + scene.nodes.len();
    let world = budget.world.min(work / cost).max(64);
    // A traced camera ray costs up to `SECONDARY_STEPS` evaluations, its secondary rays (a
    // reflected one traced too, shadow rays, normals) about three times that.
    let hits = budget.hits.min(work / (cost * 512));
    let below: Vec<Option<NodeId>> = annotated
        .iter()
        .map(|&id| expression_below(scene, id))
        .collect();
    let mut recorded = annotated.clone();
    recorded.extend(below.iter().flatten());
    recorded.sort_unstable();
    recorded.dedup();
    let seen = reach::where_rays_evaluate(scene, &recorded, world, (hits, budget.per_ray));
    for (k, &id) in annotated.iter().enumerate() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ (k as u64 + 1));
        let expr = below[k].map(|e| (e, seen[&e].as_slice()));
        match check_node(scene, (id, &seen[&id]), expr, &budget, &mut rng) {
            Err(d) => out.push(d),
            Ok((slope, proven)) => out.extend(super::converge::too_loose(scene, id, slope, proven)),
        }
    }
    out
}

/// The `implicit` whose slope is the annotated node's: the node itself, or one under moves and
/// turns only (rigid motions keep slopes), whose body the interval search can then search.
fn expression_below(scene: &Scene, id: NodeId) -> Option<NodeId> {
    let mut at = id;
    loop {
        match &scene.nodes[at].kind {
            NodeKind::Implicit { .. } => return Some(at),
            NodeKind::Operator { op, children, .. }
                if children.len() == 1
                    && matches!(op.traits.motion, Motion::Move | Motion::Turn) =>
            {
                at = children[0];
            }
            _ => return None,
        }
    }
}

/// The points to sample node `id` at: those rays reach (`from_rays`), and its own box (grown
/// by a quarter; [−4, 4]³ for an unbounded node) on a jittered grid.
fn region_points(
    scene: &Scene,
    id: NodeId,
    from_rays: &[(DVec3, Ray)],
    budget: &Budget,
    rng: &mut Rng,
) -> Vec<(DVec3, Ray)> {
    let node = &scene.nodes[id];
    let mut points: Vec<(DVec3, Ray)> = from_rays.to_vec();
    let (lo, hi) = if node.bound.is_finite() {
        let grow = ((node.bound.hi - node.bound.lo) * 0.25).max(DVec3::splat(1e-3));
        (node.bound.lo - grow, node.bound.hi + grow)
    } else {
        (DVec3::splat(-4.0), DVec3::splat(4.0))
    };
    let framed = (scene.camera.eye - scene.camera.target).length().max(1e-6);
    points.extend(stratified(lo, hi, budget.local, framed, rng).map(|p| (p, Ray::Region)));
    points
}

/// The box the points span, and its largest side.
fn span(points: &[(DVec3, Ray)]) -> (DVec3, DVec3, f64) {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for (p, _) in points {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    (lo, hi, (hi - lo).max_element().max(1e-6))
}

/// The check of one annotated node given the points rays evaluate it at, and the `implicit`
/// its slope is (itself or one under moves and turns) with the points rays evaluate that at:
/// the steepest slope found and the interval bound over the region (an `implicit`), or the
/// warning.
fn check_node(
    scene: &Scene,
    (id, from_rays): (NodeId, &[(DVec3, Ray)]),
    expr: Option<(NodeId, &[(DVec3, Ray)])>,
    budget: &Budget,
    rng: &mut Rng,
) -> Result<(f64, Option<f64>), Diagnostic> {
    let lambda = scene.nodes[id].lambda;
    let field = |p: DVec3| eval::node(scene, id, p).d;
    let points = region_points(scene, id, from_rays, budget, rng);
    // A costly node (shared `let`s, `repeat` copies) gets fewer points: each slope is six
    // evaluations of it.
    let cost = scene.nodes[id].evaluations.max(1.0) as usize;
    let points = thin_out(points, (budget.work / (6 * cost)).max(64));
    let (rlo, _, size) = span(&points);
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
    // An expression: search the region box by box, guided by interval bounds (in the
    // coordinates of the `implicit`, whose slope is the node's).
    let mut proven = None;
    let mut inner = false;
    if let Some((e, seen)) = expr
        && let NodeKind::Implicit { field: body } = &scene.nodes[e].kind
    {
        let points = if e == id {
            points
        } else {
            region_points(scene, e, seen, budget, rng)
        };
        let (lo, hi, size) = span(&points);
        let region = [0, 1, 2].map(|i| Interval::new(lo[i], hi[i]));
        // (The safe bound holds over the parameters' ranges; the search is at the values
        // checked: over the whole ranges, a width parameter's widest spike would hide its
        // narrowest.)
        proven = Some(bound_in(body, &region));
        let body = &body.pinned();
        if best.0 <= lambda * MARGIN {
            let efield = |p: DVec3| eval::node(scene, e, p).d;
            let eslope = |p: DVec3| slope_at(&efield, p, size * 1e-6);
            let found = search(body, &eslope, region, lambda, budget.boxes, rng);
            if found.0 > best.0 {
                let (s, at) = climb(&eslope, found.1, found.0, size, steps, rng);
                best = (s, at, nearest_kind(&points, at));
                inner = e != id;
            }
        }
    }
    if best.0 <= lambda * MARGIN {
        return Ok((best.0, proven));
    }
    Err(too_small(scene, id, (best, inner), proven))
}

/// At most `most` of `points`, evenly spread over the list (which interleaves the kinds of
/// rays and the box).
fn thin_out(points: Vec<(DVec3, Ray)>, most: usize) -> Vec<(DVec3, Ray)> {
    if points.len() <= most {
        return points;
    }
    let step = points.len() as f64 / most as f64;
    (0..most)
        .map(|k| points[(k as f64 * step) as usize])
        .collect()
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
    ((seen, at, ray), inner): ((f64, DVec3, Ray), bool),
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
    let frame = match inner {
        true => "the coordinates of the `implicit` under its moves and turns",
        false => "the annotated shape's own coordinates",
    };
    super::with_call(node, d).note(format!("the point is in {frame}; {}", ray.say()))
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
    let side = |b: &[Interval; 3]| (0..3).map(|i| b[i].hi - b[i].lo).fold(0.0, f64::max);
    // Boxes smaller than this are not split: at a point where a gradient's interval does not
    // shrink (the apex of `length`), the bound stays high at every size.
    let finest = side(&region) * 1e-7;
    for _ in 0..budget {
        // The box with the largest bound, the larger of equal ones (a linear scan: the list
        // stays small).
        let key = |k: usize| (boxes[k].0, side(&boxes[k].1));
        let Some(i) = (0..boxes.len()).max_by(|&a, &b| {
            let (ka, kb) = (key(a), key(b));
            ka.0.total_cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
        }) else {
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
        if side(&b) < finest {
            continue;
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
