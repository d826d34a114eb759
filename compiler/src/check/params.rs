//! Checking parameters: `param` declarations and the built-in `time`, values computed from them
//! (kept as expressions the shader evaluates), and their use as arguments over their whole range.

use super::{Checker, Dim, Value};
use crate::catalog;
use crate::diag::{Diagnostic, Span};
use crate::interval::Interval;
use crate::scene::{Field, ParamDecl, ParamKind, ParamRef};
use crate::syntax::{BinOp, Expr, Ident};
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

    fn param_decl(
        &mut self,
        name: &Ident,
        value: &Expr,
        range: Option<&(Expr, Expr)>,
        span: Span,
    ) -> Option<ParamDecl> {
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
        let n = kind.components();
        let range = match range {
            // A colour's components are 0…1 whatever the host sets.
            None if kind == ParamKind::Color => Some((DVec3::ZERO, DVec3::ONE)),
            None => None,
            Some((lo, hi)) => {
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
                        Diagnostic::error(value.span, "the default is outside the range")
                            .label("not in the range")
                            .also(lo.span.to(hi.span), "the range"),
                    );
                    return None;
                }
                Some((a, b))
            }
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
