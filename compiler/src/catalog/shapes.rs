//! More of Inigo Quilez's exact primitives (restated for sdfc's conventions: centred on their
//! bounding box, vertical ones along y): hexagonal and triangular prisms, round cone, link,
//! pyramid, rounded cylinder. Each is an exact distance (λ = 1); `tests/data/iq_reference.py`
//! computes each a second, independent way.

use super::geometry::HEX_FOLD;
use super::gpu::shapes as ir;
use super::{Bound, Ctx, NO_SWAP, Primitive, Ty, Val, opt};
use glam::{DVec2, DVec3};

const fn num(x: f64) -> Val {
    Val::Num(x)
}

/// GLSL's sign: 0 at 0 (Rust's `signum` gives 1), so that the CPU agrees with the shader.
pub(crate) fn sign0(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// An exact 2D distance `d` in a plane extruded to `half` on each side along the third axis,
/// whose coordinate is `w` (IQ's extrusion: exact when `d` is).
pub fn extrude(d: f64, w: f64, half: f64) -> f64 {
    let e = DVec2::new(d, w.abs() - half);
    e.max_element().min(0.0) + e.max(DVec2::ZERO).length()
}

/// Hexagonal prism along y: the hexagon in xz of inradius `r` (flat sides at z = ±r), height
/// `h`.
pub fn sd_hex_prism(p: DVec3, r: f64, h: f64) -> f64 {
    let (kx, kz, t) = HEX_FOLD;
    let (mut x, mut z) = (p.x.abs(), p.z.abs());
    let fold = 2.0 * (kx * x + kz * z).min(0.0);
    x -= fold * kx;
    z -= fold * kz;
    let d = DVec2::new(x - x.clamp(-t * r, t * r), z - r).length() * sign0(z - r);
    extrude(d, p.y, h / 2.0)
}

/// Round cone along y: a ball of `r1` at y = −h/2, one of `r2` at y = h/2, and their hull; the
/// larger ball alone when one holds the other.
pub fn sd_round_cone(p: DVec3, r1: f64, r2: f64, h: f64) -> f64 {
    let q = DVec2::new(DVec2::new(p.x, p.z).length(), p.y + h / 2.0);
    if h <= (r1 - r2).abs() {
        return if r1 >= r2 {
            q.length() - r1
        } else {
            (q - DVec2::new(0.0, h)).length() - r2
        };
    }
    let b = (r1 - r2) / h;
    let a = (1.0 - b * b).sqrt();
    let k = q.dot(DVec2::new(-b, a));
    if k < 0.0 {
        q.length() - r1
    } else if k > a * h {
        (q - DVec2::new(0.0, h)).length() - r2
    } else {
        q.dot(DVec2::new(a, b)) - r1
    }
}

/// A chain link in the xy plane: two half rings of `radius` joined by straight parts of
/// `length`, a tube of `thickness`.
pub fn sd_link(p: DVec3, length: f64, radius: f64, thickness: f64) -> f64 {
    let y = (p.y.abs() - length / 2.0).max(0.0);
    DVec2::new(DVec2::new(p.x, y).length() - radius, p.z).length() - thickness
}

/// Equilateral triangle of side `s` in the xy plane, apex up, centroid at the origin
/// (IQ's exact 2D triangle).
pub fn sd_triangle(x: f64, y: f64, s: f64) -> f64 {
    let k = 3f64.sqrt();
    let r = s / 2.0;
    let (mut x, mut y) = (x.abs() - r, y + r / k);
    if x + k * y > 0.0 {
        (x, y) = ((x - k * y) / 2.0, (-k * x - y) / 2.0);
    }
    x -= x.clamp(-2.0 * r, 0.0);
    -DVec2::new(x, y).length() * sign0(y)
}

/// Pyramid of a square base of side `s` at y = −h/2 and its apex at y = h/2 (IQ's exact
/// pyramid, with its base case and, inside, the base's plane, which takes a base of side 1: scaled by `s`).
pub fn sd_pyramid(p: DVec3, s: f64, h: f64) -> f64 {
    let h1 = h / s;
    let m2 = h1 * h1 + 0.25;
    let (mut x, y, mut z) = (p.x.abs() / s, (p.y + h / 2.0) / s, p.z.abs() / s);
    if y <= 0.0 {
        // At or below the base: the whole solid lies over the base square, so the square is
        // the nearest part.
        return s * DVec3::new((x - 0.5).max(0.0), -y, (z - 0.5).max(0.0)).length();
    }
    if z > x {
        (x, z) = (z, x);
    }
    x -= 0.5;
    z -= 0.5;
    let q = DVec3::new(z, h1 * y - 0.5 * x, h1 * x + 0.5 * y);
    let k = (-q.x).max(0.0);
    let t = ((q.y - 0.5 * z) / (m2 + 0.25)).clamp(0.0, 1.0);
    let a = m2 * (q.x + k) * (q.x + k) + q.y * q.y;
    let b = m2 * (q.x + 0.5 * t) * (q.x + 0.5 * t) + (q.y - m2 * t) * (q.y - m2 * t);
    let d2 = if q.y.min(-q.x * m2 - q.y * 0.5) > 0.0 {
        0.0
    } else {
        a.min(b)
    };
    let d = ((d2 + q.z * q.z) / m2).sqrt() * sign0(q.z.max(-y));
    // Inside, IQ's value is the distance to the nearest side face; the base is a face too.
    s * if d < 0.0 { d.max(-y) } else { d }
}

/// Vertical cylinder of `radius` and `height` whose rims are rounded by `r` (at most the
/// radius and half the height): the `r`-offset of the smaller cylinder inside.
pub fn sd_rounded_cylinder(p: DVec3, radius: f64, height: f64, r: f64) -> f64 {
    let r = r.min(radius).min(height / 2.0);
    // The inner cylinder is its radial distance extruded along y.
    extrude(
        DVec2::new(p.x, p.z).length() - (radius - r),
        p.y,
        height / 2.0 - r,
    ) - r
}

/// A box centred at `centre` with half extents `half`, and its sphere.
fn boxed(centre: DVec3, half: DVec3) -> Bound {
    Bound::centered_box(half).moved(centre)
}

const VERTICAL: fn(&Ctx) -> [bool; 3] = |_| [true, false, true];

/// `hex_prism`
pub const HEX_PRISM: Primitive = Primitive {
    name: "hex_prism",
    lower: ir::hex_prism,
    doc: "Hexagonal prism along y: a regular hexagon of inradius `radius` (flat sides facing ±z), \
          `height` tall, centred.",
    params: &[
        opt("radius", Ty::Length, num(0.5)),
        opt("height", Ty::Length, num(1.0)),
    ],
    bake: false,
    planar: false,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| {
        let r = c.num(0);
        boxed(
            DVec3::ZERO,
            DVec3::new(r / HEX_FOLD.0.abs(), c.num(1) / 2.0, r),
        )
    },
    swap: NO_SWAP,
    mirror: |_| [true; 3],
    eval: |c, p| sd_hex_prism(p, c.num(0), c.num(1)),
};

/// `round_cone`
pub const ROUND_CONE: Primitive = Primitive {
    name: "round_cone",
    lower: ir::round_cone,
    doc: "Round cone along y: a ball of radius `bottom` at y = −height/2, one of `top` at \
          +height/2, and the hull of the two.",
    params: &[
        opt("bottom", Ty::Length, num(0.5)),
        opt("top", Ty::Length, num(0.25)),
        opt("height", Ty::Length, num(1.0)),
    ],
    bake: false,
    planar: false,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| {
        let (r1, r2, h) = (c.num(0), c.num(1), c.num(2));
        let r = r1.max(r2);
        // Each ball's extent (one may hold the other and reach past its centre).
        let lo = (-h / 2.0 - r1).min(h / 2.0 - r2);
        let hi = (h / 2.0 + r2).max(-h / 2.0 + r1);
        boxed(
            DVec3::new(0.0, (lo + hi) / 2.0, 0.0),
            DVec3::new(r, (hi - lo) / 2.0, r),
        )
    },
    swap: NO_SWAP,
    mirror: VERTICAL,
    eval: |c, p| sd_round_cone(p, c.num(0), c.num(1), c.num(2)),
};

/// `link`
pub const LINK: Primitive = Primitive {
    name: "link",
    lower: ir::link,
    doc: "Chain link in the xy plane: half rings of `radius` joined by straight parts `length` \
          long along y, a tube of `thickness`.",
    params: &[
        opt("length", Ty::Length, num(1.0)),
        opt("radius", Ty::Length, num(0.4)),
        opt("thickness", Ty::Length, num(0.1)),
    ],
    bake: false,
    planar: false,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| {
        let (l, r, t) = (c.num(0), c.num(1), c.num(2));
        boxed(DVec3::ZERO, DVec3::new(r + t, l / 2.0 + r + t, t))
    },
    swap: NO_SWAP,
    mirror: |_| [true; 3],
    eval: |c, p| sd_link(p, c.num(0), c.num(1), c.num(2)),
};

/// `tri_prism`
pub const TRI_PRISM: Primitive = Primitive {
    name: "tri_prism",
    lower: ir::tri_prism,
    doc: "Triangular prism along z: an equilateral triangle of side `size` in the xy plane \
          (apex up, centroid at the origin), `depth` long.",
    params: &[
        opt("size", Ty::Length, num(1.0)),
        opt("depth", Ty::Length, num(1.0)),
    ],
    bake: false,
    planar: false,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| {
        let (s, d) = (c.num(0), c.num(1));
        let k = 3f64.sqrt();
        let (lo, hi) = (-s / (2.0 * k), s / k);
        boxed(
            DVec3::new(0.0, (lo + hi) / 2.0, 0.0),
            DVec3::new(s / 2.0, (hi - lo) / 2.0, d / 2.0),
        )
    },
    swap: NO_SWAP,
    mirror: |_| [true, false, true],
    eval: |c, p| extrude(sd_triangle(p.x, p.y, c.num(0)), p.z, c.num(1) / 2.0),
};

/// `pyramid`
pub const PYRAMID: Primitive = Primitive {
    name: "pyramid",
    lower: ir::pyramid,
    doc: "Pyramid of a square base of side `size` (at y = −height/2) and its apex at \
          y = +height/2.",
    params: &[
        opt("size", Ty::Positive, num(1.0)),
        opt("height", Ty::Length, num(1.0)),
    ],
    bake: false,
    planar: false,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| {
        boxed(
            DVec3::ZERO,
            DVec3::new(c.num(0) / 2.0, c.num(1) / 2.0, c.num(0) / 2.0),
        )
    },
    swap: NO_SWAP,
    mirror: VERTICAL,
    eval: |c, p| sd_pyramid(p, c.num(0), c.num(1)),
};

/// `rounded_cylinder`
pub const ROUNDED_CYLINDER: Primitive = Primitive {
    name: "rounded_cylinder",
    lower: ir::rounded_cylinder,
    doc: "Vertical cylinder of `radius` and `height`, centred, its rims rounded by `rounding` \
          (inside the size; at most the radius and half the height).",
    params: &[
        opt("radius", Ty::Length, num(0.5)),
        opt("height", Ty::Length, num(1.0)),
        opt("rounding", Ty::Length, num(0.1)),
    ],
    bake: false,
    planar: false,
    exact: true,
    estimate: false,
    unit_gradient: |_| true,
    lipschitz: |_| 1.0,
    bound: |c| boxed(DVec3::ZERO, DVec3::new(c.num(0), c.num(1) / 2.0, c.num(0))),
    swap: NO_SWAP,
    mirror: |_| [true; 3],
    eval: |c, p| sd_rounded_cylinder(p, c.num(0), c.num(1), c.num(2)),
};
