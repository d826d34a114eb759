//! The pre-pass's second walk (`lower/data/prune.rs`): the kept instructions packed in place in
//! the cell's scratch,
//! their `FIRST` and `SPILL` bits made anew from each part's parent as `program::encode` sets
//! them for the pruned tree.

use super::super::join::has_bit;
use super::{Buffers, DROPPED, Walk, array_of};
use crate::ir::{Ex, FnBuilder};
use crate::tape::program::{END, FIRST, NO_PARENT, OFFSET, SPILL};
use naga::BinaryOperator as Op;

/// Packs the kept instructions in place with their `FIRST` and `SPILL` bits made anew, as
/// `program::encode` gives them for the pruned tree; returns how many were kept and the
/// leaves among them.
pub(super) fn walk(b: &mut FnBuilder, walk: Walk, height: usize) -> (Ex, Ex) {
    let u32t = b.m.u32();
    let uty = array_of(b, u32t, height);
    let zero = b.u(0);
    let open = Open {
        fold: b.local("o_fold", uty, None),
        first: b.local("o_first", uty, None),
        sp: b.local("o_sp", u32t, Some(zero)),
    };
    let kept = b.local("kept", u32t, Some(zero));
    let leaves = b.local("leaves", u32t, Some(zero));
    let first = b.local("first", u32t, None);
    let spill = b.local("spill", u32t, None);
    let Buffers { meta, scratch, .. } = walk.bufs;
    b.repeat("i", walk.len, |b, i| {
        let at = b.add(walk.start, i);
        let ptr = b.index(scratch, at);
        let ins = b.load(ptr);
        let dropped = b.u(DROPPED);
        let live = b.bin(Op::NotEqual, ins, dropped);
        b.if_(
            live,
            |b| {
                let mask = b.u(OFFSET);
                let off = b.bin(Op::And, ins, mask);
                let is_end = has_bit(b, ins, END);
                let zero = b.u(0);
                b.store(spill, zero);
                b.if_(
                    is_end,
                    |b| {
                        let sp = b.decrement(open.sp);
                        let p = b.index(open.first, sp);
                        let f = b.load(p);
                        b.store(first, f);
                    },
                    |b| {
                        b.increment(leaves);
                        opened(b, (meta, open), off, (first, spill));
                    },
                );
                let (f, s) = (b.load(first), b.load(spill));
                let (end_bit, first_bit, spill_bit) = (b.u(END), b.u(FIRST), b.u(SPILL));
                let e = b.select(is_end, end_bit, zero);
                let f = b.mul(f, first_bit);
                let s = b.mul(s, spill_bit);
                let word = b.bin(Op::InclusiveOr, off, e);
                let word = b.bin(Op::InclusiveOr, word, f);
                let word = b.bin(Op::InclusiveOr, word, s);
                let k = b.load(kept);
                let at = b.add(walk.start, k);
                let ptr = b.index(scratch, at);
                b.store(ptr, word);
                b.increment(kept);
            },
            |_| {},
        );
    });
    (b.load(kept), b.load(leaves))
}

/// The second walk's open folds: each one's head offset and whether it is the first its parent
/// keeps (1 or 0); how many are open.
#[derive(Clone, Copy)]
struct Open {
    fold: Ex,
    first: Ex,
    sp: Ex,
}

/// Whether the leaf at `off` is the first its fold keeps (into `first`, 1 or 0) and spills
/// (`spill`), opening the folds above it that are not open yet.
fn opened(b: &mut FnBuilder, (meta, open): (Ex, Open), off: Ex, (first, spill): (Ex, Ex)) {
    let parent_of = |b: &mut FnBuilder, at: Ex| {
        let ptr = b.index(meta, at);
        let m = b.load(ptr);
        b.at(m, 0)
    };
    let parent = parent_of(b, off);
    let none = b.u(NO_PARENT);
    let sp = b.load(open.sp);
    let zero = b.u(0);
    let one = b.u(1);
    let has_top = b.gt(sp, zero);
    let below = b.sub(sp, one);
    let top_at = b.select(has_top, below, zero);
    let ptr = b.index(open.fold, top_at);
    let top = b.load(ptr);
    let top = b.select(has_top, top, none);
    let root = b.bin(Op::Equal, parent, none);
    let open_here = b.bin(Op::Equal, parent, top);
    let settled = b.bin(Op::LogicalOr, root, open_here);
    // (A lone leaf is the root: first. A leaf whose parent is open is not.)
    let lone = b.select(root, one, zero);
    b.store(first, lone);
    b.if_(
        settled,
        |_| {},
        |b| {
            let u32t = b.m.u32();
            let a = b.local("a", u32t, Some(parent));
            let h = b.local("h", u32t, Some(one));
            b.loop_(|b| {
                let x = b.load(a);
                let up = parent_of(b, x);
                let at_root = b.bin(Op::Equal, up, none);
                let at_top = b.bin(Op::Equal, up, top);
                let stop = b.bin(Op::LogicalOr, at_root, at_top);
                b.break_if(stop);
                b.store(a, up);
                b.increment(h);
            });
            // The highest fold opened is first in its parent only if it is the root; the
            // rest are first in theirs; a later fold's first leaf spills.
            let highest = b.load(a);
            let above = parent_of(b, highest);
            let later = b.bin(Op::NotEqual, above, none);
            let n = b.load(h);
            let fold = b.local("fold", u32t, Some(parent));
            b.repeat("j", n, |b, j| {
                let depth = b.sub(n, j);
                let depth = b.sub(depth, one);
                let at = b.add(sp, depth);
                let f = b.load(fold);
                let p = b.index(open.fold, at);
                b.store(p, f);
                let is_highest = b.bin(Op::Equal, depth, zero);
                let not_first = b.bin(Op::LogicalAnd, is_highest, later);
                let x = b.select(not_first, zero, one);
                let p = b.index(open.first, at);
                b.store(p, x);
                let up = parent_of(b, f);
                b.store(fold, up);
            });
            let sp = b.add(sp, n);
            b.store(open.sp, sp);
            b.store(first, one);
            let s = b.select(later, one, zero);
            b.store(spill, s);
        },
    );
}
