//! The ray-list compute entry of the tests: one ray (origin, direction, footprint, start) in,
//! one `vec4(t, steps, flags, cover)` out per invocation.

use super::builder::{FnBuilder, ModuleBuilder};
use super::entry::{compute_main, global};
use super::tracer::{Pass, RAYS_WORKGROUP, Tracer};
use naga::{
    AddressSpace, Binding, BuiltIn, Expression, ScalarKind, StorageAccess, TypeInner, VectorSize,
};

/// The ray-list compute entry ([`Entry::Rays`]), 64 rays per workgroup.
pub(super) fn add_rays(mb: &mut ModuleBuilder, tracer: &Tracer) {
    let v4 = mb.vec(VectorSize::Quad);
    let u3 = mb.uvec(VectorSize::Tri);
    let arr = mb.ty(TypeInner::Array {
        base: v4,
        size: naga::ArraySize::Dynamic,
        stride: 16,
    });
    let rays = global(
        mb,
        "rays",
        arr,
        AddressSpace::Storage {
            access: StorageAccess::LOAD,
        },
        0,
    );
    let hits = global(
        mb,
        "hits",
        arr,
        AddressSpace::Storage {
            access: StorageAccess::LOAD | StorageAccess::STORE,
        },
        1,
    );
    let mut b = FnBuilder::new(mb, "main", &[("gid", u3)], None);
    b.func.arguments[0].binding = Some(Binding::BuiltIn(BuiltIn::GlobalInvocationId));
    let gid = b.arg(0);
    let i = b.at(gid, 0);
    let out = b.expr(Expression::GlobalVariable(hits));
    let n = b.expr(Expression::ArrayLength(out));
    let beyond = b.ge(i, n);
    b.if_(beyond, |b| b.ret(None), |_| {});
    let two = b.u(2);
    let first = b.mul(i, two);
    let one = b.u(1);
    let second = b.add(first, one);
    let input = b.expr(Expression::GlobalVariable(rays));
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
    let ptr = b.expr(Expression::Access {
        base: out,
        index: i,
    });
    b.store(ptr, v);
    let f = b.finish();
    compute_main(mb, f, [RAYS_WORKGROUP, 1, 1]);
}
