//! Arguments in the shader: a literal, or computed from the `Params` uniform at run time when
//! it reads parameters.

use crate::catalog::{Ctx, Field, Ty, Val};
use crate::ir::{Ex, FnBuilder};

/// Components computed from parameters (or of the coordinates), as one value (a `vec3` for three).
pub fn components(b: &mut FnBuilder, comps: &[Field], p: Ex) -> Ex {
    let parts: Vec<Ex> = comps.iter().map(|f| super::field::lower(b, f, p)).collect();
    match parts[..] {
        [x] => x,
        [x, y, z] => b.compose_vec3([x, y, z]),
        _ => unreachable!("one or three components"),
    }
}

/// An argument of type `ty`: computed from the uniform if it reads parameters, else a literal.
pub fn arg(b: &mut FnBuilder, ty: Ty, v: Val, sym: Option<&[Field]>, p: Ex) -> Ex {
    match sym {
        Some(comps) => components(b, comps, p),
        None => match ty {
            Ty::Count | Ty::CountTo(_) | Ty::WholeIn(..) => b.u(v.num() as u32),
            Ty::Vec3 | Ty::Size | Ty::Scale | Ty::Axis | Ty::Color | Ty::Counts => {
                b.vec3_lit(v.vec())
            }
            _ => b.f(v.num()),
        },
    }
}

/// Argument `i` of an operator as a number (`p` is any expression of the function: parameters
/// do not read it).
pub fn num(b: &mut FnBuilder, c: &Ctx, i: usize, p: Ex) -> Ex {
    arg(b, Ty::Number, c.args[i], c.sym(i), p)
}

/// Argument `i` of an operator as a vector.
pub fn vec3(b: &mut FnBuilder, c: &Ctx, i: usize, p: Ex) -> Ex {
    arg(b, Ty::Vec3, c.args[i], c.sym(i), p)
}

/// Whether argument `i` is read at run time.
pub fn varies(c: &Ctx, i: usize) -> bool {
    c.sym(i).is_some()
}
