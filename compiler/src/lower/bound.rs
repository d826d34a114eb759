//! A convex bound in IR (Keinert §3.5): `trace_bounded` clips the ray to the declared volume,
//! culls rays that miss it, and traces rays starting inside a convex object backwards from the
//! volume's far side; step for step the same as `crate::reference::trace::bounded`.

use super::march::{EXHAUSTED, HIT, Inputs, is_hit};
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::scene::{AXIS_GUARD, BoundShape, Convex};
use naga::{BinaryOperator as B, Function, Handle, Type};

/// Adds `trace_bounded`, which takes the same inputs as the variant it calls and returns the
/// same `TraceResult` (with the anti-aliasing cover fields if `antialias`).
pub(super) fn add(
    mb: &mut ModuleBuilder,
    map: Handle<Function>,
    (result_ty, antialias): (Handle<Type>, bool),
    variant: Handle<Function>,
    inputs: Inputs,
    bound: &Convex,
) -> Handle<Function> {
    let out = Out {
        ty: result_ty,
        cover: antialias,
    };
    let args = inputs.arguments(mb);
    let u32t = mb.u32();
    let mut b = FnBuilder::new(mb, "trace_bounded", &args, Some(result_ty));
    let all: Vec<Ex> = (0..args.len() as u32).map(|i| b.arg(i)).collect();
    let (ro, rd) = (all[0], all[1]);
    let at = |name: &str| args.iter().position(|a| a.0 == name).map(|i| all[i]);
    let (start, end) = (at("start").expect("segment"), at("end").expect("segment"));
    let cone = at("cone");
    let (near, far, meets) = interval(&mut b, &bound.shape, ro, rd);
    let lo = b.max(near, start);
    let hi = b.min(far, end);
    let zero_u = b.u(0);
    let culled = out.make(&mut b, None, [start, zero_u, zero_u]);
    let result = b.local("result", result_ty, Some(culled));
    let inverted = b.gt(lo, hi);
    let misses = b.expr(naga::Expression::Unary {
        op: naga::UnaryOperator::LogicalNot,
        expr: meets,
    });
    let culled = b.bin(B::LogicalOr, misses, inverted);
    let forward = |b: &mut FnBuilder, extra: Ex| {
        let mut a = all.clone();
        let i = a.iter().position(|&x| x == start).expect("start");
        a[i] = lo;
        a[i + 1] = hi;
        let r = b.call(variant, a);
        let (t, s, f) = (b.at(r, 0), b.at(r, 1), b.at(r, 2));
        let s = b.add(s, extra);
        let v = out.make(b, Some((r, true)), [t, s, f]);
        b.store(result, v);
    };
    b.if_(
        culled,
        |_| {},
        |b| {
            if !bound.convex {
                let none = b.u(0);
                forward(b, none);
                return;
            }
            let (is_inside, extra) =
                starts_inside(b, map, (ro, rd), (near, start, lo), (zero_u, u32t));
            b.if_(
                is_inside,
                |b| backwards(b, (&all, variant, out), result, (start, lo, hi, cone)),
                |b| forward(b, extra),
            );
        },
    );
    let r = b.load(result);
    b.ret(Some(r));
    let f = b.finish();
    mb.add_function(f)
}

/// Keinert §3.5, case 3: whether the ray starts inside the object — `map` at the clipped
/// start `lo` is negative, tested only where the volume's `near` side is at or behind the ray's
/// `start` — and the evaluations that took (0 or 1), each loaded from a variable set to it.
fn starts_inside(
    b: &mut FnBuilder,
    map: Handle<Function>,
    (ro, rd): (Ex, Ex),
    (near, start, lo): (Ex, Ex, Ex),
    (zero_u, u32t): (Ex, Handle<Type>),
) -> (Ex, Ex) {
    let tested = b.local("tested", u32t, Some(zero_u));
    let bool_ty = b.m.bool();
    let no = b.boolean(false);
    let inside = b.local("inside", bool_ty, Some(no));
    let at_start = b.bin(B::LessEqual, near, start);
    b.if_(
        at_start,
        |b| {
            let s = b.mul(rd, lo);
            let p = b.add(ro, s);
            let d = b.call(map, vec![p]);
            let zero = b.f(0.0);
            let neg = b.lt(d, zero);
            b.store(inside, neg);
            let one = b.u(1);
            b.store(tested, one);
        },
        |_| {},
    );
    (b.load(inside), b.load(tested))
}

/// Traces from the far side `hi` back towards `lo` and reports the point found as the hit
/// (t = hi − s); ε is measured from the far side. In a cone pass the ray stays at `start`.
fn backwards(
    b: &mut FnBuilder,
    (all, variant, out): (&[Ex], Handle<Function>, Out),
    result: Ex,
    (start, lo, hi, cone): (Ex, Ex, Ex, Option<Ex>),
) {
    let run = |b: &mut FnBuilder| {
        let (ro, rd) = (all[0], all[1]);
        let s = b.mul(rd, hi);
        let from = b.add(ro, s);
        let back = b.neg(rd);
        let mut a = all.to_vec();
        a[0] = from;
        a[1] = back;
        let i = a.iter().position(|&x| x == start).expect("start");
        a[i] = b.f(0.0);
        a[i + 1] = b.sub(hi, lo);
        if let Some(c) = cone {
            let ci = a.iter().position(|&x| x == c).expect("cone");
            a[ci] = b.f(0.0);
        }
        let r = b.call(variant, a);
        let (s, steps, flags) = (b.at(r, 0), b.at(r, 1), b.at(r, 2));
        let one = b.u(1);
        let steps = b.add(steps, one);
        let hit = is_hit(b, flags);
        let hit_bit = b.u(HIT);
        let exit = b.sub(hi, s);
        let t = b.select(hit, exit, lo);
        let ex = b.u(EXHAUSTED);
        let ex = b.bin(B::And, flags, ex);
        let flags = b.bin(B::InclusiveOr, ex, hit_bit);
        let v = out.make(b, Some((r, false)), [t, steps, flags]);
        b.store(result, v);
    };
    match cone {
        Some(c) => {
            let zero = b.f(0.0);
            let coarse = b.gt(c, zero);
            b.if_(
                coarse,
                |b| {
                    let one = b.u(1);
                    let zero_u = b.u(0);
                    let v = out.make(b, None, [start, one, zero_u]);
                    b.store(result, v);
                },
                run,
            );
        }
        None => run(b),
    }
}

/// The `TraceResult` type, and whether it has the anti-aliasing cover fields.
#[derive(Clone, Copy)]
struct Out {
    ty: Handle<Type>,
    cover: bool,
}

impl Out {
    /// A result of t, steps and flags; the cover fields, if any, are taken from `from` (its
    /// coverage kept or zeroed) or zero.
    fn make(self, b: &mut FnBuilder, from: Option<(Ex, bool)>, [t, s, f]: [Ex; 3]) -> Ex {
        let mut fields = vec![t, s, f];
        if self.cover {
            let zero = b.f(0.0);
            let extra = match from {
                Some((r, keep)) => [b.at(r, 3), if keep { b.at(r, 4) } else { zero }],
                None => [zero, zero],
            };
            fields.extend(extra);
        }
        b.compose(self.ty, fields)
    }
}

/// (entry, exit, whether the line meets the volume) of the line `ro + t·rd`.
fn interval(b: &mut FnBuilder, shape: &BoundShape, ro: Ex, rd: Ex) -> (Ex, Ex, Ex) {
    match *shape {
        BoundShape::Sphere { center, radius } => {
            let c = b.vec3_lit(center);
            let oc = b.sub(ro, c);
            let half_b = b.dot(oc, rd);
            let oo = b.dot(oc, oc);
            let r2 = b.f(radius * radius);
            let cc = b.sub(oo, r2);
            let bb = b.mul(half_b, half_b);
            let disc = b.sub(bb, cc);
            let zero = b.f(0.0);
            let meets = b.ge(disc, zero);
            let safe = b.max(disc, zero);
            let h = b.sqrt(safe);
            let mb_ = b.neg(half_b);
            (b.sub(mb_, h), b.add(mb_, h), meets)
        }
        BoundShape::Box { center, half } => {
            let zero3 = b.splat3(0.0);
            let g3 = b.splat3(AXIS_GUARD);
            let ng3 = b.splat3(-AXIS_GUARD);
            let negative = b.lt(rd, zero3);
            let signed = b.select(negative, ng3, g3);
            let a = b.abs(rd);
            let small = b.lt(a, g3);
            let d = b.select(small, signed, rd);
            let one = b.splat3(1.0);
            let inv = b.div(one, d);
            let lo_c = b.vec3_lit(center - half);
            let hi_c = b.vec3_lit(center + half);
            let la = b.sub(lo_c, ro);
            let la = b.mul(la, inv);
            let ha = b.sub(hi_c, ro);
            let ha = b.mul(ha, inv);
            let mn = b.min(la, ha);
            let mx = b.max(la, ha);
            let near = b.max3(mn);
            let far = b.min3(mx);
            let meets = b.bin(B::LessEqual, near, far);
            (near, far, meets)
        }
    }
}
