//! Converting a checked expression to a catalog value of a parameter's type, with its range
//! checked, and (for arguments that may be) its components as expressions of parameters.

use super::{Checker, Dim, Value};
use crate::catalog::{self, Ty, Val};
use crate::diag::Diagnostic;
use crate::scene::Field;
use crate::syntax::{Expr, ExprKind};
use glam::DVec3;

impl Checker<'_> {
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
                        if let Some(w) = self.did_you_mean(&id.name, words.iter().copied()) {
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
