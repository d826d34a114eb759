//! Expressions of the coordinates and of parameters in IR: `implicit` bodies and arguments
//! computed from parameters.

use crate::catalog::ParamRef;
use crate::catalog::field::{Field, MAX_WHOLE_POWER};
use crate::ir::{Ex, FnBuilder};
use crate::syntax::BinOp;
use naga::Expression;
use naga::MathFunction;

/// An `implicit` body in IR. Whole powers with |n| ≤ 64 are multiplied out by repeated squaring
/// (WGSL's `pow` is undefined for negative bases; the CPU's `powf` is exact there), negative
/// ones as the reciprocal.
pub fn lower(b: &mut FnBuilder, f: &Field, p: Ex) -> Ex {
    match f {
        Field::Const(c) => b.f(*c),
        Field::Param(r) => load(b, r),
        Field::Coord(i) => b.at(p, *i as u32),
        Field::Neg(a) => {
            let a = lower(b, a, p);
            b.neg(a)
        }
        Field::Binary(BinOp::Pow, a, n) if matches!(**n, Field::Const(k) if k.fract() == 0.0 && k.abs() <= MAX_WHOLE_POWER) =>
        {
            let Field::Const(k) = **n else { unreachable!() };
            let a = lower(b, a, p);
            let power = whole_power(b, a, k.abs() as u32);
            if k < 0.0 {
                let one = b.f(1.0);
                b.div(one, power)
            } else {
                power
            }
        }
        Field::Binary(op, x, y) => {
            let (x, y) = (lower(b, x, p), lower(b, y, p));
            match op {
                BinOp::Add => b.add(x, y),
                BinOp::Sub => b.sub(x, y),
                BinOp::Mul => b.mul(x, y),
                BinOp::Div => b.div(x, y),
                BinOp::Pow => b.math(MathFunction::Pow, &[x, y]),
            }
        }
        Field::Call(func, args) => {
            let args: Vec<Ex> = args.iter().map(|a| lower(b, a, p)).collect();
            if func.lower == MathFunction::Length {
                let v = b.compose_vec3([args[0], args[1], args[2]]);
                return b.length(v);
            }
            match func.name {
                // a − b·floor(a / b)
                "mod" => {
                    let q = b.div(args[0], args[1]);
                    let k = b.math(MathFunction::Floor, &[q]);
                    let m = b.mul(args[1], k);
                    return b.sub(args[0], m);
                }
                // t²·(3 − 2t), t = clamp((c − a) / (b − a), 0, 1), written out (the
                // built-in's result for b < a is not the same in every shading language).
                "smoothstep" => {
                    let n = b.sub(args[2], args[0]);
                    let w = b.sub(args[1], args[0]);
                    let t = b.div(n, w);
                    let (zero, one) = (b.f(0.0), b.f(1.0));
                    let t = b.clamp(t, zero, one);
                    let tt = b.mul(t, t);
                    let two = b.f(2.0);
                    let three = b.f(3.0);
                    let t2 = b.mul(two, t);
                    let r = b.sub(three, t2);
                    return b.mul(tt, r);
                }
                _ => {}
            }
            b.math(func.lower, &args)
        }
    }
}

/// aⁿ by repeated squaring (n = 0 gives 1).
pub fn whole_power(b: &mut FnBuilder, a: Ex, n: u32) -> Ex {
    let mut result: Option<Ex> = None;
    let mut square = a;
    let mut n = n;
    while n > 0 {
        if n & 1 == 1 {
            result = Some(match result {
                Some(r) => b.mul(r, square),
                None => square,
            });
        }
        n >>= 1;
        if n > 0 {
            square = b.mul(square, square);
        }
    }
    result.unwrap_or_else(|| b.f(1.0))
}

/// One component of a parameter, loaded from the uniform.
pub fn load(b: &mut FnBuilder, r: &ParamRef) -> Ex {
    let global =
        b.m.params
            .expect("a module with parameters has the uniform");
    let g = b.expr(Expression::GlobalVariable(global));
    let ptr = b.at(g, r.index as u32);
    let v = b.load(ptr);
    let vector = matches!(
        b.m.module.types[b.m.module.global_variables[global].ty].inner,
        naga::TypeInner::Struct { ref members, .. }
            if matches!(b.m.module.types[members[r.index].ty].inner, naga::TypeInner::Vector { .. })
    );
    if vector { b.at(v, r.comp as u32) } else { v }
}
