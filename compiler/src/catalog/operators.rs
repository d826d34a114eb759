//! Operators: CSG, smooth blends, metamorphosis, transforms and domain operations, each with its
//! Lipschitz rule (in its doc line) and f64 evaluation.
//!
//! Convention: operators that combine children (CSG, blends, blobs) first divide each child by its
//! λ, so their own result has λ = 1 (Liktor §2.2: min/max of 1-Lipschitz functions stay 1-Lipschitz;
//! IQ's polynomial smooth minimum is a convex combination of its operands' gradients). Operators
//! that only move the domain keep the child's λ, or raise it by their Jacobian's norm.

use super::geometry::{FALLOFF_SLOPE, rotate};
use super::gpu::ops as ir;
use super::symmetry::{
    CHILD, EVERY, NONE, SWAP_CHILD, SWAP_EVERY, and, rotated_mirror, rotated_swap,
};
use super::traits::{Helper, Motion, PLAIN, Plane, PlaneRule, Traits};
use super::warp::{bend_point, twist_point, twist_stretch, warp, warp_lambda};
use super::{
    Arity, Bound, ChildEval, Ctx, MatRule, NO_SWAP, Operator, Ty, Val, equal_pairs, opt, req,
};
use glam::DVec3;

const fn num(x: f64) -> Val {
    Val::Num(x)
}

const SAME: fn(&Ctx) -> f64 = |c| c.child_lambda[0];
const ONE: fn(&Ctx) -> f64 = |_| 1.0;
/// Keeps a unit gradient (min, max, moves and folds of unit-gradient fields).
const KEEPS: fn(&Ctx) -> bool = |_| true;
/// Makes gradients shorter than λ somewhere (blends, warps, weighted sums).
const SHORTENS: fn(&Ctx) -> bool = |_| false;

/// Child `i` at `p`, divided by its λ.
fn norm(c: &Ctx, child: ChildEval, i: usize, p: DVec3) -> f64 {
    child(i, p) / c.child_lambda[i]
}

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

/// Every operator of the language.
pub static OPERATORS: &[Operator] = &[
    Operator {
        name: "union",
        fixed_args: false,
        traits: Traits {
            groups: true,
            plane: Plane::Keeps,
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
            plane: Plane::Keeps,
            helper: Some(Helper {
                name: "op_smooth_intersect",
                body: ir::smooth_max_body,
            }),
            ..PLAIN
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
            plane: Plane::Keeps,
            helper: Some(Helper {
                name: "op_smooth_intersect",
                body: ir::smooth_max_body,
            }),
            ..PLAIN
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
    Operator {
        name: "translate",
        fixed_args: false,
        traits: Traits {
            motion: Motion::Move,
            plane: Plane::Keeps,
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: KEEPS,
        keeps_exact: KEEPS,
        lower: ir::translate,
        doc: "Moves its shape by `offset` (λ unchanged). `s at (x, y, z)` is the same.",
        params: &[req("offset", Ty::Vec3)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| c.child_bound[0].moved(c.vec(0)),
        swap: |c| and(c.child_swap[0], equal_pairs(c.vec(0))),
        mirror: |c| [0, 1, 2].map(|i| c.child_mirror[0][i] && c.vec(0)[i] == 0.0),
        eval: |c, p, child| child(0, p - c.vec(0)),
    },
    Operator {
        name: "rotate",
        fixed_args: false,
        traits: Traits {
            motion: Motion::Turn,
            plane: Plane::KeepsIf(PlaneRule {
                keeps: |a| (a.z.abs() - 1.0).abs() <= 1e-12,
                message: "a 2D shape turns only in its plane",
                help: "turn it about `z`, or turn the solid after `extrude` or `revolve`",
            }),
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: KEEPS,
        keeps_exact: KEEPS,
        lower: ir::rotate,
        doc: "Rotates its shape by `angle` about `axis` through the origin (λ unchanged).",
        params: &[req("axis", Ty::Axis), req("angle", Ty::Angle)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| c.child_bound[0].isometry(|v| rotate(v, c.vec(0), c.num(1))),
        swap: rotated_swap,
        mirror: rotated_mirror,
        eval: |c, p, child| child(0, rotate(p, c.vec(0), -c.num(1))),
    },
    Operator {
        name: "scale",
        fixed_args: false,
        traits: Traits {
            motion: Motion::Scale,
            plane: Plane::Keeps,
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: |c| c.vec(0).min_element() == c.vec(0).max_element(),
        keeps_exact: |c| c.vec(0).min_element() == c.vec(0).max_element(),
        lower: ir::scale,
        doc: "Scales its shape by `factor` (a number, or a vector for non-uniform scale): \
              f(p/s)·min(s), λ unchanged (p/s stretches slopes by at most 1/min(s), which the \
              factor min(s) undoes). A box, or a cylinder scaled alike in x and z, takes the \
              scale into its sizes, also through moves and turns about a coordinate axis whose \
              other two factors are equal (any turn for a uniform scale): the exact distance \
              instead of a bound (not with its \
              own material, name or annotation).",
        params: &[req("factor", Ty::Scale)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| c.child_bound[0].scaled(c.vec(0)),
        swap: |c| and(c.child_swap[0], equal_pairs(c.vec(0))),
        mirror: CHILD,
        eval: |c, p, child| {
            let s = c.vec(0);
            child(0, p / s) * s.min_element()
        },
    },
    Operator {
        name: "repeat",
        fixed_args: true,
        traits: Traits {
            plane: Plane::KeepsIf(PlaneRule {
                keeps: |a| a.z == 0.0,
                message: "a 2D shape repeats only in its plane",
                help: "give the spacing 0 along z: `repeat((sx, sy, 0)) { … }`",
            }),
            copies: Some(super::repeat::COPIES),
            unbounded: Some(
                "`repeat` can only be bounded when its shape is bounded along the repeated axes",
            ),
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: KEEPS,
        keeps_exact: KEEPS,
        lower: ir::repeat,
        doc: "Repeats its shape every `spacing` along each axis (0: not on that axis), `count` \
              copies per axis (0: without end); the neighbouring cells are evaluated too where \
              the shape is not symmetric about its cell or overflows it (λ unchanged; a shape without \
              end along a repeated axis needs an annotation).",
        params: &[req("spacing", Ty::Size), opt("count", Ty::Counts, num(0.0))],
        arity: Arity::Exactly(1),
        lipschitz: |c| {
            // Copies of a shape without end along a repeated axis overlap without limit: no
            // window of cells holds the nearest one.
            let (s, b) = (c.vec(0), c.child_bound[0]);
            let unbounded =
                (0..3).any(|i| s[i] > 0.0 && !(b.lo[i].is_finite() && b.hi[i].is_finite()));
            if unbounded {
                f64::INFINITY
            } else {
                c.child_lambda[0]
            }
        },
        bound: |c| {
            let (s, n) = (c.vec(0), c.vec(1));
            if (0..3).any(|i| s[i] > 0.0 && n[i] == 0.0) {
                return Bound::INFINITE;
            }
            let half = s * (n - DVec3::ONE).max(DVec3::ZERO) / 2.0;
            c.child_bound[0].grown_box(half, half.length())
        },
        swap: NO_SWAP,
        mirror: CHILD,
        eval: |c, p, child| super::repeat::field(c, p, child),
    },
    Operator {
        name: "mirror",
        fixed_args: false,
        traits: Traits {
            plane: Plane::KeepsIf(PlaneRule {
                keeps: |a| a.z == 0.0 || (a.z.abs() - 1.0).abs() <= 1e-12,
                message: "a 2D shape mirrors only within its plane",
                help: "mirror it across a plane through the z axis (a normal `(x, y, 0)`), or mirror the solid",
            }),
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: KEEPS,
        keeps_exact: SHORTENS,
        lower: ir::mirror,
        doc: "Mirrors the half-space in front of the plane through the origin with normal `axis` \
              onto the back (λ unchanged).",
        params: &[req("axis", Ty::Axis)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| {
            let b = c.child_bound[0];
            let n = c.vec(0);
            b.union(b.isometry(|v| v - 2.0 * v.dot(n) * n))
        },
        swap: NO_SWAP,
        mirror: |c| {
            let n = c.vec(0);
            [0, 1, 2].map(|i| {
                if n[i].abs() == 1.0 {
                    true
                } else {
                    n[i] == 0.0 && c.child_mirror[0][i]
                }
            })
        },
        eval: |c, p, child| {
            let n = c.vec(0);
            child(0, p - 2.0 * p.dot(n).min(0.0) * n)
        },
    },
    Operator {
        name: "twist",
        fixed_args: true,
        traits: Traits {
            unbounded: Some("`twist` can only be bounded when its shape is bounded"),
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: SHORTENS,
        keeps_exact: SHORTENS,
        lower: super::gpu::warp::twist,
        doc: "Twists its shape about the y axis by `rate` radians per unit of y; normalised by \
              the Jacobian bound (a + √(a²+4))/2, a = |rate|·ρ, inside the bounding cylinder of \
              radius ρ, points outside projected onto it (λ = 1; an unbounded shape needs an \
              annotation).",
        params: &[req("rate", Ty::Number)],
        arity: Arity::Exactly(1),
        lipschitz: warp_lambda,
        bound: |c| {
            let b = c.child_bound[0];
            let rho = b.cylinder_radius(DVec3::Y);
            Bound::sphere(DVec3::new(0.0, b.center.y, 0.0), rho.hypot(b.radius))
                .with_box(DVec3::new(-rho, b.lo.y, -rho), DVec3::new(rho, b.hi.y, rho))
        },
        swap: NO_SWAP,
        mirror: NONE,
        eval: |c, p, child| {
            let rho_max = c.child_bound[0].cylinder_radius(DVec3::Y);
            let stretch = twist_stretch(c.num(0), rho_max);
            warp(c, child, p, [0, 2], rho_max, stretch, |q| {
                twist_point(q, c.num(0))
            })
        },
    },
    Operator {
        name: "bend",
        fixed_args: true,
        traits: Traits {
            unbounded: Some("`bend` can only be bounded when its shape is bounded"),
            ..PLAIN
        },
        materials: MatRule::Pass,
        unit_gradient: SHORTENS,
        keeps_exact: SHORTENS,
        lower: super::gpu::warp::bend,
        doc: "Bends its shape in the xy plane by `rate` radians per unit of x; normalised by the \
              Jacobian bound 1 + |rate|·ρ inside the bounding cylinder about z (λ = 1).",
        params: &[req("rate", Ty::Number)],
        arity: Arity::Exactly(1),
        lipschitz: warp_lambda,
        bound: |c| {
            let b = c.child_bound[0];
            let rho = b.cylinder_radius(DVec3::Z);
            Bound::sphere(DVec3::new(0.0, 0.0, b.center.z), rho.hypot(b.radius))
                .with_box(DVec3::new(-rho, -rho, b.lo.z), DVec3::new(rho, rho, b.hi.z))
        },
        swap: NO_SWAP,
        mirror: NONE,
        eval: |c, p, child| {
            let rho_max = c.child_bound[0].cylinder_radius(DVec3::Z);
            let stretch = 1.0 + c.num(0).abs() * rho_max;
            warp(c, child, p, [0, 1], rho_max, stretch, |q| {
                bend_point(q, c.num(0))
            })
        },
    },
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
];
