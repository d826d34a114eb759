//! Far-field culling for the camera's trace (Barbier, Sanchez et al. 2025, §4.3): `tape_trace(p)`
//! answers in a cell far from every surface with the cell's clearance — a lower bound of the
//! field over the whole cell, which the pre-pass keeps in the cell's count
//! (`tape::data::far_count`) — instead of running its program; elsewhere it runs the program as
//! `tape_eval` does. Only the trace takes it: a step by a lower bound is safe and crosses the
//! cell in a few, where shading (soft shadows' penumbrae, occlusion) needs the field itself.

use super::grid::Grid;
use crate::ir::{Ex, FnBuilder};
use crate::tape::data::{FAR, FAR_MOST, FAR_SHIFT, FAR_STEPS};
use naga::BinaryOperator as Op;

/// `if` the cell (whose range is `range`; `inside` the grid) is far: `return` its clearance.
pub(super) fn answer(b: &mut FnBuilder, range: Ex, inside: Ex, grid: &Grid) {
    let count = b.at(range, 1);
    let far = b.u(FAR);
    let bit = b.bin(Op::And, count, far);
    let zero = b.u(0);
    let is_far = b.bin(Op::NotEqual, bit, zero);
    let culled = b.bin(Op::LogicalAnd, inside, is_far);
    let size = grid.size;
    b.if_(
        culled,
        |b| {
            let shift = b.u(FAR_SHIFT);
            let steps = b.bin(Op::ShiftRight, count, shift);
            let most = b.u(FAR_MOST);
            let steps = b.bin(Op::And, steps, most);
            let steps = b.cast(steps, naga::ScalarKind::Float);
            let unit = b.f(1.0 / FAR_STEPS);
            let unit = b.mul(size, unit);
            let clearance = b.mul(steps, unit);
            b.ret(Some(clearance));
        },
        |_| {},
    );
}
