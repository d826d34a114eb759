//! Arithmetic on checked values: numbers with their units, vectors, fields and (through
//! `params.rs`) parameters; every result checked to be finite.

use super::{Checker, Dim, Value};
use crate::diag::{Diagnostic, Span};
use crate::scene::{Field, binary};
use crate::syntax::BinOp;
use glam::DVec3;

impl Checker<'_> {
    pub(super) fn no_arithmetic(&mut self, span: Span, op: &str, v: &Value) -> Option<Value> {
        let mut d = Diagnostic::error(
            span,
            format!("`{op}` cannot be applied to {}", v.describe()),
        )
        .label("unsupported operand");
        if matches!(v, Value::Shape(_)) {
            d = d.help(match op {
                "+" => "combine shapes with `union { a b }`",
                "-" => "cut shapes with `subtract { a b }` or turn them inside out with `complement { a }`",
                _ => "shapes combine with operators such as `union`, `intersect` and `mix`",
            });
        }
        self.diags.push(d);
        None
    }

    pub(super) fn binary(&mut self, op: BinOp, a: Value, b: Value, span: Span) -> Option<Value> {
        if matches!(a, Value::Param(_)) || matches!(b, Value::Param(_)) {
            return self.param_binary(op, a, b, span);
        }
        match (a, b) {
            (Value::Num(x, _), Value::Num(y, _))
                if op == BinOp::Pow && x < 0.0 && y.fract() != 0.0 =>
            {
                self.diags.push(
                    Diagnostic::error(span, format!("{x} ^ {y} is not a real number"))
                        .label("a negative base to a power that is not whole")
                        .help("use a whole exponent, or the power of the magnitude: `abs(a) ^ b`"),
                );
                None
            }
            (Value::Num(x, da), Value::Num(y, db)) => {
                let dim = match (op, da, db) {
                    (_, Dim::None, Dim::None) => Dim::None,
                    (BinOp::Add | BinOp::Sub, d1, d2) if d1 == d2 => d1,
                    (BinOp::Mul, Dim::Angle, Dim::None) | (BinOp::Mul, Dim::None, Dim::Angle) => {
                        Dim::Angle
                    }
                    (BinOp::Div, Dim::Angle, Dim::None) => Dim::Angle,
                    (BinOp::Div, Dim::Angle, Dim::Angle) => Dim::None,
                    (_, Dim::Angle, Dim::Angle) => {
                        self.diags.push(
                            Diagnostic::error(
                                span,
                                format!("`{}` of two angles is not an angle", op.symbol()),
                            )
                            .label("angle times angle, or a power of an angle")
                            .help("give one operand a unit, or neither"),
                        );
                        return None;
                    }
                    _ => {
                        self.diags.push(
                            Diagnostic::error(span, "mixed units")
                                .label(format!("`{}` of an angle and a plain number", op.symbol()))
                                .help("give both operands a unit, or neither"),
                        );
                        return None;
                    }
                };
                self.finite(binary(op, x, y), span)
                    .map(|r| Value::Num(r, dim))
            }
            (Value::Vec3(v), Value::Num(s, Dim::None)) if matches!(op, BinOp::Mul | BinOp::Div) => {
                let r = if op == BinOp::Mul { v * s } else { v / s };
                self.finite_vec(r, span)
            }
            (Value::Num(s, Dim::None), Value::Vec3(v)) if op == BinOp::Mul => {
                self.finite_vec(v * s, span)
            }
            (Value::Vec3(a), Value::Vec3(b)) if matches!(op, BinOp::Add | BinOp::Sub) => {
                self.finite_vec(if op == BinOp::Add { a + b } else { a - b }, span)
            }
            (
                a @ (Value::Field(_) | Value::Num(_, Dim::None)),
                b @ (Value::Field(_) | Value::Num(_, Dim::None)),
            ) => Some(Value::Field(Field::Binary(
                op,
                Box::new(as_field(a)),
                Box::new(as_field(b)),
            ))),
            (a, b) => {
                let bad = if matches!(a, Value::Num(..) | Value::Field(_)) {
                    b
                } else {
                    a
                };
                self.no_arithmetic(span, op.symbol(), &bad)
            }
        }
    }

    pub(super) fn finite(&mut self, x: f64, span: Span) -> Option<f64> {
        if x.is_finite() {
            return Some(x);
        }
        let what = if x.is_nan() {
            "not a number (NaN)"
        } else {
            "infinite"
        };
        self.diags.push(
            Diagnostic::error(span, format!("this value is {what}"))
                .label("computed here")
                .note("every number in a scene must be finite"),
        );
        None
    }

    fn finite_vec(&mut self, v: DVec3, span: Span) -> Option<Value> {
        for i in 0..3 {
            self.finite(v[i], span)?;
        }
        Some(Value::Vec3(v))
    }
}

pub(super) fn as_field(v: Value) -> Field {
    match v {
        Value::Num(x, _) => Field::Const(x),
        Value::Field(f) => f,
        Value::Param(s) => s.comps[0].clone(),
        _ => Field::Const(f64::NAN),
    }
}
