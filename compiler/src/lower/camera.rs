//! The camera entries' globals: the `View` uniform (with `view_field` to read it), storage
//! arrays, and `camera_ray`, the pinhole camera.

use super::globals::{global, struct_ty};
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::layout::{self, VIEW_FIELDS};
use naga::{
    AddressSpace, Expression, Function, Handle, MathFunction as M, StorageAccess, Type, TypeInner,
    VectorSize,
};

/// The `View` uniform at group 0, binding 0 (with the `pass` field only for passes).
pub(super) fn add_view(mb: &mut ModuleBuilder, passes: bool) -> Handle<naga::GlobalVariable> {
    let v4 = mb.vec(VectorSize::Quad);
    let u4 = mb.uvec(VectorSize::Quad);
    let fields = if passes { 7 } else { 6 };
    let members: Vec<(&str, Handle<Type>, u32)> = VIEW_FIELDS[..fields]
        .iter()
        .enumerate()
        .map(|(i, n)| (*n, if *n == "offset" { u4 } else { v4 }, 16 * i as u32))
        .collect();
    let ty = struct_ty(mb, "View", &members, 16 * fields as u32);
    global(mb, "view", ty, AddressSpace::Uniform, layout::VIEW_BINDING)
}

/// The runtime-sized storage array `buffer` of the interface (`crate::layout`): elements of
/// `base`; the shader may write it if `write`.
pub(super) fn storage_array(
    mb: &mut ModuleBuilder,
    buffer: layout::Buffer,
    (base, write): (Handle<Type>, bool),
) -> Handle<naga::GlobalVariable> {
    let ty = mb.ty(TypeInner::Array {
        base,
        size: naga::ArraySize::Dynamic,
        stride: buffer.stride as u32,
    });
    let access = match write {
        true => StorageAccess::LOAD | StorageAccess::STORE,
        false => StorageAccess::LOAD,
    };
    global(
        mb,
        buffer.name,
        ty,
        AddressSpace::Storage { access },
        buffer.binding,
    )
}

/// Loads the view uniform's field `name` (`layout::VIEW_FIELDS`).
pub(super) fn view_field(b: &mut FnBuilder, view: Handle<naga::GlobalVariable>, name: &str) -> Ex {
    let g = b.expr(Expression::GlobalVariable(view));
    let ptr = b.at(g, layout::view_field(name) as u32);
    b.load(ptr)
}

/// `camera_ray(pixel)`: the pinhole camera (Munini §2.1), pixel coordinates with y down.
pub(super) fn add_camera_ray(
    mb: &mut ModuleBuilder,
    view: Handle<naga::GlobalVariable>,
) -> Handle<Function> {
    let v2 = mb.vec(VectorSize::Bi);
    let v3 = mb.vec3();
    let mut b = FnBuilder::new(mb, "camera_ray", &[("pixel", v2)], Some(v3));
    let pixel = b.arg(0);
    let [right, up, forward, size] = ["right", "up", "forward", "size"].map(|name| {
        let v = view_field(&mut b, view, name);
        b.swizzle(v, &[0, 1, 2])
    });
    let size = b.swizzle(size, &[0, 1]);
    let two = b.f(2.0);
    let one = b.f(1.0);
    let uv = b.div(pixel, size);
    let uv = b.mul(uv, two);
    let [u, v] = [b.at(uv, 0), b.at(uv, 1)];
    let u = b.sub(u, one);
    let v = b.sub(one, v);
    let ru = b.mul(right, u);
    let uvv = b.mul(up, v);
    let d = b.add(forward, ru);
    let d = b.add(d, uvv);
    let d = b.math(M::Normalize, &[d]);
    b.ret(Some(d));
    let f = b.finish();
    mb.add_function(f)
}
