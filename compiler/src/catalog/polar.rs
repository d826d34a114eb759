//! `repeat_polar(n)`: n copies of a shape turned about the y axis, copy k by k·2π/n (from +x
//! towards +z), evaluated as `repeat` is — the own sector where that is exact, else a window
//! of the copies that can be nearest — so the field is the union of every copy.
//!
//! With α = 2π/n and the shape's angular extent [lo, hi] about the y axis (from its bound, in
//! the frame of copy 0), the argument of `catalog::repeat` carries over to turns: for a point
//! at angle θ, K₋ = ⌊(θ − hi)/α⌋ is the last copy whose extent ends at or before θ and K₊ =
//! ⌈(θ − lo)/α⌉ the first that starts at or after it. The point of copy K₊ that corresponds to
//! a point q of a copy beyond it is q turned back towards θ, still on the far side of θ, so
//! its angular distance to the point is smaller and, at the same radius and height, so is its
//! distance (likewise below K₋). Hence the window K₋..K₊ — at most ⌊(hi − lo)/α⌋ + 3 copies —
//! holds the nearest copy. When the shape lies inside its sector (−α/2 ≤ lo, hi ≤ α/2) and is
//! symmetric about the sector's middle (z → −z), each neighbour is the mirror image of the own
//! copy across the plane between them: the own copy alone is exact (Inigo Quilez's and
//! hg_sdf's folding, with its condition). A shape around the axis has no angular extent: all
//! copies are evaluated. Turns keep distances, so λ is the shape's.

use super::{Arity, Bound, ChildEval, Ctx, MatRule, NO_SWAP, Operator, Ty, req};
use crate::lower::builder::{Ex, FnBuilder};
use crate::lower::ops::ChildLower;
use glam::{DVec2, DVec3};
use naga::MathFunction;
use std::f64::consts::{PI, TAU};

/// Most copies `repeat_polar` may make.
pub const MAX_POLAR_COPIES: u32 = 4096;

/// How a `repeat_polar` node is evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PolarPlan {
    /// The own sector only.
    Own,
    /// Every copy.
    All,
    /// This many copies from K₋ on.
    Window(u32),
}

/// The angle between copies and the plan for a node.
pub fn plan(c: &Ctx) -> (f64, PolarPlan) {
    let n = c.num(0).max(1.0);
    let alpha = TAU / n;
    let Some((lo, hi)) = extent(c.child_bound[0]) else {
        return (alpha, PolarPlan::All);
    };
    if c.child_mirror[0][2] && lo >= -alpha / 2.0 && hi <= alpha / 2.0 {
        return (alpha, PolarPlan::Own);
    }
    let window = ((hi - lo) / alpha).floor() + 3.0;
    if n <= window {
        (alpha, PolarPlan::All)
    } else {
        (alpha, PolarPlan::Window(window as u32))
    }
}

/// How many copies one evaluation looks at.
pub fn copies(c: &Ctx) -> f64 {
    match plan(c).1 {
        PolarPlan::Own => 1.0,
        PolarPlan::All => c.num(0),
        PolarPlan::Window(w) => f64::from(w),
    }
}

/// The angles about the y axis (from +x towards +z) the bound spans, if it keeps away from
/// the axis: the tighter of its box's corners and its sphere's cone.
pub fn extent(b: Bound) -> Option<(f64, f64)> {
    if !b.is_finite() {
        return None;
    }
    let mut best: Option<(f64, f64)> = None;
    let mut narrow = |lo: f64, hi: f64| {
        best = Some(match best {
            Some((a, b)) => (a.max(lo), b.min(hi)),
            None => (lo, hi),
        });
    };
    // The rectangle of the box in xz, when the axis is outside it.
    let (x0, x1, z0, z1) = (b.lo.x, b.hi.x, b.lo.z, b.hi.z);
    if x0 > 0.0 || x1 < 0.0 || z0 > 0.0 || z1 < 0.0 {
        let centre = DVec2::new((x0 + x1) / 2.0, (z0 + z1) / 2.0);
        let mid = centre.y.atan2(centre.x);
        let rel = [(x0, z0), (x0, z1), (x1, z0), (x1, z1)].map(|(x, z)| wrap(z.atan2(x) - mid));
        let lo = rel.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = rel.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        narrow(mid + lo, mid + hi);
    }
    // The cone of the sphere seen from the axis, when the axis is outside it.
    let r = DVec2::new(b.center.x, b.center.z).length();
    if r > b.radius {
        let mid = b.center.z.atan2(b.center.x);
        let half = (b.radius / r).asin();
        narrow(mid - half, mid + half);
    }
    // The two descriptions of the same region overlap: their intersection is the extent (it
    // may straddle ±π, the copies' angles are taken modulo a turn).
    best.filter(|(lo, hi)| lo <= hi)
}

/// An angle moved into (−π, π].
fn wrap(a: f64) -> f64 {
    let w = a - TAU * ((a + PI) / TAU).floor();
    if w <= -PI { w + TAU } else { w }
}

/// `p` turned by −φ about y (the point in the frame of a copy turned by φ).
fn unturn(p: DVec3, phi: f64) -> DVec3 {
    let (s, c) = phi.sin_cos();
    DVec3::new(p.x * c + p.z * s, p.y, -p.x * s + p.z * c)
}

/// The copies' indices one evaluation at angle `theta` looks at.
fn indices(c: &Ctx, theta: f64) -> Vec<f64> {
    let (alpha, plan) = plan(c);
    match plan {
        PolarPlan::Own => vec![super::repeat::round_half_up(theta / alpha)],
        PolarPlan::All => (0..c.num(0) as u32).map(f64::from).collect(),
        PolarPlan::Window(w) => {
            let (_, hi) = extent(c.child_bound[0]).expect("a window has an extent");
            let first = ((theta - hi) / alpha).floor();
            (0..w).map(|j| first + f64::from(j)).collect()
        }
    }
}

/// The field at `p`: the smallest of the copies the plan looks at (the child's λ).
pub fn field(c: &Ctx, p: DVec3, child: ChildEval) -> f64 {
    let alpha = plan(c).0;
    indices(c, p.z.atan2(p.x))
        .into_iter()
        .map(|k| child(0, unturn(p, k * alpha)))
        .fold(f64::INFINITY, f64::min)
}

/// The bound of every copy: a ring about the y axis.
fn bound(c: &Ctx) -> Bound {
    let b = c.child_bound[0];
    if !b.is_finite() {
        return Bound::INFINITE;
    }
    let corners = [
        (b.lo.x, b.lo.z),
        (b.lo.x, b.hi.z),
        (b.hi.x, b.lo.z),
        (b.hi.x, b.hi.z),
    ];
    let reach = corners
        .iter()
        .map(|&(x, z)| DVec2::new(x, z).length())
        .fold(0.0, f64::max);
    let r = DVec2::new(b.center.x, b.center.z).length() + b.radius;
    let ring = reach.min(r);
    let centre = DVec3::new(0.0, b.center.y, 0.0);
    Bound::sphere(centre, r).with_box(
        DVec3::new(-ring, b.lo.y, -ring),
        DVec3::new(ring, b.hi.y, ring),
    )
}

/// The shader's field, as [`field`]: the angle, then each copy's point turned back.
pub fn lower(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let (alpha, plan) = plan(c);
    let [x, y, z] = b.xyz(p);
    // The point turned by −φ, given sin φ and cos φ (as `unturn`).
    let unturned = |b: &mut FnBuilder, s: Ex, co: Ex| {
        let (xc, zs) = (b.mul(x, co), b.mul(z, s));
        let (xs, zc) = (b.mul(x, s), b.mul(z, co));
        let u = b.add(xc, zs);
        let w = b.sub(zc, xs);
        b.compose_vec3([u, y, w])
    };
    let turned = |b: &mut FnBuilder, k: Ex, child: &mut ChildLower| {
        let a = b.f(alpha);
        let phi = b.mul(k, a);
        let (s, co) = (
            b.math(MathFunction::Sin, &[phi]),
            b.math(MathFunction::Cos, &[phi]),
        );
        let q = unturned(b, s, co);
        child(b, 0, q)
    };
    let mut child = child;
    let mut ds = Vec::new();
    match plan {
        PolarPlan::All => {
            for k in 0..c.num(0) as u32 {
                // Constant turns: sin and cos folded here.
                let (s, co) = (f64::from(k) * alpha).sin_cos();
                let (s, co) = (b.f(s), b.f(co));
                let q = unturned(b, s, co);
                ds.push(child(b, 0, q));
            }
        }
        PolarPlan::Own | PolarPlan::Window(_) => {
            let theta = b.math(MathFunction::Atan2, &[z, x]);
            let inv = b.f(1.0 / alpha);
            let ks = match plan {
                PolarPlan::Own => {
                    let at = b.mul(theta, inv);
                    vec![b.round_half_up(at, None)]
                }
                PolarPlan::Window(w) => {
                    let (_, hi) = extent(c.child_bound[0]).expect("a window has an extent");
                    let hi = b.f(hi);
                    let from = b.sub(theta, hi);
                    let at = b.mul(from, inv);
                    let first = b.math(MathFunction::Floor, &[at]);
                    (0..w)
                        .map(|j| {
                            if j == 0 {
                                first
                            } else {
                                let j = b.f(f64::from(j));
                                b.add(first, j)
                            }
                        })
                        .collect()
                }
                PolarPlan::All => unreachable!(),
            };
            for k in ks {
                ds.push(turned(b, k, &mut child));
            }
        }
    }
    let mut d = ds[0];
    for &e in &ds[1..] {
        d = b.min(d, e);
    }
    d
}

/// The catalog entry.
pub const REPEAT_POLAR: Operator = Operator {
    name: "repeat_polar",
    fixed_args: true,
    materials: MatRule::Pass,
    unit_gradient: |_| true,
    keeps_exact: |_| true,
    lower,
    doc: "`count` copies of its shape turned about the y axis, evenly (copy k by k·360°/count, \
          from +x towards +z); the own sector is evaluated where the shape fits it and is \
          symmetric about its middle, else the copies that can be nearest (λ unchanged).",
    params: &[req("count", Ty::CountTo(MAX_POLAR_COPIES))],
    arity: Arity::Exactly(1),
    lipschitz: |c| c.child_lambda[0],
    bound,
    swap: NO_SWAP,
    mirror: |c| [false, c.child_mirror[0][1], false],
    eval: field,
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_keeps_angles_in_a_half_turn() {
        for a in [-7.0, -PI, -1.0, 0.0, 1.0, PI, 4.0, 10.0] {
            let w = wrap(a);
            assert!(w > -PI && w <= PI, "{a} → {w}");
            assert!(((w - a) / TAU - ((w - a) / TAU).round()).abs() < 1e-12);
        }
    }

    #[test]
    fn extent_of_a_box_beside_the_axis() {
        let b = Bound::centered_box(DVec3::splat(0.5)).moved(DVec3::new(2.0, 0.0, 0.0));
        let (lo, hi) = extent(b).expect("away from the axis");
        assert!((hi - (0.5f64).atan2(1.5)).abs() < 1e-12, "{hi}");
        assert!((lo + hi).abs() < 1e-12);
        assert!(extent(Bound::origin(1.0)).is_none());
    }
}
