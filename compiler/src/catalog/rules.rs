//! Shorthands the catalog's entries write their rules with: λ rules, gradient rules, a child's
//! field divided by its λ.

use super::{ChildEval, Ctx, Val};
use glam::DVec3;

/// A number argument's default.
pub const fn num(x: f64) -> Val {
    Val::Num(x)
}

/// λ of the only child.
pub const SAME: fn(&Ctx) -> f64 = |c| c.child_lambda[0];
/// λ = 1.
pub const ONE: fn(&Ctx) -> f64 = |_| 1.0;
/// Keeps a unit gradient (min, max, moves and folds of unit-gradient fields).
pub const KEEPS: fn(&Ctx) -> bool = |_| true;
/// Makes gradients shorter than λ somewhere (blends, warps, weighted sums).
pub const SHORTENS: fn(&Ctx) -> bool = |_| false;

/// Child `i` at `p`, divided by its λ.
pub fn norm(c: &Ctx, child: ChildEval, i: usize, p: DVec3) -> f64 {
    child(i, p) / c.child_lambda[i]
}
