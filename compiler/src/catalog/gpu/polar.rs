//! `repeat_polar` in IR: the angle, then each copy's point turned back (the plan is
//! `polar_plan` in `catalog/repeat.rs`, its proof the catalog entry's, `catalog/polar.rs`).

use super::ChildLower;
use crate::catalog::Ctx;
use crate::catalog::repeat::{PolarPlan, polar_extent as extent, polar_plan as plan};
use crate::ir::{Ex, FnBuilder};
use naga::MathFunction;

/// The shader's field, as [`crate::catalog::polar::field`]: the angle, then each copy's point turned back.
pub fn repeat_polar(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
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
