//! The `Params` uniform (the scene's parameters, set by the host at run time) and arguments
//! computed from it.

use crate::catalog::gpu::args::components;
use crate::ir::builder::{Ex, FnBuilder, ModuleBuilder};
use crate::scene::{Field, ParamDecl, ParamKind, Scene};
use naga::{AddressSpace, Handle, VectorSize};

/// The byte offset of each parameter in the `Params` uniform and the struct's size: std140
/// (and WGSL uniform) layout, a number 4-byte aligned, a vector or colour a `vec3<f32>`
/// 16-byte aligned, the whole a multiple of 16 bytes.
pub fn layout(params: &[ParamDecl]) -> (Vec<u32>, u32) {
    let mut offset = 0u32;
    let mut offsets = Vec::with_capacity(params.len());
    for p in params {
        let (align, size) = match p.kind.components() {
            1 => (4, 4),
            _ => (16, 12),
        };
        offset = offset.div_ceil(align) * align;
        offsets.push(offset);
        offset += size;
    }
    (offsets, offset.div_ceil(16).max(1) * 16)
}

/// The `Params` uniform's bytes for the parameters' values (`ParamDecl::value`), laid out as
/// [`layout`] says (little-endian f32).
pub fn bytes(params: &[ParamDecl]) -> Vec<u8> {
    let (offsets, size) = layout(params);
    let mut out = vec![0u8; size as usize];
    for (p, &o) in params.iter().zip(&offsets) {
        for (i, v) in p.values().iter().enumerate() {
            let at = o as usize + 4 * i;
            out[at..at + 4].copy_from_slice(&(*v as f32).to_le_bytes());
        }
    }
    out
}

/// The WGSL type a parameter has in the uniform.
pub fn wgsl_type(kind: ParamKind) -> &'static str {
    match kind.components() {
        1 => "f32",
        _ => "vec3<f32>",
    }
}

/// Adds `var<uniform> params: Params` at group 0, `binding` when the scene has parameters
/// (`var<private>` if `private`: `Options::private_params`).
pub(super) fn add(
    mb: &mut ModuleBuilder,
    scene: &Scene,
    (private, binding): (bool, u32),
) -> Option<Handle<naga::GlobalVariable>> {
    if scene.params.is_empty() {
        return None;
    }
    let (offsets, size) = layout(&scene.params);
    let (f, v3) = (mb.f32(), mb.vec(VectorSize::Tri));
    let names: Vec<String> = scene
        .params
        .iter()
        .map(|p| super::interface::shader_name(&p.name))
        .collect();
    let members: Vec<(&str, Handle<naga::Type>, u32)> = scene
        .params
        .iter()
        .zip(&names)
        .zip(&offsets)
        .map(|((p, n), &o)| {
            let ty = if p.kind.components() == 1 { f } else { v3 };
            (n.as_str(), ty, o)
        })
        .collect();
    let ty = super::globals::struct_ty(mb, "Params", &members, size);
    if private {
        return Some(mb.module.global_variables.append(
            naga::GlobalVariable {
                name: Some("params".into()),
                space: AddressSpace::Private,
                binding: None,
                ty,
                init: None,
                memory_decorations: naga::MemoryDecorations::empty(),
            },
            naga::Span::UNDEFINED,
        ));
    }
    Some(super::globals::global(
        mb,
        "params",
        ty,
        AddressSpace::Uniform,
        binding,
    ))
}

/// Setting `i` of a material or light (`Material::sym`, `Light::sym`), if computed from
/// parameters.
pub(super) fn setting(sym: &crate::catalog::ArgSyms, i: usize) -> Option<&[Field]> {
    sym.get(i).and_then(|s| s.as_deref())
}

/// An sRGB colour setting as linear light: the sRGB curve (`crate::color::to_linear`)
/// computed in the shader if it reads parameters, else folded.
pub(super) fn linear_color(
    b: &mut FnBuilder,
    c: glam::DVec3,
    sym: Option<&[Field]>,
    any: Ex,
) -> Ex {
    let Some(comps) = sym else {
        return b.vec3_lit(crate::color::linear(c));
    };
    let c = components(b, comps, any);
    let knee = b.splat3(0.04045);
    let low = b.bin(naga::BinaryOperator::LessEqual, c, knee);
    let k = b.splat3(1.0 / 12.92);
    let below = b.mul(c, k);
    let a = b.splat3(0.055);
    let shifted = b.add(c, a);
    let k = b.splat3(1.0 / 1.055);
    let scaled = b.mul(shifted, k);
    let e = b.splat3(2.4);
    let above = b.math(naga::MathFunction::Pow, &[scaled, e]);
    b.select(low, below, above)
}
