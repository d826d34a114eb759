//! Primitive shapes: parameters, Lipschitz bound, bounding sphere and f64 distance of each.
//!
//! Distance formulas follow Inigo Quilez's catalogue of exact distance functions (restated here,
//! not copied); the dodecahedron is the generalised distance function of Akleman et al. as used in
//! the Keinert seed (Fig. 11); the Mandelbulb is the distance estimator of Bálint's test scene.

use super::geometry::{ELLIPSOID_MIN_RADIUS, dodecahedron_normals, mandelbulb_radius};
use super::gpu::prims as ir;
use super::{Bound, Ctx, NO_SWAP, Primitive, Ty, Val, equal_pairs, opt};
use glam::{DVec2, DVec3};

const ONE: fn(&Ctx) -> f64 = |_| 1.0;
const ALL_AXES: fn(&Ctx) -> [bool; 3] = |_| [true; 3];
/// Round about y: x and z may be exchanged.
const ABOUT_Y: fn(&Ctx) -> [bool; 3] = |_| [false, true, false];

const fn num(x: f64) -> Val {
    Val::Num(x)
}

const fn vec3(x: f64, y: f64, z: f64) -> Val {
    Val::Vec3(DVec3::new(x, y, z))
}

/// Every primitive of the language.
pub static PRIMITIVES: &[Primitive] = &[
    Primitive {
        name: "sphere",
        lower: ir::sphere,
        doc: "Sphere of `radius` at the origin.",
        params: &[opt("radius", Ty::Length, num(1.0))],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| Bound::origin(c.num(0)),
        swap: ALL_AXES,
        mirror: ALL_AXES,
        eval: |c, p| p.length() - c.num(0),
    },
    Primitive {
        name: "box",
        lower: ir::cuboid,
        doc: "Axis-aligned box of full edge lengths `size`, centred.",
        params: &[opt("size", Ty::Size, num(1.0))],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| Bound::centered_box(c.vec(0) / 2.0),
        swap: |c| equal_pairs(c.vec(0)),
        mirror: ALL_AXES,
        eval: |c, p| sd_box(p, c.vec(0) / 2.0),
    },
    Primitive {
        name: "rounded_box",
        lower: ir::rounded_box,
        doc: "Box of full edge lengths `size` whose edges are rounded by `radius` (inside the \
              size; at most half the smallest edge).",
        params: &[
            opt("size", Ty::Size, num(1.0)),
            opt("radius", Ty::Length, num(0.1)),
        ],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| Bound::centered_box(c.vec(0) / 2.0),
        swap: |c| equal_pairs(c.vec(0)),
        mirror: ALL_AXES,
        eval: |c, p| {
            let half = c.vec(0) / 2.0;
            let r = c.num(1).min(half.min_element());
            sd_box(p, half - DVec3::splat(r)) - r
        },
    },
    Primitive {
        name: "plane",
        lower: ir::plane,
        doc: "Half-space below the plane through `offset`·`normal` (normal `y` is the floor y = offset).",
        params: &[
            opt("normal", Ty::Axis, vec3(0.0, 1.0, 0.0)),
            opt("offset", Ty::Number, num(0.0)),
        ],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |_| Bound::INFINITE,
        swap: |c| equal_pairs(c.vec(0)),
        mirror: |c| c.vec(0).to_array().map(|n| n == 0.0),
        eval: |c, p| p.dot(c.vec(0)) - c.num(1),
    },
    Primitive {
        name: "torus",
        lower: ir::torus,
        doc: "Torus in the xz plane: ring radius `major`, tube radius `minor` (inside a spindle \
              torus, minor > major, a bound).",
        params: &[
            opt("major", Ty::Length, num(1.0)),
            opt("minor", Ty::Length, num(0.25)),
        ],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| {
            let (r, t) = (c.num(0) + c.num(1), c.num(1));
            Bound::origin(r).with_box(-DVec3::new(r, t, r), DVec3::new(r, t, r))
        },
        swap: ABOUT_Y,
        mirror: ALL_AXES,
        eval: |c, p| DVec2::new(DVec2::new(p.x, p.z).length() - c.num(0), p.y).length() - c.num(1),
    },
    Primitive {
        name: "capsule",
        lower: ir::capsule,
        doc: "Vertical capsule: a segment of `height` along y, centred, swept by a ball of `radius`.",
        params: &[
            opt("height", Ty::Length, num(1.0)),
            opt("radius", Ty::Length, num(0.25)),
        ],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| {
            let (r, h) = (c.num(1), c.num(0) / 2.0 + c.num(1));
            Bound::origin(h).with_box(-DVec3::new(r, h, r), DVec3::new(r, h, r))
        },
        swap: ABOUT_Y,
        mirror: ALL_AXES,
        eval: |c, p| {
            let h = c.num(0) / 2.0;
            DVec3::new(p.x, p.y - p.y.clamp(-h, h), p.z).length() - c.num(1)
        },
    },
    Primitive {
        name: "cylinder",
        lower: ir::cylinder,
        doc: "Capped vertical cylinder of `radius` and `height`, centred.",
        params: &[
            opt("radius", Ty::Length, num(0.5)),
            opt("height", Ty::Length, num(1.0)),
        ],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| {
            let half = DVec3::new(c.num(0), c.num(1) / 2.0, c.num(0));
            Bound::origin(DVec2::new(c.num(0), c.num(1) / 2.0).length()).with_box(-half, half)
        },
        swap: ABOUT_Y,
        mirror: ALL_AXES,
        eval: |c, p| {
            let d = DVec2::new(DVec2::new(p.x, p.z).length(), p.y).abs()
                - DVec2::new(c.num(0), c.num(1) / 2.0);
            d.x.max(d.y).min(0.0) + d.max(DVec2::ZERO).length()
        },
    },
    Primitive {
        name: "cone",
        lower: ir::cone,
        doc: "Capped vertical cone of `height`, centred: base `radius` at the bottom, `top` radius above.",
        params: &[
            opt("radius", Ty::Length, num(0.5)),
            opt("height", Ty::Length, num(1.0)),
            opt("top", Ty::Length, num(0.0)),
        ],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| {
            let r = c.num(0).max(c.num(2));
            let half = DVec3::new(r, c.num(1) / 2.0, r);
            Bound::origin(DVec2::new(r, c.num(1) / 2.0).length()).with_box(-half, half)
        },
        swap: ABOUT_Y,
        mirror: |_| [true, false, true],
        eval: |c, p| sd_capped_cone(p, c.num(1) / 2.0, c.num(0), c.num(2)),
    },
    Primitive {
        name: "ellipsoid",
        lower: ir::ellipsoid,
        doc: "Ellipsoid with semi-axes `radii`; a bound (λ = 1), exact only for spheres.",
        params: &[opt("radii", Ty::Size, vec3(1.0, 0.5, 0.5))],
        bake: false,
        planar: false,
        exact: false,
        estimate: false,
        unit_gradient: |_| false,
        lipschitz: ONE,
        bound: |c| Bound::origin(c.vec(0).max_element()).with_box(-c.vec(0), c.vec(0)),
        swap: |c| equal_pairs(c.vec(0)),
        mirror: ALL_AXES,
        // |p / r| - 1 has gradient at most 1 / min(r); scaling by min(r) makes it 1-Lipschitz.
        eval: |c, p| {
            let r = c.vec(0).max(DVec3::splat(ELLIPSOID_MIN_RADIUS));
            ((p / r).length() - 1.0) * r.min_element()
        },
    },
    Primitive {
        name: "octahedron",
        lower: ir::octahedron,
        doc: "Regular octahedron |x| + |y| + |z| = `size`.",
        params: &[opt("size", Ty::Length, num(1.0))],
        bake: false,
        planar: false,
        exact: true,
        estimate: false,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| Bound::origin(c.num(0)),
        swap: ALL_AXES,
        mirror: ALL_AXES,
        eval: |c, p| sd_octahedron(p, c.num(0)),
    },
    Primitive {
        name: "dodecahedron",
        lower: ir::dodecahedron,
        doc: "Dodecahedron of inradius `radius` as a generalised distance (Akleman; Keinert Fig. 11); \
              `exponent` 0 is the sharp max form (λ = 1), e ≥ 1 the e-norm of the six face \
              distances, rounder as e falls (λ = √2·6^max(0, 1/e − 1/2)).",
        params: &[
            opt("radius", Ty::Length, num(1.0)),
            opt("exponent", Ty::ZeroOrAtLeast(1.0), num(0.0)),
        ],
        bake: false,
        planar: false,
        exact: false,
        estimate: false,
        unit_gradient: |c| c.num(1) == 0.0,
        // The six unit normals form a tight frame (Σ nnᵀ = 2I), so |Np|₂ ≤ √2|p|; and
        // |v|_e ≤ 6^(1/e − 1/2)|v|₂ for e < 2, |v|_e ≤ |v|₂ for e ≥ 2.
        // ‖Np‖ₑ for the six unit normals N: at most √2·6^max(0, 1/e − 1/2)·|p| (N is a tight
        // frame, NᵀN = 2I, then Hölder), and at most 6^(1/e)·‖Np‖∞ ≤ 6^(1/e)·|p|; the smaller.
        lipschitz: |c| match c.num(1) {
            0.0 => 1.0,
            e => (std::f64::consts::SQRT_2 * 6f64.powf((1.0 / e - 0.5).max(0.0)))
                .min(6f64.powf(1.0 / e)),
        },
        // The inradius-r dodecahedron has circumradius r·√3·tan(π/5)·φ ≈ 1.2584 r.
        bound: |c| Bound::origin(c.num(0) * 1.2585),
        swap: NO_SWAP,
        mirror: ALL_AXES,
        eval: |c, p| gdf_dodecahedron(p, c.num(0), c.num(1)),
    },
    Primitive {
        name: "mandelbulb",
        lower: ir::mandelbulb,
        doc: "Power-`power` Mandelbulb by its distance estimator (Bálint's test scene); an estimate, \
              not a proven bound.",
        params: &[
            opt("power", Ty::Range(2.0, 32.0), num(8.0)),
            opt(
                "iterations",
                Ty::CountTo(MANDELBULB_MAX_ITERATIONS),
                num(8.0),
            ),
        ],
        bake: true,
        planar: false,
        exact: false,
        estimate: true,
        unit_gradient: |_| true,
        lipschitz: ONE,
        bound: |c| Bound::origin(mandelbulb_radius(c.num(0))),
        swap: NO_SWAP,
        mirror: |_| [false; 3],
        eval: |c, p| mandelbulb(p, c.num(0), c.num(1) as u32),
    },
    super::shapes::HEX_PRISM,
    super::shapes::TRI_PRISM,
    super::shapes::PYRAMID,
    super::shapes::ROUND_CONE,
    super::shapes::ROUNDED_CYLINDER,
    super::shapes::LINK,
    super::planar::CIRCLE,
    super::planar::RECTANGLE,
    super::planar::POLYGON,
    super::planar::TRIANGLE,
];

/// Distance to a box of half extents `b` (IQ's exact box).
pub fn sd_box(p: DVec3, b: DVec3) -> f64 {
    let q = p.abs() - b;
    q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
}

/// Capped cone of half height `h`, bottom radius `r1`, top radius `r2` (IQ's exact capped cone).
fn sd_capped_cone(p: DVec3, h: f64, r1: f64, r2: f64) -> f64 {
    let q = DVec2::new(DVec2::new(p.x, p.z).length(), p.y);
    let k1 = DVec2::new(r2, h);
    let k2 = DVec2::new(r2 - r1, 2.0 * h);
    let ca = DVec2::new(
        q.x - q.x.min(if q.y < 0.0 { r1 } else { r2 }),
        q.y.abs() - h,
    );
    let k2_len2 = k2.length_squared();
    let t = if k2_len2 > 0.0 {
        ((k1 - q).dot(k2) / k2_len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let cb = q - k1 + k2 * t;
    // Inside the slanted side: q.x below the side's radius at height q.y, tested on the side
    // line's equation rather than IQ's `cb.x < 0`, which for a flat cone is the x component
    // of a nearly vertical vector and flips sign under f32 rounding.
    let inside_side = 2.0 * h * (q.x - r2) + (r1 - r2) * (q.y - h) < 0.0;
    let s = if inside_side && ca.y < 0.0 { -1.0 } else { 1.0 };
    s * ca.length_squared().min(cb.length_squared()).sqrt()
}

/// IQ's exact octahedron.
fn sd_octahedron(p: DVec3, s: f64) -> f64 {
    let p = p.abs();
    let m = p.x + p.y + p.z - s;
    let q = if 3.0 * p.x < m {
        p
    } else if 3.0 * p.y < m {
        DVec3::new(p.y, p.z, p.x)
    } else if 3.0 * p.z < m {
        DVec3::new(p.z, p.x, p.y)
    } else {
        return m * (1.0 / 3f64.sqrt());
    };
    let k = (0.5 * (q.z - q.y + s)).clamp(0.0, s);
    DVec3::new(q.x, q.y - s + k, q.z - k).length()
}

/// Generalised distance: max of |p·n| (exponent 0) or the `e`-norm of the |p·n| minus the radius.
fn gdf_dodecahedron(p: DVec3, r: f64, e: f64) -> f64 {
    let dots = dodecahedron_normals().map(|n| p.dot(n).abs());
    if e == 0.0 {
        return dots.iter().fold(0.0f64, |a, &b| a.max(b)) - r;
    }
    // Scale by the largest term before the power so large |p| cannot overflow.
    let m = dots.iter().fold(0.0f64, |a, &b| a.max(b));
    if m == 0.0 {
        return -r;
    }
    m * dots
        .iter()
        .map(|d| (d / m).powf(e))
        .sum::<f64>()
        .powf(1.0 / e)
        - r
}

/// Most iterations a Mandelbulb may ask for (each evaluation loops this often).
pub const MANDELBULB_MAX_ITERATIONS: u32 = 64;

/// Mandelbulb distance estimate 0.5·ln r·r/dr; far outside (beyond twice the escape radius) the
/// distance to the escape sphere, which is a true bound where the estimator is not.
fn mandelbulb(p: DVec3, power: f64, iterations: u32) -> f64 {
    let escape = mandelbulb_radius(power);
    if p.length() > 2.0 * escape {
        return p.length() - escape;
    }
    let mut z = p;
    let mut dr = 1.0;
    let mut r = z.length();
    for _ in 0..iterations {
        // (r is |z|: set before the loop and at the end of each iteration.)
        if r > 2.0 {
            break;
        }
        // θ by atan2 rather than acos: lavapipe's acos is coarse, and both sides must agree.
        let theta = DVec2::new(z.x, z.y).length().atan2(z.z) * power;
        let phi = z.y.atan2(z.x) * power;
        dr = r.powf(power - 1.0) * power * dr + 1.0;
        let zr = r.powf(power);
        z =
            zr * DVec3::new(
                theta.sin() * phi.cos(),
                phi.sin() * theta.sin(),
                theta.cos(),
            ) + p;
        r = z.length();
    }
    let r = r.max(1e-20);
    0.5 * r.ln() * r / dr
}
