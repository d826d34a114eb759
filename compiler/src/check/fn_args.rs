//! Binding a call's arguments to a user-defined function's parameters: positional, named and
//! default arguments, each typed by its declaration or its default's literal, every problem
//! reported at the call with the definition beside it.

use super::params::SymKind;
use super::{Checker, Dim, Value};
use crate::diag::{Diagnostic, Span, did_you_mean};
use crate::scene::NodeId;
use crate::syntax::{Call, Expr, ExprKind, FnDef, FnParam};

/// The types a parameter may declare.
pub(super) const TYPES: &[&str] = &["number", "angle", "vector", "color", "shape"];

impl Checker<'_> {
    /// The arguments of a call by parameter (none where the default applies), each checked in
    /// the caller's scope and against the parameter's type; every problem reported.
    pub(super) fn fn_args(
        &mut self,
        def: &FnDef,
        call: &Call,
        piped: Option<NodeId>,
    ) -> Option<Vec<Option<Value>>> {
        let name = &def.name.name;
        let n = def.params.len();
        let mut slots: Vec<Option<(Value, Span)>> = vec![None; n];
        let mut ok = true;
        let mut next = 0;
        if let Some(s) = piped {
            if n == 0 {
                self.diags.push(
                    Diagnostic::error(
                        call.span,
                        format!("`{name}` takes no arguments, so no shape from `|>`"),
                    )
                    .label("a shape piped in")
                    .also(def.name.span, "defined here"),
                );
                return None;
            }
            slots[0] = Some((Value::Shape(s), call.span));
            next = 1;
        }
        let mut seen_named = false;
        let mut extra_reported = false;
        // A misspelt name is likely the missing argument: not reported twice; neither is a
        // parameter given an argument that failed (its error is reported).
        let mut unknown_named = false;
        let mut given = vec![false; n];
        for arg in &call.args {
            let value = self.value(&arg.value);
            let index = match &arg.name {
                Some(a) => {
                    seen_named = true;
                    match def.params.iter().position(|p| p.name.name == a.name) {
                        Some(k) => k,
                        None => {
                            let mut d = Diagnostic::error(
                                a.span,
                                format!("`{name}` has no parameter `{}`", a.name),
                            )
                            .label("unknown parameter")
                            .also(def.name.span, "defined here");
                            let names = def.params.iter().map(|p| p.name.name.as_str());
                            d = match did_you_mean(&a.name, names) {
                                Some(s) => d.help(format!("did you mean `{s}`?")),
                                None => d.help(format!("the parameters are: {}", signature(def))),
                            };
                            self.diags.push(d);
                            ok = false;
                            unknown_named = true;
                            continue;
                        }
                    }
                }
                None if seen_named => {
                    self.diags.push(
                        Diagnostic::error(arg.value.span, "positional argument after a named one")
                            .label("give this one a name too")
                            .help(signature(def)),
                    );
                    ok = false;
                    continue;
                }
                None if next >= n => {
                    if !extra_reported {
                        let s = if n == 1 { "" } else { "s" };
                        self.diags.push(
                            Diagnostic::error(
                                arg.value.span,
                                format!("`{name}` takes {n} argument{s}, but more were given"),
                            )
                            .label("unexpected argument")
                            .also(def.name.span, "defined here")
                            .help(signature(def)),
                        );
                        extra_reported = true;
                    }
                    ok = false;
                    continue;
                }
                None => {
                    next += 1;
                    next - 1
                }
            };
            let param = &def.params[index];
            if let Some((_, first)) = &slots[index] {
                self.diags.push(
                    Diagnostic::error(
                        arg.value.span,
                        format!("`{}` is given twice", param.name.name),
                    )
                    .label("second value")
                    .also(*first, "first value"),
                );
                ok = false;
                continue;
            }
            given[index] = true;
            let Some(value) = value else {
                ok = false;
                continue;
            };
            if let Some(want) = self.param_type(param)
                && !fits(want, &value)
            {
                self.diags.push(
                    Diagnostic::error(
                        arg.value.span,
                        format!("`{}` of `{name}` takes {}", param.name.name, article(want)),
                    )
                    .label(format!("this is {}", value.describe()))
                    .also(
                        param.name.span,
                        format!("declared {}", declared_how(param, want)),
                    ),
                );
                ok = false;
            }
            slots[index] = Some((value, arg.value.span));
        }
        for ((p, slot), given) in def.params.iter().zip(&slots).zip(&given) {
            if slot.is_none() && !given && p.default.is_none() && !unknown_named && ok {
                self.diags.push(
                    Diagnostic::error(
                        call.span,
                        format!("`{name}` needs its argument `{}`", p.name.name),
                    )
                    .label("missing argument")
                    .also(p.name.span, "a parameter without a default")
                    .help(signature(def)),
                );
                ok = false;
            }
        }
        ok.then(|| slots.into_iter().map(|s| s.map(|(v, _)| v)).collect())
    }

    /// A parameter's type: declared, or its default's when that is written as a literal.
    fn param_type(&self, p: &FnParam) -> Option<&'static str> {
        match &p.ty {
            Some(t) => TYPES
                .iter()
                .copied()
                .find(|n| *n == t.name || (t.name == "colour" && *n == "color")),
            None => p.default.as_ref().and_then(literal_type),
        }
    }
}

/// The type of a default written as a literal: `1`, `30deg`, `(0, 1, 0)`, `#fff`, or a shape
/// (a primitive or operator call, or a shape moved, tagged, piped or annotated).
fn literal_type(e: &Expr) -> Option<&'static str> {
    match &e.kind {
        ExprKind::Number { unit: None, .. } => Some("number"),
        ExprKind::Number { unit: Some(_), .. } => Some("angle"),
        ExprKind::Color(_) => Some("color"),
        ExprKind::Vector(_) => Some("vector"),
        ExprKind::Neg(a) => literal_type(a),
        ExprKind::Call(c)
            if crate::catalog::primitive(&c.name.name).is_some()
                || (crate::catalog::operator(&c.name.name).is_some() && c.block.is_some()) =>
        {
            Some("shape")
        }
        ExprKind::At(..) | ExprKind::Tag(..) | ExprKind::Annotation(..) => Some("shape"),
        _ => None,
    }
}

/// Whether `v` is of the type `ty` names.
fn fits(ty: &str, v: &Value) -> bool {
    match (ty, v) {
        ("number", Value::Num(_, Dim::None) | Value::Field(_)) => true,
        ("angle", Value::Num(_, Dim::Angle)) => true,
        ("vector", Value::Vec3(_)) => true,
        ("color", Value::Color(_)) => true,
        ("shape", Value::Shape(_)) => true,
        (_, Value::Param(s)) => matches!(
            (ty, s.kind),
            ("number", SymKind::Num(Dim::None))
                | ("angle", SymKind::Num(Dim::Angle))
                | ("vector", SymKind::Vec3)
                | ("color", SymKind::Color)
        ),
        _ => false,
    }
}

fn article(ty: &str) -> String {
    match ty {
        "angle" => "an angle".into(),
        "shape" => "a shape".into(),
        _ => format!("a {ty}"),
    }
}

fn declared_how(p: &FnParam, ty: &str) -> String {
    match &p.ty {
        Some(_) => format!("`{}: {ty}` here", p.name.name),
        None => format!("{} by its default", article(ty)),
    }
}

/// `pillar(h, r = 0.2)` for messages.
pub(super) fn signature(def: &FnDef) -> String {
    let ps: Vec<String> = def
        .params
        .iter()
        .map(|p| {
            let mut s = p.name.name.clone();
            if let Some(t) = &p.ty {
                s += &format!(": {}", t.name);
            }
            if p.default.is_some() {
                s += " = …";
            }
            s
        })
        .collect();
    format!("{}({})", def.name.name, ps.join(", "))
}
