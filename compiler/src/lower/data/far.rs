//! Far-field culling for the camera's trace (Barbier, Sanchez et al. 2025, §4.3): `tape_trace(p)`
//! answers in a cell far from every surface with the cell's clearance — a lower bound of the
//! field over the whole cell, which the pre-pass keeps in the cell's count
//! (`tape::data::far_count`) — instead of running its program; elsewhere it is `tape_eval`'s
//! value. Only the trace takes it: a step by a lower bound is safe and crosses the cell in a
//! few, where shading (soft shadows' penumbrae, occlusion) needs the field itself.

use super::grid::cell_range;
use crate::ir::{FnBuilder, ModuleBuilder};
use crate::tape::data::{FAR, FAR_MOST, FAR_SHIFT, FAR_STEPS, Layout};
use naga::{BinaryOperator as Op, Function, Handle};

/// Adds `tape_trace` over the ranges buffer (`ranges`) and `tape_eval` (`eval`); none where
/// the scene has no grid (no cells to cull).
pub(super) fn add(
    mb: &mut ModuleBuilder,
    layout: &Layout,
    ranges: Handle<naga::GlobalVariable>,
    eval: Handle<Function>,
) -> Option<Handle<Function>> {
    if layout.n.iter().product::<usize>() == 0 {
        return None;
    }
    let (v3, f32t) = (mb.vec3(), mb.f32());
    let mut b = FnBuilder::new(mb, "tape_trace", &[("p", v3)], Some(f32t));
    let p = b.arg(0);
    let ranges = b.expr(naga::Expression::GlobalVariable(ranges));
    let (range, grid) = cell_range(&mut b, layout, ranges, p);
    let (inside, grid) = grid.expect("a grid");
    let count = b.at(range, 1);
    let far = b.u(FAR);
    let bit = b.bin(Op::And, count, far);
    let zero = b.u(0);
    let is_far = b.bin(Op::NotEqual, bit, zero);
    let culled = b.bin(Op::LogicalAnd, inside, is_far);
    let d = b.local("d", f32t, None);
    b.if_(
        culled,
        |b| {
            let shift = b.u(FAR_SHIFT);
            let steps = b.bin(Op::ShiftRight, count, shift);
            let most = b.u(FAR_MOST);
            let steps = b.bin(Op::And, steps, most);
            let steps = b.cast(steps, naga::ScalarKind::Float);
            let unit = b.f(1.0 / FAR_STEPS);
            let unit = b.mul(grid.size, unit);
            let clearance = b.mul(steps, unit);
            b.store(d, clearance);
        },
        |b| {
            let r = b.call(eval, vec![p]);
            let v = b.at(r, 0);
            b.store(d, v);
        },
    );
    let out = b.load(d);
    b.ret(Some(out));
    let f = b.finish();
    Some(mb.add_helper("tape_trace", f))
}
