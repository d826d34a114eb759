//! The list entries of the tests: the ray list (one ray — origin, direction, footprint, start —
//! in, one `vec4(t, steps, flags, cover)` out per invocation) and the field list (one point in,
//! `map` at it out).

use super::camera::storage_array;
use super::entry::compute_main;
use super::fns::Tracer;
use super::tracer::Pass;
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::layout::{self, FIELD_WORKGROUP, RAYS_WORKGROUP};
use naga::{Binding, BuiltIn, Expression, Function, Handle, ScalarKind, VectorSize};

/// The ray-list compute entry ([`Entry::Rays`]), 64 rays per workgroup.
pub(super) fn add_rays(mb: &mut ModuleBuilder, tracer: &Tracer) {
    let List {
        mut b,
        i,
        input,
        out,
        v4,
    } = List::new(mb, ["rays", "hits"]);
    let two = b.u(2);
    let first = b.mul(i, two);
    let one = b.u(1);
    let second = b.add(first, one);
    let [o, d] = [first, second].map(|index| {
        let ptr = b.expr(Expression::Access { base: input, index });
        b.load(ptr)
    });
    let ro = b.swizzle(o, &[0, 1, 2]);
    let rd = b.swizzle(d, &[0, 1, 2]);
    let pixel = b.at(o, 3);
    let start = b.at(d, 3);
    let budget = b.u(tracer.steps);
    let cone = b.f(0.0);
    let pass = Pass {
        start,
        budget,
        cone,
    };
    let r = tracer.call(&mut b, ro, rd, pixel, Some(pass));
    let t = b.at(r, 0);
    let s = b.at(r, 1);
    let s = b.cast(s, ScalarKind::Float);
    let fl = b.at(r, 2);
    let fl = b.cast(fl, ScalarKind::Float);
    let fourth = if tracer.antialias {
        b.at(r, 4)
    } else {
        b.f(0.0)
    };
    let v = b.compose(v4, vec![t, s, fl, fourth]);
    let f = List::store(b, (out, i), v);
    compute_main(mb, f, [RAYS_WORKGROUP, 1, 1]);
}

/// The field-list compute entry ([`Entry::Field`](super::Entry::Field)), 64 points per
/// workgroup: `vec4(map(p), map(p)·λ, 0, 0)` for each point `p` (the `xyz` of its vec4), λ the
/// root's bound, so that `y` is the root's raw field (up to one f32 rounding when λ ≠ 1).
pub(super) fn add_field(mb: &mut ModuleBuilder, map: Handle<Function>, lambda: f64) {
    let List {
        mut b,
        i,
        input,
        out,
        v4,
    } = List::new(mb, ["points", "values"]);
    let ptr = b.expr(Expression::Access {
        base: input,
        index: i,
    });
    let q = b.load(ptr);
    let p = b.swizzle(q, &[0, 1, 2]);
    let d = b.call(map, vec![p]);
    let raw = if lambda == 1.0 {
        d
    } else {
        let l = b.f(lambda);
        b.mul(d, l)
    };
    let zero = b.f(0.0);
    let v = b.compose(v4, vec![d, raw, zero, zero]);
    let f = List::store(b, (out, i), v);
    compute_main(mb, f, [FIELD_WORKGROUP, 1, 1]);
}

/// What the two list entries share: an input and an output array of vec4 (bindings 0 and 1),
/// `main` with the invocation's index `i`, returning early past the output's end.
struct List<'m> {
    b: FnBuilder<'m>,
    i: Ex,
    input: Ex,
    out: Ex,
    v4: Handle<naga::Type>,
}

impl<'m> List<'m> {
    fn new(mb: &'m mut ModuleBuilder, names: [&'static str; 2]) -> List<'m> {
        let v4 = mb.vec(VectorSize::Quad);
        let u3 = mb.uvec(VectorSize::Tri);
        let [input, output] = [0, 1].map(|k| {
            let buffer = layout::Buffer {
                name: names[k],
                binding: layout::LIST_BINDINGS[k],
                stride: layout::LIST_STRIDE,
                element: layout::Element::Vec4F32,
            };
            storage_array(mb, buffer, (v4, k == 1))
        });
        let mut b = FnBuilder::new(mb, "main", &[("gid", u3)], None);
        b.func.arguments[0].binding = Some(Binding::BuiltIn(BuiltIn::GlobalInvocationId));
        let gid = b.arg(0);
        let i = b.at(gid, 0);
        let out = b.expr(Expression::GlobalVariable(output));
        let n = b.expr(Expression::ArrayLength(out));
        let beyond = b.ge(i, n);
        b.if_(beyond, |b| b.ret(None), |_| {});
        let input = b.expr(Expression::GlobalVariable(input));
        List {
            b,
            i,
            input,
            out,
            v4,
        }
    }

    /// Stores `value` as element `i` of the output; the finished `main`.
    fn store(mut b: FnBuilder, (out, i): (Ex, Ex), value: Ex) -> Function {
        let ptr = b.expr(Expression::Access {
            base: out,
            index: i,
        });
        b.store(ptr, value);
        b.finish()
    }
}
