//! Checking `param` declarations: a parameter's kind and default, its range, and the value
//! asked for it from outside (`sdfc render --param`).

use super::params::TIME;
use super::{Checker, Dim, Value};
use crate::catalog;
use crate::diag::{Diagnostic, Span};
use crate::scene::{ParamDecl, ParamKind};
use crate::syntax::{Expr, Ident};
use glam::DVec3;

impl Checker<'_> {
    /// `param name = default in lo..hi`.
    pub(super) fn param_statement(
        &mut self,
        name: &Ident,
        value: &Expr,
        range: Option<&(Expr, Expr)>,
        span: Span,
    ) {
        if name.name != TIME
            && let Some(d) = self.reserved_name(name)
        {
            self.diags.push(d);
            self.failed.insert(name.name.clone());
            return;
        }
        if self.defined_twice(name) {
            return;
        }
        let decl = self.param_decl(name, value, range, span);
        match decl {
            Some(d) => {
                self.param_index
                    .insert(name.name.clone(), self.params.len());
                if name.name != TIME {
                    // `param time` gives the built-in a range: every body may read it.
                    self.item_of.insert(name.name.clone(), self.item);
                }
                self.params.push(d);
                self.param_used.push(false);
            }
            None => {
                self.failed.insert(name.name.clone());
            }
        }
    }

    /// A `param` declaration's parameter: its kind and default from the default's value, its
    /// range (a colour's is 0…1), and its value (the default, or the one asked for from
    /// outside); `None` when an error was reported.
    fn param_decl(
        &mut self,
        name: &Ident,
        value: &Expr,
        range: Option<&(Expr, Expr)>,
        span: Span,
    ) -> Option<ParamDecl> {
        let (kind, default) = self.param_default(name, value)?;
        let range = match range {
            // A colour's components are 0…1 whatever the host sets.
            None if kind == ParamKind::Color => Some((DVec3::ZERO, DVec3::ONE)),
            None => None,
            Some((lo, hi)) => Some(self.param_range(lo, hi, kind, default, value.span)?),
        };
        let mut decl = ParamDecl {
            name: name.name.clone(),
            kind,
            default,
            value: default,
            range,
            span,
        };
        if let Some(asked) = self.overrides.get(&name.name).cloned() {
            decl.value = self.asked_value(&decl, &asked, span)?;
        }
        Some(decl)
    }

    /// A parameter's kind and default, from the default's value: a constant number, angle,
    /// vector or colour (`time` a number) within the GPU's range.
    fn param_default(&mut self, name: &Ident, value: &Expr) -> Option<(ParamKind, DVec3)> {
        let v = self.value(value)?;
        let (kind, default) = match v {
            Value::Num(x, Dim::None) => (ParamKind::Number, DVec3::new(x, 0.0, 0.0)),
            Value::Num(x, Dim::Angle) => (ParamKind::Angle, DVec3::new(x, 0.0, 0.0)),
            Value::Vec3(v) => (ParamKind::Vector, v),
            Value::Color(c) => (ParamKind::Color, c),
            other => {
                let d = Diagnostic::error(
                    value.span,
                    "a parameter's default must be a constant number, angle, vector or colour",
                )
                .label(format!("this is {}", other.describe()));
                let d = if matches!(other, Value::Param(_)) {
                    d.help("a value computed from parameters is a `let`: `let d = r * 2`")
                } else {
                    d
                };
                self.diags.push(d);
                return None;
            }
        };
        if name.name == TIME && kind != ParamKind::Number {
            self.diags.push(
                Diagnostic::error(value.span, "`time` is a number of seconds")
                    .label(format!("this is {}", v.describe())),
            );
            return None;
        }
        if !catalog::fits_gpu(default.max_element()) || !catalog::fits_gpu(default.min_element()) {
            self.diags.push(
                Diagnostic::error(
                    value.span,
                    "this value is beyond what the GPU's f32 arithmetic can use",
                )
                .label("out of range"),
            );
            return None;
        }
        Some((kind, default))
    }

    /// The range `lo..hi` of a parameter of `kind`: within the GPU's range, not empty, and
    /// holding the default (written at `default_span`).
    fn param_range(
        &mut self,
        lo: &Expr,
        hi: &Expr,
        kind: ParamKind,
        default: DVec3,
        default_span: Span,
    ) -> Option<(DVec3, DVec3)> {
        let n = kind.components();
        let (a, b) = (self.range_end(lo, kind), self.range_end(hi, kind));
        let (a, b) = (a?, b?);
        if (0..n).any(|i| !catalog::fits_gpu(a[i]) || !catalog::fits_gpu(b[i])) {
            self.diags.push(
                Diagnostic::error(lo.span.to(hi.span), "this range goes beyond what the GPU's f32 arithmetic can use")
                    .label("out of range")
                    .note(format!(
                        "a host may set any value in the range: its ends must be 0 or between {:e} and {:e} in size",
                        catalog::GPU_RANGE.0,
                        catalog::GPU_RANGE.1
                    )),
            );
            return None;
        }
        if (0..n).any(|i| a[i] > b[i]) {
            self.diags.push(
                Diagnostic::error(lo.span.to(hi.span), "this range is empty")
                    .label("the low end is above the high end"),
            );
            return None;
        }
        if (0..n).any(|i| default[i] < a[i] || default[i] > b[i]) {
            self.diags.push(
                Diagnostic::error(default_span, "the default is outside the range")
                    .label("not in the range")
                    .also(lo.span.to(hi.span), "the range"),
            );
            return None;
        }
        Some((a, b))
    }

    /// The value given for a parameter from outside (`sdfc render --param`), checked against
    /// its kind and range.
    fn asked_value(&mut self, decl: &ParamDecl, asked: &[f64], span: Span) -> Option<DVec3> {
        let n = decl.kind.components();
        let name = &decl.name;
        if asked.len() != n {
            self.diags.push(
                Diagnostic::error(
                    span,
                    format!("`{name}` takes {n} number(s), {} were given", asked.len()),
                )
                .label(format!("`{name}` is {} here", decl.kind.name())),
            );
            return None;
        }
        let mut v = DVec3::ZERO;
        for (i, x) in asked.iter().enumerate() {
            v[i] = *x;
        }
        if let Some((lo, hi)) = decl.range
            && (0..n).any(|i| v[i] < lo[i] || v[i] > hi[i])
        {
            self.diags.push(
                Diagnostic::error(
                    span,
                    format!("the value asked for `{name}` is outside its range"),
                )
                .label(format!(
                    "{} was asked for; it is not in the range",
                    show(v, n)
                )),
            );
            return None;
        }
        if !(0..n).all(|i| catalog::fits_gpu(v[i])) {
            self.diags.push(
                Diagnostic::error(span, format!("the value asked for `{name}` is beyond f32"))
                    .label("out of range"),
            );
            return None;
        }
        Some(v)
    }

    /// One end of a range, as the parameter's kind.
    fn range_end(&mut self, e: &Expr, kind: ParamKind) -> Option<DVec3> {
        let v = self.value(e)?;
        match (kind, v) {
            (ParamKind::Number, Value::Num(x, Dim::None))
            | (ParamKind::Angle, Value::Num(x, Dim::Angle)) => Some(DVec3::new(x, 0.0, 0.0)),
            (ParamKind::Vector, Value::Vec3(v)) | (ParamKind::Color, Value::Color(v)) => Some(v),
            (ParamKind::Vector, Value::Num(x, Dim::None)) => Some(DVec3::splat(x)),
            (ParamKind::Color, Value::Vec3(v)) => Some(v),
            (kind, other) => {
                self.diags.push(
                    Diagnostic::error(
                        e.span,
                        format!(
                            "the range of {} parameter must be of its kind",
                            article(kind)
                        ),
                    )
                    .label(format!("this is {}", other.describe())),
                );
                None
            }
        }
    }
}

fn article(kind: ParamKind) -> &'static str {
    match kind {
        ParamKind::Number => "a number",
        ParamKind::Angle => "an angle",
        ParamKind::Vector => "a vector",
        ParamKind::Color => "a colour",
    }
}

fn show(v: DVec3, n: usize) -> String {
    if n == 1 {
        format!("{}", v.x)
    } else {
        format!("({}, {}, {})", v.x, v.y, v.z)
    }
}
