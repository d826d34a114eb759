//! The confirmation of a hit where f/λ is not a distance to first order, in IR: step for step
//! `crate::reference::trace::careful` (the variant's hit stands where the nearest part is not loose
//! (`map_loose`); else the ray goes on as basic sphere tracing in which a zone of f < ε(t) over
//! a loose part is crossed in steps of ε(t) until the field turns negative, a crossing placed
//! by regula falsi, or rises above ε).

use super::hybrid::regula_falsi;
use super::march::{Cx, EXHAUSTED, HIT};
use crate::ir::builder::{Ex, FnBuilder};
use crate::reference::trace::{CROSSING_REFINE, ZONE_STEP};
use naga::BinaryOperator as B;
use naga::{Function, Handle};

/// Emits the confirmation after the variant's loop: it runs when the variant hit (and did not
/// run out of steps), outside a coarse pass.
pub(super) fn careful(b: &mut FnBuilder, cx: &Cx, loose: Handle<Function>) {
    let flags = b.load(cx.flags);
    let only_hit = b.u(HIT);
    let mut run = b.bin(B::Equal, flags, only_hit);
    if let Some(alpha) = cx.cone() {
        let zero = b.f(0.0);
        let ray = b.bin(B::Equal, alpha, zero);
        run = b.bin(B::LogicalAnd, run, ray);
    }
    b.if_(
        run,
        |b| {
            // The variant may have left the point behind t (hybrid's regula falsi sets t only).
            let t0 = b.load(cx.t);
            let along = b.mul(cx.rd, t0);
            let p0 = b.add(cx.ro, along);
            b.store(cx.p, p0);
            // Where the nearest part is not loose, f/λ is the distance: the hit stands.
            let l = b.call(loose, vec![p0]);
            b.increment(cx.steps);
            let zero_u = b.u(0);
            let is_loose = b.bin(B::NotEqual, l, zero_u);
            b.if_(is_loose, |b| confirm(b, cx, loose), |_| {});
        },
        |_| {},
    );
}

/// The confirmation's loop from the variant's hit, known loose: basic sphere tracing that
/// crosses a zone of f < ε(t) over a loose part in steps of ε(t), a hit where the field turns
/// negative (the crossing placed by regula falsi) or where a part that is not loose is near.
fn confirm(b: &mut FnBuilder, cx: &Cx, loose: Handle<Function>) {
    let zero_u = b.u(0);
    b.store(cx.flags, zero_u);
    let (f32t, boolean) = (b.m.f32(), b.m.bool());
    let no = b.boolean(false);
    let in_zone = b.local("in_zone", boolean, Some(no));
    // Known loose at the variant's hit: the first zone needs no second look.
    let yes = b.boolean(true);
    let fresh = b.local("fresh", boolean, Some(yes));
    let zero = b.f(0.0);
    let t_out = b.local("t_out", f32t, Some(zero));
    let minus = b.f(-1.0);
    let d_out = b.local("d_out", f32t, Some(minus));
    let step = b.local("step", f32t, Some(zero));
    b.loop_(|b| {
        cx.budget(b, EXHAUSTED, |_| {});
        let (t, d) = cx.here(b, "d_confirm");
        let zero = b.f(0.0);
        // On or inside the surface (a zero is a hit too: it would leave regula falsi 0/0).
        let inside = b.bin(B::LessEqual, d, zero);
        b.if_(
            inside,
            |b| {
                let dp = b.load(d_out);
                let outside_before = b.ge(dp, zero);
                b.if_(
                    outside_before,
                    |b| cross(b, cx, (t_out, d_out), (t, d)),
                    |_| {},
                );
                let hit = b.u(HIT);
                b.store(cx.flags, hit);
                b.brk();
            },
            |_| {},
        );
        let e = cx.eps(b, t);
        let near = b.lt(d, e);
        b.if_(
            near,
            |b| enter_zone(b, cx, loose, (in_zone, fresh, step), (d, e)),
            |b| {
                let no = b.boolean(false);
                b.store(in_zone, no);
                b.store(step, d);
            },
        );
        let no = b.boolean(false);
        b.store(fresh, no);
        b.store(t_out, t);
        b.store(d_out, d);
        let s = b.load(step);
        let nt = cx.advance(b, t, s);
        let far = cx.far(b);
        let beyond = b.gt(nt, far);
        cx.stop_if(b, beyond, 0);
    });
}

/// Within ε of the surface: entering a zone (not at the variant's hit, known loose), a part
/// that is not loose is a hit at once; in the zone, the step is at least [`ZONE_STEP`]·ε.
/// The variables: `in_zone`, `fresh` (still at the variant's hit) and `step`.
fn enter_zone(
    b: &mut FnBuilder,
    cx: &Cx,
    loose: Handle<Function>,
    (in_zone, fresh, step): (Ex, Ex, Ex),
    (d, e): (Ex, Ex),
) {
    let entered = b.load(in_zone);
    let not_in = not(b, entered);
    let first = b.load(fresh);
    let again = not(b, first);
    let recheck = b.bin(B::LogicalAnd, not_in, again);
    b.if_(
        recheck,
        |b| {
            let p = b.load(cx.p);
            let l = b.call(loose, vec![p]);
            b.increment(cx.steps);
            let zero_u = b.u(0);
            let tight = b.bin(B::Equal, l, zero_u);
            cx.stop_if(b, tight, HIT);
        },
        |_| {},
    );
    let yes = b.boolean(true);
    b.store(in_zone, yes);
    let k = b.f(ZONE_STEP);
    let ke = b.mul(e, k);
    let s = b.max(d, ke);
    b.store(step, s);
}

/// !a
fn not(b: &mut FnBuilder, a: Ex) -> Ex {
    b.expr(naga::Expression::Unary {
        op: naga::UnaryOperator::LogicalNot,
        expr: a,
    })
}

/// Places the crossing between the outside point (t_out, d_out) and the inside one (t, d) by
/// [`CROSSING_REFINE`] regula falsi steps; t and the point move there.
fn cross(b: &mut FnBuilder, cx: &Cx, (t_out, d_out): (Ex, Ex), (t, d): (Ex, Ex)) {
    let root = regula_falsi(b, cx, (t_out, d_out), (t, d), CROSSING_REFINE);
    let t0 = b.load(cx.t);
    let back = b.sub(root, t0);
    cx.advance(b, t0, back);
}
