//! How a part's value and tag join its fold's running one in the data form's evaluator (the
//! shader's side of `crate::tape::program::run`): a first part starts it, a later one is
//! combined into it by the fold's way and radius, a fold's end decides its material and
//! whether it is loose.

use crate::ir::{Ex, FnBuilder};
use crate::tape::program::{
    ALL_LOOSE, FLAGS_SHIFT, LARGEST, LOOSE, MATERIAL, NEGATED, OUT_LOOSE, OWN_LARGEST,
};
use naga::ScalarKind;

/// Whether `bit` is set in `word`.
pub(super) fn has_bit(b: &mut FnBuilder, word: Ex, bit: u32) -> Ex {
    let m = b.u(bit);
    let x = b.bin(naga::BinaryOperator::And, word, m);
    let zero = b.u(0);
    b.bin(naga::BinaryOperator::NotEqual, x, zero)
}

/// Whether the head's flag `flag` is set.
pub(super) fn flag(b: &mut FnBuilder, head: Ex, flag: u32) -> Ex {
    let kind = b.at(head, 0);
    has_bit(b, kind, flag << FLAGS_SHIFT)
}

/// A first part's value (and tag) starting its fold: negated if its head says; in a largest
/// fold, the tag starts [`ALL_LOOSE`] if the part is loose and [`OUT_LOOSE`] if it is also
/// positive.
pub(super) fn start(b: &mut FnBuilder, (v, tag): (Ex, Ex), head: Ex) -> [Ex; 3] {
    let negated = flag(b, head, NEGATED);
    let minus = b.neg(v);
    let v = b.select(negated, minus, v);
    let largest = flag(b, head, LARGEST);
    let loose = has_bit(b, tag, LOOSE);
    let (all, none) = (b.u(ALL_LOOSE), b.u(0));
    let all = b.select(loose, all, none);
    let out = out_loose(b, loose, v);
    let helpers = b.bin(naga::BinaryOperator::InclusiveOr, all, out);
    let marked = b.bin(naga::BinaryOperator::InclusiveOr, tag, helpers);
    let tag = b.select(largest, marked, tag);
    [v, v, tag]
}

/// [`OUT_LOOSE`] where a part is `loose` and positive (`v`), else 0.
fn out_loose(b: &mut FnBuilder, loose: Ex, v: Ex) -> Ex {
    let zero = b.f(0.0);
    let positive = b.gt(v, zero);
    let both = b.bin(naga::BinaryOperator::LogicalAnd, loose, positive);
    let (out, none) = (b.u(OUT_LOOSE), b.u(0));
    b.select(both, out, none)
}

/// A later part's value `v` (with tag `ct`) folded into the running `(a, a_best, a_tag)` as
/// its head says (its parent's way and radius, whether it is negated).
pub(super) fn fold_in(
    b: &mut FnBuilder,
    [a, a_best, a_tag]: [Ex; 3],
    (v, ct): (Ex, Ex),
    head: Ex,
) -> [Ex; 3] {
    let largest = flag(b, head, LARGEST);
    let negated = flag(b, head, NEGATED);
    let minus = b.neg(v);
    let v = b.select(negated, minus, v);
    let k = b.at(head, 1);
    let k = b.bitcast(k, ScalarKind::Float);
    // IQ's quadratic smooth minimum and maximum as `op_smooth_union` and `op_smooth_intersect`
    // compute them, operation for operation; at k = 0 the blend term is 0 and they are min and
    // max.
    let term = crate::catalog::gpu::ops::blend(b, a, v, k);
    let (m, big) = (b.min(a, v), b.max(a, v));
    let lo = b.sub(m, term);
    let hi = b.add(big, term);
    let value = b.select(largest, hi, lo);
    let nearer = b.lt(v, a_best);
    let farther = b.gt(v, a_best);
    let better = b.select(largest, farther, nearer);
    let best = b.select(better, v, a_best);
    // The material of the better, loose as it is for a minimum; for a maximum, every child so
    // far loose and a loose child positive (`start`; its end decides).
    let picked = b.select(better, ct, a_tag);
    let material_bits = b.u(MATERIAL);
    let material = b.bin(naga::BinaryOperator::And, picked, material_bits);
    let loose = has_bit(b, ct, LOOSE);
    let (all_bit, none) = (b.u(ALL_LOOSE), b.u(0));
    let all = b.bin(naga::BinaryOperator::And, a_tag, all_bit);
    let all = b.select(loose, all, none);
    let out_bit = b.u(OUT_LOOSE);
    let out = b.bin(naga::BinaryOperator::And, a_tag, out_bit);
    let out_here = out_loose(b, loose, v);
    let out = b.bin(naga::BinaryOperator::InclusiveOr, out, out_here);
    let helpers = b.bin(naga::BinaryOperator::InclusiveOr, all, out);
    let marked = b.bin(naga::BinaryOperator::InclusiveOr, material, helpers);
    let tag = b.select(largest, marked, picked);
    [value, best, tag]
}

/// A fold's tag at its end: the material it picked, else its own; loose where it is itself,
/// and where what it picked is (a smallest fold) or by `MatRule::pick_loose` (a largest one:
/// every child loose, or a loose child positive).
pub(super) fn end_tag(b: &mut FnBuilder, tag: Ex, own: Ex, head: Ex) -> Ex {
    let loose_bit = b.u(LOOSE);
    let material_bits = b.u(MATERIAL);
    let picked = b.bin(naga::BinaryOperator::And, tag, material_bits);
    let given = b.bin(naga::BinaryOperator::And, own, material_bits);
    let zero = b.u(0);
    let has = b.bin(naga::BinaryOperator::NotEqual, picked, zero);
    let material = b.select(has, picked, given);
    let largest = flag(b, head, OWN_LARGEST);
    let nearest = has_bit(b, tag, LOOSE);
    let by_rule = has_bit(b, tag, ALL_LOOSE | OUT_LOOSE);
    let inner = b.select(largest, by_rule, nearest);
    let itself = has_bit(b, own, LOOSE);
    let loose = b.bin(naga::BinaryOperator::LogicalOr, inner, itself);
    let loose = b.select(loose, loose_bit, zero);
    b.bin(naga::BinaryOperator::InclusiveOr, material, loose)
}
