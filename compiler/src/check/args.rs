//! Binding call arguments and settings to catalog parameters, with type and range checks.

use super::{Checker, Dim, Value};
use crate::catalog::{self, Param, Ty, Val};
use crate::diag::{Diagnostic, Span, did_you_mean};
use crate::scene::Field;
use crate::syntax::{Arg, Expr, ExprKind};
use glam::DVec3;

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
            let index = match &arg.name {
                Some(name) => {
                    seen_named = true;
                    match params.iter().position(|p| p.name == name.name) {
                        Some(k) => k,
                        None => {
                            let mut d = Diagnostic::error(
                                name.span,
                                format!("`{what}` has no parameter `{}`", name.name),
                            )
                            .label("unknown parameter");
                            d = match did_you_mean(&name.name, params.iter().map(|p| p.name)) {
                                Some(s) => d.help(format!("did you mean `{s}`?")),
                                None => d.help(format!(
                                    "the parameters are: {}",
                                    Self::shape_of(what, params)
                                )),
                            };
                            self.diags.push(d);
                            ok = false;
                            continue;
                        }
                    }
                }
                None if seen_named => {
                    self.diags.push(
                        Diagnostic::error(arg.value.span, "positional argument after a named one")
                            .label("give this one a name too")
                            .help(Self::shape_of(what, params)),
                    );
                    ok = false;
                    continue;
                }
                None if i >= params.len() && i > params.len() => {
                    // Reported once, with the first extra argument.
                    ok = false;
                    continue;
                }
                None if i >= params.len() => {
                    let n = params.len();
                    let s = if n == 1 { "" } else { "s" };
                    let mut d = Diagnostic::error(
                        arg.value.span,
                        format!("`{what}` takes {n} argument{s}, but more were given"),
                    )
                    .label("unexpected argument")
                    .help(Self::shape_of(what, params));
                    if matches!(arg.value.kind, ExprKind::Number { .. })
                        && params
                            .iter()
                            .any(|p| matches!(p.ty, Ty::Size | Ty::Vec3 | Ty::Scale))
                    {
                        d = d.help("a vector is written in its own parentheses: `box((1, 2, 3))`");
                    }
                    self.diags.push(d);
                    ok = false;
                    continue;
                }
                None => i,
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
        let mut out = Vec::with_capacity(params.len());
        for (slot, p) in slots.iter().zip(params) {
            match (slot, p.default) {
                (Some((v, _)), _) => out.push(*v),
                (None, Some(d)) => out.push(d),
                (None, None) => {
                    if ok {
                        self.diags.push(
                            Diagnostic::error(call_span, format!("missing argument `{}`", p.name))
                                .label(format!("`{what}` needs `{}`", p.name))
                                .help(Self::shape_of(what, params)),
                        );
                    }
                    ok = false;
                }
            }
        }
        ok.then_some((out, catalog::arg_syms(syms)))
    }

    /// Converts an expression to a value of type `ty`, checking its range.
    pub(super) fn convert(&mut self, e: &Expr, ty: Ty, param: &str) -> Option<Val> {
        self.convert_full(e, ty, param, None).map(|(v, _)| v)
    }

    /// As [`Self::convert`], where the value may be computed from parameters when `call` names
    /// the primitive or operator it is an argument of: then also its components as
    /// expressions for the shader.
    pub(super) fn convert_arg(
        &mut self,
        e: &Expr,
        ty: Ty,
        param: &str,
        call: &str,
    ) -> Option<(Val, Option<Vec<Field>>)> {
        self.convert_full(e, ty, param, Some(call))
    }

    fn convert_full(
        &mut self,
        e: &Expr,
        ty: Ty,
        param: &str,
        call: Option<&str>,
    ) -> Option<(Val, Option<Vec<Field>>)> {
        // Words that are not names of bindings: axes and enumerations.
        if let ExprKind::Name(id) = &e.kind
            && !self.lets.contains_key(&id.name)
        {
            match ty {
                Ty::Axis => {
                    if let Some(i) = ["x", "y", "z"].iter().position(|a| *a == id.name) {
                        return Some((Val::Vec3(DVec3::AXES[i]), None));
                    }
                    if !self.declared.contains_key(&id.name) {
                        let d = Diagnostic::error(id.span, format!("unknown axis `{}`", id.name))
                            .label("not an axis")
                            .help("the axes are `x`, `y` and `z` (lower case), or any vector `(x, y, z)`");
                        self.diags.push(d);
                        return None;
                    }
                }
                Ty::PositiveOr(words) | Ty::Word(words) => {
                    if let Some(i) = words.iter().position(|w| *w == id.name) {
                        return Some((Val::Word(i), None));
                    }
                    if !self.declared.contains_key(&id.name) {
                        let mut d = Diagnostic::error(
                            id.span,
                            format!("`{param}` must be {}", ty.describe()),
                        )
                        .label(format!("`{}` is not a word it knows", id.name));
                        if let Some(w) = did_you_mean(&id.name, words.iter().copied()) {
                            d = d.help(format!("did you mean `{w}`?"));
                        }
                        self.diags.push(d);
                        return None;
                    }
                }
                _ => {}
            }
        }
        if let (Ty::Axis, ExprKind::Neg(inner)) = (ty, &e.kind)
            && let ExprKind::Name(id) = &inner.kind
            && !self.lets.contains_key(&id.name)
            && let Some(i) = ["x", "y", "z"].iter().position(|a| *a == id.name)
        {
            return Some((Val::Vec3(-DVec3::AXES[i]), None));
        }
        let value = self.value(e)?;
        if let (Value::Param(s), Some(call)) = (&value, call) {
            if let Some(op) = catalog::operator(call)
                && op.fixed_args
            {
                self.diags.push(
                    Diagnostic::error(e.span, format!("the arguments of `{call}` cannot be parameters"))
                        .label("computed from parameters")
                        .note(format!("`{call}` shapes the shader's code by its arguments' values, and the shader is compiled once")),
                );
                return None;
            }
            let (v, comps) = self.param_arg(e, ty, param, s.clone())?;
            return Some((v, Some(comps)));
        }
        if let Value::Param(_) = &value {
            self.diags.push(
                Diagnostic::error(e.span, format!("`{param}` cannot be a parameter"))
                    .label(format!("this is {}", value.describe()))
                    .note(format!("the shader is compiled with `{param}` in it; what can change at run time: shapes' and operators' arguments, a material's `color` and `specular`, a light's direction or position, `color` and `intensity`")),
            );
            return None;
        }
        self.convert_checked(e, ty, param, value).map(|v| (v, None))
    }

    /// [`Self::convert_value`] and the check that the value fits f32.
    fn convert_checked(&mut self, e: &Expr, ty: Ty, param: &str, value: Value) -> Option<Val> {
        let v = self.convert_value(e, ty, param, value)?;
        if !v.fits_gpu() {
            self.diags.push(
                Diagnostic::error(e.span, format!("`{param}` is beyond what the GPU's f32 arithmetic can use"))
                    .label("out of range")
                    .note(format!(
                        "numbers in a scene must be 0 or between {:e} and {:e} in size: the shader computes in f32, and squares or reciprocals of larger (or smaller) values overflow",
                        catalog::GPU_RANGE.0,
                        catalog::GPU_RANGE.1
                    )),
            );
            return None;
        }
        Some(v)
    }

    /// The value of an argument as its parameter's type, or an error.
    pub(super) fn convert_value(
        &mut self,
        e: &Expr,
        ty: Ty,
        param: &str,
        value: Value,
    ) -> Option<Val> {
        // Described only for an error (a string per argument was 2% of checking 10 000 nodes).
        let shown = value.clone();
        let found = || shown.describe();
        let bad = |this: &mut Self, why: String| {
            this.diags.push(
                Diagnostic::error(e.span, format!("`{param}` must be {}", ty.describe()))
                    .label(why),
            );
            None
        };
        match (ty, value) {
            (Ty::Angle, Value::Num(x, Dim::Angle)) => Some(Val::Num(x)),
            (Ty::Angle, Value::Num(x, Dim::None)) => {
                let help = if matches!(e.kind, ExprKind::Number { .. }) {
                    format!("write `{x}deg` or `{x}rad`")
                } else {
                    // A computed number (`pi / 4`): its unit is a factor.
                    "multiply it by a unit: `(…) * 1rad` for radians, `* 1deg` for degrees".into()
                };
                self.diags.push(
                    Diagnostic::error(e.span, format!("`{param}` is an angle and needs a unit"))
                        .label("no unit")
                        .help(help),
                );
                None
            }
            (_, Value::Num(_, Dim::Angle)) if !matches!(ty, Ty::Angle) => {
                bad(self, "found an angle".into())
            }
            (ty, Value::Num(x, _)) if ty.accepts_number(x) => Some(Val::Num(x)),
            (Ty::Size, Value::Num(x, _)) if x >= 0.0 => Some(Val::Vec3(DVec3::splat(x))),
            (Ty::Size, Value::Vec3(v)) if v.min_element() >= 0.0 => Some(Val::Vec3(v)),
            (Ty::Counts, Value::Num(x, _)) if x >= 0.0 && x.fract() == 0.0 => {
                Some(Val::Vec3(DVec3::splat(x)))
            }
            (Ty::Counts, Value::Vec3(v)) if v.min_element() >= 0.0 && v.fract() == DVec3::ZERO => {
                Some(Val::Vec3(v))
            }
            (Ty::Scale, Value::Num(x, _)) if x > 0.0 => Some(Val::Vec3(DVec3::splat(x))),
            (Ty::Scale, Value::Vec3(v)) if v.min_element() > 0.0 => Some(Val::Vec3(v)),
            (Ty::Vec3, Value::Vec3(v)) => Some(Val::Vec3(v)),
            (Ty::Axis, Value::Vec3(v)) if v.length() > 1e-12 => Some(Val::Vec3(v.normalize())),
            (Ty::Color, Value::Color(c)) => Some(Val::Vec3(c)),
            (Ty::Color, Value::Vec3(v)) if v.min_element() >= 0.0 && v.max_element() <= 1.0 => {
                Some(Val::Vec3(v))
            }
            (Ty::Scale, Value::Num(..) | Value::Vec3(_)) => {
                let d = Diagnostic::error(e.span, format!("`{param}` must be {}", ty.describe()))
                    .label(format!("found {}", found()))
                    .note("a zero or negative scale has no distance field; mirror with `mirror(axis)`");
                self.diags.push(d);
                None
            }
            (Ty::Axis, Value::Vec3(_)) => bad(self, "a zero vector has no direction".into()),
            (_, Value::Num(..)) if !matches!(ty, Ty::Vec3 | Ty::Axis | Ty::Color) => {
                bad(self, format!("found {}", found()))
            }
            (Ty::Size | Ty::Counts | Ty::Color, Value::Vec3(_)) => {
                bad(self, format!("found {}", found()))
            }
            _ => bad(self, format!("found {}", found())),
        }
    }
}
