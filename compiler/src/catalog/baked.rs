//! `bake`: a part replaced by its distance map (Liktor §3; `crate::bake`), baked when the scene
//! is checked — so a part with no usable Lipschitz bound can be traced, and a costly one read
//! for the price of eight texels.

use super::gpu::baked as ir;
use super::rules::{SHORTENS, num};
use super::symmetry::NONE;
use super::traits::{PLAIN, Plane, Traits};
use super::{Arity, Bound, MatRule, NO_SWAP, Operator, Ty, opt};

/// `bake(res = N, size = s) { shape }`.
pub const BAKE: Operator = Operator {
    name: "bake",
    // The volume is made from the arguments' values when the scene is checked.
    fixed_args: true,
    traits: Traits {
        bakes: true,
        plane: Plane::Solids,
        ..PLAIN
    },
    materials: MatRule::Pass,
    unit_gradient: SHORTENS,
    keeps_exact: SHORTENS,
    lower: ir::bake,
    doc: "Replaces its shape by a distance map baked on a grid of `res` points along the longest \
          side of its bound (or of the box of half extents `size`, if given): trilinear inside, \
          the box's distance outside; its shape may have no Lipschitz bound (λ proven from the \
          map: 1.3–1.7 measured); materials from its shape.",
    params: &[
        opt(
            "res",
            Ty::WholeIn(crate::bake::MIN_RES as u32, crate::bake::MAX_RES as u32),
            num(64.0),
        ),
        opt("size", Ty::Size, num(0.0)),
    ],
    arity: Arity::Exactly(1),
    lipschitz: |c| c.baked.as_ref().map_or(f64::INFINITY, |v| v.lambda),
    bound: |c| match &c.baked {
        Some(v) => {
            let (lo, hi) = (v.grid.lo, v.grid.hi);
            let reach = v.reach_outside();
            Bound::sphere((lo + hi) / 2.0, (hi - lo).length() / 2.0 + reach)
                .with_box(lo - reach, hi + reach)
        }
        None => Bound::INFINITE,
    },
    swap: NO_SWAP,
    mirror: NONE,
    eval: |c, p, _| c.baked.as_ref().map_or(f64::INFINITY, |v| v.field(p)),
};
