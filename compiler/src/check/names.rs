//! Checking a name: a coordinate, a function's argument, a `let`, a parameter or a constant;
//! or, when it is none, the most likely mistake (a function or operator without its call, a
//! definition further down, a misspelling).

use super::{Binding, Checker, Dim, Value, functions};
use crate::catalog;
use crate::diag::{Diagnostic, Span};
use crate::scene::Field;
use crate::syntax::Ident;

/// Named constants: π and τ = 2π.
pub(super) const CONSTANTS: &[(&str, f64)] =
    &[("pi", std::f64::consts::PI), ("tau", std::f64::consts::TAU)];

impl Checker<'_> {
    /// A name's value; `None` with the problem reported when it has none.
    pub(super) fn name(&mut self, id: &Ident) -> Option<Value> {
        if self.in_implicit
            && let Some(i) = ["x", "y", "z"].iter().position(|a| *a == id.name)
        {
            return Some(Value::Field(Field::Coord(i)));
        }
        if let Some(v) = self.fn_arg(&id.name) {
            return Some(v);
        }
        if !self.visible(&id.name) {
            return self.defined_after_fn(id);
        }
        if let Some((binding, _)) = self.lets.get(&id.name) {
            return match binding {
                Binding::Value(v) => Some(v.clone()),
                Binding::Failed => None,
            };
        }
        if let Some(v) = self.param_ref(&id.name) {
            return Some(v);
        }
        // The circle constants, plain numbers (radians need no unit where a number is taken;
        // an angle argument takes `pi * 1rad`).
        if let Some(&(_, x)) = CONSTANTS.iter().find(|(n, _)| *n == id.name) {
            return Some(Value::Num(x, Dim::None));
        }
        if self.failed.contains(&id.name) {
            return None;
        }
        let d = self.not_a_value(id);
        self.diags.push(d);
        None
    }

    /// The diagnostic for a name that has no value here: a function or operator written
    /// without its call, a name used in its own definition or before it, or an unknown name.
    fn not_a_value(&mut self, id: &Ident) -> Diagnostic {
        if let Some(f) = self.fns.get(&id.name) {
            Diagnostic::error(id.span, format!("`{}` is a function", id.name))
                .label("a function, written without its arguments")
                .also(f.def.name.span, "defined here")
                .help(format!("call it: `{}`", functions::signature(f.def)))
        } else if let Some((name, def)) = self.defining.filter(|(n, _)| *n == id.name) {
            let mut d = Diagnostic::error(id.span, format!("`{name}` refers to itself"))
                .label("used inside its own definition")
                .note("definitions cannot be recursive");
            if self.line_of(id.span.start) > self.line_of(def.start) {
                d = d.help(format!("if the value of `let {name} =` is missing, add it: a line break does not end a `let`"));
            }
            d
        } else if let Some(def) = self.declared.get(&id.name) {
            let what = if self.materials.iter().any(|m| m.name == id.name)
                || self.is_material_declared_at(*def)
            {
                "a material, not a value"
            } else {
                "defined later in the file"
            };
            Diagnostic::error(
                id.span,
                format!("`{}` is used before its definition", id.name),
            )
            .label(what)
            .also(*def, "defined here")
            .help("move the definition above its first use")
        } else if catalog::operator(&id.name).is_some() {
            Diagnostic::error(id.span, format!("`{}` needs a block of shapes", id.name))
                .label("an operator, written without its shapes")
                .help(format!(
                    "write `{} {{ a b }}` or `a |> {}`",
                    id.name, id.name
                ))
        } else if catalog::all_names().any(|n| n == id.name) {
            Diagnostic::error(id.span, format!("`{}` needs arguments", id.name))
                .label("a call, written without parentheses")
                .help(format!("write `{}(...)`", id.name))
        } else {
            self.unknown_name(id)
        }
    }

    /// An unknown name, with the nearest `let` or block keyword (a misspelt block keyword
    /// also marks its line, so the rest of the statement is not another error).
    fn unknown_name(&mut self, id: &Ident) -> Diagnostic {
        let mut d =
            Diagnostic::error(id.span, format!("unknown name `{}`", id.name)).label("not defined");
        let lets: Vec<&str> = self.lets.keys().map(String::as_str).collect();
        if let Some(s) = self.did_you_mean(&id.name, lets) {
            d = d.help(format!("did you mean `{s}`?"));
        } else if let Some(k) =
            self.did_you_mean(&id.name, super::settings::BLOCK_KEYWORDS.iter().copied())
        {
            d = d.help(format!("did you mean the `{k}` block?"));
            // `matrial gold { … }`: the block's name and settings, read as a call, are
            // not another mistake.
            self.keyword_typo_line = Some(self.line_of(id.span.start));
        } else if ["x", "y", "z"].contains(&id.name.as_str()) {
            d = d.note("coordinates exist only inside `implicit { ... }`");
        }
        d
    }

    fn is_material_declared_at(&self, span: Span) -> bool {
        self.material_spans.contains(&span)
    }
}
