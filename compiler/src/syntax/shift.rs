//! Moving every span of a parsed file by an offset: an imported file's spans live after the
//! main file's in one span space, so a diagnostic names the file it points into.

use super::{Arg, Call, Expr, ExprKind, File, Ident, Item};
use crate::diag::{Diagnostic, Span};

fn span(s: &mut Span, by: usize) {
    s.start += by;
    s.end += by;
}

fn ident(i: &mut Ident, by: usize) {
    span(&mut i.span, by);
}

/// Moves every span of `file` by `by` bytes.
pub(super) fn file(file: &mut File, by: usize) {
    for item in &mut file.items {
        match item {
            Item::Let { name, value } => {
                ident(name, by);
                expr(value, by);
            }
            Item::Param {
                name,
                value,
                range,
                span: s,
            } => {
                ident(name, by);
                expr(value, by);
                if let Some(r) = range {
                    expr(&mut r.0, by);
                    expr(&mut r.1, by);
                }
                span(s, by);
            }
            Item::Block {
                keyword,
                kind,
                settings,
                span: s,
            } => {
                ident(keyword, by);
                if let Some(k) = kind {
                    ident(k, by);
                }
                for setting in settings {
                    ident(&mut setting.key, by);
                    expr(&mut setting.value, by);
                }
                span(s, by);
            }
            Item::Value { keyword, value } => {
                ident(keyword, by);
                expr(value, by);
            }
            Item::Scene(e) => expr(e, by),
            Item::Fn(def) => {
                ident(&mut def.name, by);
                for p in &mut def.params {
                    ident(&mut p.name, by);
                    if let Some(t) = &mut p.ty {
                        ident(t, by);
                    }
                    if let Some(d) = &mut p.default {
                        expr(d, by);
                    }
                }
                expr(&mut def.body, by);
                span(&mut def.span, by);
            }
            Item::Import {
                path_span, span: s, ..
            } => {
                span(path_span, by);
                span(s, by);
            }
        }
    }
}

fn args(args: &mut [Arg], by: usize) {
    for a in args {
        if let Some(n) = &mut a.name {
            ident(n, by);
        }
        expr(&mut a.value, by);
    }
}

fn call(c: &mut Call, by: usize) {
    ident(&mut c.name, by);
    args(&mut c.args, by);
    for e in c.block.iter_mut().flatten() {
        expr(e, by);
    }
    span(&mut c.span, by);
}

/// Moves every span of `e` by `by` bytes (recursive, as building the AST is).
fn expr(e: &mut Expr, by: usize) {
    span(&mut e.span, by);
    match &mut e.kind {
        ExprKind::Number { unit, .. } => {
            if let Some(u) = unit {
                ident(u, by);
            }
        }
        ExprKind::Color(_) => {}
        ExprKind::Vector(parts) => parts.iter_mut().for_each(|p| expr(p, by)),
        ExprKind::Name(i) => ident(i, by),
        ExprKind::Call(c) => call(c, by),
        ExprKind::Neg(a) => expr(a, by),
        ExprKind::Binary(_, a, b) | ExprKind::At(a, b) => {
            expr(a, by);
            expr(b, by);
        }
        ExprKind::Pipe(a, c) => {
            expr(a, by);
            call(c, by);
        }
        ExprKind::Tag(a, i) | ExprKind::Component(a, i) => {
            expr(a, by);
            ident(i, by);
        }
        ExprKind::Annotation(a, i, xs) => {
            expr(a, by);
            ident(i, by);
            args(xs, by);
        }
    }
}

/// Moves a diagnostic's spans by `by` bytes.
pub(super) fn diagnostic(d: &mut Diagnostic, by: usize) {
    span(&mut d.span, by);
    for (s, _) in &mut d.secondary {
        span(s, by);
    }
}
