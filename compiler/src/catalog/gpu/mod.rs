//! The catalog's shader side: each entry's body in naga IR (built with `crate::ir`), beside
//! its f64 twin in the entry's own file, and the arguments and `implicit` expressions they read.
//!
//! An entry names its body by a function pointer ([`PrimLower`], [`OpLower`]); the lowering
//! walks the scene and calls them, and never builds a shape's IR itself.

pub mod args;
pub mod baked;
pub mod domain;
pub mod field;
pub mod ops;
pub mod planar;
pub mod polar;
pub mod prims;
pub mod prune;
pub mod shapes;
pub mod warp;

use crate::catalog::Ctx;
use crate::ir::{Ex, FnBuilder};

/// A primitive's IR: builder, point, arguments; returns its field.
pub type PrimLower = fn(&mut FnBuilder, Ex, &[Ex]) -> Ex;

/// Lowers child `i` at a point; returns its raw field.
pub type ChildLower<'a> = &'a mut dyn FnMut(&mut FnBuilder, usize, Ex) -> Ex;

/// An operator's IR: builder, arguments, point, children.
pub type OpLower = fn(&mut FnBuilder, &Ctx, Ex, ChildLower) -> Ex;

/// Child `i` at `p` divided by its λ (no division when λ = 1).
pub fn norm(b: &mut FnBuilder, c: &Ctx, child: ChildLower, i: usize, p: Ex) -> Ex {
    let d = child(b, i, p);
    scale_by(b, d, 1.0 / c.child_lambda[i])
}

/// d·k, skipped when k = 1.
pub fn scale_by(b: &mut FnBuilder, d: Ex, k: f64) -> Ex {
    if k == 1.0 {
        return d;
    }
    let k = b.f(k);
    b.mul(d, k)
}
