//! Binding a call's arguments to a user-defined function's parameters: positional, named and
//! default arguments, each typed by its declaration or its default's literal, every problem
//! reported at the call with the definition beside it.

use super::params::SymKind;
use super::{Checker, Dim, Value};
use crate::diag::{Diagnostic, Span};
use crate::scene::NodeId;
use crate::syntax::{Arg, Call, Expr, ExprKind, FnDef, FnParam};

/// The types a parameter may declare.
pub(super) const TYPES: &[&str] = &["number", "angle", "vector", "color", "shape"];

/// The state of binding one call's arguments, argument by argument.
struct Binding {
    /// Each parameter's value and the span it came from.
    slots: Vec<Option<(Value, Span)>>,
    /// Each parameter given an argument, even one that failed (its error is reported).
    given: Vec<bool>,
    /// No problem reported so far.
    ok: bool,
    /// The next positional parameter.
    next: usize,
    /// A named argument came before.
    seen_named: bool,
    /// "More were given" is reported once.
    extra_reported: bool,
    /// A misspelt name is likely the missing argument: not reported twice.
    unknown_named: bool,
    /// The parameters' indices by name, made at the first named argument (a linear search
    /// per argument made a call with 100 000 named ones quadratic).
    by_name: Option<std::collections::HashMap<String, usize>>,
}

impl Checker<'_> {
    /// The arguments of a call by parameter (none where the default applies), each checked in
    /// the caller's scope and against the parameter's type; every problem reported.
    pub(super) fn fn_args(
        &mut self,
        def: &FnDef,
        call: &Call,
        piped: Option<NodeId>,
    ) -> Option<Vec<Option<Value>>> {
        let n = def.params.len();
        let mut b = Binding {
            slots: vec![None; n],
            given: vec![false; n],
            ok: true,
            next: 0,
            seen_named: false,
            extra_reported: false,
            unknown_named: false,
            by_name: None,
        };
        if let Some(s) = piped {
            if n == 0 {
                self.diags.push(
                    Diagnostic::error(
                        call.span,
                        format!(
                            "`{}` takes no arguments, so no shape from `|>`",
                            def.name.name
                        ),
                    )
                    .label("a shape piped in")
                    .also(def.name.span, "defined here"),
                );
                return None;
            }
            b.slots[0] = Some((Value::Shape(s), call.span));
            b.next = 1;
        }
        for arg in &call.args {
            let value = self.value(&arg.value);
            if let Some(index) = self.arg_index(def, arg, &mut b) {
                self.fill_slot(def, index, arg, value, &mut b);
            }
        }
        self.report_missing(def, call, &mut b);
        b.ok.then(|| b.slots.into_iter().map(|s| s.map(|(v, _)| v)).collect())
    }

    /// The parameter `arg` binds to: by its name, or the next positional one; `None`, with the
    /// problem reported, for an unknown name, a positional argument after a named one, or one
    /// too many.
    fn arg_index(&mut self, def: &FnDef, arg: &Arg, b: &mut Binding) -> Option<usize> {
        let name = &def.name.name;
        let n = def.params.len();
        match &arg.name {
            Some(a) => {
                b.seen_named = true;
                let by_name = b.by_name.get_or_insert_with(|| {
                    // (The first of two same-named parameters, as a search would find.)
                    let mut m = std::collections::HashMap::new();
                    for (i, p) in def.params.iter().enumerate() {
                        m.entry(p.name.name.clone()).or_insert(i);
                    }
                    m
                });
                let found = by_name.get(&a.name).copied();
                if found.is_none() {
                    let mut d = Diagnostic::error(
                        a.span,
                        format!("`{name}` has no parameter `{}`", a.name),
                    )
                    .label("unknown parameter")
                    .also(def.name.span, "defined here");
                    let names = def.params.iter().map(|p| p.name.name.as_str());
                    d = match self.did_you_mean(&a.name, names) {
                        Some(s) => d.help(format!("did you mean `{s}`?")),
                        None => d.help(format!("the parameters are: {}", signature(def))),
                    };
                    self.diags.push(d);
                    b.ok = false;
                    b.unknown_named = true;
                }
                found
            }
            None if b.seen_named => {
                self.diags.push(
                    Diagnostic::error(arg.value.span, "positional argument after a named one")
                        .label("give this one a name too")
                        .help(signature(def)),
                );
                b.ok = false;
                None
            }
            None if b.next >= n => {
                if !b.extra_reported {
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
                    b.extra_reported = true;
                }
                b.ok = false;
                None
            }
            None => {
                b.next += 1;
                Some(b.next - 1)
            }
        }
    }

    /// Puts an argument's value in its parameter's slot: refused if the slot is taken, or if
    /// the value is not of the parameter's type.
    fn fill_slot(
        &mut self,
        def: &FnDef,
        index: usize,
        arg: &Arg,
        value: Option<Value>,
        b: &mut Binding,
    ) {
        let param = &def.params[index];
        if let Some((_, first)) = &b.slots[index] {
            self.diags.push(
                Diagnostic::error(
                    arg.value.span,
                    format!("`{}` is given twice", param.name.name),
                )
                .label("second value")
                .also(*first, "first value"),
            );
            b.ok = false;
            return;
        }
        b.given[index] = true;
        let Some(value) = value else {
            b.ok = false;
            return;
        };
        if let Some(want) = self.param_type(param)
            && !fits(want, &value)
        {
            self.diags.push(
                Diagnostic::error(
                    arg.value.span,
                    format!(
                        "`{}` of `{}` takes {}",
                        param.name.name,
                        def.name.name,
                        article(want)
                    ),
                )
                .label(format!("this is {}", value.describe()))
                .also(
                    param.name.span,
                    format!("declared {}", declared_how(param, want)),
                ),
            );
            b.ok = false;
        }
        b.slots[index] = Some((value, arg.value.span));
    }

    /// Reports each parameter without a default that got no argument (only when nothing else
    /// went wrong: a failed or misspelt argument is likely the missing one).
    fn report_missing(&mut self, def: &FnDef, call: &Call, b: &mut Binding) {
        for ((p, slot), given) in def.params.iter().zip(&b.slots).zip(&b.given) {
            if slot.is_none() && !given && p.default.is_none() && !b.unknown_named && b.ok {
                self.diags.push(
                    Diagnostic::error(
                        call.span,
                        format!("`{}` needs its argument `{}`", def.name.name, p.name.name),
                    )
                    .label("missing argument")
                    .also(p.name.span, "a parameter without a default")
                    .help(signature(def)),
                );
                b.ok = false;
            }
        }
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

/// The most parameters a signature in a message lists (a function of 100 000 parameters
/// listed them all in each of its calls' errors).
const SIGNATURE_PARAMS: usize = 12;

/// `pillar(h, r = 0.2)` for messages; a long list cut after [`SIGNATURE_PARAMS`] with the count.
pub(super) fn signature(def: &FnDef) -> String {
    let n = def.params.len();
    let mut ps: Vec<String> = def
        .params
        .iter()
        .take(SIGNATURE_PARAMS)
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
    if n > SIGNATURE_PARAMS {
        ps.push(format!("… {} more", n - SIGNATURE_PARAMS));
    }
    format!("{}({})", def.name.name, ps.join(", "))
}
