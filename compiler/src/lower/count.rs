//! Counting the field's evaluations outside the camera ray's trace — normals, materials, shadow
//! rays, occlusion, reflected and refracted rays — in the compute entry, so that `sdfc bench`
//! reports what shading costs as measured, not as estimated.

use crate::ir::builder::{FnBuilder, ModuleBuilder};
use naga::{AddressSpace, Expression, GlobalVariable, Span};

/// Adds the per-invocation counter (`var<private> evaluations: u32 = 0`) that [`count`] adds
/// to; only the compute entry's module has one.
pub(super) fn add_counter(mb: &mut ModuleBuilder) {
    let u32t = mb.u32();
    let zero = mb
        .module
        .global_expressions
        .append(Expression::Literal(naga::Literal::U32(0)), Span::UNDEFINED);
    let g = mb.module.global_variables.append(
        GlobalVariable {
            name: Some("evaluations".into()),
            space: AddressSpace::Private,
            binding: None,
            ty: u32t,
            init: Some(zero),
            memory_decorations: naga::MemoryDecorations::empty(),
        },
        Span::UNDEFINED,
    );
    mb.evaluations = Some(g);
}

/// `evaluations += n`, where the module counts evaluations (nothing elsewhere, nor where it
/// counts primitive evaluations).
pub(super) fn count(b: &mut FnBuilder, n: u32) {
    if !b.m.primitives {
        add(b, n);
    }
}

/// `evaluations += 1` at the start of a primitive's function, where the module counts
/// primitive evaluations (`Options::count_primitives`: the measure of Barbier, Sanchez et al.
/// 2025, whatever the form — inline code, box trees or the data form's programs).
pub(super) fn primitive(b: &mut FnBuilder) {
    if b.m.primitives {
        add(b, 1);
    }
}

/// `evaluations += n` where the module has the counter.
fn add(b: &mut FnBuilder, n: u32) {
    let Some(g) = b.m.evaluations else {
        return;
    };
    let ptr = b.expr(Expression::GlobalVariable(g));
    let v = b.load(ptr);
    let k = b.u(n);
    let v = b.add(v, k);
    b.store(ptr, v);
}
