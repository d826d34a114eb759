//! The IR of the operators of space (`catalog/domain.rs`): moves, turns, scales, `repeat` and
//! `mirror` (the warps are in `warp.rs`), each mirroring its f64 evaluation.

use super::args as params;
use super::warp::turn;
use super::{ChildLower, scale_by};
use crate::catalog::Ctx;
use crate::catalog::geometry::rotate as rotate_point;
use crate::catalog::repeat::{AxisPlan, Plan};
use crate::ir::{Ex, FnBuilder};
use glam::DVec3;
use naga::{MathFunction as M, VectorSize};

/// f(p − offset)
pub fn translate(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let o = params::vec3(b, c, 0, p);
    let q = b.sub(p, o);
    child(b, 0, q)
}

/// f(R⁻¹p) with R⁻¹ folded into a constant matrix.
pub fn rotate(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    if params::varies(c, 0) || params::varies(c, 1) {
        // Rodrigues' formula at run time: q = p·cos θ + (k × p)·sin θ + k(k·p)(1 − cos θ),
        // θ = −angle.
        let angle = params::num(b, c, 1, p);
        let theta = b.neg(angle);
        let (s, co) = (b.math(M::Sin, &[theta]), b.math(M::Cos, &[theta]));
        // About a fixed coordinate axis: a turn in the plane across it, as written by hand.
        let axis = c.vec(0);
        if let Some(a) = (0..3)
            .filter(|_| !params::varies(c, 0))
            .find(|&a| axis[a].abs() == 1.0 && (0..3).all(|j| j == a || axis[j] == 0.0))
        {
            let s = if axis[a] < 0.0 { b.neg(s) } else { s };
            let q = turn(b, p, [(a + 1) % 3, (a + 2) % 3], (s, co));
            return child(b, 0, q);
        }
        let k = params::vec3(b, c, 0, p);
        let a = b.mul(p, co);
        let cross = b.math(M::Cross, &[k, p]);
        let cross = b.mul(cross, s);
        let kp = b.dot(k, p);
        let one = b.f(1.0);
        let rest = b.sub(one, co);
        let along = b.mul(kp, rest);
        let along = b.mul(k, along);
        let q = b.add(a, cross);
        let q = b.add(q, along);
        return child(b, 0, q);
    }
    let (axis, angle) = (c.vec(0), c.num(1));
    let cols = [DVec3::X, DVec3::Y, DVec3::Z].map(|e| rotate_point(e, axis, -angle));
    let q = linear(b, cols, p);
    child(b, 0, q)
}

/// M·p for a constant matrix given by its columns, written as a person would: entries within
/// 1e-12 of 0 or ±1 (the cosines of right angles) dropped or taken as ±p, so a turn about a
/// coordinate axis costs four products and two sums and a right-angle turn only a swizzle; a
/// dense matrix (a turn about another axis) is one matrix product.
pub fn linear(b: &mut FnBuilder, cols: [DVec3; 3], p: Ex) -> Ex {
    let snap = |v: f64| {
        if v.abs() < 1e-12 {
            0.0
        } else if (v.abs() - 1.0).abs() < 1e-12 {
            v.signum()
        } else {
            v
        }
    };
    let m = cols.map(|c| c.to_array().map(snap));
    let nonzero = m.iter().flatten().filter(|v| **v != 0.0).count();
    if nonzero > 6 {
        let cols: Vec<Ex> = cols.iter().map(|v| b.vec3_lit(*v)).collect();
        let ty = b.m.ty(naga::TypeInner::Matrix {
            columns: VectorSize::Tri,
            rows: VectorSize::Tri,
            scalar: naga::Scalar::F32,
        });
        let mat = b.compose(ty, cols);
        return b.mul(mat, p);
    }
    let coords = b.xyz(p);
    let rows = [0, 1, 2].map(|i| {
        let mut sum: Option<Ex> = None;
        // Positive terms first, so that a negative one is a subtraction, not a negation.
        let mut order = [0, 1, 2];
        order.sort_by_key(|&j| m[j][i] < 0.0);
        for j in order {
            let (v, pj) = (m[j][i], coords[j]);
            if v == 0.0 {
                continue;
            }
            let term = if v.abs() == 1.0 {
                pj
            } else {
                let k = b.f(v.abs());
                b.mul(k, pj)
            };
            sum = Some(match (sum, v < 0.0) {
                (None, false) => term,
                (None, true) => b.neg(term),
                (Some(s), false) => b.add(s, term),
                (Some(s), true) => b.sub(s, term),
            });
        }
        sum.unwrap_or_else(|| b.f(0.0))
    });
    b.compose_vec3(rows)
}

/// f(p / s)·min(s)
pub fn scale(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    if params::varies(c, 0) {
        let s = params::vec3(b, c, 0, p);
        let q = b.div(p, s);
        let d = child(b, 0, q);
        let [x, y, z] = b.xyz(s);
        let m = b.min(x, y);
        let m = b.min(m, z);
        return b.mul(d, m);
    }
    let s = c.vec(0);
    let inv = b.vec3_lit(DVec3::ONE / s);
    let q = b.mul(p, inv);
    let d = child(b, 0, q);
    scale_by(b, d, s.min_element())
}

/// The repeated field as `catalog::repeat::field`: per axis the own cell, every copy, or the
/// window of copies from K₋ on, unrolled; the smallest of them.
pub fn repeat(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let plan = Plan::new(c);
    let comps = b.xyz(p);
    let mut coords: [Vec<Ex>; 3] = Default::default();
    for (i, &x) in comps.iter().enumerate() {
        let (s, half) = (plan.spacing[i], plan.half(i));
        match plan.axes[i] {
            AxisPlan::Plain => coords[i].push(x),
            AxisPlan::Own => {
                let inv = b.f(1.0 / s);
                let at = b.mul(x, inv);
                let at = shift(b, at, half);
                let k = b.round_half_up(at, None);
                let k = clamp_copy(b, &plan, i, k);
                let c = center(b, &plan, i, k);
                coords[i].push(b.sub(x, c));
            }
            AxisPlan::All => {
                for k in 0..plan.count[i] as u32 {
                    let c = b.f(plan.center(i, f64::from(k)));
                    coords[i].push(b.sub(x, c));
                }
            }
            AxisPlan::Window(n) => {
                // K₋ = ⌊(x − hi)/s + half⌋
                let hi = b.f(plan.hi[i]);
                let from = b.sub(x, hi);
                let inv = b.f(1.0 / s);
                let at = b.mul(from, inv);
                let at = shift(b, at, half);
                let first = b.math(naga::MathFunction::Floor, &[at]);
                for j in 0..n {
                    let k = shift(b, first, f64::from(j));
                    let k = clamp_copy(b, &plan, i, k);
                    let c = center(b, &plan, i, k);
                    coords[i].push(b.sub(x, c));
                }
            }
        }
    }
    let mut d: Option<Ex> = None;
    for &x in &coords[0] {
        for &y in &coords[1] {
            for &z in &coords[2] {
                let q = b.compose_vec3([x, y, z]);
                let di = child(b, 0, q);
                d = Some(match d {
                    Some(a) => b.min(a, di),
                    None => di,
                });
            }
        }
    }
    d.expect("one copy at least")
}

/// x + k, skipped when k = 0.
fn shift(b: &mut FnBuilder, x: Ex, k: f64) -> Ex {
    if k == 0.0 {
        return x;
    }
    let k = b.f(k);
    b.add(x, k)
}

/// Copy index `k` clamped to the existing copies, as `Plan::clamp`.
fn clamp_copy(b: &mut FnBuilder, plan: &Plan, i: usize, k: Ex) -> Ex {
    let n = plan.count[i];
    if n == 0.0 {
        return k;
    }
    let (lo, hi) = (b.f(0.0), b.f(n - 1.0));
    b.clamp(k, lo, hi)
}

/// The centre of copy `k` along axis `i`, as `Plan::center`: k·s − half·s.
fn center(b: &mut FnBuilder, plan: &Plan, i: usize, k: Ex) -> Ex {
    let s = plan.spacing[i];
    let sv = b.f(s);
    let at = b.mul(k, sv);
    shift(b, at, -plan.half(i) * s)
}

/// p − 2·min(p·n, 0)·n
pub fn mirror(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let normal = c.vec(0);
    let fixed = !params::varies(c, 0);
    // Across a coordinate plane: that coordinate's absolute value (or its negation).
    if let Some(k) = (0..3)
        .filter(|_| fixed)
        .find(|&k| normal[k].abs() == 1.0 && (0..3).all(|j| j == k || normal[j].abs() < 1e-12))
    {
        let mut coords = b.xyz(p);
        let a = b.abs(coords[k]);
        coords[k] = if normal[k] > 0.0 { a } else { b.neg(a) };
        let q = b.compose_vec3(coords);
        return child(b, 0, q);
    }
    let n = params::vec3(b, c, 0, p);
    let d = b.dot(p, n);
    let zero = b.f(0.0);
    let d = b.min(d, zero);
    let two = b.f(2.0);
    let d = b.mul(two, d);
    let off = b.mul(n, d);
    let q = b.sub(p, off);
    child(b, 0, q)
}
