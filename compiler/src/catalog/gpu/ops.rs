//! Operator lowering in naga IR, inline in `map`, mirroring each catalog entry's f64 evaluation
//! in `catalog/operators.rs`; the smooth blends call small `op_*` helper functions.

use super::args as params;
use super::warp::turn;
use super::{ChildLower, norm, scale_by};
use crate::catalog::Ctx;
use crate::catalog::geometry::{FALLOFF_SLOPE, rotate as rotate_point};
use crate::catalog::repeat::{AxisPlan, Plan};
use crate::ir::{Ex, FnBuilder};
use glam::DVec3;
use naga::{MathFunction as M, VectorSize};

fn fold(
    b: &mut FnBuilder,
    c: &Ctx,
    p: Ex,
    child: ChildLower,
    f: &dyn Fn(&mut FnBuilder, Ex, Ex) -> Ex,
) -> Ex {
    let n = c.child_lambda.len();
    let mut acc = norm(b, c, child, 0, p);
    for i in 1..n {
        let d = norm(b, c, child, i, p);
        acc = f(b, acc, d);
        // Text targets inline a value used once at its use: name the running result so that
        // a long chain reads `let d_1 = min(d, next)` part after part, as written by hand,
        // not one nested expression after every part (the IR's order is the same either way).
        if n > 2 && i + 1 < n {
            b.name(acc, "d");
        }
    }
    acc
}

/// min of the normalised children; with a bounding-volume tree, see [`super::prune`].
pub fn union(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    match &c.prune {
        Some(tree) => super::prune::union(b, c, p, child, tree),
        None => fold(b, c, p, child, &|b, x, y| b.min(x, y)),
    }
}

/// max of the normalised children.
pub fn intersect(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    fold(b, c, p, child, &|b, x, y| b.max(x, y))
}

/// max(a, −b, −c, ...)
pub fn subtract(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    fold(b, c, p, child, &|b, x, y| {
        let ny = b.neg(y);
        b.max(x, ny)
    })
}

/// −f
pub fn complement(b: &mut FnBuilder, _: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let d = child(b, 0, p);
    b.neg(d)
}

fn smooth(
    b: &mut FnBuilder,
    c: &Ctx,
    p: Ex,
    child: ChildLower,
    helper: &'static str,
    negate: bool,
) -> Ex {
    let f = b.m.helper(helper);
    let k = params::num(b, c, 0, p);
    fold(b, c, p, child, &|b, x, y| {
        let y = if negate { b.neg(y) } else { y };
        b.call(f, vec![x, y, k])
    })
}

/// Folds `op_smooth_union(a, b, k)`.
pub fn smooth_union(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    smooth(b, c, p, child, "op_smooth_union", false)
}

/// Folds `op_smooth_intersect(a, b, k)`.
pub fn smooth_intersect(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    smooth(b, c, p, child, "op_smooth_intersect", false)
}

/// Folds `op_smooth_intersect(a, −b, k)`.
pub fn smooth_subtract(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    smooth(b, c, p, child, "op_smooth_intersect", true)
}

/// The blend term h²k/4 of IQ's quadratic smooth minimum, h = max(k − |a − b|, 0)/k, of the
/// helper's three arguments; with them.
fn blend_term(b: &mut FnBuilder) -> (Ex, Ex, Ex) {
    let (x, y, k) = (b.arg(0), b.arg(1), b.arg(2));
    let diff = b.sub(x, y);
    let diff = b.abs(diff);
    let kd = b.sub(k, diff);
    let zero = b.f(0.0);
    let kd = b.max(kd, zero);
    // (k = 0 is a sharp min: kd is 0 there, and 0/max(k, tiny) is 0, not NaN.)
    let tiny = b.f(1e-30);
    let kk = b.max(k, tiny);
    let h = b.div(kd, kk);
    let hh = b.mul(h, h);
    let hhk = b.mul(hh, k);
    let quarter = b.f(0.25);
    (x, y, b.mul(hhk, quarter))
}

/// Body of `op_smooth_union(a, b, k)`: min(a, b) − h²k/4.
pub fn smooth_min_body(b: &mut FnBuilder) -> Ex {
    let (x, y, dip) = blend_term(b);
    let m = b.min(x, y);
    b.sub(m, dip)
}

/// Body of `op_smooth_intersect(a, b, k)`: −smin(−a, −b, k) = max(a, b) + h²k/4.
pub fn smooth_max_body(b: &mut FnBuilder) -> Ex {
    let (x, y, bump) = blend_term(b);
    let m = b.max(x, y);
    b.add(m, bump)
}

/// (1 − w)·a + w·b
pub fn mix(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    if params::varies(c, 0) {
        let w = params::num(b, c, 0, p);
        let one = b.f(1.0);
        let rest = b.sub(one, w);
        let a = child(b, 0, p);
        let a = b.mul(a, rest);
        let d = child(b, 1, p);
        let d = b.mul(d, w);
        return b.add(a, d);
    }
    let w = c.num(0);
    let a = child(b, 0, p);
    let a = scale_by(b, a, 1.0 - w);
    let d = child(b, 1, p);
    let d = scale_by(b, d, w);
    b.add(a, d)
}

/// Blob field: threshold − Σ falloff, over its slope bound, or the influence zone's distance.
pub fn blob(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let (radius, threshold) = (c.num(0), c.num(1));
    let run_time = params::varies(c, 0);
    let r_ex = params::num(b, c, 0, p);
    let inv_r = if run_time {
        let one = b.f(1.0);
        Some(b.div(one, r_ex))
    } else {
        None
    };
    let n = c.child_lambda.len();
    let mut field = None;
    let mut nearest = None;
    for i in 0..n {
        let d = norm(b, c, child, i, p);
        let zero = b.f(0.0);
        let dp = b.max(d, zero);
        let s = match inv_r {
            Some(inv) => b.mul(dp, inv),
            None => scale_by(b, dp, 1.0 / radius),
        };
        // (1 − s²)³ clamped at 0
        let s2 = b.mul(s, s);
        let one = b.f(1.0);
        let t = b.sub(one, s2);
        let t = b.max(t, zero);
        let t2 = b.mul(t, t);
        let g = b.mul(t2, t);
        field = Some(match field {
            Some(f) => b.add(f, g),
            None => g,
        });
        nearest = Some(match nearest {
            Some(m) => b.min(m, d),
            None => d,
        });
    }
    let (field, nearest) = (field.expect("a child"), nearest.expect("a child"));
    let _ = threshold;
    let th = params::num(b, c, 1, p);
    let v = b.sub(th, field);
    let v = if run_time {
        let k = b.f(1.0 / (n as f64 * FALLOFF_SLOPE));
        let k = b.mul(r_ex, k);
        b.mul(v, k)
    } else {
        scale_by(b, v, radius / (n as f64 * FALLOFF_SLOPE))
    };
    let outside = b.sub(nearest, r_ex);
    b.max(v, outside)
}

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

/// f/λ − r
pub fn round(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let d = norm(b, c, child, 0, p);
    let r = params::num(b, c, 0, p);
    b.sub(d, r)
}

/// |f/λ| − t
pub fn onion(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let d = norm(b, c, child, 0, p);
    let d = b.abs(d);
    let t = params::num(b, c, 0, p);
    b.sub(d, t)
}

/// f(p − clamp(p, −h, h))
pub fn elongate(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower) -> Ex {
    let (hi, lo) = if params::varies(c, 0) {
        let amount = params::vec3(b, c, 0, p);
        let half = b.f(0.5);
        let hi = b.mul(amount, half);
        (hi, b.neg(hi))
    } else {
        let h = c.vec(0) / 2.0;
        (b.vec3_lit(h), b.vec3_lit(-h))
    };
    let cl = b.clamp(p, lo, hi);
    let q = b.sub(p, cl);
    child(b, 0, q)
}
