//! Bend and twist: the deformations, the Jacobian bound that normalises them, and the projection
//! onto the bounding cylinder that keeps the result a bound outside it.

use super::{ChildEval, Ctx};
use glam::DVec3;

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

pub(super) fn warp_lambda(c: &Ctx) -> f64 {
    if c.child_bound[0].radius.is_finite() {
        1.0
    } else {
        f64::INFINITY
    }
}
