//! The pre-pass's first walk (`lower/data/prune.rs`): the parent cell's program run at the
//! cell's centre and copied to the cell's scratch, with `tape::cells::keep`'s rule dropping the
//! children that cannot change their fold's result over the cell.

use super::super::join::{flag, has_bit};
use super::super::leaf;
use super::{BIG, Buffers, DROPPED, Walk, array_of};
use crate::catalog::Primitive;
use crate::ir::{Ex, FnBuilder};
use crate::tape::program::{END, FIRST, LARGEST, NEGATED, NO_PARENT, OFFSET};
use naga::{BinaryOperator as Op, Function, Handle, ScalarKind};

/// The first walk's open folds: each one's running value, the bounds of its result so far
/// (`cells::keep`'s lo, hi and lowest, as a minimum sees them), how many children it has seen
/// and where its first child's instructions start; and how many are open.
#[derive(Clone, Copy)]
pub(super) struct Frames {
    value: Ex,
    lo: Ex,
    hi: Ex,
    lowest: Ex,
    count: Ex,
    start: Ex,
    sp: Ex,
}

/// Runs the parent's program at the cell's centre, copying it to the cell's scratch, and drops
/// what cannot change the field over the cell (`DROPPED` over its instructions).
pub(super) fn walk(
    b: &mut FnBuilder,
    walk: Walk,
    kinds: &[(Handle<Function>, &'static Primitive)],
    (centre, radius, scale): (Ex, Ex, Ex),
    height: usize,
) -> Root {
    let (f32t, u32t) = (b.m.f32(), b.m.u32());
    let (fty, uty) = (array_of(b, f32t, height), array_of(b, u32t, height));
    let zero = b.u(0);
    let frames = Frames {
        value: b.local("f_value", fty, None),
        lo: b.local("f_lo", fty, None),
        hi: b.local("f_hi", fty, None),
        lowest: b.local("f_lowest", fty, None),
        count: b.local("f_count", uty, None),
        start: b.local("f_start", uty, None),
        sp: b.local("f_sp", u32t, Some(zero)),
    };
    let v = b.local("v", f32t, None);
    let cs = b.local("cs", u32t, None);
    let boolt = b.m.bool();
    let no = b.boolean(false);
    let root_fold = b.local("root_fold", boolt, Some(no));
    let Buffers {
        nodes,
        meta,
        code,
        scratch,
    } = walk.bufs;
    b.repeat("i", walk.len, |b, i| {
        let src = b.add(walk.from, i);
        let ptr = b.index(code, src);
        let ins = b.load(ptr);
        let dst = b.add(walk.start, i);
        let to = b.index(scratch, dst);
        b.store(to, ins);
        let mask = b.u(OFFSET);
        let off = b.bin(Op::And, ins, mask);
        let ptr = b.index(nodes, off);
        let head = b.load(ptr);
        let factor = b.at(head, 2);
        let factor = b.bitcast(factor, ScalarKind::Float);
        let is_end = has_bit(b, ins, END);
        b.if_(
            is_end,
            |b| {
                // A fold's children are done: its value, and its first child's start.
                let sp = b.decrement(frames.sp);
                let p = b.index(frames.value, sp);
                let x = b.load(p);
                let x = b.mul(x, factor);
                b.store(v, x);
                let p = b.index(frames.start, sp);
                let s = b.load(p);
                b.store(cs, s);
            },
            |b| {
                let d = leaf(b, nodes, (off, head), kinds, centre);
                let x = b.mul(d, factor);
                b.store(v, x);
                b.store(cs, i);
            },
        );
        let ptr = b.index(meta, off);
        let m = b.load(ptr);
        let parent = b.at(m, 0);
        let none = b.u(NO_PARENT);
        let child = b.bin(Op::NotEqual, parent, none);
        let x = b.load(v);
        let s = b.load(cs);
        let part = Child {
            ins,
            head,
            meta: m,
            value: x,
            start: s,
            at: i,
        };
        b.if_(
            child,
            |b| join(b, (walk, frames), part, (radius, scale)),
            |b| b.store(root_fold, is_end),
        );
    });
    Root {
        frames,
        fold: b.load(root_fold),
    }
}

/// What the first walk knows of the root at its end: whether it is a fold, and the frames,
/// whose first (the root fold's) holds the bounds of its result over the cell.
#[derive(Clone, Copy)]
pub(super) struct Root {
    pub frames: Frames,
    pub fold: Ex,
}

impl Root {
    /// A lower bound of the root fold's value over the cell (its result's bounds, as a minimum
    /// sees them, turned back for a largest fold, times its factor); `head`: the root's.
    pub fn lower(&self, b: &mut FnBuilder, head: Ex) -> Ex {
        let zero = b.u(0);
        let lo = b.index(self.frames.lo, zero);
        let lo = b.load(lo);
        let hi = b.index(self.frames.hi, zero);
        let hi = b.load(hi);
        let above = b.neg(hi);
        let largest = flag(b, head, crate::tape::program::OWN_LARGEST);
        let raw = b.select(largest, above, lo);
        let factor = b.at(head, 2);
        let factor = b.bitcast(factor, ScalarKind::Float);
        b.mul(raw, factor)
    }
}

/// A part the first walk has just finished: its instruction, head and meta, its value as its
/// parent sees it, and its instructions' span (`start` to `at`, both in).
#[derive(Clone, Copy)]
struct Child {
    ins: Ex,
    head: Ex,
    meta: Ex,
    value: Ex,
    start: Ex,
    at: Ex,
}

/// The finished `part` joins its fold's frame: it opens the frame if it is the fold's first
/// child, is combined into the running value, and is kept or dropped by `cells::keep`'s rule.
fn join(b: &mut FnBuilder, (walk, frames): (Walk, Frames), part: Child, (radius, scale): (Ex, Ex)) {
    let negated = flag(b, part.head, NEGATED);
    let minus = b.neg(part.value);
    let sv = b.select(negated, minus, part.value);
    let zoom = b.at(part.meta, 2);
    let zoom = b.bitcast(zoom, ScalarKind::Float);
    let reach = b.mul(zoom, radius);
    let far = b.mul(zoom, scale);
    let size = b.abs(sv);
    let size = b.add(size, reach);
    let size = b.add(size, far);
    // f32's rounding, relative to the magnitudes the value is made of — its size, the cell's
    // reach, the scene's coordinates through the parent's zoom — as `Table::meta` allows it
    // (the CPU's f64 pre-pass keeps 1e-9 of them, `cells::MARGIN`).
    let rounding = b.at(part.meta, 3);
    let rounding = b.bitcast(rounding, ScalarKind::Float);
    let margin = b.mul(size, rounding);
    let slack = b.add(reach, margin);
    let proven = b.at(part.meta, 1);
    let zero = b.u(0);
    let proven = b.bin(Op::NotEqual, proven, zero);
    let (big, small) = (b.f(BIG), b.f(-BIG));
    let lo = b.sub(sv, slack);
    let hi = b.add(sv, slack);
    let lo = b.select(proven, lo, small);
    let hi = b.select(proven, hi, big);
    // A maximum's bounds as a minimum sees them (max(a, b) = −min(−a, −b)).
    let largest = flag(b, part.head, LARGEST);
    let (nlo, nhi) = (b.neg(hi), b.neg(lo));
    let blo = b.select(largest, nlo, lo);
    let bhi = b.select(largest, nhi, hi);
    let k = b.at(part.head, 1);
    let k = b.bitcast(k, ScalarKind::Float);
    let first = has_bit(b, part.ins, FIRST);
    b.if_(
        first,
        |b| {
            let sp = b.load(frames.sp);
            let p = b.index(frames.value, sp);
            b.store(p, sv);
            let p = b.index(frames.count, sp);
            let zero = b.u(0);
            b.store(p, zero);
            let p = b.index(frames.start, sp);
            b.store(p, part.start);
            b.increment(frames.sp);
        },
        |b| {
            let sp = b.load(frames.sp);
            let one = b.u(1);
            let top = b.sub(sp, one);
            let p = b.index(frames.value, top);
            let a = b.load(p);
            // As the evaluator folds it (`join::fold_in`): the whole parent program's value.
            let term = crate::catalog::gpu::ops::blend(b, a, sv, k);
            let (m, big) = (b.min(a, sv), b.max(a, sv));
            let lo = b.sub(m, term);
            let hi = b.add(big, term);
            let x = b.select(largest, hi, lo);
            b.store(p, x);
        },
    );
    keep(b, (walk, frames), part, (blo, bhi, k));
}

/// `cells::keep`'s step for a child with bounds `blo`..`bhi` (as a minimum sees them) in the
/// top frame, whose fold blends over `k`.
fn keep(
    b: &mut FnBuilder,
    (walk, frames): (Walk, Frames),
    part: Child,
    (blo, bhi, k): (Ex, Ex, Ex),
) {
    let sp = b.load(frames.sp);
    let one = b.u(1);
    let top = b.sub(sp, one);
    let [lo, hi, lowest, count, start] = [
        frames.lo,
        frames.hi,
        frames.lowest,
        frames.count,
        frames.start,
    ]
    .map(|a| b.index(a, top));
    let set = |b: &mut FnBuilder, values: [Ex; 3]| {
        for (p, x) in [lo, hi, lowest].into_iter().zip(values) {
            b.store(p, x);
        }
    };
    let seen = b.load(count);
    let zero = b.u(0);
    let fresh = b.bin(Op::Equal, seen, zero);
    let (flo, fhi, flow) = (b.load(lo), b.load(hi), b.load(lowest));
    let hik = b.add(fhi, k);
    let above = b.gt(blo, hik);
    let bk = b.add(bhi, k);
    let below = b.lt(bk, flo);
    b.if_(
        fresh,
        |b| set(b, [blo, bhi, blo]),
        |b| {
            b.if_(
                above,
                // Always k above: it never blends in.
                |b| drop(b, walk, (part.start, part.at)),
                |b| {
                    b.if_(
                        below,
                        // Always k below: the fold's result is this child's from here.
                        |b| {
                            let first = b.load(start);
                            let one = b.u(1);
                            let before = b.sub(part.start, one);
                            let any = b.gt(part.start, first);
                            b.if_(any, |b| drop(b, walk, (first, before)), |_| {});
                            set(b, [blo, bhi, blo]);
                        },
                        |b| {
                            let h = b.min(fhi, bhi);
                            let l = b.min(flow, blo);
                            let quarter = b.f(0.25);
                            let dip = b.mul(k, quarter);
                            let m = b.min(flo, blo);
                            let m = b.sub(m, dip);
                            let floor = b.sub(l, k);
                            let m = b.max(m, floor);
                            set(b, [m, h, l]);
                        },
                    )
                },
            )
        },
    );
    let seen = b.add(seen, one);
    b.store(count, seen);
}

/// Overwrites the cell's instructions `from` to `to` (both in) with [`DROPPED`].
fn drop(b: &mut FnBuilder, walk: Walk, (from, to): (Ex, Ex)) {
    let one = b.u(1);
    let end = b.add(to, one);
    let count = b.sub(end, from);
    let dropped = b.u(DROPPED);
    b.repeat("j", count, |b, j| {
        let at = b.add(from, j);
        let at = b.add(walk.start, at);
        let p = b.index(walk.bufs.scratch, at);
        b.store(p, dropped);
    });
}
