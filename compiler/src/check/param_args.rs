//! Arguments computed from parameters: typed over every value the parameters may take (by
//! interval arithmetic over their ranges), as expressions per component for the shader.

use super::Checker;
use super::params::{Sym, SymKind, TIME, range_of};
use crate::catalog::{self, Ty, Val};
use crate::diag::Diagnostic;
use crate::interval::Interval;
use crate::scene::Field;
use crate::syntax::{BinOp, Expr};

impl Checker<'_> {
    /// An argument that depends on parameters, as a value of `ty` where the scene is checked and
    /// as per-component expressions for the shader (a number broadcast for sizes and scales,
    /// an axis normalised). Every value the parameters may take must be of the type: checked
    /// by interval arithmetic over their ranges.
    pub(super) fn param_arg(
        &mut self,
        e: &Expr,
        ty: Ty,
        param: &str,
        s: Sym,
    ) -> Option<(Val, Vec<Field>)> {
        let fixed = matches!(
            ty,
            Ty::Count
                | Ty::CountTo(_)
                | Ty::WholeIn(..)
                | Ty::UpTo(_)
                | Ty::Counts
                | Ty::Word(_)
                | Ty::PositiveOr(_)
                | Ty::ZeroOrAtLeast(_)
        );
        if fixed {
            self.diags.push(
                Diagnostic::error(e.span, format!("`{param}` cannot be a parameter"))
                    .label(format!("reads {}", self.reads_text(&s)))
                    .note(format!(
                        "`{param}` is {}: it decides the shape of the shader's code, which is compiled once",
                        ty.describe()
                    )),
            );
            return None;
        }
        let val = self.convert_value(e, ty, param, s.value())?;
        self.check_over_ranges(e, ty, param, &s)?;
        let comps = self.shader_comps(e, ty, param, s, &val)?;
        Some((val, comps))
    }

    /// Every value the parameters `s` reads may take gives a defined value of `ty`: checked per
    /// component by interval arithmetic over their ranges.
    fn check_over_ranges(&mut self, e: &Expr, ty: Ty, param: &str, s: &Sym) -> Option<()> {
        for c in &s.comps {
            let (range, undefined) = range_of(c);
            if let Some(why) = undefined {
                self.diags.push(
                    Diagnostic::error(
                        e.span,
                        format!(
                            "`{param}` is not defined for every value of {}",
                            self.reads_text(s)
                        ),
                    )
                    .label(why)
                    .help(self.range_help(s)),
                );
                return None;
            }
            if !range_fits(ty, range) {
                self.diags.push(
                    Diagnostic::error(
                        e.span,
                        format!(
                            "`{param}` must be {} for every value of {}",
                            ty.describe(),
                            self.reads_text(s)
                        ),
                    )
                    .label(if range.lo.is_finite() && range.hi.is_finite() {
                        format!("ranges over [{}, {}]", range.lo, range.hi)
                    } else {
                        "it may be any value".to_string()
                    })
                    .help(self.range_help(s)),
                );
                return None;
            }
        }
        Some(())
    }

    /// The argument's components as expressions for the shader: an axis normalised (refused
    /// where it may be zero), a number broadcast where the value is a vector.
    fn shader_comps(
        &mut self,
        e: &Expr,
        ty: Ty,
        param: &str,
        s: Sym,
        val: &Val,
    ) -> Option<Vec<Field>> {
        Some(match (ty, s.kind) {
            (Ty::Axis, SymKind::Vec3) => {
                let len = Field::Call(catalog::math_fn("length").expect("length"), s.comps.clone());
                if range_of(&len).0.lo <= 1e-12 {
                    self.diags.push(
                        Diagnostic::error(
                            e.span,
                            format!("`{param}` may be a zero vector, which has no direction"),
                        )
                        .label(format!("for some values of {}", self.reads_text(&s)))
                        .help(self.range_help(&s)),
                    );
                    return None;
                }
                s.comps
                    .iter()
                    .map(|c| Field::Binary(BinOp::Div, Box::new(c.clone()), Box::new(len.clone())))
                    .collect()
            }
            (_, SymKind::Num(_)) if matches!(val, Val::Vec3(_)) => s.three().to_vec(),
            _ => s.comps,
        })
    }

    /// "`r`" or "`a` and `b`": the parameters a value reads.
    pub(super) fn reads_text(&self, s: &Sym) -> String {
        let names: Vec<String> = s
            .reads(&self.params)
            .iter()
            .map(|n| format!("`{n}`"))
            .collect();
        names.join(" and ")
    }

    fn range_help(&self, s: &Sym) -> String {
        let unranged: Vec<String> = s
            .reads(&self.params)
            .into_iter()
            .filter(|n| self.params[self.param_index[n]].range.is_none())
            .collect();
        match unranged.first() {
            Some(n) if n == TIME => "give `time` a range: `param time = 0 in 0..10`".into(),
            Some(n) => {
                format!("give `{n}` a range that keeps it valid: `param {n} = … in low..high`")
            }
            None => "narrow the parameters' ranges".into(),
        }
    }
}

/// Whether every value in `r` is a value of `ty` (the number types; vectors per component).
fn range_fits(ty: Ty, r: Interval) -> bool {
    match ty {
        Ty::Number | Ty::Vec3 | Ty::Angle | Ty::Axis => true,
        Ty::Length | Ty::Size => r.lo >= 0.0,
        Ty::Positive | Ty::Scale => r.lo > 0.0,
        Ty::Fraction | Ty::Color => r.lo >= 0.0 && r.hi <= 1.0,
        Ty::Range(lo, hi) => r.lo >= lo && r.hi < hi,
        _ => false,
    }
}
