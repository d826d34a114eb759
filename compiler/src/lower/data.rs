//! The data form's evaluator (issue 33): `tape_eval(p)` runs the program of the grid cell that
//! holds `p` (`crate::tape::data`: words and ranges in two storage buffers) with a small stack,
//! one `switch` arm per primitive kind the scene uses, and returns vec2(value, tag bits): the
//! material + 1 and the looseness bit (`program::LOOSE`); `map`, `map_material` and
//! `map_loose` read it. The code does not grow with the number of parts.

use crate::ir::{Arm, Ex, FnBuilder, ModuleBuilder};
use crate::layout;
use crate::tape::data::Layout;
use crate::tape::program::{COMBINE, END, LEAF, LOOSE, MAX_STACK, MOVED, NEGATE};
use naga::{
    AddressSpace, ArraySize, Function, Handle, ScalarKind, StorageAccess, TypeInner, VectorSize,
};

/// Declares the buffers and adds `tape_eval`.
pub(super) fn add(mb: &mut ModuleBuilder, layout: &Layout) -> Handle<Function> {
    let u32t = mb.u32();
    let f32t = mb.f32();
    let uvec4 = mb.uvec(VectorSize::Quad);
    let uvec2 = mb.uvec(VectorSize::Bi);
    let read = AddressSpace::Storage {
        access: StorageAccess::LOAD,
    };
    let words_ty = mb.ty(TypeInner::Array {
        base: uvec4,
        size: ArraySize::Dynamic,
        stride: 16,
    });
    let ranges_ty = mb.ty(TypeInner::Array {
        base: uvec2,
        size: ArraySize::Dynamic,
        stride: 8,
    });
    let [w, r] = layout::TAPE_BINDINGS;
    let words = super::globals::global(mb, "tape_words", words_ty, read, w);
    let ranges = super::globals::global(mb, "tape_ranges", ranges_ty, read, r);
    let stack = |mb: &mut ModuleBuilder, base| {
        let size =
            ArraySize::Constant(std::num::NonZeroU32::new(MAX_STACK as u32).expect("a stack"));
        let stride = 4;
        mb.ty(TypeInner::Array { base, size, stride })
    };
    let (values_ty, tags_ty) = (stack(mb, f32t), stack(mb, u32t));
    let v3 = mb.vec3();
    let v2 = mb.vec(VectorSize::Bi);
    let kinds: Vec<Handle<Function>> = layout
        .kinds
        .iter()
        .map(|k| mb.helper(&format!("sd_{}", k.name)))
        .collect();
    let mut b = FnBuilder::new(mb, "tape_eval", &[("p", v3)], Some(v2));
    let p = b.arg(0);
    let words = b.expr(naga::Expression::GlobalVariable(words));
    let ranges = b.expr(naga::Expression::GlobalVariable(ranges));
    let (range, inside) = cell_range(&mut b, layout, ranges, p);
    let start = b.at(range, 0);
    let len = b.at(range, 1);
    let end = b.add(start, len);
    let value = b.local("value", values_ty, None);
    let best = b.local("best", values_ty, None);
    let tag = b.local("tag", tags_ty, None);
    let zero = b.u(0);
    // An empty program (outside a grid that holds every part) leaves "nothing here".
    let (v0, t0) = (b.index(value, zero), b.index(tag, zero));
    let far = b.f(crate::ir::FAR);
    b.store(v0, far);
    b.store(t0, zero);
    let sp = b.local("sp", u32t, Some(zero));
    let pc = b.local("pc", u32t, Some(start));
    let at = Stack {
        value,
        best,
        tag,
        sp,
    };
    let kinds: Vec<(Handle<Function>, &'static crate::catalog::Primitive)> = kinds
        .into_iter()
        .zip(layout.kinds.iter().copied())
        .collect();
    b.loop_(|b| instruction(b, at, (words, pc, end), &kinds, p));
    let first = b.u(0);
    let v0 = b.index(value, first);
    let mut v0 = b.load(v0);
    let t0 = b.index(tag, first);
    let t0 = b.load(t0);
    let t0 = b.bitcast(t0, ScalarKind::Float);
    if let (Some(margin), Some(inside)) = (layout.proxy, inside) {
        let d = proxy(&mut b, layout, p, margin);
        let nearer = b.min(v0, d);
        v0 = b.select(inside, v0, nearer);
    }
    let out = b.compose(v2, vec![v0, t0]);
    b.ret(Some(out));
    let f = b.finish();
    mb.add_helper("tape_eval", f)
}

/// `map`'s value from `tape_eval` (`eval`) at `p`.
pub(super) fn value(b: &mut FnBuilder, eval: Handle<Function>, p: Ex) -> Ex {
    let r = b.call(eval, vec![p]);
    b.at(r, 0)
}

/// `tape_eval`'s tag at `p`, as a u32.
fn tag_bits(b: &mut FnBuilder, eval: Handle<Function>, p: Ex) -> Ex {
    let r = b.call(eval, vec![p]);
    let bits = b.at(r, 1);
    b.bitcast(bits, ScalarKind::Uint)
}

/// `map_material`'s material (+ 1, 0 for none) from the tag.
pub(super) fn material(b: &mut FnBuilder, eval: Handle<Function>, p: Ex) -> Ex {
    let bits = tag_bits(b, eval, p);
    let material = b.u(!LOOSE);
    b.bin(naga::BinaryOperator::And, bits, material)
}

/// `map_loose`'s 1 or 0 from the tag's looseness bit (its highest).
pub(super) fn loose(b: &mut FnBuilder, eval: Handle<Function>, p: Ex) -> Ex {
    let bits = tag_bits(b, eval, p);
    let shift = b.u(LOOSE.trailing_zeros());
    b.bin(naga::BinaryOperator::ShiftRight, bits, shift)
}

/// One turn of the evaluator's loop: the instruction at `pc` (below `end`) of `words` run on
/// the stack, `pc` moved past it; the loop left at `end`.
fn instruction(
    b: &mut FnBuilder,
    at: Stack,
    (words, pc, end): (Ex, Ex, Ex),
    kinds: &[(Handle<Function>, &'static crate::catalog::Primitive)],
    p: Ex,
) {
    let here = b.load(pc);
    let done = b.ge(here, end);
    b.break_if(done);
    let ptr = b.index(words, here);
    let word = b.load(ptr);
    let op = b.at(word, 0);
    let one = b.u(1);
    let mut cases: Vec<Arm> = vec![
        (
            COMBINE,
            Box::new(move |b: &mut FnBuilder| combine(b, at, word)),
        ),
        (NEGATE, Box::new(move |b: &mut FnBuilder| negate(b, at))),
        (
            END,
            Box::new(move |b: &mut FnBuilder| end_fold(b, at, word)),
        ),
    ];
    for (i, &(f, kind)) in kinds.iter().enumerate() {
        cases.push((
            LEAF + i as u32,
            Box::new(move |b: &mut FnBuilder| leaf(b, at, (words, here, word), (f, kind), p)),
        ));
    }
    b.switch_(op, cases, |_| {});
    // A leaf moves on by its words, anything else by one.
    let leaf_op = b.u(LEAF);
    let is_leaf = b.ge(op, leaf_op);
    let size = b.at(word, 1);
    let count = b.u(!MOVED);
    let size = b.bin(naga::BinaryOperator::And, size, count);
    let step = b.select(is_leaf, size, one);
    let moved = b.add(here, step);
    b.store(pc, moved);
}

/// The evaluator's stack: pointers to its three arrays and its height.
#[derive(Clone, Copy)]
struct Stack {
    value: Ex,
    best: Ex,
    tag: Ex,
    sp: Ex,
}

/// The distance from `p` to the grid's box plus `margin`: outside it, a distance bound for the
/// parts the grid holds (they lie `margin` inside it: `tape::data::Layout::proxy`).
fn proxy(b: &mut FnBuilder, layout: &Layout, p: Ex, margin: f64) -> Ex {
    let [nx, ny, nz] = layout.n.map(|n| n as f64);
    let half = glam::DVec3::new(nx, ny, nz) * layout.size / 2.0;
    let center = b.vec3_lit(layout.lo + half);
    let half = b.vec3_lit(half);
    let rel = b.sub(p, center);
    let d = crate::catalog::gpu::prims::box_half(b, rel, half);
    let m = b.f(margin);
    b.add(d, m)
}

/// The range (first word, words) of the cell holding `p`, the last range where the grid does
/// not; and whether it does (none without a grid).
fn cell_range(b: &mut FnBuilder, layout: &Layout, ranges: Ex, p: Ex) -> (Ex, Option<Ex>) {
    let [nx, ny, nz] = layout.n;
    let total = b.u((nx * ny * nz) as u32);
    if nx * ny * nz == 0 {
        let ptr = b.index(ranges, total);
        return (b.load(ptr), None);
    }
    let lo = b.vec3_lit(layout.lo);
    let inv = b.f(1.0 / layout.size);
    let rel = b.sub(p, lo);
    let rel = b.mul(rel, inv);
    let c = b.math(naga::MathFunction::Floor, &[rel]);
    let zero = b.splat3(0.0);
    let n = b.vec3_lit(glam::DVec3::new(nx as f64, ny as f64, nz as f64));
    let above = b.bin(naga::BinaryOperator::GreaterEqual, c, zero);
    let below = b.bin(naga::BinaryOperator::Less, c, n);
    let above = b.expr(naga::Expression::Relational {
        fun: naga::RelationalFunction::All,
        argument: above,
    });
    let below = b.expr(naga::Expression::Relational {
        fun: naga::RelationalFunction::All,
        argument: below,
    });
    let inside = b.bin(naga::BinaryOperator::LogicalAnd, above, below);
    // (Clamped before the conversion: a point far outside would not fit a u32.)
    let top = b.vec3_lit(glam::DVec3::new(
        nx as f64 - 1.0,
        ny as f64 - 1.0,
        nz as f64 - 1.0,
    ));
    let c = b.clamp(c, zero, top);
    let c = b.cast(c, ScalarKind::Uint);
    let [x, y, z] = b.xyz(c);
    let (cnx, cny) = (b.u(nx as u32), b.u(ny as u32));
    let zy = b.mul(z, cny);
    let zy = b.add(zy, y);
    let zyx = b.mul(zy, cnx);
    let index = b.add(zyx, x);
    let index = b.select(inside, index, total);
    let ptr = b.index(ranges, index);
    (b.load(ptr), Some(inside))
}

/// The index of the entry `depth` below the stack's top (1: the top).
fn below_top(b: &mut FnBuilder, s: Stack, depth: u32) -> Ex {
    let sp = b.load(s.sp);
    let d = b.u(depth);
    b.sub(sp, d)
}

/// The stack's entry `k` (three pointers).
fn entry(b: &mut FnBuilder, s: Stack, k: Ex) -> [Ex; 3] {
    [b.index(s.value, k), b.index(s.best, k), b.index(s.tag, k)]
}

/// Pushes a value with its material bits.
fn push(b: &mut FnBuilder, s: Stack, value: Ex, tag: Ex) {
    let sp = b.load(s.sp);
    let [v, bst, t] = entry(b, s, sp);
    b.store(v, value);
    b.store(bst, value);
    b.store(t, tag);
    b.increment(s.sp);
}

/// `COMBINE`: the top (a child, negated if flagged) folded into the entry below.
fn combine(b: &mut FnBuilder, s: Stack, word: Ex) {
    let (one, two) = (b.u(1), b.u(2));
    let top = below_top(b, s, 1);
    let below = below_top(b, s, 2);
    let [cv, _, ct] = entry(b, s, top);
    let (cv, ct) = (b.load(cv), b.load(ct));
    let [av, ab, at] = entry(b, s, below);
    let (a, a_best, a_tag) = (b.load(av), b.load(ab), b.load(at));
    let flags = b.at(word, 1);
    let largest = b.bin(naga::BinaryOperator::And, flags, one);
    let largest = b.bin(naga::BinaryOperator::Equal, largest, one);
    let negate = b.bin(naga::BinaryOperator::And, flags, two);
    let negate = b.bin(naga::BinaryOperator::Equal, negate, two);
    let minus = b.neg(cv);
    let v = b.select(negate, minus, cv);
    let k = b.at(word, 2);
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
    // The material of the better; loose as the nearest is for a minimum, and where either is
    // for a maximum (more than `eval::loose` says: a hit confirmed where it need not be).
    let picked = b.select(better, ct, a_tag);
    let loose_bit = b.u(LOOSE);
    let either = b.bin(naga::BinaryOperator::InclusiveOr, ct, a_tag);
    let either = b.bin(naga::BinaryOperator::And, either, loose_bit);
    let with_either = b.bin(naga::BinaryOperator::InclusiveOr, picked, either);
    let tag = b.select(largest, with_either, picked);
    b.store(av, value);
    b.store(ab, best);
    b.store(at, tag);
    b.store(s.sp, top);
}

/// `NEGATE`: the top's value negated.
fn negate(b: &mut FnBuilder, s: Stack) {
    let top = below_top(b, s, 1);
    let [v, bst, _] = entry(b, s, top);
    let x = b.load(v);
    let x = b.neg(x);
    b.store(v, x);
    b.store(bst, x);
}

/// `END`: the fold's result times its factor, its material where it picked none.
fn end_fold(b: &mut FnBuilder, s: Stack, word: Ex) {
    let top = below_top(b, s, 1);
    let [v, bst, t] = entry(b, s, top);
    let factor = b.at(word, 2);
    let factor = b.bitcast(factor, ScalarKind::Float);
    let x = b.load(v);
    let x = b.mul(x, factor);
    b.store(v, x);
    b.store(bst, x);
    let own = b.at(word, 3);
    let tag = b.load(t);
    let loose_bit = b.u(LOOSE);
    let material_bits = b.u(!LOOSE);
    let picked = b.bin(naga::BinaryOperator::And, tag, material_bits);
    let given = b.bin(naga::BinaryOperator::And, own, material_bits);
    let zero = b.u(0);
    let has = b.bin(naga::BinaryOperator::NotEqual, picked, zero);
    let material = b.select(has, picked, given);
    let loose = b.bin(naga::BinaryOperator::InclusiveOr, tag, own);
    let loose = b.bin(naga::BinaryOperator::And, loose, loose_bit);
    let tag = b.bin(naga::BinaryOperator::InclusiveOr, material, loose);
    b.store(t, tag);
}

/// A leaf: its frame's point, its arguments from the words after the header, `sd_<kind>`.
fn leaf(
    b: &mut FnBuilder,
    s: Stack,
    (words, here, header): (Ex, Ex, Ex),
    (f, kind): (Handle<Function>, &'static crate::catalog::Primitive),
    p: Ex,
) {
    let word = |b: &mut FnBuilder, k: u32| {
        let offset = b.u(k);
        let at = b.add(here, offset);
        let ptr = b.index(words, at);
        let w = b.load(ptr);
        b.bitcast(w, ScalarKind::Float)
    };
    let mut q = Vec::with_capacity(3);
    let mut t = Vec::with_capacity(3);
    for row in 1..=3 {
        let r = word(b, row);
        let m = b.swizzle(r, &[0, 1, 2]);
        t.push(b.at(r, 3));
        let d = b.dot(m, p);
        q.push(b.add(d, t[row as usize - 1]));
    }
    let turned = b.compose_vec3([q[0], q[1], q[2]]);
    let offset = b.compose_vec3([t[0], t[1], t[2]]);
    let moved = b.add(p, offset);
    let count = b.at(header, 1);
    let flag = b.u(MOVED);
    let only = b.bin(naga::BinaryOperator::And, count, flag);
    let only = b.bin(naga::BinaryOperator::Equal, only, flag);
    let q = b.select(only, moved, turned);
    let mut args = vec![q];
    for (i, param) in kind.params.iter().enumerate() {
        let w = word(b, 4 + i as u32);
        args.push(match param.ty {
            crate::catalog::Ty::Count
            | crate::catalog::Ty::CountTo(_)
            | crate::catalog::Ty::WholeIn(..) => {
                let x = b.at(w, 0);
                b.cast(x, ScalarKind::Uint)
            }
            ty if crate::tape::program::vector(ty) => b.swizzle(w, &[0, 1, 2]),
            _ => b.at(w, 0),
        });
    }
    let d = b.call(f, args);
    let factor = b.at(header, 2);
    let factor = b.bitcast(factor, ScalarKind::Float);
    let d = b.mul(d, factor);
    let tag = b.at(header, 3);
    push(b, s, d, tag);
}
