//! Multi-resolution passes in the compute entries (Bálint §4): the hand-over buffers, where a
//! pass starts each ray, and what it hands to the next.

use super::camera::{storage_array, view_field};
use super::fns::{Fns, trace_pixel};
use super::tracer::Pass;
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use naga::{Expression, Handle, MathFunction as M, ScalarKind, VectorSize};

/// With passes: the hand-over buffers (`pass_in` at binding 6, read; `pass_out` at 7).
pub(super) fn hand_over(
    mb: &mut ModuleBuilder,
    fns: &Fns,
) -> Option<(Handle<naga::GlobalVariable>, Handle<naga::GlobalVariable>)> {
    fns.passes.then(|| {
        let v2 = mb.vec(VectorSize::Bi);
        (
            storage_array(mb, crate::layout::HAND_OVER[0], (v2, false)),
            storage_array(mb, crate::layout::HAND_OVER[1], (v2, true)),
        )
    })
}

/// The pixel's ray traced — with passes, from where the previous pass stopped, handing t and
/// the steps so far to the next pass and returning early from a coarse (cone) pass: the
/// traced ray and its steps over all passes.
pub(super) fn trace_in_pass(
    b: &mut FnBuilder,
    fns: &Fns,
    hand_over: Option<(Handle<naga::GlobalVariable>, Handle<naga::GlobalVariable>)>,
    (index, pixel): (Ex, Ex),
) -> ((Ex, Ex, Ex, Ex), Ex) {
    let pass = hand_over.map(|(pass_in, _)| previous_pass(b, fns, pixel, pass_in));
    let traced = trace_pixel(b, fns, pixel, pass.map(|p| p.0));
    let result = traced.2;
    let mut steps = b.at(result, 1);
    if let (Some((p, before)), Some((_, pass_out))) = (pass, hand_over) {
        steps = b.add(before, steps);
        let t = b.at(result, 0);
        let sf = b.cast(steps, ScalarKind::Float);
        let v2 = b.m.vec(VectorSize::Bi);
        let v = b.compose(v2, vec![t, sf]);
        let base = b.expr(Expression::GlobalVariable(pass_out));
        let ptr = b.expr(Expression::Access { base, index });
        b.store(ptr, v);
        let zero = b.f(0.0);
        let coarse = b.gt(p.cone, zero);
        b.if_(coarse, |b| b.ret(None), |_| {});
    }
    (traced, steps)
}

/// Where a pass starts the ray through `pixel`: the t the previous pass reached at the nearest
/// of its pixels (0 in the first pass), with the budget and cone slope of the view's `pass`
/// field; and the steps the previous passes spent there.
fn previous_pass(
    b: &mut FnBuilder,
    fns: &Fns,
    pixel: Ex,
    pass_in: Handle<naga::GlobalVariable>,
) -> (Pass, Ex) {
    let pv = view_field(b, fns.view(), "handoff");
    let cone = b.at(pv, 0);
    let budget = b.at(pv, 1);
    let budget = b.cast(budget, ScalarKind::Uint);
    let f32t = b.m.f32();
    let u32t = b.m.u32();
    let zero = b.f(0.0);
    let start = b.local("start", f32t, Some(zero));
    let zero_u = b.u(0);
    let before = b.local("before", u32t, Some(zero_u));
    let pw = b.at(pv, 2);
    let earlier = b.gt(pw, zero);
    b.if_(
        earlier,
        |b| {
            let size = view_field(b, fns.view(), "size");
            let here = b.swizzle(size, &[0, 1]);
            let there = b.swizzle(pv, &[2, 3]);
            let q = b.mul(pixel, there);
            let q = b.div(q, here);
            let q = b.math(M::Floor, &[q]);
            let one = b.f(1.0);
            let one2 = b.splat(one, VectorSize::Bi);
            let last = b.sub(there, one2);
            let q = b.min(q, last);
            let zero2 = b.splat(zero, VectorSize::Bi);
            let q = b.max(q, zero2);
            let q = b.cast(q, ScalarKind::Uint);
            let width = b.cast(pw, ScalarKind::Uint);
            let (qx, qy) = (b.at(q, 0), b.at(q, 1));
            let row = b.mul(qy, width);
            let j = b.add(row, qx);
            let base = b.expr(Expression::GlobalVariable(pass_in));
            let ptr = b.expr(Expression::Access { base, index: j });
            let e = b.load(ptr);
            let t = b.at(e, 0);
            b.store(start, t);
            let s = b.at(e, 1);
            let s = b.cast(s, ScalarKind::Uint);
            b.store(before, s);
        },
        |_| {},
    );
    let pass = Pass {
        start: b.load(start),
        budget,
        cone,
    };
    (pass, b.load(before))
}
