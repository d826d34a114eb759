//! Checking math-function calls, `implicit` bodies (their Lipschitz bound inferred, their domain
//! checked) and `@lipschitz` annotations.

use super::params::{Sym, SymKind};
use super::{Checker, Dim, Value};
use crate::catalog::{self};
use crate::diag::{Diagnostic, Span};
use crate::lipschitz;
use crate::scene::{Field, NodeId, NodeKind};
use crate::syntax::{Arg, Call, Ident};

impl Checker<'_> {
    pub(super) fn math_call(&mut self, f: &'static catalog::MathFn, call: &Call) -> Option<Value> {
        let args = self.function_args((f.name, f.arity, f.doc), call)?;
        let spans: Vec<Span> = call.args.iter().map(|a| a.value.span).collect();
        self.apply_math(f, args, &spans, call.span)
    }

    /// The checked arguments of a call of a math function (`name`, its arity and doc line):
    /// exactly so many, positional, no block; `None` when reported.
    pub(super) fn function_args(
        &mut self,
        (name, arity, doc): (&str, usize, &str),
        call: &Call,
    ) -> Option<Vec<Value>> {
        if call.block.is_some()
            || call.args.iter().any(|a| a.name.is_some())
            || call.args.len() != arity
        {
            let s = if arity == 1 { "" } else { "s" };
            self.diags.push(
                Diagnostic::error(call.span, format!("`{name}` takes {arity} argument{s}"))
                    .label(format!("`{name}`: {doc}")),
            );
            return None;
        }
        let mut args = Vec::new();
        for a in &call.args {
            args.push(self.value(&a.value));
        }
        args.into_iter().collect()
    }

    /// A math function applied to checked arguments (at `spans`; the call at `span`): folded
    /// when all are numbers, an expression of coordinates or parameters otherwise.
    pub(super) fn apply_math(
        &mut self,
        f: &'static catalog::MathFn,
        args: Vec<Value>,
        spans: &[Span],
        span: Span,
    ) -> Option<Value> {
        if let Some((bad, at)) = args.iter().zip(spans).find(|(a, _)| {
            !matches!(a, Value::Num(..) | Value::Field(_))
                && !matches!(a, Value::Param(s) if matches!(s.kind, SymKind::Num(_)))
        }) {
            return self.no_arithmetic(*at, f.name, bad);
        }
        let dims: Vec<Dim> = args
            .iter()
            .map(|a| match a {
                Value::Num(_, d) => *d,
                Value::Param(Sym {
                    kind: SymKind::Num(d),
                    ..
                }) => *d,
                _ => Dim::None,
            })
            .collect();
        let out = match f.units {
            catalog::Units::AngleIn => Dim::None,
            catalog::Units::Same if dims.iter().all(|d| *d == dims[0]) => dims[0],
            catalog::Units::AngleOut | catalog::Units::Plain | catalog::Units::Same => {
                if let Some(i) = dims.iter().position(|d| *d == Dim::Angle) {
                    let d = Diagnostic::error(
                        spans[i],
                        format!("`{}` takes plain numbers", f.name),
                    )
                    .label("this is an angle")
                    .help("drop the unit, or divide by `1rad` to get the plain number of radians");
                    self.diags.push(d);
                    return None;
                }
                if f.units == catalog::Units::AngleOut {
                    Dim::Angle
                } else {
                    Dim::None
                }
            }
        };
        if args.iter().all(|a| matches!(a, Value::Num(..))) {
            let xs: Vec<f64> = args
                .iter()
                .map(|a| if let Value::Num(x, _) = a { *x } else { 0.0 })
                .collect();
            return self.finite((f.eval)(&xs), span).map(|r| Value::Num(r, out));
        }
        let field = Field::Call(f, args.into_iter().map(super::arith::as_field).collect());
        if !field.has_coords() {
            // Computed from parameters only: a number the shader computes at run time.
            return Some(Value::Param(Sym {
                kind: SymKind::Num(out),
                comps: vec![field],
            }));
        }
        Some(Value::Field(field))
    }

    pub(super) fn implicit(&mut self, call: &Call, piped: Option<NodeId>) -> Option<Value> {
        let body = match (&call.block, piped, call.args.is_empty()) {
            (Some(b), None, true) if b.len() == 1 => &b[0],
            _ => {
                self.diags.push(
                    Diagnostic::error(
                        call.span,
                        "`implicit` takes one expression of x, y and z in a block",
                    )
                    .label("e.g. `implicit { length(x, y, z) - 1 }`"),
                );
                return None;
            }
        };
        let outer = std::mem::replace(&mut self.in_implicit, true);
        let v = self.value(body);
        self.in_implicit = outer;
        let field = match v? {
            Value::Field(f) => f,
            Value::Num(x, Dim::None) => Field::Const(x),
            Value::Param(s) if s.kind == SymKind::Num(Dim::None) => s.comps[0].clone(),
            other => {
                self.diags.push(
                    Diagnostic::error(body.span, "`implicit` needs a number-valued expression")
                        .label(format!("this is {}", other.describe())),
                );
                return None;
            }
        };
        let lambda = match lipschitz::infer(&field) {
            Ok(l) => l,
            Err(what) => {
                self.diags.push(
                    Diagnostic::error(body.span, "this field is not defined everywhere")
                        .label(what)
                        .note("the field would be NaN or infinite there, and rays would pass through or stop at random")
                        .help("keep arguments in their domain and values within f32 (about ±3.4e38), e.g. `sqrt(abs(a))`, `log(1 + a^2)`, `a / max(b, 1e-6)`"),
                );
                return None;
            }
        };
        self.push_node(
            NodeKind::Implicit { field },
            lambda,
            catalog::Bound::INFINITE,
            call.span,
        )
        .map(Value::Shape)
    }

    pub(super) fn annotation(&mut self, name: &Ident, args: &[Arg], span: Span) -> Option<f64> {
        if name.name != "lipschitz" {
            let mut d =
                Diagnostic::error(name.span, format!("unknown annotation `@{}`", name.name))
                    .label("not an annotation");
            d = match self.did_you_mean(&name.name, ["lipschitz"]) {
                Some(s) => d.help(format!("did you mean `@{s}`?")),
                None => d.note("the only annotation is `@lipschitz(L)`"),
            };
            self.diags.push(d);
            return None;
        }
        let [Arg { name: None, value }] = args else {
            self.diags.push(
                Diagnostic::error(span, "`@lipschitz` takes one number")
                    .label("e.g. `@lipschitz(2)`"),
            );
            return None;
        };
        match self.value(value)? {
            Value::Num(l, Dim::None) if l.is_finite() && l > 0.0 => Some(l),
            other => {
                self.diags.push(
                    Diagnostic::error(value.span, "a Lipschitz bound must be a finite number > 0")
                        .label(format!("found {}", other.describe())),
                );
                None
            }
        }
    }
}
