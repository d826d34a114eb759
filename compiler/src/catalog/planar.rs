//! 2D shapes and the operators that make solids of them. A 2D shape lies in the xy plane; as a
//! field of space it is the same at every z (its distance in the plane), so 2D shapes combine
//! and move in their plane with the usual operators, and only `extrude` (along z) and `revolve`
//! (about y) turn them into solids. Both are exact for an exact shape (Inigo Quilez's
//! extrusion and revolution), with λ = 1 and the child's λ.

use super::gpu::planar as ir;
use super::shapes::sign0;
use super::traits::{PLAIN, Plane, Traits};
use super::{Arity, Bound, MatRule, NO_SWAP, Operator, Primitive, Ty, Val, opt, shapes};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

const fn num(x: f64) -> Val {
    Val::Num(x)
}

/// The 2D primitives' names, in the catalog's order.
pub fn primitives_2d() -> impl Iterator<Item = &'static str> {
    super::PRIMITIVES
        .iter()
        .filter(|p| p.planar)
        .map(|p| p.name)
}

/// The bound of a 2D shape within `lo..hi` of the plane: every z.
fn planar(lo: DVec2, hi: DVec2) -> Bound {
    Bound {
        center: DVec3::ZERO,
        radius: f64::INFINITY,
        lo: DVec3::new(lo.x, lo.y, f64::NEG_INFINITY),
        hi: DVec3::new(hi.x, hi.y, f64::INFINITY),
    }
}

/// A rectangle of half extents `h` (IQ's 2D box).
pub fn sd_rectangle(p: DVec2, h: DVec2) -> f64 {
    let q = p.abs() - h;
    q.max(DVec2::ZERO).length() + q.max_element().min(0.0)
}

/// A regular polygon of `n` sides inscribed in a circle of radius `r`, a vertex on +y (IQ's
/// exact regular polygon).
pub fn sd_polygon(p: DVec2, n: f64, r: f64) -> f64 {
    let an = PI / n;
    let (s, c) = an.sin_cos();
    // The sector of p: its angle from +y, reduced to [−an, an) (GLSL's mod).
    let a = p.x.atan2(p.y);
    let bn = a - 2.0 * an * (a / (2.0 * an)).floor() - an;
    let l = p.length();
    let mut q = DVec2::new(l * bn.cos(), l * bn.sin().abs()) - r * DVec2::new(c, s);
    q.y += (-q.y).clamp(0.0, r * s);
    q.length() * sign0(q.x)
}

/// `circle`
pub const CIRCLE: Primitive = Primitive {
    name: "circle",
    lower: ir::circle,
    doc: "2D: a disc of `radius` in the xy plane, centred (extrude or revolve it).",
    params: &[opt("radius", Ty::Length, num(0.5))],
    bake: false,
    planar: true,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| planar(DVec2::splat(-c.num(0)), DVec2::splat(c.num(0))),
    swap: NO_SWAP,
    mirror: |_| [true; 3],
    eval: |c, p| DVec2::new(p.x, p.y).length() - c.num(0),
};

/// `rectangle`
pub const RECTANGLE: Primitive = Primitive {
    name: "rectangle",
    lower: ir::rectangle,
    doc: "2D: a rectangle `width` along x and `height` along y, centred.",
    params: &[
        opt("width", Ty::Length, num(1.0)),
        opt("height", Ty::Length, num(1.0)),
    ],
    bake: false,
    planar: true,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| {
        let h = DVec2::new(c.num(0), c.num(1)) / 2.0;
        planar(-h, h)
    },
    swap: NO_SWAP,
    mirror: |_| [true; 3],
    eval: |c, p| sd_rectangle(DVec2::new(p.x, p.y), DVec2::new(c.num(0), c.num(1)) / 2.0),
};

/// `polygon`
pub const POLYGON: Primitive = Primitive {
    name: "polygon",
    lower: ir::polygon,
    doc: "2D: a regular polygon of `sides` inscribed in a circle of `radius`, a corner on +y.",
    params: &[
        opt("sides", Ty::WholeIn(3, 64), num(6.0)),
        opt("radius", Ty::Length, num(0.5)),
    ],
    bake: false,
    planar: true,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| planar(DVec2::splat(-c.num(1)), DVec2::splat(c.num(1))),
    swap: NO_SWAP,
    mirror: |c| [true, c.num(0) % 2.0 == 0.0, true],
    eval: |c, p| sd_polygon(DVec2::new(p.x, p.y), c.num(0), c.num(1)),
};

/// `triangle`
pub const TRIANGLE: Primitive = Primitive {
    name: "triangle",
    lower: ir::triangle,
    doc: "2D: an equilateral triangle of side `size`, apex up (+y), centroid at the origin.",
    params: &[opt("size", Ty::Length, num(1.0))],
    bake: false,
    planar: true,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| {
        let s = c.num(0);
        let k = 3f64.sqrt();
        planar(
            DVec2::new(-s / 2.0, -s / (2.0 * k)),
            DVec2::new(s / 2.0, s / k),
        )
    },
    swap: NO_SWAP,
    mirror: |_| [true, false, true],
    eval: |c, p| shapes::sd_triangle(p.x, p.y, c.num(0)),
};

/// `extrude`
pub const EXTRUDE: Operator = Operator {
    name: "extrude",
    fixed_args: false,
    traits: Traits {
        plane: Plane::Makes,
        ..PLAIN
    },
    materials: MatRule::Pass,
    unit_gradient: |_| true,
    keeps_exact: |_| true,
    lower: ir::extrude,
    doc: "Makes a solid of a 2D shape: its `height` along z, centred (the shape's distance \
          d/λ and |z| − height/2 combined as a box's sides are; exact for an exact shape, λ = 1).",
    params: &[opt("height", Ty::Length, num(1.0))],
    arity: Arity::Exactly(1),
    lipschitz: |_| 1.0,
    bound: |c| {
        let b = c.child_bound[0];
        let h = c.num(0) / 2.0;
        let (lo, hi) = (
            DVec3::new(b.lo.x, b.lo.y, -h),
            DVec3::new(b.hi.x, b.hi.y, h),
        );
        if !(lo.is_finite() && hi.is_finite()) {
            return Bound::INFINITE;
        }
        Bound::centered_box((hi - lo) / 2.0).moved((lo + hi) / 2.0)
    },
    swap: NO_SWAP,
    mirror: |c| [c.child_mirror[0][0], c.child_mirror[0][1], true],
    eval: |c, p, child| shapes::extrude(child(0, p) / c.child_lambda[0], p.z, c.num(0) / 2.0),
};

/// `revolve`
pub const REVOLVE: Operator = Operator {
    name: "revolve",
    fixed_args: false,
    traits: Traits {
        plane: Plane::Makes,
        ..PLAIN
    },
    materials: MatRule::Pass,
    unit_gradient: |_| true,
    keeps_exact: |c| c.child_bound[0].lo.x >= -c.num(0),
    lower: ir::revolve,
    doc: "Makes a solid of a 2D shape by turning it about the y axis: x of the shape is the \
          distance from the axis less `radius` (the shape at (length(x, z) − radius, y); λ is \
          the shape's; exact outside where the shape does not reach past the axis).",
    params: &[opt("radius", Ty::Number, num(0.0))],
    arity: Arity::Exactly(1),
    lipschitz: |c| c.child_lambda[0],
    bound: |c| {
        let b = c.child_bound[0];
        let reach = (c.num(0) + b.hi.x).max(0.0);
        let (lo, hi) = (
            DVec3::new(-reach, b.lo.y, -reach),
            DVec3::new(reach, b.hi.y, reach),
        );
        if !(lo.is_finite() && hi.is_finite()) {
            return Bound::INFINITE;
        }
        Bound::centered_box((hi - lo) / 2.0).moved((lo + hi) / 2.0)
    },
    swap: NO_SWAP,
    mirror: |c| [true, c.child_mirror[0][1], true],
    eval: |c, p, child| {
        let q = DVec3::new(DVec2::new(p.x, p.z).length() - c.num(0), p.y, 0.0);
        child(0, q)
    },
};
