//! Checking parameters: the built-in `time`, values computed from parameters (kept as
//! expressions the shader evaluates), and their use as arguments over their whole range
//! (`param_decl.rs` has the `param` declarations).

use super::{Checker, Dim, Value};
use crate::diag::{Diagnostic, Span};
use crate::interval::Interval;
use crate::scene::{Field, ParamDecl, ParamKind, ParamRef};
use crate::syntax::BinOp;
use glam::DVec3;

/// The name of the built-in parameter: seconds since the animation started, set by the host.
pub const TIME: &str = "time";

/// A value that depends on parameters: one expression per component.
#[derive(Clone, Debug)]
pub(crate) struct Sym {
    /// What it is.
    pub kind: SymKind,
    /// One component (numbers) or three (vectors, colours).
    pub comps: Vec<Field>,
}

/// What a [`Sym`] holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SymKind {
    /// A number with its dimension.
    Num(Dim),
    /// A vector.
    Vec3,
    /// A colour.
    Color,
}

impl Sym {
    /// Its value where the scene is checked (every parameter at its value).
    pub fn value(&self) -> Value {
        let at = |i: usize| self.comps[i].eval(DVec3::ZERO);
        match self.kind {
            SymKind::Num(d) => Value::Num(at(0), d),
            SymKind::Vec3 => Value::Vec3(DVec3::new(at(0), at(1), at(2))),
            SymKind::Color => Value::Color(DVec3::new(at(0), at(1), at(2))),
        }
    }

    /// Its components as three (a number repeated).
    pub(super) fn three(&self) -> [Field; 3] {
        [0, 1, 2].map(|i| self.comps[i.min(self.comps.len() - 1)].clone())
    }

    /// The names of the parameters it reads, each once.
    pub(super) fn reads(&self, params: &[ParamDecl]) -> Vec<String> {
        let mut seen: Vec<usize> = Vec::new();
        for c in &self.comps {
            c.params(&mut |r| {
                if !seen.contains(&r.index) {
                    seen.push(r.index);
                }
            });
        }
        seen.iter().map(|&i| params[i].name.clone()).collect()
    }
}

/// A value as constant components (numbers and vectors), for mixing with a [`Sym`].
fn comps_of(v: &Value) -> Vec<Field> {
    match v {
        Value::Param(s) => s.comps.clone(),
        Value::Num(x, _) => vec![Field::Const(*x)],
        Value::Vec3(v) | Value::Color(v) => v.to_array().map(Field::Const).to_vec(),
        Value::Field(f) => vec![f.clone()],
        Value::Shape(_) => vec![Field::Const(f64::NAN)],
    }
}

/// The range of each component of an expression over every value its parameters may take,
/// and the first reason it may be undefined there.
pub(crate) fn range_of(f: &Field) -> (Interval, Option<String>) {
    crate::lipschitz::value_range(f)
}

impl Checker<'_> {
    /// The value of a parameter's name, if it is one (`time` is declared on first use).
    pub(super) fn param_ref(&mut self, name: &str) -> Option<Value> {
        let index = match self.param_index.get(name) {
            Some(&i) => i,
            None if name == TIME => {
                let value = match self.overrides.get(TIME) {
                    Some(v) => v.first().copied().unwrap_or(0.0),
                    None => 0.0,
                };
                self.params.push(ParamDecl {
                    name: TIME.into(),
                    kind: ParamKind::Number,
                    default: DVec3::ZERO,
                    value: DVec3::new(value, 0.0, 0.0),
                    range: None,
                    span: Span::new(0, 0),
                });
                self.param_used.push(false);
                self.param_index.insert(TIME.into(), self.params.len() - 1);
                self.params.len() - 1
            }
            None => return None,
        };
        self.param_used[index] = true;
        let decl = &self.params[index];
        let comps = (0..decl.kind.components())
            .map(|comp| {
                let (lo, hi) = match decl.range {
                    Some((lo, hi)) => (lo[comp], hi[comp]),
                    None => (f64::NEG_INFINITY, f64::INFINITY),
                };
                Field::Param(ParamRef {
                    index,
                    comp,
                    value: decl.value[comp],
                    lo,
                    hi,
                })
            })
            .collect();
        let kind = match decl.kind {
            ParamKind::Number => SymKind::Num(Dim::None),
            ParamKind::Angle => SymKind::Num(Dim::Angle),
            ParamKind::Vector => SymKind::Vec3,
            ParamKind::Color => SymKind::Color,
        };
        Some(Value::Param(Sym { kind, comps }))
    }

    /// `a ∘ b` where one side depends on parameters: typed as the constant values are (which
    /// also checks them where the scene is checked), computed per component at run time.
    pub(super) fn param_binary(
        &mut self,
        op: BinOp,
        a: Value,
        b: Value,
        span: Span,
    ) -> Option<Value> {
        let constant = |v: &Value| match v {
            Value::Param(s) => s.value(),
            other => other.clone(),
        };
        let result = self.binary(op, constant(&a), constant(&b), span)?;
        let (fa, fb) = (comps_of(&a), comps_of(&b));
        let bin =
            |x: &Field, y: &Field| Field::Binary(op, Box::new(x.clone()), Box::new(y.clone()));
        Some(match result {
            Value::Field(_) => Value::Field(bin(&fa[0], &fb[0])),
            Value::Num(_, d) => Value::Param(Sym {
                kind: SymKind::Num(d),
                comps: vec![bin(&fa[0], &fb[0])],
            }),
            Value::Vec3(_) => {
                let at = |f: &[Field], i: usize| f[i.min(f.len() - 1)].clone();
                Value::Param(Sym {
                    kind: SymKind::Vec3,
                    comps: (0..3).map(|i| bin(&at(&fa, i), &at(&fb, i))).collect(),
                })
            }
            other => other,
        })
    }

    /// `(a, b, c)` where a component depends on parameters.
    pub(super) fn param_vector(&mut self, parts: &[Value]) -> Value {
        let comps = parts.iter().map(|p| comps_of(p)[0].clone()).collect();
        Value::Param(Sym {
            kind: SymKind::Vec3,
            comps,
        })
    }

    /// Warnings for declared parameters the scene never reads.
    pub(super) fn unused_params(&mut self) {
        for (i, p) in self.params.iter().enumerate() {
            if !self.param_used[i] && p.name != TIME {
                self.diags.push(
                    Diagnostic::warning(p.span, format!("parameter `{}` is never used", p.name))
                        .label("declared here")
                        .note("the library keeps it in its `Params` uniform for a host; the other entries leave it out"),
                );
            }
        }
    }
}
