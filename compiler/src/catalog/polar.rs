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

use super::repeat::{PolarPlan, polar_extent as extent, polar_plan as plan};
use super::traits::{PLAIN, Traits};
use super::{Arity, Bound, ChildEval, Ctx, MatRule, NO_SWAP, Operator, Ty, req};
use glam::{DVec2, DVec3};

/// Most copies `repeat_polar` may make.
pub const MAX_POLAR_COPIES: u32 = 4096;

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

/// The catalog entry.
pub const REPEAT_POLAR: Operator = Operator {
    name: "repeat_polar",
    fixed_args: true,
    traits: Traits {
        copies: Some(super::repeat::POLAR_COPIES),
        ..PLAIN
    },
    materials: MatRule::Pass,
    unit_gradient: |_| true,
    keeps_exact: |_| true,
    lower: super::gpu::polar::repeat_polar,
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
