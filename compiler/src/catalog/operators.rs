//! Operators: CSG, smooth blends, metamorphosis, transforms and domain operations, each with its
//! Lipschitz rule (in its doc line) and f64 evaluation.
//!
//! Convention: operators that combine children (CSG, blends, blobs) first divide each child by its
//! λ, so their own result has λ = 1 (Liktor §4: min/max of 1-Lipschitz functions stay 1-Lipschitz;
//! IQ's polynomial smooth minimum is a convex combination of its operands' gradients). Operators
//! that only move the domain keep the child's λ, or raise it by their Jacobian's norm.

use super::{Arity, Bound, ChildEval, Ctx, MatRule, Operator, Ty, Val, opt, req};
use crate::lower::ops as ir;
use glam::DVec3;

const fn num(x: f64) -> Val {
    Val::Num(x)
}

const SAME: fn(&Ctx) -> f64 = |c| c.child_lambda[0];
const ONE: fn(&Ctx) -> f64 = |_| 1.0;

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
        .min_by(|a, b| a.radius.total_cmp(&b.radius))
        .unwrap_or(Bound::INFINITE)
}

fn all(c: &Ctx) -> Bound {
    c.child_bound
        .iter()
        .copied()
        .reduce(Bound::union)
        .unwrap_or(Bound::INFINITE)
}

fn grow(b: Bound, by: f64) -> Bound {
    Bound {
        radius: b.radius + by,
        ..b
    }
}

/// Rodrigues' rotation of `v` by `angle` about the unit `axis`.
pub fn rotate(v: DVec3, axis: DVec3, angle: f64) -> DVec3 {
    let (s, co) = angle.sin_cos();
    v * co + axis.cross(v) * s + axis * axis.dot(v) * (1.0 - co)
}

/// Wyvill's blob falloff (1 − s²)³ on [0, 1]; its slope is at most 96/(25√5) ≈ 1.7173.
pub fn falloff(s: f64) -> f64 {
    let t = (1.0 - s * s).max(0.0);
    t * t * t
}

/// The steepest slope of [`falloff`], reached at s = 1/√5.
pub const FALLOFF_SLOPE: f64 = 1.717_300_316_677_839_6;

/// Largest singular value of the twist's Jacobian at distance ρ from the axis: with a = |k|ρ,
/// JᵀJ has eigenvalues 1, and the two roots of s² − (2 + a²)s + 1, the larger being
/// ((a + √(a² + 4)) / 2)².
pub fn twist_stretch(rate: f64, rho: f64) -> f64 {
    let a = rate.abs() * rho;
    (a + (a * a + 4.0).sqrt()) / 2.0
}

/// A domain bend or twist. The child's surface lies inside the infinite cylinder of radius
/// `rho_max` about the warp's axis (`radial` are the two coordinates across it), where the
/// deformation stretches distances by at most `stretch`. A point outside is first projected
/// radially onto the cylinder (a 1-Lipschitz map that brings it no nearer to anything inside),
/// and the distance to the cylinder is a second bound: max(f(deform(proj p))/(λ·stretch),
/// ρ − ρmax) is 1-Lipschitz and never exceeds the distance to the warped surface. With an
/// unbounded child the raw field is returned (λ is then infinite and must be annotated).
pub fn warp(
    c: &Ctx,
    child: ChildEval,
    p: DVec3,
    radial: [usize; 2],
    rho_max: f64,
    stretch: f64,
    deform: impl Fn(DVec3) -> DVec3,
) -> f64 {
    if !rho_max.is_finite() {
        return child(0, deform(p));
    }
    let rho = p[radial[0]].hypot(p[radial[1]]);
    let mut q = p;
    if rho > rho_max {
        let s = rho_max / rho;
        q[radial[0]] *= s;
        q[radial[1]] *= s;
    }
    (child(0, deform(q)) / (c.child_lambda[0] * stretch)).max(rho - rho_max)
}

/// Twist about y by `rate`·y.
pub fn twist_point(p: DVec3, rate: f64) -> DVec3 {
    let (s, co) = (rate * p.y).sin_cos();
    DVec3::new(co * p.x - s * p.z, p.y, s * p.x + co * p.z)
}

/// Bend in the xy plane by `rate`·x.
pub fn bend_point(p: DVec3, rate: f64) -> DVec3 {
    let (s, co) = (rate * p.x).sin_cos();
    DVec3::new(co * p.x - s * p.y, s * p.x + co * p.y, p.z)
}

fn warp_lambda(c: &Ctx) -> f64 {
    if c.child_bound[0].radius.is_finite() {
        1.0
    } else {
        f64::INFINITY
    }
}

/// Every operator of the language.
pub static OPERATORS: &[Operator] = &[
    Operator {
        name: "union",
        materials: MatRule::Nearest,
        lower: ir::union,
        doc: "Union of its shapes: min (λ = 1 after dividing each child by its λ); the nearest \
              shape's material.",
        params: &[],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: all,
        eval: |c, p, child| fold(c, p, child, f64::min),
    },
    Operator {
        name: "intersect",
        materials: MatRule::Farthest,
        lower: ir::intersect,
        doc: "Intersection: max (λ = 1); the material of the shape that bounds the result.",
        params: &[],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: smallest,
        eval: |c, p, child| fold(c, p, child, f64::max),
    },
    Operator {
        name: "subtract",
        materials: MatRule::Cut,
        lower: ir::subtract,
        doc: "The first shape minus the others: max(a, −b) (λ = 1); cut faces take the cutter's \
              material.",
        params: &[],
        arity: Arity::AtLeast(2),
        lipschitz: ONE,
        bound: |c| c.child_bound[0],
        eval: |c, p, child| fold(c, p, child, |a, b| a.max(-b)),
    },
    Operator {
        name: "complement",
        materials: MatRule::Pass,
        lower: ir::complement,
        doc: "Inside out: −f (λ unchanged).",
        params: &[],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |_| Bound::INFINITE,
        eval: |_, p, child| -child(0, p),
    },
    Operator {
        name: "smooth_union",
        materials: MatRule::Nearest,
        lower: ir::smooth_union,
        doc: "Union blended over `radius` by IQ's polynomial smooth minimum (λ = 1); the nearer \
              shape's material.",
        params: &[req("radius", Ty::Length)],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: |c| grow(all(c), c.num(0) / 4.0),
        eval: |c, p, child| fold(c, p, child, |a, b| smin(a, b, c.num(0))),
    },
    Operator {
        name: "smooth_intersect",
        materials: MatRule::Farthest,
        lower: ir::smooth_intersect,
        doc: "Intersection blended over `radius` (λ = 1).",
        params: &[req("radius", Ty::Length)],
        arity: Arity::AtLeast(1),
        lipschitz: ONE,
        bound: smallest,
        eval: |c, p, child| fold(c, p, child, |a, b| smax(a, b, c.num(0))),
    },
    Operator {
        name: "smooth_subtract",
        materials: MatRule::Cut,
        lower: ir::smooth_subtract,
        doc: "The first shape minus the others, blended over `radius` (λ = 1).",
        params: &[req("radius", Ty::Length)],
        arity: Arity::AtLeast(2),
        lipschitz: ONE,
        bound: |c| c.child_bound[0],
        eval: |c, p, child| fold(c, p, child, |a, b| smax(a, -b, c.num(0))),
    },
    Operator {
        name: "mix",
        materials: MatRule::Weighted,
        lower: ir::mix,
        doc: "Metamorphosis (Liktor Fig. 9): (1 − `weight`)·a + `weight`·b of the raw fields, \
              λ = (1 − w)·λa + w·λb; the heavier shape's material.",
        params: &[req("weight", Ty::Fraction)],
        arity: Arity::Exactly(2),
        lipschitz: |c| (1.0 - c.num(0)) * c.child_lambda[0] + c.num(0) * c.child_lambda[1],
        bound: all,
        eval: |c, p, child| {
            let w = c.num(0);
            (1.0 - w) * child(0, p) + w * child(1, p)
        },
    },
    Operator {
        name: "blob",
        materials: MatRule::Nearest,
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
        bound: |c| grow(all(c), c.num(0)),
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
        materials: MatRule::Pass,
        lower: ir::translate,
        doc: "Moves its shape by `offset` (λ unchanged). `s at (x, y, z)` is the same.",
        params: &[req("offset", Ty::Vec3)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| Bound {
            center: c.child_bound[0].center + c.vec(0),
            ..c.child_bound[0]
        },
        eval: |c, p, child| child(0, p - c.vec(0)),
    },
    Operator {
        name: "rotate",
        materials: MatRule::Pass,
        lower: ir::rotate,
        doc: "Rotates its shape by `angle` about `axis` through the origin (λ unchanged).",
        params: &[req("axis", Ty::Axis), req("angle", Ty::Angle)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| Bound {
            center: rotate(c.child_bound[0].center, c.vec(0), c.num(1)),
            ..c.child_bound[0]
        },
        eval: |c, p, child| child(0, rotate(p, c.vec(0), -c.num(1))),
    },
    Operator {
        name: "scale",
        materials: MatRule::Pass,
        lower: ir::scale,
        doc: "Scales its shape by `factor` (a number, or a vector for non-uniform scale): \
              f(p/s)·min(s), λ multiplied by max(s)/min(s).",
        params: &[req("factor", Ty::Scale)],
        arity: Arity::Exactly(1),
        lipschitz: |c| c.child_lambda[0] * c.vec(0).max_element() / c.vec(0).min_element(),
        bound: |c| Bound {
            center: c.child_bound[0].center * c.vec(0),
            radius: c.child_bound[0].radius * c.vec(0).max_element(),
        },
        eval: |c, p, child| {
            let s = c.vec(0);
            child(0, p / s) * s.min_element()
        },
    },
    Operator {
        name: "repeat",
        materials: MatRule::Pass,
        lower: ir::repeat,
        doc: "Repeats its shape every `spacing` along each axis (0: not on that axis), `count` \
              copies per axis (0: without end); λ unchanged while the shape fits in its cell.",
        params: &[req("spacing", Ty::Size), opt("count", Ty::Counts, num(0.0))],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| {
            let (s, n) = (c.vec(0), c.vec(1));
            if (0..3).any(|i| s[i] > 0.0 && n[i] == 0.0) {
                return Bound::INFINITE;
            }
            let half = s * (n - DVec3::ONE).max(DVec3::ZERO) / 2.0;
            grow(c.child_bound[0], half.length())
        },
        eval: |c, p, child| child(0, repeat_cell(p, c.vec(0), c.vec(1))),
    },
    Operator {
        name: "mirror",
        materials: MatRule::Pass,
        lower: ir::mirror,
        doc: "Mirrors the half-space in front of the plane through the origin with normal `axis` \
              onto the back (λ unchanged).",
        params: &[req("axis", Ty::Axis)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| {
            let b = c.child_bound[0];
            let n = c.vec(0);
            let mirrored = Bound {
                center: b.center - 2.0 * b.center.dot(n) * n,
                ..b
            };
            b.union(mirrored)
        },
        eval: |c, p, child| {
            let n = c.vec(0);
            child(0, p - 2.0 * p.dot(n).min(0.0) * n)
        },
    },
    Operator {
        name: "twist",
        materials: MatRule::Pass,
        lower: ir::twist,
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
            Bound {
                center: DVec3::new(0.0, b.center.y, 0.0),
                radius: rho.hypot(b.radius),
            }
        },
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
        materials: MatRule::Pass,
        lower: ir::bend,
        doc: "Bends its shape in the xy plane by `rate` radians per unit of x; normalised by the \
              Jacobian bound 1 + |rate|·ρ inside the bounding cylinder about z (λ = 1).",
        params: &[req("rate", Ty::Number)],
        arity: Arity::Exactly(1),
        lipschitz: warp_lambda,
        bound: |c| {
            let b = c.child_bound[0];
            let rho = b.cylinder_radius(DVec3::Z);
            Bound {
                center: DVec3::new(0.0, 0.0, b.center.z),
                radius: rho.hypot(b.radius),
            }
        },
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
        materials: MatRule::Pass,
        lower: ir::round,
        doc: "Rounds its shape outward by `radius`: f/λ − r (λ = 1).",
        params: &[req("radius", Ty::Length)],
        arity: Arity::Exactly(1),
        lipschitz: ONE,
        bound: |c| grow(c.child_bound[0], c.num(0)),
        eval: |c, p, child| norm(c, child, 0, p) - c.num(0),
    },
    Operator {
        name: "onion",
        materials: MatRule::Pass,
        lower: ir::onion,
        doc: "Hollows its shape into a shell of `thickness`: |f/λ| − t (λ = 1).",
        params: &[req("thickness", Ty::Length)],
        arity: Arity::Exactly(1),
        lipschitz: ONE,
        bound: |c| grow(c.child_bound[0], c.num(0)),
        eval: |c, p, child| norm(c, child, 0, p).abs() - c.num(0),
    },
    Operator {
        name: "elongate",
        materials: MatRule::Pass,
        lower: ir::elongate,
        doc: "Stretches its shape by inserting `amount` of straight extent along each axis at the \
              origin: f(p − clamp(p, −h, h)), h = amount/2 (λ unchanged).",
        params: &[req("amount", Ty::Size)],
        arity: Arity::Exactly(1),
        lipschitz: SAME,
        bound: |c| grow(c.child_bound[0], c.vec(0).length() / 2.0),
        eval: |c, p, child| {
            let h = c.vec(0) / 2.0;
            child(0, p - p.clamp(-h, h))
        },
    },
];

/// The point of `p`'s repetition cell that the original shape is evaluated at.
pub fn repeat_cell(p: DVec3, spacing: DVec3, count: DVec3) -> DVec3 {
    let mut q = p;
    for i in 0..3 {
        let s = spacing[i];
        if s <= 0.0 {
            continue;
        }
        let n = count[i];
        q[i] = if n == 0.0 {
            p[i] - s * round_half_up(p[i] / s)
        } else {
            let half = (n - 1.0) / 2.0;
            p[i] - s * (round_half_up(p[i] / s + half).clamp(0.0, n - 1.0) - half)
        };
    }
    q
}

/// floor(x + 0.5): the rounding the shaders use too, so cells agree at exact halves.
pub fn round_half_up(x: f64) -> f64 {
    (x + 0.5).floor()
}
