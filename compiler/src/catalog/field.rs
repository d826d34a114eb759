//! Expressions of the coordinates and of parameters: `implicit` bodies and arguments computed
//! from parameters at run time.

use super::MathFn;
use crate::syntax::BinOp;
use glam::DVec3;

/// The largest |n| for which the shaders multiply out `a ^ n` with a whole n (WGSL's `pow` is
/// undefined for negative bases), so that it agrees with the CPU's `powf`, exact there.
pub const MAX_WHOLE_POWER: f64 = 64.0;

/// A use of one component of a parameter in an expression.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamRef {
    /// Index into [`crate::scene::Scene::params`].
    pub index: usize,
    /// The component (0 for numbers).
    pub comp: usize,
    /// Its value where the scene was checked (the default, or the value asked for).
    pub value: f64,
    /// The lowest value it may take (−∞ without a declared range).
    pub lo: f64,
    /// The highest value it may take (+∞ without a declared range).
    pub hi: f64,
}

impl ParamRef {
    /// Whether the parameter was declared with a range.
    pub fn ranged(&self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }
}

/// An expression of the coordinates x, y, z (the body of `implicit`), constants folded.
#[derive(Clone, Debug, PartialEq)]
pub enum Field {
    /// A constant.
    Const(f64),
    /// Coordinate 0 (x), 1 (y) or 2 (z).
    Coord(usize),
    /// −a
    Neg(Box<Field>),
    /// a ∘ b
    Binary(BinOp, Box<Field>, Box<Field>),
    /// f(args)
    Call(&'static MathFn, Vec<Field>),
    /// A component of a parameter, read from the `Params` uniform at run time.
    Param(ParamRef),
}

impl Field {
    /// Value at a point, in f64.
    pub fn eval(&self, p: DVec3) -> f64 {
        match self {
            Field::Const(c) => *c,
            Field::Coord(i) => p[*i],
            Field::Neg(a) => -a.eval(p),
            Field::Binary(op, a, b) => binary(*op, a.eval(p), b.eval(p)),
            Field::Call(f, args) => {
                let v: Vec<f64> = args.iter().map(|a| a.eval(p)).collect();
                (f.eval)(&v)
            }
            Field::Param(r) => r.value,
        }
    }

    /// The same expression with every parameter's value replaced by `value(use)`.
    pub fn with_values(&self, value: &dyn Fn(&ParamRef) -> f64) -> Field {
        self.map_params(&|r| ParamRef {
            value: value(r),
            ..*r
        })
    }

    /// The same expression with every parameter held at its value: its range is that value
    /// alone (interval bounds then hold at these values, not over the whole range).
    pub fn pinned(&self) -> Field {
        self.map_params(&|r| ParamRef {
            lo: r.value,
            hi: r.value,
            ..*r
        })
    }

    /// The same expression with every parameter use replaced by `f(use)`.
    fn map_params(&self, f: &dyn Fn(&ParamRef) -> ParamRef) -> Field {
        match self {
            Field::Param(r) => Field::Param(f(r)),
            Field::Neg(a) => Field::Neg(Box::new(a.map_params(f))),
            Field::Binary(op, a, b) => {
                Field::Binary(*op, Box::new(a.map_params(f)), Box::new(b.map_params(f)))
            }
            Field::Call(c, args) => Field::Call(c, args.iter().map(|a| a.map_params(f)).collect()),
            other => other.clone(),
        }
    }

    /// Calls `each` on every parameter use in the expression.
    pub fn params(&self, each: &mut dyn FnMut(&ParamRef)) {
        match self {
            Field::Param(r) => each(r),
            Field::Neg(a) => a.params(each),
            Field::Binary(_, a, b) => {
                a.params(each);
                b.params(each);
            }
            Field::Call(_, args) => args.iter().for_each(|a| a.params(each)),
            _ => {}
        }
    }

    /// Whether the expression reads the coordinates (an `implicit` body) rather than only
    /// parameters and constants.
    pub fn has_coords(&self) -> bool {
        match self {
            Field::Coord(_) => true,
            Field::Neg(a) => a.has_coords(),
            Field::Binary(_, a, b) => a.has_coords() || b.has_coords(),
            Field::Call(_, args) => args.iter().any(Field::has_coords),
            _ => false,
        }
    }
}

/// Applies a binary operator to numbers.
pub fn binary(op: BinOp, a: f64, b: f64) -> f64 {
    match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul => a * b,
        BinOp::Div => a / b,
        BinOp::Pow => a.powf(b),
    }
}
