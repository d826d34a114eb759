//! The operators' material rules in IR: which child's tag a sharp operator picks
//! (`catalog::MatRule::pick`) and how a smooth one blends two (`crate::reference::blend::pick`).

use crate::catalog::MatRule;
use crate::ir::builder::{Ex, FnBuilder};

/// The material rule of `catalog::MatRule::pick`, in IR.
pub(super) fn pick_material(
    b: &mut FnBuilder,
    rule: MatRule,
    ctx: &crate::catalog::Ctx,
    seen: &[(Ex, Option<Ex>)],
    zero: &dyn Fn(&mut FnBuilder) -> Ex,
) -> Option<Ex> {
    if seen.iter().all(|(_, m)| m.is_none()) {
        return None;
    }
    let mat = |b: &mut FnBuilder, i: usize| seen[i].1.unwrap_or_else(|| zero(b));
    let rule = rule.sharp();
    match rule {
        MatRule::Pass => seen[0].1,
        MatRule::Weighted if crate::catalog::gpu::args::varies(ctx, 0) => {
            let w = crate::catalog::gpu::args::num(b, ctx, 0, seen[0].0);
            let half = b.f(0.5);
            let second = b.gt(w, half);
            let (first, other) = (mat(b, 0), mat(b, 1));
            Some(b.select(second, other, first))
        }
        MatRule::Weighted => Some(mat(b, usize::from(ctx.num(0) > 0.5))),
        MatRule::Nearest | MatRule::Farthest | MatRule::Cut => {
            let sign = if rule == MatRule::Cut { -1.0 } else { 1.0 };
            let mut d = crate::catalog::gpu::scale_by(b, seen[0].0, 1.0 / ctx.child_lambda[0]);
            let mut m = mat(b, 0);
            for (i, &(di, _)) in seen.iter().enumerate().skip(1) {
                let di = crate::catalog::gpu::scale_by(b, di, sign / ctx.child_lambda[i]);
                let better = if rule == MatRule::Nearest {
                    b.lt(di, d)
                } else {
                    b.gt(di, d)
                };
                let mi = mat(b, i);
                m = b.select(better, mi, m);
                d = b.select(better, di, d);
            }
            Some(m)
        }
        _ => unreachable!("sharp rules only"),
    }
}

/// Looseness (1 or 0) of an operator's result in IR, as [`MatRule::pick_loose`] computes it:
/// at an intersection or a cut, 1 where some loose operand is positive (a cut's later ones
/// negated) or every operand is loose; elsewhere as the materials pick.
pub(super) fn pick_loose(
    b: &mut FnBuilder,
    rule: MatRule,
    ctx: &crate::catalog::Ctx,
    seen: &[(Ex, Option<Ex>)],
    zero: &dyn Fn(&mut FnBuilder) -> Ex,
) -> Option<Ex> {
    let sharp = rule.sharp();
    if !matches!(sharp, MatRule::Farthest | MatRule::Cut) {
        return pick_material(b, rule, ctx, seen, zero);
    }
    if seen.iter().all(|(_, m)| m.is_none()) {
        return None;
    }
    // (A child statically not loose adds nothing to `any` and makes `all` false.)
    let every = seen.iter().all(|(_, m)| m.is_some());
    let (mut any, mut all) = (None, None);
    for (i, &(d, m)) in seen.iter().enumerate() {
        let Some(m) = m else { continue };
        let z = b.u(0);
        let loose = b.bin(naga::BinaryOperator::NotEqual, m, z);
        let zero_f = b.f(0.0);
        let outside = if sharp == MatRule::Cut && i > 0 {
            b.lt(d, zero_f)
        } else {
            b.gt(d, zero_f)
        };
        let here = b.bin(naga::BinaryOperator::LogicalAnd, loose, outside);
        any = Some(match any {
            None => here,
            Some(a) => b.bin(naga::BinaryOperator::LogicalOr, a, here),
        });
        if every {
            all = Some(match all {
                None => loose,
                Some(a) => b.bin(naga::BinaryOperator::LogicalAnd, a, loose),
            });
        }
    }
    let any = any.expect("a loose child");
    let either = match all {
        Some(all) => b.bin(naga::BinaryOperator::LogicalOr, any, all),
        None => any,
    };
    let (one, none) = (b.u(1), b.u(0));
    Some(b.select(either, one, none))
}

/// The blend of a blending operator's children in IR, as `crate::reference::blend::pick` computes it.
pub(super) fn pick_blend(
    b: &mut FnBuilder,
    rule: MatRule,
    ctx: &crate::catalog::Ctx,
    seen: &[(Ex, Option<Ex>)],
) -> Option<Ex> {
    if seen.iter().all(|(_, m)| m.is_none()) {
        return None;
    }
    let tag = |b: &mut FnBuilder, i: usize| match seen[i].1 {
        None => b.f(0.0),
        Some(v) => dominant(b, v),
    };
    let v3 = b.m.vec3();
    if rule == MatRule::Weighted {
        let (a, c) = (tag(b, 0), tag(b, 1));
        let w = crate::catalog::gpu::args::num(b, ctx, 0, seen[0].0);
        return Some(b.compose(v3, vec![a, c, w]));
    }
    let k = Radius::of(b, ctx, seen[0].0);
    let mut d = crate::catalog::gpu::scale_by(b, seen[0].0, 1.0 / ctx.child_lambda[0]);
    let mut blend = seen[0].1.unwrap_or_else(|| b.splat3(0.0));
    for (i, &(di, _)) in seen.iter().enumerate().skip(1) {
        let di = crate::catalog::gpu::scale_by(b, di, 1.0 / ctx.child_lambda[i]);
        // smax(a, b) = −smin(−a, −b); the cut is smax(d, −dᵢ).
        let (x, y) = match rule {
            MatRule::SmoothNearest => (d, di),
            MatRule::SmoothFarthest => (b.neg(d), b.neg(di)),
            _ => (b.neg(d), di),
        };
        let second = |b: &mut FnBuilder| tag(b, i);
        let whole = |b: &mut FnBuilder| seen[i].1.unwrap_or_else(|| b.splat3(0.0));
        blend = blend_step(b, (x, y), k, blend, (second, whole));
        let m = smin(b, x, y, k);
        d = match rule {
            MatRule::SmoothNearest => m,
            _ => b.neg(m),
        };
    }
    Some(blend)
}

/// The dominant material of a blend vec3(first, second, weight): the first up to weight ½
/// (`crate::reference::blend::Blend::dominant`).
pub(super) fn dominant(b: &mut FnBuilder, v: Ex) -> Ex {
    let [x, y, t] = b.xyz(v);
    let half = b.f(0.5);
    let first = b.bin(naga::BinaryOperator::LessEqual, t, half);
    b.select(first, x, y)
}

/// One step of `crate::reference::blend::pick`: the running blend `blend` of a fold whose
/// running value is `x`, after a child of value `y` (both already negated as the rule says)
/// with dominant material `second` and whole blend `whole` (made when needed): outside the
/// seam (|x − y| ≥ k) one side whole, blend included; in it, the two dominants and IQ's mix
/// factor. Shared by the inline walk and the data form's `tape_blend`.
pub(super) fn blend_step(
    b: &mut FnBuilder,
    (x, y): (Ex, Ex),
    k: Radius,
    blend: Ex,
    (second, whole): (
        impl FnOnce(&mut FnBuilder) -> Ex,
        impl FnOnce(&mut FnBuilder) -> Ex,
    ),
) -> Ex {
    let v3 = b.m.vec3();
    let t = smin_weight(b, x, y, k);
    let first = dominant(b, blend);
    let second = second(b);
    let mixed = b.compose(v3, vec![first, second, t]);
    let whole = whole(b);
    let gap = b.sub(x, y);
    let gap = b.abs(gap);
    let outside = b.ge(gap, k.ex);
    let first_side = b.bin(naga::BinaryOperator::LessEqual, x, y);
    let side = b.select(first_side, blend, whole);
    b.select(outside, side, mixed)
}

/// A smooth operator's radius: its value if fixed, and the expression (a parameter's may be
/// 0 at run time: divisions by it use max(k, 1e-30), which gives the sharp result there).
#[derive(Clone, Copy)]
pub(super) struct Radius {
    ex: Ex,
    fixed: Option<f64>,
}

impl Radius {
    /// A radius known only at run time (read from a buffer).
    pub(super) fn at_run_time(ex: Ex) -> Radius {
        Radius { ex, fixed: None }
    }

    fn of(b: &mut FnBuilder, ctx: &crate::catalog::Ctx, any: Ex) -> Radius {
        if crate::catalog::gpu::args::varies(ctx, 0) {
            Radius {
                ex: crate::catalog::gpu::args::num(b, ctx, 0, any),
                fixed: None,
            }
        } else {
            let k = ctx.num(0);
            Radius {
                ex: b.f(k),
                fixed: Some(k),
            }
        }
    }

    /// Whether it is a fixed 0 (or less): the sharp operator.
    fn sharp(self) -> bool {
        self.fixed.is_some_and(|k| k <= 0.0)
    }

    /// The divisor: k, or max(k, 1e-30) at run time.
    fn divisor(self, b: &mut FnBuilder) -> Ex {
        match self.fixed {
            Some(_) => self.ex,
            None => {
                let tiny = b.f(1e-30);
                b.max(self.ex, tiny)
            }
        }
    }
}

/// IQ's quadratic smooth minimum of radius `k` (`catalog::operators::smin`).
fn smin(b: &mut FnBuilder, x: Ex, y: Ex, k: Radius) -> Ex {
    let low = b.min(x, y);
    if k.sharp() {
        return low;
    }
    let h = smin_h(b, x, y, k);
    let hh = b.mul(h, h);
    let kq = match k.fixed {
        Some(k) => b.f(k * 0.25),
        None => {
            let quarter = b.f(0.25);
            b.mul(k.ex, quarter)
        }
    };
    let dent = b.mul(hh, kq);
    b.sub(low, dent)
}

/// max(k − |x − y|, 0)/k.
fn smin_h(b: &mut FnBuilder, x: Ex, y: Ex, k: Radius) -> Ex {
    let diff = b.sub(x, y);
    let diff = b.abs(diff);
    let h = b.sub(k.ex, diff);
    let zero = b.f(0.0);
    let h = b.max(h, zero);
    let kk = k.divisor(b);
    b.div(h, kk)
}

/// The weight of `y` in the smooth minimum of `x` and `y` (`crate::reference::blend::smin_weight`).
fn smin_weight(b: &mut FnBuilder, x: Ex, y: Ex, k: Radius) -> Ex {
    let first = b.bin(naga::BinaryOperator::LessEqual, x, y);
    if k.sharp() {
        let (zero, one) = (b.f(0.0), b.f(1.0));
        return b.select(first, zero, one);
    }
    let h = smin_h(b, x, y, k);
    let half = b.f(0.5);
    let hh = b.mul(h, h);
    let m = b.mul(half, hh);
    let one = b.f(1.0);
    let rest = b.sub(one, m);
    b.select(first, m, rest)
}
