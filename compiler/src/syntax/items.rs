//! Building the AST's top-level statements from the parser's pairs: `let`, `param`, `fn`,
//! `import`, settings blocks, values and the scene's shapes.

use super::{FnDef, FnParam, Item, Rule, Setting, expr, ident};
use crate::diag::Span;
use pest::iterators::Pair;

/// One top-level statement.
pub(super) fn item(p: Pair<Rule>) -> Item {
    let span: Span = p.as_span().into();
    match p.as_rule() {
        Rule::let_stmt => {
            let mut it = p.into_inner();
            let name = ident(it.next().expect("let name"));
            let value = expr(it.next().expect("let value"));
            Item::Let { name, value }
        }
        Rule::param_stmt => {
            let mut it = p.into_inner().filter(|q| q.as_rule() != Rule::in_kw);
            let _keyword = it.next();
            let name = ident(it.next().expect("param name"));
            let value = expr(it.next().expect("param value"));
            let range = it
                .next()
                .map(|lo| Box::new((expr(lo), expr(it.next().expect("range end")))));
            Item::Param {
                name,
                value,
                range,
                span,
            }
        }
        Rule::block_stmt => {
            let mut keyword = None;
            let mut kind = None;
            let mut settings = Vec::new();
            for q in p.into_inner() {
                match q.as_rule() {
                    Rule::block_kw => keyword = Some(ident(q)),
                    Rule::ident => kind = Some(ident(q)),
                    _ => settings = q.into_inner().map(setting).collect(),
                }
            }
            Item::Block {
                keyword: keyword.expect("block keyword"),
                kind,
                settings,
                span,
            }
        }
        Rule::value_stmt => {
            let mut it = p.into_inner();
            let keyword = ident(it.next().expect("value keyword"));
            let value = expr(it.next().expect("value"));
            Item::Value { keyword, value }
        }
        Rule::fn_stmt => Item::Fn(fn_def(p, span)),
        Rule::import_stmt => {
            let string = p
                .into_inner()
                .find(|q| q.as_rule() == Rule::string)
                .expect("import path");
            let path_span: Span = string.as_span().into();
            let text = string.as_str();
            Item::Import {
                path: text[1..text.len() - 1].to_string(),
                path_span,
                span,
            }
        }
        _ => Item::Scene(expr(p.into_inner().next().expect("scene expression"))),
    }
}

fn setting(p: Pair<Rule>) -> Setting {
    let mut it = p.into_inner();
    Setting {
        key: ident(it.next().expect("setting key")),
        value: expr(it.next().expect("setting value")),
    }
}

fn fn_def(p: Pair<Rule>, span: Span) -> FnDef {
    let mut it = p.into_inner().filter(|q| q.as_rule() != Rule::fn_kw);
    let name = ident(it.next().expect("fn name"));
    let params = it
        .next()
        .expect("fn parameters")
        .into_inner()
        .map(|q| {
            let mut ty = None;
            let mut default = None;
            let mut parts = q.into_inner();
            let name = ident(parts.next().expect("parameter name"));
            for part in parts {
                match part.as_rule() {
                    Rule::ident => ty = Some(ident(part)),
                    _ => default = Some(expr(part)),
                }
            }
            FnParam { name, ty, default }
        })
        .collect();
    let body = expr(it.next().expect("fn body"));
    FnDef {
        name,
        params,
        body,
        span,
    }
}
