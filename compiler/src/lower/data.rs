//! The data form's evaluator (issue 33): `tape_eval(p)` runs the program of the grid cell that
//! holds `p` (`crate::tape::program`: a table of parts, the cells' programs and their ranges in
//! three storage buffers) with a running value in registers and a small stack for nested folds,
//! one `switch` arm per primitive kind the scene uses, and returns vec2(value, tag bits): the
//! material + 1 and the looseness bit (`program::LOOSE`); `map`, `map_material` and
//! `map_loose` read it; where the scene blends materials, `tape_blend(p)` walks the same way
//! and gives `map_blend` its blend (`data/blend.rs`). The code does not grow with the number of
//! parts.

mod blend;
mod far;
mod grid;
mod join;
pub(super) mod prune;

use crate::ir::{Arm, Ex, FnBuilder, ModuleBuilder};
use crate::layout;
use crate::tape::data::Layout;
use crate::tape::program::{END, FIRST, LOOSE, MATERIAL, MOVED, OFFSET, SPILL};
use grid::{cell_range, proxy};
use join::{end_tag, flag, fold_in, has_bit, start};
use naga::{
    AddressSpace, ArraySize, Function, Handle, ScalarKind, StorageAccess, TypeInner, VectorSize,
};

/// The data form's evaluators: `tape_eval`, `tape_blend` where the scene blends materials
/// (see [`blend_at`]), and `tape_trace`, the camera's trace's `map` where the scene has a grid
/// (far cells answer with their clearance: `far.rs`).
pub(super) struct Evaluators {
    pub eval: Handle<Function>,
    pub blend: Option<Handle<Function>>,
    pub trace: Option<Handle<Function>>,
}

/// Declares the buffers and adds the evaluators (`tape_blend` with `blends`).
pub(super) fn add(mb: &mut ModuleBuilder, layout: &Layout, blends: bool) -> Evaluators {
    let u32t = mb.u32();
    let uvec4 = mb.uvec(VectorSize::Quad);
    let uvec2 = mb.uvec(VectorSize::Bi);
    let read = AddressSpace::Storage {
        access: StorageAccess::LOAD,
    };
    let array = |mb: &mut ModuleBuilder, base, stride| {
        mb.ty(TypeInner::Array {
            base,
            size: ArraySize::Dynamic,
            stride,
        })
    };
    let (nodes_ty, code_ty, ranges_ty) = (
        array(mb, uvec4, 16),
        array(mb, u32t, 4),
        array(mb, uvec2, 8),
    );
    let [n, c, r] = layout::TAPE_BINDINGS;
    let nodes = super::globals::global(mb, "tape_nodes", nodes_ty, read, n);
    let code = super::globals::global(mb, "tape_code", code_ty, read, c);
    let ranges = super::globals::global(mb, "tape_ranges", ranges_ty, read, r);
    let buffers = [nodes, code, ranges];
    let grid = layout.n.iter().product::<usize>() > 0;
    Evaluators {
        eval: evaluator(mb, layout, buffers, Kind::Eval),
        blend: blends.then(|| evaluator(mb, layout, buffers, Kind::Blend)),
        trace: grid.then(|| evaluator(mb, layout, buffers, Kind::Trace)),
    }
}

/// The evaluator over the buffers: `tape_eval(p) -> vec2(value, tag bits)`, or with `blend`
/// `tape_blend(p) -> vec3` (the blended materials at `p`: `blend::fold`'s rule on the same
/// walk).
/// What an evaluator returns: `tape_eval`'s value and tag, `tape_blend`'s blend, or
/// `tape_trace`'s value, which a far cell answers with its clearance (`far.rs`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Eval,
    Blend,
    Trace,
}

fn evaluator(
    mb: &mut ModuleBuilder,
    layout: &Layout,
    [nodes, code, ranges]: [Handle<naga::GlobalVariable>; 3],
    kind: Kind,
) -> Handle<Function> {
    let blend = kind == Kind::Blend;
    let (u32t, f32t) = (mb.u32(), mb.f32());
    // (As deep as the scene's tree needs: none for one fold of leaves.)
    let stack_ty = |mb: &mut ModuleBuilder, base| {
        let size = ArraySize::Constant(std::num::NonZeroU32::new(layout.depth as u32)?);
        let stride = 4;
        Some(mb.ty(TypeInner::Array { base, size, stride }))
    };
    let stack_tys = stack_ty(mb, f32t).zip(stack_ty(mb, u32t));
    let v3 = mb.vec3();
    let v2 = mb.vec(VectorSize::Bi);
    let blend_stack_ty = (layout.depth > 0 && blend).then(|| {
        let size = ArraySize::Constant(std::num::NonZeroU32::new(layout.depth as u32).unwrap());
        mb.ty(TypeInner::Array {
            base: v3,
            size,
            stride: 16,
        })
    });
    let (name, ret) = match kind {
        Kind::Blend => ("tape_blend", v3),
        Kind::Eval => ("tape_eval", v2),
        Kind::Trace => ("tape_trace", f32t),
    };
    let kinds: Vec<(Handle<Function>, &'static crate::catalog::Primitive)> = layout
        .kinds
        .iter()
        .map(|k| (mb.helper(&format!("sd_{}", k.name)), *k))
        .collect();
    let mut b = FnBuilder::new(mb, name, &[("p", v3)], Some(ret));
    let p = b.arg(0);
    let nodes = b.expr(naga::Expression::GlobalVariable(nodes));
    let code = b.expr(naga::Expression::GlobalVariable(code));
    let ranges = b.expr(naga::Expression::GlobalVariable(ranges));
    let (range, inside) = cell_range(&mut b, layout, ranges, p);
    if let (Kind::Trace, Some((inside, grid))) = (kind, &inside) {
        far::answer(&mut b, range, *inside, grid);
    }
    let start = b.at(range, 0);
    let len = b.at(range, 1);
    let len = grid::length(&mut b, len);
    let end = b.add(start, len);
    // An empty program (outside a grid that holds every part) leaves "nothing here".
    let far = b.f(crate::ir::FAR);
    let zero = b.u(0);
    let running = [
        b.local("value", f32t, Some(far)),
        b.local("best", f32t, Some(far)),
        b.local("tag", u32t, Some(zero)),
    ];
    let stack = stack_tys.map(|(values_ty, tags_ty)| Stack {
        value: b.local("stack_value", values_ty, None),
        best: b.local("stack_best", values_ty, None),
        tag: b.local("stack_tag", tags_ty, None),
        sp: b.local("sp", u32t, Some(zero)),
    });
    let none = b.splat3(0.0);
    let blends = blend.then(|| Blends {
        running: b.local("blend", v3, Some(none)),
        stack: blend_stack_ty.map(|ty| b.local("stack_blend", ty, None)),
    });
    let pc = b.local("pc", u32t, Some(start));
    let at = Eval {
        nodes,
        running,
        stack,
        blends,
    };
    b.loop_(|b| instruction(b, at, (code, pc, end), &kinds, p));
    if let Some(blends) = blends {
        let out = b.load(blends.running);
        b.ret(Some(out));
        let f = b.finish();
        return mb.add_helper(name, f);
    }
    let mut v0 = b.load(running[0]);
    let t0 = b.load(running[2]);
    let t0 = b.bitcast(t0, ScalarKind::Float);
    if let (Some(_), Some((inside, grid))) = (layout.proxy, inside) {
        let d = proxy(&mut b, &grid, p);
        let nearer = b.min(v0, d);
        v0 = b.select(inside, v0, nearer);
    }
    let out = match kind {
        Kind::Trace => v0,
        _ => b.compose(v2, vec![v0, t0]),
    };
    b.ret(Some(out));
    let f = b.finish();
    mb.add_helper(name, f)
}

/// `map_blend`'s blended materials from `tape_blend` (`blend`) at `p`.
pub(super) fn blend_at(b: &mut FnBuilder, blend: Handle<Function>, p: Ex) -> Ex {
    b.call(blend, vec![p])
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
    let material = b.u(MATERIAL);
    b.bin(naga::BinaryOperator::And, bits, material)
}

/// `map_loose`'s 1 or 0 from the tag's looseness bit (its highest).
pub(super) fn loose(b: &mut FnBuilder, eval: Handle<Function>, p: Ex) -> Ex {
    let bits = tag_bits(b, eval, p);
    let shift = b.u(LOOSE.trailing_zeros());
    b.bin(naga::BinaryOperator::ShiftRight, bits, shift)
}

/// One turn of the evaluator's loop: the instruction at `pc` (below `end`) of `code` run,
/// `pc` moved past it; the loop left at `end`.
fn instruction(
    b: &mut FnBuilder,
    at: Eval,
    (code, pc, end): (Ex, Ex, Ex),
    kinds: &[(Handle<Function>, &'static crate::catalog::Primitive)],
    p: Ex,
) {
    let here = b.load(pc);
    let done = b.ge(here, end);
    b.break_if(done);
    let ptr = b.index(code, here);
    let ins = b.load(ptr);
    let one = b.u(1);
    let next = b.add(here, one);
    b.store(pc, next);
    let mask = b.u(OFFSET);
    let offset = b.bin(naga::BinaryOperator::And, ins, mask);
    let ptr = b.index(at.nodes, offset);
    let head = b.load(ptr);
    let first = has_bit(b, ins, FIRST);
    let is_end = has_bit(b, ins, END);
    let factor = b.at(head, 2);
    let factor = b.bitcast(factor, ScalarKind::Float);
    let own = b.at(head, 3);
    b.if_(
        is_end,
        |b| {
            let [v, _, tag] = at.running.map(|r| b.load(r));
            let v = b.mul(v, factor);
            let tag = end_tag(b, tag, own, head);
            let ended = at.blends.map(|bl| {
                let r = b.load(bl.running);
                (bl, blend::end(b, r, own))
            });
            let started = |b: &mut FnBuilder| {
                let x = start(b, (v, tag), head);
                set(b, at.running, x);
                if let Some((bl, cb)) = ended {
                    b.store(bl.running, cb);
                }
            };
            // (Without a stack every fold is a first part.)
            let Some(stack) = at.stack else {
                return started(b);
            };
            b.if_(first, started, |b| {
                let sp = b.decrement(stack.sp);
                let below = stack.entry(b, sp).map(|e| b.load(e));
                let x = fold_in(b, below, (v, tag), head);
                set(b, at.running, x);
                if let (Some((bl, cb)), Some(entries)) = (ended, at.blends.and_then(|x| x.stack)) {
                    let ptr = b.index(entries, sp);
                    let under = b.load(ptr);
                    let nb = blend::fold(b, (below[0], v), head, (under, cb));
                    b.store(bl.running, nb);
                }
            });
        },
        |b| {
            let d = leaf(b, at.nodes, (offset, head), kinds, p);
            let v = b.mul(d, factor);
            let own_blend = at.blends.map(|bl| (bl, blend::plain(b, own)));
            b.if_(
                first,
                |b| {
                    if let Some(stack) = at.stack {
                        let spill = has_bit(b, ins, SPILL);
                        b.if_(spill, |b| push(b, at, stack), |_| {});
                    }
                    let x = start(b, (v, own), head);
                    set(b, at.running, x);
                    if let Some((bl, lb)) = own_blend {
                        b.store(bl.running, lb);
                    }
                },
                |b| {
                    let a = at.running.map(|r| b.load(r));
                    let x = fold_in(b, a, (v, own), head);
                    set(b, at.running, x);
                    if let Some((bl, lb)) = own_blend {
                        let run = b.load(bl.running);
                        let nb = blend::fold(b, (a[0], v), head, (run, lb));
                        b.store(bl.running, nb);
                    }
                },
            );
        },
    );
}

/// Pushes the running value (and blend) onto the stack: a first part whose fold's running
/// value below must be kept for a later fold (`program::SPILL`).
fn push(b: &mut FnBuilder, at: Eval, stack: Stack) {
    let sp = b.load(stack.sp);
    let to = stack.entry(b, sp);
    for (to, from) in to.into_iter().zip(at.running) {
        let x = b.load(from);
        b.store(to, x);
    }
    if let Some(Blends {
        running,
        stack: Some(entries),
    }) = at.blends
    {
        let to = b.index(entries, sp);
        let x = b.load(running);
        b.store(to, x);
    }
    b.increment(stack.sp);
}

/// What the evaluator's loop works on: the table, the running value (value, best, tag) and
/// the stack (none where no program needs one).
#[derive(Clone, Copy)]
struct Eval {
    nodes: Ex,
    running: [Ex; 3],
    stack: Option<Stack>,
    /// The running blend and its stack, in `tape_blend`.
    blends: Option<Blends>,
}

/// Pointers to the running blend (vec3) and to its stack (none without a stack).
#[derive(Clone, Copy)]
struct Blends {
    running: Ex,
    stack: Option<Ex>,
}

/// The evaluator's stack: pointers to its three arrays and its height.
#[derive(Clone, Copy)]
struct Stack {
    value: Ex,
    best: Ex,
    tag: Ex,
    sp: Ex,
}

impl Stack {
    /// Pointers to entry `k`'s value, best and tag.
    fn entry(self, b: &mut FnBuilder, k: Ex) -> [Ex; 3] {
        [
            b.index(self.value, k),
            b.index(self.best, k),
            b.index(self.tag, k),
        ]
    }
}

/// Stores (value, best, tag) into the running value's three variables.
fn set(b: &mut FnBuilder, running: [Ex; 3], values: [Ex; 3]) {
    for (to, v) in running.into_iter().zip(values) {
        b.store(to, v);
    }
}

/// A leaf's raw field: its frame's point (one word if it only moves, else three rows), its
/// arguments from the words after the frame, `sd_<kind>` by a `switch` on its kind.
fn leaf(
    b: &mut FnBuilder,
    nodes: Ex,
    (offset, head): (Ex, Ex),
    kinds: &[(Handle<Function>, &'static crate::catalog::Primitive)],
    p: Ex,
) -> Ex {
    let word = |b: &mut FnBuilder, base: Ex, k: u32| {
        let k = b.u(k);
        let at = b.add(base, k);
        let ptr = b.index(nodes, at);
        let w = b.load(ptr);
        b.bitcast(w, ScalarKind::Float)
    };
    let v3 = b.m.vec3();
    let (f32t, u32t) = (b.m.f32(), b.m.u32());
    let q = b.local("q", v3, None);
    let args = b.local("args", u32t, None);
    let moved = flag(b, head, MOVED);
    b.if_(
        moved,
        |b| {
            let t = word(b, offset, 1);
            let t = b.swizzle(t, &[0, 1, 2]);
            let x = b.add(p, t);
            b.store(q, x);
            let two = b.u(2);
            let a = b.add(offset, two);
            b.store(args, a);
        },
        |b| {
            let mut c = Vec::with_capacity(3);
            for row in 1..=3 {
                let r = word(b, offset, row);
                let m = b.swizzle(r, &[0, 1, 2]);
                let t = b.at(r, 3);
                let d = b.dot(m, p);
                c.push(b.add(d, t));
            }
            let x = b.compose_vec3([c[0], c[1], c[2]]);
            b.store(q, x);
            let four = b.u(4);
            let a = b.add(offset, four);
            b.store(args, a);
        },
    );
    let far = b.f(crate::ir::FAR);
    let d = b.local("d", f32t, Some(far));
    let kind = b.at(head, 0);
    let low = b.u(0xff);
    let kind = b.bin(naga::BinaryOperator::And, kind, low);
    let mut cases: Vec<Arm> = Vec::with_capacity(kinds.len());
    for (i, &(f, prim)) in kinds.iter().enumerate() {
        cases.push((
            i as u32,
            Box::new(move |b: &mut FnBuilder| {
                let point = b.load(q);
                let base = b.load(args);
                let mut call = vec![point];
                for (j, param) in prim.params.iter().enumerate() {
                    let w = word(b, base, j as u32);
                    call.push(match param.ty {
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
                let x = b.call(f, call);
                b.store(d, x);
            }),
        ));
    }
    b.switch_(kind, cases, |_| {});
    b.load(d)
}
