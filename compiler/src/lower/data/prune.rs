//! The data form's pre-pass on the GPU (issue 33 §2): a compute entry that prunes each cell of
//! one grid from the program of the coarser cell holding it — `tape::cells`' pruning (Barbier,
//! Sanchez et al. 2025, §4) done on the programs themselves — and writes the cell's program as
//! `tape::program::encode` writes it.
//!
//! One invocation a cell. The first walk runs the parent cell's program at the cell's centre,
//! copying it into room taken from a shared counter, and keeps for each open fold its running
//! value and the bounds `cells::keep` keeps; a child that cannot change its fold's result over
//! the cell is overwritten with [`DROPPED`], and so are the children before one that replaces
//! them. The second walk packs what is left in place and sets each part's `FIRST` and `SPILL`
//! again from its parent (`Table::meta`): a leaf whose parent is not open opens the folds above
//! it up to one that is, the first of them not first in its own parent.

mod first;
mod pack;

use crate::catalog::Primitive;
use crate::ir::{Ex, FnBuilder, ModuleBuilder};
use crate::layout::{PRUNE_BINDINGS, PRUNE_COUNTER_FIELDS, PRUNE_LEVEL_BYTES, PRUNE_LEVEL_FIELDS};
use naga::{
    AddressSpace, ArraySize, BinaryOperator as Op, Binding, BuiltIn, Expression, Function, Handle,
    Scalar, ScalarKind, StorageAccess, TypeInner, VectorSize,
};

/// What the first walk writes over a dropped part's instruction (no part has this offset).
pub const DROPPED: u32 = u32::MAX;

/// The margin on the cells' half-diagonal (f32's rounding of the cell's size and centre).
const MARGIN: f64 = 1.0 / 65536.0;

/// A value no bound reaches (an unproven child's bounds: shaders have no infinities).
const BIG: f64 = 1e30;

/// The entry's buffers.
#[derive(Clone, Copy)]
pub(super) struct Buffers {
    nodes: Ex,
    meta: Ex,
    code: Ex,
    scratch: Ex,
}

/// One cell's walk: its parent's program (`from`, `len` instructions) and its own room
/// (`start`).
#[derive(Clone, Copy)]
pub(super) struct Walk {
    bufs: Buffers,
    from: Ex,
    len: Ex,
    start: Ex,
}

/// Adds `main`, the pre-pass over one grid (`layout::PRUNE_BINDINGS`), for a table of leaves
/// of `kinds` whose folds nest at most `height` deep; the module must have their `sd_`
/// functions.
pub(in crate::lower) fn add(mb: &mut ModuleBuilder, kinds: &[&'static Primitive], height: usize) {
    let globals = declare(mb);
    let kinds: Vec<(Handle<Function>, &'static Primitive)> = kinds
        .iter()
        .map(|k| (mb.helper(&format!("sd_{}", k.name)), *k))
        .collect();
    let (uvec3, uvec2) = (mb.uvec(VectorSize::Tri), mb.uvec(VectorSize::Bi));
    let mut b = FnBuilder::new(mb, "main", &[("gid", uvec3)], None);
    b.func.arguments[0].binding = Some(Binding::BuiltIn(BuiltIn::GlobalInvocationId));
    let gid = b.arg(0);
    let [nodes, meta, code, ranges, level, counter, scratch] =
        globals.map(|g| b.expr(Expression::GlobalVariable(g)));
    let field = |b: &mut FnBuilder, name: &str| {
        let i = PRUNE_LEVEL_FIELDS.iter().position(|(n, _)| *n == name);
        let p = b.at(level, i.expect("a field of the level") as u32);
        b.load(p)
    };
    let first_cell = field(&mut b, "first_cell");
    let cell = b.at(gid, 0);
    let cell = b.add(cell, first_cell);
    let total = field(&mut b, "total");
    let past = b.ge(cell, total);
    b.if_(past, |b| b.ret(None), |_| {});
    let n = field(&mut b, "n");
    let xyz = cell_of(&mut b, n, cell);
    let (up, split) = (field(&mut b, "up"), field(&mut b, "split"));
    let parent = parent_of(&mut b, (up, split), xyz);
    let in_base = field(&mut b, "in_base");
    let at = b.add(in_base, parent);
    let ptr = b.index(ranges, at);
    let range = b.load(ptr);
    let (from, len) = (b.at(range, 0), b.at(range, 1));
    let out_base = field(&mut b, "out_base");
    let out_at = b.add(out_base, cell);
    let out = b.index(ranges, out_at);
    let room = Room {
        counter,
        out,
        empty: uvec2,
    };
    let scratch_room = field(&mut b, "scratch_capacity");
    let start = room.take(&mut b, COUNTER_SCRATCH, len, scratch_room);
    let (lo, size) = (field(&mut b, "lo"), field(&mut b, "size"));
    let centre = centre_of(&mut b, xyz, (lo, size));
    let half_diagonal = b.f(3f64.sqrt() / 2.0 * (1.0 + MARGIN));
    let radius = b.mul(size, half_diagonal);
    let scale = field(&mut b, "scale");
    let bufs = Buffers {
        nodes,
        meta,
        code,
        scratch,
    };
    let walk = Walk {
        bufs,
        from,
        len,
        start,
    };
    let root = first::walk(&mut b, walk, &kinds, (centre, radius, scale), height);
    let (kept, leaves) = pack::walk(&mut b, walk, height);
    // The cell's program, from its scratch to the programs' buffer.
    let capacity = field(&mut b, "capacity");
    let to = room.take(&mut b, COUNTER_NEXT, kept, capacity);
    b.repeat("c", kept, |b, k| {
        let at = b.add(start, k);
        let p = b.index(scratch, at);
        let w = b.load(p);
        let at = b.add(to, k);
        let p = b.index(code, at);
        b.store(p, w);
    });
    let counting = field(&mut b, "count_leaves");
    let zero = b.u(0);
    let counting = b.bin(Op::NotEqual, counting, zero);
    let count = far_count(&mut b, (root, kept), (nodes, meta), (size, counting));
    let range = b.compose(uvec2, vec![to, count]);
    b.store(out, range);
    b.if_(
        counting,
        |b| {
            let total = b.at(counter, COUNTER_LEAVES);
            b.atomic_add(total, leaves);
        },
        |_| {},
    );
    let f = b.finish();
    super::super::entry::compute_main(mb, f, [crate::layout::PRUNE_WORKGROUP, 1, 1]);
}

/// The cell's count: `kept` words, marked far with its clearance (`tape::data::far_count`)
/// where this is the layout's grid (`last`), the root is a proven fold, and its value's lower
/// bound over the cell (its frame's, `first::Root::lower`) is at least the cell's
/// half-diagonal (cells of edge `size`).
fn far_count(
    b: &mut FnBuilder,
    (root, kept): (first::Root, Ex),
    (nodes, meta): (Ex, Ex),
    (size, last): (Ex, Ex),
) -> Ex {
    use crate::tape::data::{FAR, FAR_LENGTH, FAR_MOST, FAR_SHIFT, FAR_STEPS};
    let zero = b.u(0);
    let ptr = b.index(nodes, zero);
    let head = b.load(ptr);
    let ptr = b.index(meta, zero);
    let m = b.load(ptr);
    let proven = b.at(m, 1);
    let proven = b.bin(Op::NotEqual, proven, zero);
    let lower = root.lower(b, head);
    // (f32's rounding of the frame's few operations.)
    let slack = b.abs(lower);
    let tiny = b.f(1.0 / 1_048_576.0);
    let slack = b.mul(slack, tiny);
    let lower = b.sub(lower, slack);
    let half_diagonal = b.f(3f64.sqrt() / 2.0);
    let radius = b.mul(size, half_diagonal);
    let clear = b.ge(lower, radius);
    let short = b.u(FAR_LENGTH);
    let short = b.le(kept, short);
    let mut far = b.bin(Op::LogicalAnd, root.fold, proven);
    for c in [clear, short, last] {
        far = b.bin(Op::LogicalAnd, far, c);
    }
    let steps = b.div(lower, size);
    let per = b.f(FAR_STEPS);
    let steps = b.mul(steps, per);
    let steps = b.math(naga::MathFunction::Floor, &[steps]);
    let most = b.f(f64::from(FAR_MOST));
    let steps = b.min(steps, most);
    let zerof = b.f(0.0);
    let steps = b.max(steps, zerof);
    let steps = b.cast(steps, ScalarKind::Uint);
    let shift = b.u(FAR_SHIFT);
    let steps = b.bin(Op::ShiftLeft, steps, shift);
    let bit = b.u(FAR);
    let marked = b.bin(Op::InclusiveOr, bit, steps);
    let marked = b.bin(Op::InclusiveOr, marked, kept);
    b.select(far, marked, kept)
}

/// The counter's fields (`layout::PRUNE_COUNTER_FIELDS`).
const COUNTER_NEXT: u32 = 0;
const COUNTER_OVERFLOW: u32 = 1;
const COUNTER_LEAVES: u32 = 2;
const COUNTER_SCRATCH: u32 = 3;

/// Where a cell takes room from a counter: the counter, the cell's range (left empty where
/// there is no room) and its type.
#[derive(Clone, Copy)]
struct Room {
    counter: Ex,
    out: Ex,
    empty: Handle<naga::Type>,
}

impl Room {
    /// `words` taken from the counter's field `field` within `capacity`: their first word; where
    /// they do not fit, the overflow counted, the cell's range left empty and the invocation
    /// ended (the host then runs the pre-pass again with more room).
    fn take(self, b: &mut FnBuilder, field: u32, words: Ex, capacity: Ex) -> Ex {
        // (The host tells the two apart: the programs' buffer counts ones, the scratch 2¹⁶s.)
        let missed = if field == COUNTER_SCRATCH {
            crate::layout::PRUNE_SCRATCH_MISSED
        } else {
            1
        };
        let next = b.at(self.counter, field);
        let start = b.atomic_add(next, words);
        let too_long = b.gt(words, capacity);
        let room = b.sub(capacity, words);
        let beyond = b.gt(start, room);
        let over = b.bin(Op::LogicalOr, too_long, beyond);
        b.if_(
            over,
            |b| {
                let overflow = b.at(self.counter, COUNTER_OVERFLOW);
                let missed = b.u(missed);
                b.atomic_add(overflow, missed);
                let zero = b.u(0);
                let none = b.compose(self.empty, vec![zero, zero]);
                b.store(self.out, none);
                b.ret(None);
            },
            |_| {},
        );
        start
    }
}

/// The table, meta, programs, ranges, level, counter and scratch globals, in
/// `PRUNE_BINDINGS`' order.
fn declare(mb: &mut ModuleBuilder) -> [Handle<naga::GlobalVariable>; 7] {
    let (u32t, f32t, v3) = (mb.u32(), mb.f32(), mb.vec3());
    let (uvec4, uvec3, uvec2) = (
        mb.uvec(VectorSize::Quad),
        mb.uvec(VectorSize::Tri),
        mb.uvec(VectorSize::Bi),
    );
    let array = |mb: &mut ModuleBuilder, base, stride| {
        mb.ty(TypeInner::Array {
            base,
            size: ArraySize::Dynamic,
            stride,
        })
    };
    let read = AddressSpace::Storage {
        access: StorageAccess::LOAD,
    };
    let write = AddressSpace::Storage {
        access: StorageAccess::LOAD | StorageAccess::STORE,
    };
    let level_types = [
        v3, f32t, uvec3, u32t, uvec3, u32t, u32t, u32t, u32t, f32t, u32t, u32t, u32t,
    ];
    let members: Vec<(&str, Handle<naga::Type>, u32)> = PRUNE_LEVEL_FIELDS
        .iter()
        .zip(level_types)
        .map(|(&(n, offset), ty)| (n, ty, offset))
        .collect();
    let level_ty = super::super::globals::struct_ty(mb, "Level", &members, PRUNE_LEVEL_BYTES);
    let atomic = mb.ty(TypeInner::Atomic(Scalar::U32));
    let counter_members: Vec<(&str, Handle<naga::Type>, u32)> = PRUNE_COUNTER_FIELDS
        .iter()
        .enumerate()
        .map(|(i, n)| (*n, atomic, 4 * i as u32))
        .collect();
    let counter_ty = super::super::globals::struct_ty(mb, "Counter", &counter_members, 16);
    let tys = [
        (array(mb, uvec4, 16), read, "tape_nodes"),
        (array(mb, uvec4, 16), read, "tape_meta"),
        (array(mb, u32t, 4), write, "tape_code"),
        (array(mb, uvec2, 8), write, "tape_ranges"),
        (level_ty, AddressSpace::Uniform, "level"),
        (counter_ty, write, "counter"),
        (array(mb, u32t, 4), write, "tape_scratch"),
    ];
    let mut i = 0;
    tys.map(|(ty, space, name)| {
        let g = super::super::globals::global(mb, name, ty, space, PRUNE_BINDINGS[i]);
        i += 1;
        g
    })
}

/// The cell's x, y and z from its index (x fastest) in a grid of `n` cells a side.
fn cell_of(b: &mut FnBuilder, n: Ex, cell: Ex) -> [Ex; 3] {
    let (nx, ny) = (b.at(n, 0), b.at(n, 1));
    let x = b.bin(Op::Modulo, cell, nx);
    let row = b.div(cell, nx);
    let y = b.bin(Op::Modulo, row, ny);
    let z = b.div(row, ny);
    [x, y, z]
}

/// The index of the coarser grid's cell (`up` cells a side, `split` fine cells a side each)
/// that holds cell `xyz`.
fn parent_of(b: &mut FnBuilder, (up, split): (Ex, Ex), xyz: [Ex; 3]) -> Ex {
    let [x, y, z] = xyz.map(|c| b.div(c, split));
    let (ux, uy) = (b.at(up, 0), b.at(up, 1));
    let t = b.mul(uy, z);
    let t = b.add(y, t);
    let t = b.mul(ux, t);
    b.add(x, t)
}

/// The centre of cell `xyz` of the grid from `lo` of cells of edge `size`.
fn centre_of(b: &mut FnBuilder, xyz: [Ex; 3], (lo, size): (Ex, Ex)) -> Ex {
    let c = xyz.map(|c| b.cast(c, ScalarKind::Float));
    let c = b.compose_vec3(c);
    let half = b.splat3(0.5);
    let c = b.add(c, half);
    let c = b.mul(c, size);
    b.add(lo, c)
}

/// A function-local array of `height` (at least one) elements of `base`.
pub(super) fn array_of(
    b: &mut FnBuilder,
    base: Handle<naga::Type>,
    height: usize,
) -> Handle<naga::Type> {
    let size = std::num::NonZeroU32::new(height.max(1) as u32).expect("at least one");
    b.m.ty(TypeInner::Array {
        base,
        size: ArraySize::Constant(size),
        stride: 4,
    })
}
