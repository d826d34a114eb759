//! The derived math functions (`pow`; `catalog::DERIVED_FUNCTIONS`): a call is expanded into
//! the operators it is made of, so its folding, units, interval range, slope and lowering are
//! theirs. (`mod` and `smoothstep` are math functions of their own: expanded, their arguments
//! would be copied into the expression tree, which doubled at each level of nesting, and
//! interval arithmetic on the parts lost what ties a to floor(a / b).)

use super::params::SymKind;
use super::{Checker, Value};
use crate::catalog::DerivedFn;
use crate::diag::Diagnostic;
use crate::syntax::{BinOp, Call};

impl Checker<'_> {
    /// A call of a derived function.
    pub(super) fn derived_call(&mut self, f: &'static DerivedFn, call: &Call) -> Option<Value> {
        let args = self.function_args((f.name, f.arity, f.doc), call)?;
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
        match f.name {
            "pow" => {
                let [a, b] = <[Value; 2]>::try_from(args).ok()?;
                self.binary(BinOp::Pow, a, b, span)
            }
            other => unreachable!("derived function `{other}` without an expansion"),
        }
    }
}
