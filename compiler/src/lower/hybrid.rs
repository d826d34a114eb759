//! Liktor's sphere-tracing and linear-search hybrid in IR (one loop, one `map` call), and the
//! regula falsi refinement it shares with the hit confirmation.

use super::march::{Cx, EXHAUSTED, HIT, var};
use crate::ir::builder::{Ex, FnBuilder};
use naga::BinaryOperator as B;

/// Liktor §5.4 (see `crate::reference::trace::hybrid`), as one loop with one `map` call: each iteration
/// evaluates either the search's next point or, once a step has landed inside, the bracket's
/// regula falsi point (`refining` counts those iterations, from 1), so that SIMD lanes in
/// either phase share the call (the notes' performance facts: a second call site cost up to
/// 1.7× at equal evaluations). The same points in the same order as the CPU's two loops.
pub(super) fn hybrid(b: &mut FnBuilder, cx: &Cx) {
    let t_out = var(b, "t_out", 0.0);
    let f_out = var(b, "f_out", 0.0);
    let (lo, f_lo) = (var(b, "lo", 0.0), var(b, "f_lo", 0.0));
    let (hi, f_hi) = (var(b, "hi", 0.0), var(b, "f_hi", 0.0));
    let u32t = b.m.u32();
    let zero_u = b.u(0);
    let refining = b.local("refining", u32t, Some(zero_u));
    let refine = cx.trace.refine;
    b.loop_(|b| {
        let k = b.load(refining);
        let zero_u = b.u(0);
        let searching = b.bin(B::Equal, k, zero_u);
        // The budget binds the search; the refinement's iterations are counted beyond it.
        b.if_(searching, |b| cx.budget(b, EXHAUSTED, |_| {}), |_| {});
        let (t, p) = (b.load(cx.t), b.load(cx.p));
        let tm = falsi(b, lo, f_lo, hi, f_hi);
        let at = b.select(searching, t, tm);
        let s = b.mul(cx.rd, tm);
        let q = b.add(cx.ro, s);
        let point = b.select(searching, p, q);
        let d = cx.field_at(b, point, at);
        b.name(d, "d");
        b.if_(
            searching,
            |b| {
                let zero = b.f(0.0);
                let inside = b.lt(d, zero);
                let n = b.load(cx.steps);
                let one_u = b.u(1);
                let not_first = b.gt(n, one_u);
                let crossed = b.bin(B::LogicalAnd, inside, not_first);
                b.if_(
                    crossed,
                    |b| {
                        let (a, fa) = (b.load(t_out), b.load(f_out));
                        b.store(lo, a);
                        b.store(f_lo, fa);
                        b.store(hi, t);
                        b.store(f_hi, d);
                        if refine == 0 {
                            finish(b, cx, (lo, f_lo, hi, f_hi));
                        } else {
                            let one = b.u(1);
                            b.store(refining, one);
                        }
                    },
                    |b| {
                        let e = cx.eps(b, t);
                        let close = b.lt(d, e);
                        cx.stop_if(b, close, HIT);
                        b.store(t_out, t);
                        b.store(f_out, d);
                        let linear =
                            crate::reference::trace::hybrid_linear(&cx.trace, cx.loose.is_some());
                        let lin = b.f(linear);
                        let lin = b.mul(lin, e);
                        let far = cx.far(b);
                        let gone = b.ge(t, far);
                        cx.stop_if(b, gone, 0);
                        let step = b.max(d, lin);
                        let left = b.sub(far, t);
                        let step = b.min(step, left);
                        cx.advance(b, t, step);
                    },
                );
            },
            |b| {
                narrow(b, (lo, f_lo, hi, f_hi), (tm, d));
                let one = b.u(1);
                let next = b.add(k, one);
                b.store(refining, next);
                let last = b.u(refine);
                let done = b.gt(next, last);
                b.if_(done, |b| finish(b, cx, (lo, f_lo, hi, f_hi)), |_| {});
            },
        );
    });
}

/// The hit at the bracket's regula falsi point: t, the hit flag, and out of the loop.
fn finish(b: &mut FnBuilder, cx: &Cx, (lo, f_lo, hi, f_hi): (Ex, Ex, Ex, Ex)) {
    let root = falsi(b, lo, f_lo, hi, f_hi);
    b.store(cx.t, root);
    let hit = b.u(HIT);
    b.store(cx.flags, hit);
    b.brk();
}

/// The crossing between the outside point in the variables (`t_out`, `f_out`) and the inside
/// point (t, d), after `iterations` regula falsi steps (each an evaluation).
pub(super) fn regula_falsi(
    b: &mut FnBuilder,
    cx: &Cx,
    (t_out, f_out): (Ex, Ex),
    (t, d): (Ex, Ex),
    iterations: u32,
) -> Ex {
    let (a0, fa0) = (b.load(t_out), b.load(f_out));
    let f32t = b.m.f32();
    let a = b.local("lo", f32t, Some(a0));
    let fa = b.local("f_lo", f32t, Some(fa0));
    let c = b.local("hi", f32t, Some(t));
    let fc = b.local("f_hi", f32t, Some(d));
    if iterations > 0 {
        let limit = b.u(iterations);
        b.repeat("k", limit, |b, _| {
            let tm = falsi(b, a, fa, c, fc);
            let fm = cx.field(b, tm);
            narrow(b, (a, fa, c, fc), (tm, fm));
        });
    }
    falsi(b, a, fa, c, fc)
}

/// The bracket held in the variables (lo, f(lo)) outside and (hi, f(hi)) inside, narrowed by
/// the point `t` of field `f`: it replaces the end on its side of the surface.
fn narrow(b: &mut FnBuilder, (lo, f_lo, hi, f_hi): (Ex, Ex, Ex, Ex), (t, f): (Ex, Ex)) {
    let zero = b.f(0.0);
    let outside = b.gt(f, zero);
    b.if_(
        outside,
        |b| {
            b.store(lo, t);
            b.store(f_lo, f);
        },
        |b| {
            b.store(hi, t);
            b.store(f_hi, f);
        },
    );
}

/// The regula falsi point a + (c − a)·f(a)/(f(a) − f(c)) of the bracket held in the variables
/// (a, f(a)) outside and (c, f(c)) inside.
fn falsi(b: &mut FnBuilder, a: Ex, fa: Ex, c: Ex, fc: Ex) -> Ex {
    let (av, fav, cv, fcv) = (b.load(a), b.load(fa), b.load(c), b.load(fc));
    let width = b.sub(cv, av);
    let drop = b.sub(fav, fcv);
    let ratio = b.div(fav, drop);
    let off = b.mul(width, ratio);
    b.add(av, off)
}
