//! Operators: CSG, smooth blends, metamorphosis, blobs, `round`, `onion` and `elongate`, each
//! with its Lipschitz rule (in its doc line) and f64 evaluation; the table of every operator
//! ([`OPERATORS`]), whose operators of space are in `domain.rs`.
//!
//! Convention: operators that combine children (CSG, blends, blobs) first divide each child by its
//! λ, so their own result has λ = 1 (Liktor §2.2: min/max of 1-Lipschitz functions stay 1-Lipschitz;
//! IQ's polynomial smooth minimum is a convex combination of its operands' gradients). Operators
//! that only move the domain keep the child's λ, or raise it by their Jacobian's norm.

use super::geometry::FALLOFF_SLOPE;
use super::gpu::ops as ir;
use super::rules::{KEEPS, ONE, SAME, SHORTENS, norm, num};
use super::symmetry::{CHILD, EVERY, SWAP_CHILD, SWAP_EVERY};
use super::traits::{Fold, Helper, PLAIN, Plane, Traits};
use super::{Arity, Bound, ChildEval, Ctx, MatRule, NO_SWAP, Operator, Ty, opt, req};
use glam::DVec3;

/// Folds the normalised children with `f`.
fn fold(c: &Ctx, p: DVec3, child: ChildEval, f: impl Fn(f64, f64) -> f64) -> f64 {
    let first = norm(c, child, 0, p);
    (1..c.child_lambda.len()).fold(first, |acc, i| f(acc, norm(c, child, i, p)))
}

/// IQ's quadratic polynomial smooth minimum with blend radius `k`.
pub fn smin(a: f64, b: f64, k: f64) -> f64 {
    if k <= 0.0 {
        return a.min(b);
    }
    let h = (k - (a - b).abs()).max(0.0) / k;
    a.min(b) - h * h * k * 0.25
}

/// The smooth maximum, −smin(−a, −b).
pub fn smax(a: f64, b: f64, k: f64) -> f64 {
    -smin(-a, -b, k)
}

fn smallest(c: &Ctx) -> Bound {
    c.child_bound
        .iter()
        .copied()
        .reduce(Bound::intersection)
        .unwrap_or(Bound::INFINITE)
}

fn all(c: &Ctx) -> Bound {
    c.child_bound
        .iter()
        .copied()
        .reduce(Bound::union)
        .unwrap_or(Bound::INFINITE)
}

/// Wyvill's blob falloff (1 − s²)³ on [0, 1]; its slope is at most 96/(25√5) ≈ 1.7173.
pub fn falloff(s: f64) -> f64 {
    let t = (1.0 - s * s).max(0.0);
    t * t * t
}

/// The traits of `smooth_intersect` and `smooth_subtract`: both call the smooth maximum.
const SMOOTH_MAX: Traits = Traits {
    plane: Plane::Keeps,
    helper: Some(Helper {
        name: "op_smooth_intersect",
        body: ir::smooth_max_body,
    }),
    ..PLAIN
};

/// Every operator of the language.
pub static OPERATORS: &[Operator] = &[
    Operator {
        name: "union",
        fixed_args: false,
        traits: Traits {
            groups: true,
            plane: Plane::Keeps,
            fold: Some(Fold {
                largest: false,
                smooth: false,
                negates_later: false,
            }),
            ..PLAIN
        },
        materials: MatRule::Nearest,
        unit_gradient: KEEPS,
        keeps_exact: KEEPS,
        lower: ir::union,
        doc: "Union of its shapes: min (λ = 1 after dividing each child by its λ); the nearest \
              shape's material.",
        params: &[],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: all,
        swap: SWAP_EVERY,
        mirror: EVERY,
        eval: |c, p, child| match &c.prune {
            Some(tree) => tree.min(p, &mut |i| norm(c, child, i, p)),
            None => fold(c, p, child, f64::min),
        },
    },
    Operator {
        name: "intersect",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            fold: Some(Fold {
                largest: true,
                smooth: false,
                negates_later: false,
            }),
            ..PLAIN
        },
        materials: MatRule::Farthest,
        unit_gradient: KEEPS,
        keeps_exact: SHORTENS,
        lower: ir::intersect,
        doc: "Intersection: max (λ = 1); the material of the shape that bounds the result.",
        params: &[],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: smallest,
        swap: SWAP_EVERY,
        mirror: EVERY,
        eval: |c, p, child| fold(c, p, child, f64::max),
    },
    Operator {
        name: "subtract",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            fold: Some(Fold {
                largest: true,
                smooth: false,
                negates_later: true,
            }),
            ..PLAIN
        },
        materials: MatRule::Cut,
        unit_gradient: KEEPS,
        keeps_exact: SHORTENS,
        lower: ir::subtract,
        doc: "The first shape minus the others: max(a, −b) (λ = 1); cut faces take the cutter's \
              material.",
        params: &[],
        arity: Arity::AtLeast(2),
        lipschitz: ONE,
        bound: |c| c.child_bound[0],
        swap: SWAP_EVERY,
        mirror: EVERY,
        eval: |c, p, child| fold(c, p, child, |a, b| a.max(-b)),
    },
    Operator {
        name: "complement",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: KEEPS,
        keeps_exact: SHORTENS,
        lower: ir::complement,
        doc: "Inside out: −f (λ unchanged).",
        params: &[],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |_| Bound::INFINITE,
        swap: SWAP_CHILD,
        mirror: CHILD,
        eval: |_, p, child| -child(0, p),
    },
    Operator {
        name: "smooth_union",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            helper: Some(Helper {
                name: "op_smooth_union",
                body: ir::smooth_min_body,
            }),
            fold: Some(Fold {
                largest: false,
                smooth: true,
                negates_later: false,
            }),
            ..PLAIN
        },
        materials: MatRule::SmoothNearest,
        unit_gradient: SHORTENS,
        keeps_exact: SHORTENS,
        lower: ir::smooth_union,
        doc: "Union blended over `radius` by IQ's polynomial smooth minimum (λ = 1); the \
              materials blend across the seam by its mix factor.",
        params: &[req("radius", Ty::Length)],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: |c| c.grown_if_exact(all(c), c.num(0) / 4.0),
        swap: SWAP_EVERY,
        mirror: EVERY,
        eval: |c, p, child| fold(c, p, child, |a, b| smin(a, b, c.num(0))),
    },
    Operator {
        name: "smooth_intersect",
        fixed_args: false,
        traits: Traits {
            fold: Some(Fold {
                largest: true,
                smooth: true,
                negates_later: false,
            }),
            ..SMOOTH_MAX
        },
        materials: MatRule::SmoothFarthest,
        unit_gradient: SHORTENS,
        keeps_exact: SHORTENS,
        lower: ir::smooth_intersect,
        doc: "Intersection blended over `radius` (λ = 1).",
        params: &[req("radius", Ty::Length)],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: smallest,
        swap: SWAP_EVERY,
        mirror: EVERY,
        eval: |c, p, child| fold(c, p, child, |a, b| smax(a, b, c.num(0))),
    },
    Operator {
        name: "smooth_subtract",
        fixed_args: false,
        traits: Traits {
            fold: Some(Fold {
                largest: true,
                smooth: true,
                negates_later: true,
            }),
            ..SMOOTH_MAX
        },
        materials: MatRule::SmoothCut,
        unit_gradient: SHORTENS,
        keeps_exact: SHORTENS,
        lower: ir::smooth_subtract,
        doc: "The first shape minus the others, blended over `radius` (λ = 1).",
        params: &[req("radius", Ty::Length)],
        arity: Arity::AtLeast(2),
        lipschitz: ONE,
        bound: |c| c.child_bound[0],
        swap: SWAP_EVERY,
        mirror: EVERY,
        eval: |c, p, child| fold(c, p, child, |a, b| smax(a, -b, c.num(0))),
    },
    Operator {
        name: "mix",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            ..PLAIN
        },
        materials: MatRule::Weighted,
        unit_gradient: SHORTENS,
        keeps_exact: SHORTENS,
        lower: ir::mix,
        doc: "Metamorphosis (Liktor Fig. 9): (1 − `weight`)·a + `weight`·b of the raw fields, \
              λ = (1 − w)·λa + w·λb; the materials blend by the weight too.",
        params: &[req("weight", Ty::Fraction)],
        arity: Arity::Exactly(2),
        lipschitz: |c| (1.0 - c.num(0)) * c.child_lambda[0] + c.num(0) * c.child_lambda[1],
        bound: all,
        swap: SWAP_EVERY,
        mirror: EVERY,
        eval: |c, p, child| {
            let w = c.num(0);
            (1.0 - w) * child(0, p) + w * child(1, p)
        },
    },
    Operator {
        name: "blob",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            ..PLAIN
        },
        materials: MatRule::Nearest,
        unit_gradient: SHORTENS,
        keeps_exact: SHORTENS,
        lower: ir::blob,
        doc: "Blob field (Liktor §2): `threshold` − Σ (1 − (dᵢ/`radius`)²)³ over the children's \
              distances dᵢ ≥ 0, divided by its slope bound n·1.7173/`radius`, and the distance to \
              the children's influence zone outside it (λ = 1).",
        params: &[
            opt("radius", Ty::Positive, num(1.0)),
            opt("threshold", Ty::Range(0.0, 1.0), num(0.5)),
        ],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: |c| c.grown_if_exact(all(c), c.num(0)),
        swap: SWAP_EVERY,
        mirror: EVERY,
        eval: |c, p, child| {
            let (radius, threshold) = (c.num(0), c.num(1));
            let n = c.child_lambda.len();
            let mut field = 0.0;
            let mut nearest = f64::INFINITY;
            for i in 0..n {
                let d = norm(c, child, i, p);
                field += falloff(d.max(0.0) / radius);
                nearest = nearest.min(d);
            }
            let slope = n as f64 * FALLOFF_SLOPE / radius;
            ((threshold - field) / slope).max(nearest - radius)
        },
    },
    super::domain::TRANSLATE,
    super::domain::ROTATE,
    super::domain::SCALE,
    super::domain::REPEAT,
    super::domain::MIRROR,
    super::domain::TWIST,
    super::domain::BEND,
    Operator {
        name: "round",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: KEEPS,
        keeps_exact: KEEPS,
        lower: ir::round,
        doc: "Rounds its shape outward by `radius`: f/λ − r (λ = 1).",
        params: &[req("radius", Ty::Length)],
        arity: Arity::Exactly(1),
        lipschitz: ONE,
        bound: |c| c.grown_if_exact(c.child_bound[0], c.num(0)),
        swap: SWAP_CHILD,
        mirror: CHILD,
        eval: |c, p, child| norm(c, child, 0, p) - c.num(0),
    },
    Operator {
        name: "onion",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: KEEPS,
        keeps_exact: KEEPS,
        lower: ir::onion,
        doc: "Hollows its shape into a shell of `thickness`: |f/λ| − t (λ = 1).",
        params: &[req("thickness", Ty::Length)],
        arity: Arity::Exactly(1),
        lipschitz: ONE,
        bound: |c| c.grown_if_exact(c.child_bound[0], c.num(0)),
        swap: SWAP_CHILD,
        mirror: CHILD,
        eval: |c, p, child| norm(c, child, 0, p).abs() - c.num(0),
    },
    Operator {
        name: "elongate",
        fixed_args: false,
        traits: Traits {
            plane: Plane::Keeps,
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: |c| (0..3).all(|i| c.vec(0)[i] == 0.0 || c.child_mirror[0][i]),
        keeps_exact: SHORTENS,
        lower: ir::elongate,
        doc: "Stretches its shape by inserting `amount` of straight extent along each axis at the \
              origin: f(p − clamp(p, −h, h)), h = amount/2 (λ unchanged).",
        params: &[req("amount", Ty::Size)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| c.child_bound[0].grown_box(c.vec(0) / 2.0, c.vec(0).length() / 2.0),
        swap: NO_SWAP,
        mirror: CHILD,
        eval: |c, p, child| {
            let h = c.vec(0) / 2.0;
            child(0, p - p.clamp(-h, h))
        },
    },
    super::polar::REPEAT_POLAR,
    super::planar::EXTRUDE,
    super::planar::REVOLVE,
    super::baked::BAKE,
];
