//! The derived math functions (`pow`, `mod`, `smoothstep`; `catalog::DERIVED_FUNCTIONS`):
//! a call is expanded into the math functions and arithmetic it is made of, so its folding,
//! units, interval range, slope and lowering are theirs.

use super::params::SymKind;
use super::{Checker, Value};
use crate::catalog::{self, DerivedFn};
use crate::diag::Diagnostic;
use crate::syntax::{BinOp, Call};

impl Checker<'_> {
    /// A call of a derived function.
    pub(super) fn derived_call(&mut self, f: &'static DerivedFn, call: &Call) -> Option<Value> {
        if call.block.is_some()
            || call.args.iter().any(|a| a.name.is_some())
            || call.args.len() != f.arity
        {
            let s = if f.arity == 1 { "" } else { "s" };
            self.diags.push(
                Diagnostic::error(
                    call.span,
                    format!("`{}` takes {} argument{s}", f.name, f.arity),
                )
                .label(format!("`{}`: {}", f.name, f.doc)),
            );
            return None;
        }
        let mut args = Vec::new();
        for a in &call.args {
            args.push(self.value(&a.value));
        }
        let args: Vec<Value> = args.into_iter().collect::<Option<_>>()?;
        if let Some((bad, arg)) = args.iter().zip(&call.args).find(|(a, _)| {
            !matches!(a, Value::Num(..) | Value::Field(_))
                && !matches!(a, Value::Param(s) if matches!(s.kind, SymKind::Num(_)))
        }) {
            self.diags.push(
                Diagnostic::error(arg.value.span, format!("`{}` takes numbers", f.name))
                    .label(format!("this is {}", bad.describe())),
            );
            return None;
        }
        let span = call.span;
        let math = |name: &str| catalog::math_fn(name).expect("a math function of the catalog");
        match f.name {
            "pow" => {
                let [a, b] = <[Value; 2]>::try_from(args).ok()?;
                self.binary(BinOp::Pow, a, b, span)
            }
            "mod" => {
                // a − b·floor(a / b)
                let [a, b] = <[Value; 2]>::try_from(args).ok()?;
                let q = self.binary(BinOp::Div, a.clone(), b.clone(), span)?;
                let fl = self.apply_math(math("floor"), vec![q], &[span], span)?;
                let m = self.binary(BinOp::Mul, b, fl, span)?;
                self.binary(BinOp::Sub, a, m, span)
            }
            "smoothstep" => {
                // t²·(3 − 2t), t = clamp((x − e0) / (e1 − e0), 0, 1)
                let [e0, e1, x] = <[Value; 3]>::try_from(args).ok()?;
                let num = self.binary(BinOp::Sub, x, e0.clone(), span)?;
                let den = self.binary(BinOp::Sub, e1, e0, span)?;
                let r = self.binary(BinOp::Div, num, den, span)?;
                let (zero, one) = (num_value(0.0), num_value(1.0));
                let t = self.apply_math(math("clamp"), vec![r, zero, one], &[span; 3], span)?;
                let tt = self.binary(BinOp::Mul, t.clone(), t.clone(), span)?;
                let two_t = self.binary(BinOp::Mul, num_value(2.0), t, span)?;
                let rest = self.binary(BinOp::Sub, num_value(3.0), two_t, span)?;
                self.binary(BinOp::Mul, tt, rest, span)
            }
            other => unreachable!("derived function `{other}` without an expansion"),
        }
    }
}

fn num_value(x: f64) -> Value {
    Value::Num(x, super::Dim::None)
}
