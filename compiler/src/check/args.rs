//! Binding call arguments and settings to catalog parameters, with type and range checks.

use super::Checker;
use crate::catalog::{self, Param, Ty, Val};
use crate::diag::{Diagnostic, Span};
use crate::syntax::{Arg, ExprKind};

/// Which arguments of a call or settings block may be computed from parameters.
#[derive(Clone, Copy)]
pub(super) enum RunTime {
    /// None: settings compiled into the shader.
    Never,
    /// Every one (shapes' and operators' arguments; the catalog's types still decide).
    All,
    /// These settings.
    Only(&'static [&'static str]),
}

/// A signature for messages: `sphere(radius = 1)`.
pub fn signature(name: &str, params: &[Param]) -> String {
    let ps: Vec<String> = params
        .iter()
        .map(|p| match p.default {
            Some(d) => format!("{} = {}", p.name, show_val(d, p.ty)),
            None => p.name.to_string(),
        })
        .collect();
    format!("{name}({})", ps.join(", "))
}

/// A settings block's shape for messages: `trace basic { steps 128  epsilon pixel }`.
pub fn settings_signature(name: &str, params: &[Param]) -> String {
    let ps: Vec<String> = params
        .iter()
        .map(|p| match p.default {
            Some(d) => format!("{} {}", p.name, show_val(d, p.ty)),
            None => format!("{} …", p.name),
        })
        .collect();
    format!("{name} {{ {} }}", ps.join("  "))
}

/// A default value as the docs show it.
pub fn show_val(v: Val, ty: Ty) -> String {
    match (v, ty) {
        (Val::Num(x), Ty::Angle) => format!("{}deg", (x.to_degrees() * 1e6).round() / 1e6),
        (Val::Num(x), _) => format!("{x}"),
        (Val::Vec3(v), _) => format!("({}, {}, {})", v.x, v.y, v.z),
        (Val::Word(i), Ty::PositiveOr(words) | Ty::Word(words)) => words[i].to_string(),
        // A colour that defaults to the scene's background (`fog`).
        (Val::Word(_), Ty::Color) => "background".into(),
        (Val::Word(_), _) => "…".into(),
    }
}

/// `translate(0, 1, 0)`, `box(1, 2, 3)`: three plain numbers where the first parameter is a
/// vector and there are fewer than three parameters; the vector meant, said once.
fn loose_vector(what: &str, params: &[Param], args: &[Arg]) -> Option<Diagnostic> {
    let vector = params
        .first()
        .is_some_and(|p| matches!(p.ty, Ty::Vec3 | Ty::Size | Ty::Scale | Ty::Axis | Ty::Color));
    let numbers: Vec<String> = args
        .iter()
        .map(|a| match (&a.name, &a.value.kind) {
            (None, ExprKind::Number { value, unit: None }) => Some(format!("{value}")),
            _ => None,
        })
        .collect::<Option<_>>()?;
    if !vector || numbers.len() != 3 || params.len() >= 3 || is_settings(what) {
        return None;
    }
    let span = args[0].value.span.to(args[2].value.span);
    Some(
        Diagnostic::error(
            span,
            format!(
                "`{}` is a vector, written in its own parentheses",
                params[0].name
            ),
        )
        .label("three numbers")
        .help(format!("write `{what}(({}))`", numbers.join(", "))),
    )
}

/// Whether `what` names a settings block rather than a call.
fn is_settings(what: &str) -> bool {
    super::settings::BLOCK_KEYWORDS
        .iter()
        .any(|k| what.split(' ').next() == Some(k))
}

impl Checker<'_> {
    fn shape_of(what: &str, params: &[Param]) -> String {
        if is_settings(what) {
            settings_signature(what, params)
        } else {
            signature(what, params)
        }
    }

    /// Binds positional and named arguments to `params`; reports every problem found. A
    /// value computed from parameters is an error here (settings are compiled in).
    pub(super) fn bind(
        &mut self,
        what: &str,
        params: &[Param],
        args: &[Arg],
        call_span: Span,
    ) -> Option<Vec<Val>> {
        self.bind_args(what, params, args, call_span, RunTime::Never)
            .map(|(v, _)| v)
    }

    /// As [`Self::bind`]; the arguments `run_time` allows may be computed from parameters,
    /// and each one's components as expressions come back beside the values (none: empty).
    pub(super) fn bind_args(
        &mut self,
        what: &str,
        params: &[Param],
        args: &[Arg],
        call_span: Span,
        run_time: RunTime,
    ) -> Option<(Vec<Val>, catalog::ArgSyms)> {
        if let Some(d) = loose_vector(what, params, args) {
            self.diags.push(d);
            return None;
        }
        let mut syms: catalog::ArgSyms = vec![None; params.len()];
        let mut slots: Vec<Option<(Val, Span)>> = vec![None; params.len()];
        let mut ok = true;
        let mut seen_named = false;
        for (i, arg) in args.iter().enumerate() {
            seen_named |= arg.name.is_some();
            let Some(index) = self.param_index(what, params, i, arg, seen_named) else {
                ok = false;
                continue;
            };
            let param = params[index];
            if let Some((_, first)) = slots[index] {
                self.diags.push(
                    Diagnostic::error(arg.value.span, format!("`{}` is given twice", param.name))
                        .label("second value")
                        .also(first, "first value"),
                );
                ok = false;
                continue;
            }
            let allowed = match run_time {
                RunTime::Never => false,
                RunTime::All => true,
                RunTime::Only(names) => names.contains(&param.name),
            };
            let converted = if allowed {
                self.convert_arg(&arg.value, param.ty, param.name, what)
            } else {
                self.convert(&arg.value, param.ty, param.name)
                    .map(|v| (v, None))
            };
            match converted {
                Some((v, sym)) => {
                    slots[index] = Some((v, arg.value.span));
                    syms[index] = sym;
                }
                None => ok = false,
            }
        }
        let out = self.with_defaults(what, params, &slots, call_span, &mut ok);
        ok.then_some((out, catalog::arg_syms(syms)))
    }

    /// The parameter the `i`th argument binds to: by its name, or by its place; `None`, with
    /// the problem reported, for an unknown name, a positional argument after a named one
    /// (`seen_named`: this one or one before was named), or one too many (reported once, at
    /// the first extra).
    fn param_index(
        &mut self,
        what: &str,
        params: &[Param],
        i: usize,
        arg: &Arg,
        seen_named: bool,
    ) -> Option<usize> {
        match &arg.name {
            Some(name) => {
                let found = params.iter().position(|p| p.name == name.name);
                if found.is_none() {
                    let mut d = Diagnostic::error(
                        name.span,
                        format!("`{what}` has no parameter `{}`", name.name),
                    )
                    .label("unknown parameter");
                    d = match self.did_you_mean(&name.name, params.iter().map(|p| p.name)) {
                        Some(s) => d.help(format!("did you mean `{s}`?")),
                        None => d.help(format!(
                            "the parameters are: {}",
                            Self::shape_of(what, params)
                        )),
                    };
                    self.diags.push(d);
                }
                found
            }
            None if seen_named => {
                self.diags.push(
                    Diagnostic::error(arg.value.span, "positional argument after a named one")
                        .label("give this one a name too")
                        .help(Self::shape_of(what, params)),
                );
                None
            }
            // Reported once, with the first extra argument.
            None if i > params.len() => None,
            None if i == params.len() => {
                self.diags.push(too_many(what, params, arg));
                None
            }
            None => Some(i),
        }
    }

    /// The values by parameter: each given one, else its default; a missing argument without
    /// a default reported (when nothing else was) and `ok` cleared.
    fn with_defaults(
        &mut self,
        what: &str,
        params: &[Param],
        slots: &[Option<(Val, Span)>],
        call_span: Span,
        ok: &mut bool,
    ) -> Vec<Val> {
        let mut out = Vec::with_capacity(params.len());
        for (slot, p) in slots.iter().zip(params) {
            match (slot, p.default) {
                (Some((v, _)), _) => out.push(*v),
                (None, Some(d)) => out.push(d),
                (None, None) => {
                    if *ok {
                        self.diags.push(
                            Diagnostic::error(call_span, format!("missing argument `{}`", p.name))
                                .label(format!("`{what}` needs `{}`", p.name))
                                .help(Self::shape_of(what, params)),
                        );
                    }
                    *ok = false;
                }
            }
        }
        out
    }
}

/// "takes n arguments, but more were given", at the first extra argument (with a hint when a
/// vector's components were written as arguments).
fn too_many(what: &str, params: &[Param], arg: &Arg) -> Diagnostic {
    let n = params.len();
    let s = if n == 1 { "" } else { "s" };
    let mut d = Diagnostic::error(
        arg.value.span,
        format!("`{what}` takes {n} argument{s}, but more were given"),
    )
    .label("unexpected argument")
    .help(Checker::shape_of(what, params));
    if matches!(arg.value.kind, ExprKind::Number { .. })
        && params
            .iter()
            .any(|p| matches!(p.ty, Ty::Size | Ty::Vec3 | Ty::Scale))
    {
        d = d.help("a vector is written in its own parentheses: `box((1, 2, 3))`");
    }
    d
}
