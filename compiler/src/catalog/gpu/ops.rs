//! Operator lowering in naga IR, inline in `map`, mirroring each catalog entry's f64 evaluation
//! in `catalog/operators.rs`; the smooth blends call small `op_*` helper functions.

use super::args as params;
use super::{ChildLower, norm, scale_by};
use crate::catalog::Ctx;
use crate::catalog::geometry::FALLOFF_SLOPE;
use crate::ir::{Ex, FnBuilder};

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
    (x, y, blend(b, x, y, k))
}

/// The blend term h²k/4 of IQ's quadratic smooth minimum of `x` and `y` with radius `k`, as the
/// `op_smooth_*` helpers compute it (the data form's evaluator too: `lower/data.rs`).
pub(crate) fn blend(b: &mut FnBuilder, x: Ex, y: Ex, k: Ex) -> Ex {
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
    b.mul(hhk, quarter)
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
