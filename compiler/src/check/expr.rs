//! Checking expressions: numbers with units, vectors, colours, names, arithmetic, pipes and
//! where annotations apply (`call.rs` has calls, `names.rs` names, `arith.rs` arithmetic,
//! `implicit.rs` the `implicit` bodies).

use super::params::{Sym, SymKind};
use super::{Checker, Dim, MAX_DEPTH, Value};
use crate::catalog;
use crate::diag::{Diagnostic, Span};
use crate::scene::{Field, NodeId};
use crate::syntax::{BinOp, Expr, ExprKind, Ident};
use glam::DVec3;

/// Units a number may carry, and the factor to radians.
const UNITS: &[(&str, f64)] = &[("deg", std::f64::consts::PI / 180.0), ("rad", 1.0)];

impl Checker<'_> {
    /// Checks an expression that must be a shape.
    pub(super) fn shape(&mut self, e: &Expr) -> Option<NodeId> {
        match self.value(e)? {
            Value::Shape(n) => Some(n),
            other => {
                self.diags.push(
                    Diagnostic::error(e.span, "expected a shape")
                        .label(format!("this is {}", other.describe())),
                );
                None
            }
        }
    }

    /// Checks any expression; `None` means an error was reported.
    pub(super) fn value(&mut self, e: &Expr) -> Option<Value> {
        if self.depth >= MAX_DEPTH {
            if !self.depth_reported {
                self.diags.push(
                    Diagnostic::error(e.span, "expression nested too deeply")
                        .label(format!(
                            "more than {MAX_DEPTH} levels of operators or calls"
                        ))
                        .help("split it into `let` bindings"),
                );
                self.depth_reported = true;
            }
            return None;
        }
        self.depth += 1;
        let v = self.value_inner(e);
        self.depth -= 1;
        v
    }

    /// One expression, by its kind (below the depth check of [`Checker::value`]).
    fn value_inner(&mut self, e: &Expr) -> Option<Value> {
        match &e.kind {
            ExprKind::Number { value, unit } => self.number(*value, unit.as_ref(), e.span),
            ExprKind::Color(text) => self.color(text, e.span),
            ExprKind::Vector(parts) => self.vector(&parts[..]),
            ExprKind::Name(id) => self.name(id),
            ExprKind::Call(call) => self.call(call, None),
            ExprKind::Neg(a) => self.negate(a, e.span),
            ExprKind::Binary(op, a, b) => self.binary_expr(*op, a, b, e.span),
            ExprKind::Pipe(lhs, call) => {
                let child = self.shape(lhs)?;
                self.call(call, Some(child))
            }
            ExprKind::Tag(lhs, material) => self.tag(lhs, material, e.span),
            ExprKind::Annotation(lhs, name, args) => self.annotate(lhs, name, args, e.span),
            ExprKind::Component(lhs, id) => {
                let v = self.value(lhs)?;
                self.component(v, id, e.span)
            }
            ExprKind::At(lhs, offset) => {
                let n = self.shape(lhs);
                let v = self.convert_arg(offset, catalog::Ty::Vec3, "offset", "translate");
                let (v, sym) = v?;
                let sym = if sym.is_some() { vec![sym] } else { Vec::new() };
                self.operator_node("translate", (vec![v], sym), vec![n?], e.span)
                    .map(Value::Shape)
            }
        }
    }

    /// `(x, y, z)`: three numbers, a constant vector, or a parameter's when one is.
    fn vector(&mut self, parts: &[Expr]) -> Option<Value> {
        let mut v = DVec3::ZERO;
        let mut ok = true;
        let mut values = Vec::new();
        for (i, part) in parts.iter().enumerate() {
            let value = self.value(part);
            if let Some(p) = &value {
                values.push(p.clone());
            }
            match value {
                Some(Value::Num(x, Dim::None)) => v[i] = x,
                Some(Value::Param(s)) if s.kind == SymKind::Num(Dim::None) => {}
                Some(other) => {
                    self.diags.push(
                        Diagnostic::error(part.span, "a vector's components must be numbers")
                            .label(format!("this is {}", other.describe())),
                    );
                    ok = false;
                }
                None => ok = false,
            }
        }
        if ok && values.iter().any(|p| matches!(p, Value::Param(_))) {
            return Some(self.param_vector(&values));
        }
        ok.then_some(Value::Vec3(v))
    }

    /// `-a` of a number, vector, field or parameter.
    fn negate(&mut self, a: &Expr, span: Span) -> Option<Value> {
        match self.value(a)? {
            Value::Num(x, d) => Some(Value::Num(-x, d)),
            Value::Vec3(v) => Some(Value::Vec3(-v)),
            Value::Field(f) => Some(Value::Field(Field::Neg(Box::new(f)))),
            Value::Param(s) => Some(Value::Param(Sym {
                comps: s
                    .comps
                    .into_iter()
                    .map(|c| Field::Neg(Box::new(c)))
                    .collect(),
                ..s
            })),
            other => self.no_arithmetic(span, "-", &other),
        }
    }

    /// `a op b`; `s at a + b` (a shape moved, then a vector added) refused.
    fn binary_expr(&mut self, op: BinOp, a: &Expr, b: &Expr, span: Span) -> Option<Value> {
        let at = matches!(a.kind, ExprKind::At(..)) && matches!(op, BinOp::Add | BinOp::Sub);
        let (va, vb) = (self.value(a), self.value(b));
        let (va, vb) = (va?, vb?);
        if at && matches!(va, Value::Shape(_)) && matches!(vb, Value::Vec3(_) | Value::Param(_)) {
            self.diags.push(
                Diagnostic::error(span, format!("`at` binds tighter than `{}`", op.symbol()))
                    .label("this moves the shape, then adds a vector to it")
                    .help("put the whole offset in parentheses: `s at (a + b)`"),
            );
            return None;
        }
        self.binary(op, va, vb, span)
    }

    /// `shape @ material`: a copy of the shape with the material, unless it has one already.
    fn tag(&mut self, lhs: &Expr, material: &Ident, span: Span) -> Option<Value> {
        let n = self.shape(lhs);
        let m = self.material_ref(material);
        let (n, m) = (n?, m?);
        if let Some(inner) = self.nodes[n].material {
            // The innermost tag wins (a tag covers only parts without a material of
            // their own), so this one has no effect: say so rather than ignore it.
            let inner = self.materials[inner as usize].name.clone();
            self.diags.push(
                Diagnostic::warning(material.span, "this material has no effect")
                    .label(format!("the shape is already `{inner}`"))
                    .note("a tag applies only to parts that have no material of their own; the innermost tag wins"),
            );
            return Some(Value::Shape(n));
        }
        let n = self.copy_node(n)?;
        self.nodes[n].material = Some(m);
        self.nodes[n].span = span;
        Some(Value::Shape(n))
    }

    /// `shape : lipschitz(l)`: a copy of the shape with λ = l (a warning when looser than
    /// the inferred bound).
    fn annotate(
        &mut self,
        lhs: &Expr,
        name: &Ident,
        args: &[crate::syntax::Arg],
        span: Span,
    ) -> Option<Value> {
        let n = self.shape(lhs);
        let l = self.annotation(name, args, span);
        let (n, l) = (n?, l?);
        let inferred = self.nodes[n].inferred_lambda;
        if inferred.is_finite() && l > inferred * (1.0 + 1e-9) {
            self.diags.push(
                Diagnostic::warning(span, "annotation is looser than the inferred bound")
                    .label(format!("inferred λ = {}", short(inferred)))
                    .note(format!(
                        "tracing steps by f/λ, so λ = {} makes steps {:.2}× shorter than needed",
                        short(l),
                        l / inferred
                    )),
            );
        }
        let n = self.copy_node(n)?;
        self.nodes[n].lambda = l;
        // The annotation's λ may exceed the true slope: f/λ is then no longer a
        // distance to first order.
        self.nodes[n].unit_gradient = false;
        self.nodes[n].exact = false;
        self.nodes[n].span = span;
        Some(Value::Shape(n))
    }

    /// `v.y` of a vector, `c.g` of a colour (a number; computed at run time from parameters).
    fn component(&mut self, v: Value, id: &Ident, span: Span) -> Option<Value> {
        let (vector, colour) = (["x", "y", "z"], ["r", "g", "b"]);
        let in_vec = vector.iter().position(|n| *n == id.name);
        let in_col = colour.iter().position(|n| *n == id.name);
        let is_colour = match &v {
            Value::Vec3(_) => false,
            Value::Color(_) => true,
            Value::Param(s) if s.kind == SymKind::Vec3 => false,
            Value::Param(s) if s.kind == SymKind::Color => true,
            other => {
                self.diags.push(
                    Diagnostic::error(span, format!("`.{}` takes a vector or a colour", id.name))
                        .label(format!("this is {}", other.describe())),
                );
                return None;
            }
        };
        let Some(i) = (if is_colour { in_col } else { in_vec }) else {
            let (names, what) = if is_colour {
                ("`.r`, `.g`, `.b`", "a colour")
            } else {
                ("`.x`, `.y`, `.z`", "a vector")
            };
            self.diags.push(
                Diagnostic::error(id.span, format!("{what} has no component `.{}`", id.name))
                    .label(format!("the components of {what} are {names}")),
            );
            return None;
        };
        match v {
            Value::Vec3(v) | Value::Color(v) => Some(Value::Num(v[i], Dim::None)),
            Value::Param(s) => Some(Value::Param(Sym {
                kind: SymKind::Num(Dim::None),
                comps: vec![s.comps[i.min(s.comps.len() - 1)].clone()],
            })),
            _ => None,
        }
    }

    fn number(&mut self, value: f64, unit: Option<&Ident>, span: Span) -> Option<Value> {
        if !value.is_finite() {
            self.diags.push(
                Diagnostic::error(span, "this number is too large")
                    .label("beyond the range of a 64-bit float")
                    .note("every number in a scene must be finite"),
            );
            return None;
        }
        let Some(unit) = unit else {
            return Some(Value::Num(value, Dim::None));
        };
        match UNITS.iter().find(|(u, _)| *u == unit.name) {
            Some((_, factor)) => Some(Value::Num(value * factor, Dim::Angle)),
            None => {
                let mut d = Diagnostic::error(unit.span, format!("unknown unit `{}`", unit.name))
                    .label("not a unit");
                d = match self.did_you_mean(&unit.name, UNITS.iter().map(|(u, _)| *u)) {
                    Some(s) => d.help(format!("did you mean `{s}`?")),
                    None => d.note("the units are `deg` and `rad`; lengths have no unit"),
                };
                self.diags.push(d);
                None
            }
        }
    }

    fn color(&mut self, text: &str, span: Span) -> Option<Value> {
        let hex = &text[1..];
        let digits: Option<Vec<u32>> = hex.chars().map(|c| c.to_digit(16)).collect();
        let rgb = match (digits, hex.len()) {
            (Some(d), 6) => [0, 2, 4].map(|i| (d[i] * 16 + d[i + 1]) as f64 / 255.0),
            (Some(d), 3) => [0, 1, 2].map(|i| (d[i] * 17) as f64 / 255.0),
            _ => {
                self.diags.push(
                    Diagnostic::error(span, format!("`{text}` is not a colour"))
                        .label("expected `#rrggbb` or `#rgb` in hexadecimal digits"),
                );
                return None;
            }
        };
        Some(Value::Color(DVec3::from_array(rgb)))
    }
}

/// A number printed short for messages.
fn short(x: f64) -> String {
    let s = format!("{x:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
