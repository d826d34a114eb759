//! Scales that a primitive takes into its own arguments: `box(s) |> scale(v)` is `box(s·v)`.
//!
//! Arguments are written as expressions (`Field`: constants, or parameters the host sets), so
//! that a scale read from a `param` is taken in the same way as a constant one.

use super::Field;
use super::{Ctx, Primitive, Val};
use crate::syntax::BinOp;

/// An argument as expressions: one component (a number) or three (a vector).
pub type Comps = Vec<Field>;

/// A primitive whose shape scaled by a vector is the same primitive with other arguments:
/// `args(arguments, v)` gives them, or `None` where that scale makes another shape.
pub struct Absorb {
    /// The primitive's name.
    pub name: &'static str,
    /// Its arguments (each as [`comps`] gives them) once scaled by `v` (per axis).
    pub args: fn(&[Comps], &[Field; 3]) -> Option<Vec<Comps>>,
}

/// The primitives that absorb a scale. A non-uniform `scale` of a field is a bound (f(p/s)·min
/// s); the primitive with scaled arguments is its exact distance, for the same surface.
pub const ABSORB: &[Absorb] = &[
    // Each face moves with its own axis' factor.
    Absorb {
        name: "box",
        args: |a, v| Some(vec![times3(&a[0], v)]),
    },
    // A circle stays a circle where x and z scale alike; the height scales with y.
    Absorb {
        name: "cylinder",
        args: |a, v| {
            (v[0] == v[2]).then(|| vec![vec![times(&a[0][0], &v[0])], vec![times(&a[1][0], &v[1])]])
        },
    },
];

/// `prim`'s arguments once scaled by `v`, where it absorbs that scale.
pub fn scaled(prim: &Primitive, ctx: &Ctx, v: &[Field; 3]) -> Option<Vec<Comps>> {
    let entry = ABSORB.iter().find(|a| a.name == prim.name)?;
    let args: Vec<Comps> = (0..ctx.args.len()).map(|i| comps(ctx, i)).collect();
    (entry.args)(&args, v)
}

/// Argument `i` of `ctx` as expressions (see [`comps_of`]).
pub fn comps(ctx: &Ctx, i: usize) -> Comps {
    comps_of(ctx.sym(i), ctx.args[i])
}

/// An argument as expressions: its parameter expressions `sym` where it reads any, else its
/// constant value `v` (a vector's three components, a number's one).
pub fn comps_of(sym: Option<&[Field]>, v: Val) -> Comps {
    match (sym, v) {
        (Some(c), _) => c.to_vec(),
        (None, Val::Vec3(v)) => v.to_array().map(Field::Const).to_vec(),
        (None, v) => vec![Field::Const(v.num())],
    }
}

/// One or three components as three (a number's one, spread).
pub fn spread(c: &[Field]) -> [Field; 3] {
    match c {
        [x] => [x.clone(), x.clone(), x.clone()],
        [x, y, z] => [x.clone(), y.clone(), z.clone()],
        _ => unreachable!("one or three components"),
    }
}

/// a·b, folded where both are constants.
pub fn times(a: &Field, b: &Field) -> Field {
    match (a, b) {
        (Field::Const(x), Field::Const(y)) => Field::Const(x * y),
        (Field::Const(x), other) | (other, Field::Const(x)) if *x == 1.0 => other.clone(),
        _ => Field::Binary(BinOp::Mul, Box::new(a.clone()), Box::new(b.clone())),
    }
}

/// a·v per component (a a number's one component or a vector's three).
pub fn times3(a: &[Field], v: &[Field; 3]) -> Comps {
    let a = spread(a);
    (0..3).map(|k| times(&a[k], &v[k])).collect()
}

/// An argument from expressions: its value where the scene is checked (parameters at their
/// values) and its expressions where it reads a parameter.
pub fn to_arg(c: &[Field]) -> (Val, Option<Vec<Field>>) {
    let at = |f: &Field| f.eval(glam::DVec3::ZERO);
    let val = match c {
        [x] => Val::Num(at(x)),
        _ => Val::Vec3(glam::DVec3::new(at(&c[0]), at(&c[1]), at(&c[2]))),
    };
    let constant = c.iter().all(|f| matches!(f, Field::Const(_)));
    (val, (!constant).then(|| c.to_vec()))
}
