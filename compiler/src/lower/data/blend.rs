//! Materials blended through the data form's smooth folds (`tape_blend`, `map_blend`'s body
//! for a scene drawn as data): the rule of `crate::reference::blend::pick`, run on the running
//! value of each fold as the evaluator walks a cell's program. A blend is vec3(first material
//! id, second id, weight of the second) with ids as the tag's (material + 1, 0 for none).
//!
//! Pruning keeps it exact: a dropped child stays `k` beyond the running value (the running
//! blend stays), a child `k` below replaces what came before (its own blend starts the fold),
//! as the reference rule gives for |x − y| ≥ k.

use super::join::flag;
use crate::ir::{Ex, FnBuilder};
use crate::tape::program::{LARGEST, MATERIAL, NEGATED};
use naga::ScalarKind;

/// A part's own material as a blend of one: vec3(m, m, 0) from its tag word `own`.
pub(super) fn plain(b: &mut FnBuilder, own: Ex) -> Ex {
    let bits = b.u(MATERIAL);
    let m = b.bin(naga::BinaryOperator::And, own, bits);
    let m = b.cast(m, ScalarKind::Float);
    let zero = b.f(0.0);
    b.compose_vec3([m, m, zero])
}

/// A fold's blend at its end, under its own material (`Blend::under`): an id of 0 (none)
/// takes the fold's.
pub(super) fn end(b: &mut FnBuilder, blend: Ex, own: Ex) -> Ex {
    let given = plain(b, own);
    let m = b.at(given, 0);
    let zero = b.f(0.0);
    let [x, y, t] = b.xyz(blend);
    let none_x = b.bin(naga::BinaryOperator::Equal, x, zero);
    let none_y = b.bin(naga::BinaryOperator::Equal, y, zero);
    let x = b.select(none_x, m, x);
    let y = b.select(none_y, m, y);
    b.compose_vec3([x, y, t])
}

/// The running blend `run` of a fold whose running value is `a`, after a later part of value
/// `v` (not yet negated) and blend `child`, as its head says (its parent's way, radius and
/// whether it is negated): `crate::reference::blend::pick`'s step, with x, y = a, v for a
/// minimum and −a, −v for a maximum (an intersection's, and a subtraction's with the cutter
/// already negated).
pub(super) fn fold(b: &mut FnBuilder, (a, v): (Ex, Ex), head: Ex, (run, child): (Ex, Ex)) -> Ex {
    let negated = flag(b, head, NEGATED);
    let minus = b.neg(v);
    let v = b.select(negated, minus, v);
    let largest = flag(b, head, LARGEST);
    let k = b.at(head, 1);
    let k = b.bitcast(k, ScalarKind::Float);
    let (na, nv) = (b.neg(a), b.neg(v));
    let x = b.select(largest, na, a);
    let y = b.select(largest, nv, v);
    let k = crate::lower::pick::Radius::at_run_time(k);
    let second = |b: &mut FnBuilder| crate::lower::pick::dominant(b, child);
    crate::lower::pick::blend_step(b, (x, y), k, run, (second, |_: &mut FnBuilder| child))
}
