//! Scales that a primitive takes into its own arguments: `box(s) |> scale(v)` is `box(s·v)`.

use super::{Ctx, Primitive, Val};
use glam::DVec3;

/// A primitive whose shape scaled by a vector is the same primitive with other arguments:
/// `args(ctx, v)` gives them, or `None` where that scale makes another shape.
pub struct Absorb {
    /// The primitive's name.
    pub name: &'static str,
    /// Its arguments once scaled by `v` (per axis).
    pub args: fn(&Ctx, DVec3) -> Option<Vec<Val>>,
}

/// The primitives that absorb a scale. A non-uniform `scale` of a field is a bound (f(p/s)·min
/// s); the primitive with scaled arguments is its exact distance, for the same surface.
pub const ABSORB: &[Absorb] = &[
    // Each face moves with its own axis' factor.
    Absorb {
        name: "box",
        args: |c, v| Some(vec![Val::Vec3(c.vec(0) * v)]),
    },
    // A circle stays a circle where x and z scale alike; the height scales with y.
    Absorb {
        name: "cylinder",
        args: |c, v| (v.x == v.z).then(|| vec![Val::Num(c.num(0) * v.x), Val::Num(c.num(1) * v.y)]),
    },
];

/// `prim`'s arguments once scaled by `v`, where it absorbs that scale.
pub fn scaled(prim: &Primitive, ctx: &Ctx, v: DVec3) -> Option<Vec<Val>> {
    let entry = ABSORB.iter().find(|a| a.name == prim.name)?;
    (entry.args)(ctx, v)
}
