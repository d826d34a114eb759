//! Operators of space: moves, turns and scales, `repeat` and `mirror`, and the warps `twist` and
//! `bend`, each with its Lipschitz rule (in its doc line), f64 evaluation and traits. They keep
//! the child's λ, or raise it by their Jacobian's norm.

use super::geometry::rotate;
use super::gpu::domain as ir;
use super::rules::{KEEPS, SAME, SHORTENS, num};
use super::symmetry::{CHILD, NONE, and, rotated_mirror, rotated_swap};
use super::traits::{Motion, PLAIN, Plane, PlaneRule, Traits};
use super::warp::{bend_point, twist_point, twist_stretch, warp, warp_lambda};
use super::{Arity, Bound, MatRule, NO_SWAP, Operator, Ty, equal_pairs, opt, req};
use glam::DVec3;

/// `translate`.
pub const TRANSLATE: Operator = Operator {
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
};

/// `rotate`.
pub const ROTATE: Operator = Operator {
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
};

/// `scale`.
pub const SCALE: Operator = Operator {
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
};

/// `repeat`.
pub const REPEAT: Operator = Operator {
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
        let unbounded = (0..3).any(|i| s[i] > 0.0 && !(b.lo[i].is_finite() && b.hi[i].is_finite()));
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
};

/// `mirror`.
pub const MIRROR: Operator = Operator {
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
};

/// `twist`.
pub const TWIST: Operator = Operator {
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
};

/// `bend`.
pub const BEND: Operator = Operator {
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
};
