//! Vector helpers in IR that shading and the textures share.

use crate::ir::builder::{Ex, FnBuilder};
use naga::MathFunction as M;

/// `v` normalised, or zero for the zero vector (no NaN): `crate::reference::shading::unit_or_zero`.
pub(super) fn unit_or_zero(b: &mut FnBuilder, v: Ex) -> Ex {
    let unit = b.math(M::Normalize, &[v]);
    let len2 = b.dot(v, v);
    let zero = b.f(0.0);
    let none = b.bin(naga::BinaryOperator::Equal, len2, zero);
    let zv = b.splat3(0.0);
    b.select(none, zv, unit)
}
