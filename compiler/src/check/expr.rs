//! Checking expressions: numbers with units, vectors, colours, names, arithmetic, pipes and
//! where annotations apply (`call.rs` has calls, `implicit.rs` the `implicit` bodies).

use super::params::{Sym, SymKind};
use super::{Binding, Checker, Dim, MAX_DEPTH, Value, functions};
use crate::catalog;
use crate::diag::{Diagnostic, Span, did_you_mean};
use crate::scene::{Field, NodeId, binary};
use crate::syntax::{BinOp, Expr, ExprKind, Ident};
use glam::DVec3;

/// Named constants: π and τ = 2π.
pub(super) const CONSTANTS: &[(&str, f64)] =
    &[("pi", std::f64::consts::PI), ("tau", std::f64::consts::TAU)];

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

    fn value_inner(&mut self, e: &Expr) -> Option<Value> {
        match &e.kind {
            ExprKind::Number { value, unit } => self.number(*value, unit.as_ref(), e.span),
            ExprKind::Color(text) => self.color(text, e.span),
            ExprKind::Vector(parts) => {
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
                                Diagnostic::error(
                                    part.span,
                                    "a vector's components must be numbers",
                                )
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
            ExprKind::Name(id) => self.name(id),
            ExprKind::Call(call) => self.call(call, None),
            ExprKind::Neg(a) => match self.value(a)? {
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
                other => self.no_arithmetic(e.span, "-", &other),
            },
            ExprKind::Binary(op, a, b) => {
                let at =
                    matches!(a.kind, ExprKind::At(..)) && matches!(op, BinOp::Add | BinOp::Sub);
                let (va, vb) = (self.value(a), self.value(b));
                let (va, vb) = (va?, vb?);
                if at
                    && matches!(va, Value::Shape(_))
                    && matches!(vb, Value::Vec3(_) | Value::Param(_))
                {
                    self.diags.push(
                        Diagnostic::error(
                            e.span,
                            format!("`at` binds tighter than `{}`", op.symbol()),
                        )
                        .label("this moves the shape, then adds a vector to it")
                        .help("put the whole offset in parentheses: `s at (a + b)`"),
                    );
                    return None;
                }
                self.binary(*op, va, vb, e.span)
            }
            ExprKind::Pipe(lhs, call) => {
                let child = self.shape(lhs)?;
                self.call(call, Some(child))
            }
            ExprKind::Tag(lhs, material) => {
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
                self.nodes[n].span = e.span;
                Some(Value::Shape(n))
            }
            ExprKind::Annotation(lhs, name, args) => {
                let n = self.shape(lhs);
                let l = self.annotation(name, args, e.span);
                let (n, l) = (n?, l?);
                let inferred = self.nodes[n].inferred_lambda;
                if inferred.is_finite() && l > inferred * (1.0 + 1e-9) {
                    self.diags.push(
                        Diagnostic::warning(e.span, "annotation is looser than the inferred bound")
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
                self.nodes[n].span = e.span;
                Some(Value::Shape(n))
            }
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
                d = match did_you_mean(&unit.name, UNITS.iter().map(|(u, _)| *u)) {
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

    fn name(&mut self, id: &Ident) -> Option<Value> {
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
        let d = if let Some(f) = self.fns.get(&id.name) {
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
            let mut d = Diagnostic::error(id.span, format!("unknown name `{}`", id.name))
                .label("not defined");
            let lets: Vec<&str> = self.lets.keys().map(String::as_str).collect();
            if let Some(s) = did_you_mean(&id.name, lets) {
                d = d.help(format!("did you mean `{s}`?"));
            } else if let Some(k) =
                did_you_mean(&id.name, super::settings::BLOCK_KEYWORDS.iter().copied())
            {
                d = d.help(format!("did you mean the `{k}` block?"));
                // `matrial gold { … }`: the block's name and settings, read as a call, are
                // not another mistake.
                self.keyword_typo_line = Some(self.line_of(id.span.start));
            } else if ["x", "y", "z"].contains(&id.name.as_str()) {
                d = d.note("coordinates exist only inside `implicit { ... }`");
            }
            d
        };
        self.diags.push(d);
        None
    }

    fn is_material_declared_at(&self, span: Span) -> bool {
        self.material_spans.contains(&span)
    }

    pub(super) fn no_arithmetic(&mut self, span: Span, op: &str, v: &Value) -> Option<Value> {
        let mut d = Diagnostic::error(
            span,
            format!("`{op}` cannot be applied to {}", v.describe()),
        )
        .label("unsupported operand");
        if matches!(v, Value::Shape(_)) {
            d = d.help(match op {
                "+" => "combine shapes with `union { a b }`",
                "-" => "cut shapes with `subtract { a b }` or turn them inside out with `complement { a }`",
                _ => "shapes combine with operators such as `union`, `intersect` and `mix`",
            });
        }
        self.diags.push(d);
        None
    }

    pub(super) fn binary(&mut self, op: BinOp, a: Value, b: Value, span: Span) -> Option<Value> {
        if matches!(a, Value::Param(_)) || matches!(b, Value::Param(_)) {
            return self.param_binary(op, a, b, span);
        }
        match (a, b) {
            (Value::Num(x, _), Value::Num(y, _))
                if op == BinOp::Pow && x < 0.0 && y.fract() != 0.0 =>
            {
                self.diags.push(
                    Diagnostic::error(span, format!("{x} ^ {y} is not a real number"))
                        .label("a negative base to a power that is not whole")
                        .help("use a whole exponent, or the power of the magnitude: `abs(a) ^ b`"),
                );
                None
            }
            (Value::Num(x, da), Value::Num(y, db)) => {
                let dim = match (op, da, db) {
                    (_, Dim::None, Dim::None) => Dim::None,
                    (BinOp::Add | BinOp::Sub, d1, d2) if d1 == d2 => d1,
                    (BinOp::Mul, Dim::Angle, Dim::None) | (BinOp::Mul, Dim::None, Dim::Angle) => {
                        Dim::Angle
                    }
                    (BinOp::Div, Dim::Angle, Dim::None) => Dim::Angle,
                    (BinOp::Div, Dim::Angle, Dim::Angle) => Dim::None,
                    (_, Dim::Angle, Dim::Angle) => {
                        self.diags.push(
                            Diagnostic::error(
                                span,
                                format!("`{}` of two angles is not an angle", op.symbol()),
                            )
                            .label("angle times angle, or a power of an angle")
                            .help("give one operand a unit, or neither"),
                        );
                        return None;
                    }
                    _ => {
                        self.diags.push(
                            Diagnostic::error(span, "mixed units")
                                .label(format!("`{}` of an angle and a plain number", op.symbol()))
                                .help("give both operands a unit, or neither"),
                        );
                        return None;
                    }
                };
                self.finite(binary(op, x, y), span)
                    .map(|r| Value::Num(r, dim))
            }
            (Value::Vec3(v), Value::Num(s, Dim::None)) if matches!(op, BinOp::Mul | BinOp::Div) => {
                let r = if op == BinOp::Mul { v * s } else { v / s };
                self.finite_vec(r, span)
            }
            (Value::Num(s, Dim::None), Value::Vec3(v)) if op == BinOp::Mul => {
                self.finite_vec(v * s, span)
            }
            (Value::Vec3(a), Value::Vec3(b)) if matches!(op, BinOp::Add | BinOp::Sub) => {
                self.finite_vec(if op == BinOp::Add { a + b } else { a - b }, span)
            }
            (
                a @ (Value::Field(_) | Value::Num(_, Dim::None)),
                b @ (Value::Field(_) | Value::Num(_, Dim::None)),
            ) => Some(Value::Field(Field::Binary(
                op,
                Box::new(as_field(a)),
                Box::new(as_field(b)),
            ))),
            (a, b) => {
                let bad = if matches!(a, Value::Num(..) | Value::Field(_)) {
                    b
                } else {
                    a
                };
                self.no_arithmetic(span, op.symbol(), &bad)
            }
        }
    }

    pub(super) fn finite(&mut self, x: f64, span: Span) -> Option<f64> {
        if x.is_finite() {
            return Some(x);
        }
        let what = if x.is_nan() {
            "not a number (NaN)"
        } else {
            "infinite"
        };
        self.diags.push(
            Diagnostic::error(span, format!("this value is {what}"))
                .label("computed here")
                .note("every number in a scene must be finite"),
        );
        None
    }

    fn finite_vec(&mut self, v: DVec3, span: Span) -> Option<Value> {
        for i in 0..3 {
            self.finite(v[i], span)?;
        }
        Some(Value::Vec3(v))
    }
}

pub(super) fn as_field(v: Value) -> Field {
    match v {
        Value::Num(x, _) => Field::Const(x),
        Value::Field(f) => f,
        Value::Param(s) => s.comps[0].clone(),
        _ => Field::Const(f64::NAN),
    }
}

/// A number printed short for messages.
fn short(x: f64) -> String {
    let s = format!("{x:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
