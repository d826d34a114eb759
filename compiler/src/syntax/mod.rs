//! Syntax: the pest parser of `grammar/sdf.pest` and the typed AST it produces, every node with its span.

use crate::diag::{Diagnostic, Span};
use pest::Parser as _;
use pest::iterators::Pair;
use pest::pratt_parser::{Assoc, Op, PrattParser};
use std::sync::LazyLock;

mod errors;
mod hints;
mod imports;
mod items;
mod recover;
mod scan;
mod shift;
use errors::syntax_error;
pub use imports::{FsLoader, Loader, MapLoader, NoFiles, STD, decode, load, load_at, read_limited};
use items::item;
use scan::{check_comments, check_control, check_nesting};

#[derive(pest_derive::Parser)]
#[grammar = "../../grammar/sdf.pest"]
struct SdfParser;

/// The keywords of settings blocks (`block_kw` in grammar/sdf.pest).
pub const BLOCK_KEYWORDS: &[&str] = &[
    "camera",
    "light",
    "trace",
    "material",
    "bound",
    "occlusion",
    "fog",
];

/// The keywords of definitions (`let_stmt`, `param_kw`, `fn_kw`, `import_kw` in the grammar).
pub const DEFINITION_KEYWORDS: &[&str] = &["let", "param", "fn", "import"];

/// The keywords of value statements (`value_kw` in the grammar).
pub const VALUE_KEYWORDS: &[&str] = &["background"];

/// Deepest bracket nesting accepted; deeper input is refused before parsing (no stack overflow).
pub const MAX_NESTING: usize = 200;
/// Longest source accepted, in bytes.
pub const MAX_SOURCE_BYTES: usize = 4 << 20;

/// A name as written, with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    /// The text.
    pub name: String,
    /// Where it is.
    pub span: Span,
}

/// A parsed file: its statements in order.
#[derive(Clone, Debug, PartialEq)]
pub struct File {
    /// Top-level statements.
    pub items: Vec<Item>,
}

/// A top-level statement.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// `let name = value`
    Let {
        /// The bound name.
        name: Ident,
        /// The value.
        value: Expr,
    },
    /// `param name = value in low..high`: a value set at run time.
    Param {
        /// The parameter's name.
        name: Ident,
        /// Its default value.
        value: Expr,
        /// The values it may take, if declared: `low..high` (each end included).
        range: Option<Box<(Expr, Expr)>>,
        /// The whole statement.
        span: Span,
    },
    /// `camera { .. }`, `light point { .. }`, `trace enhanced { .. }`, `material gold { .. }`
    Block {
        /// `camera`, `light`, `trace` or `material`.
        keyword: Ident,
        /// The name after the keyword, if any.
        kind: Option<Ident>,
        /// `key value` pairs.
        settings: Vec<Setting>,
        /// The whole statement.
        span: Span,
    },
    /// `background #202030`
    Value {
        /// `background`.
        keyword: Ident,
        /// The value.
        value: Expr,
    },
    /// A shape of the scene.
    Scene(Expr),
    /// `fn name(params) = body`: a shape or value defined once and used by calls.
    Fn(FnDef),
    /// `import "path"`: the definitions of another file.
    Import {
        /// The path as written, without its quotes.
        path: String,
        /// The quoted path.
        path_span: Span,
        /// The whole statement.
        span: Span,
    },
}

/// `fn name(a, b: shape, c = 1) = body`.
#[derive(Clone, Debug, PartialEq)]
pub struct FnDef {
    /// The function's name.
    pub name: Ident,
    /// Its parameters in order.
    pub params: Vec<FnParam>,
    /// What a call stands for.
    pub body: Expr,
    /// The whole statement.
    pub span: Span,
}

/// One parameter of a `fn`: a name, an optional type (`: shape`) and an optional default.
#[derive(Clone, Debug, PartialEq)]
pub struct FnParam {
    /// The name.
    pub name: Ident,
    /// The declared type, as written (`number`, `angle`, `vector`, `color`, `shape`).
    pub ty: Option<Ident>,
    /// The value when a call leaves it out.
    pub default: Option<Expr>,
}

/// `key value` inside a settings block.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    /// The key.
    pub key: Ident,
    /// The value.
    pub value: Expr,
}

/// An expression and its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where it is.
    pub span: Span,
}

/// Binary arithmetic operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`
    Pow,
}

impl BinOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "^",
        }
    }
}

/// The kinds of expression.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// `1.5`, `30deg`: the number and the unit suffix as written.
    Number {
        /// The value before units are applied.
        value: f64,
        /// The unit suffix, if any.
        unit: Option<Ident>,
    },
    /// `#d4af37` as written, `#` included.
    Color(String),
    /// `(x, y, z)`
    Vector(Box<[Expr; 3]>),
    /// A name: a `let` binding, a material, a coordinate inside `implicit`.
    Name(Ident),
    /// `name(args) { block }`
    Call(Call),
    /// `-e`
    Neg(Box<Expr>),
    /// `a + b` and friends.
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// `shape |> op(args)`: the shape becomes the operator's only child.
    Pipe(Box<Expr>, Call),
    /// `shape : material`
    Tag(Box<Expr>, Ident),
    /// `shape @name(args)`
    Annotation(Box<Expr>, Ident, Vec<Arg>),
    /// `shape at (x, y, z)`
    At(Box<Expr>, Box<Expr>),
    /// `v.y`: a component of a vector (x, y, z) or a colour (r, g, b).
    Component(Box<Expr>, Ident),
}

/// `name(args) { children }`.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    /// The called name.
    pub name: Ident,
    /// Arguments in order.
    pub args: Vec<Arg>,
    /// The `{ ... }` block, if written.
    pub block: Option<Vec<Expr>>,
    /// The whole call.
    pub span: Span,
}

/// A positional (`1`) or named (`radius = 1`) argument.
#[derive(Clone, Debug, PartialEq)]
pub struct Arg {
    /// The name, for a named argument.
    pub name: Option<Ident>,
    /// The value.
    pub value: Expr,
}

static PRATT: LazyLock<PrattParser<Rule>> = LazyLock::new(|| {
    PrattParser::new()
        .op(Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left))
        .op(Op::infix(Rule::mul, Assoc::Left) | Op::infix(Rule::div, Assoc::Left))
        .op(Op::prefix(Rule::neg))
        .op(Op::infix(Rule::pow, Assoc::Right))
        .op(Op::postfix(Rule::pipe)
            | Op::postfix(Rule::tag)
            | Op::postfix(Rule::annotation)
            | Op::postfix(Rule::at)
            | Op::postfix(Rule::component))
});

/// Parses a whole file; the first syntax error, if any (see [`parse_all`]).
pub fn parse(source: &str) -> Result<File, Diagnostic> {
    parse_all(source).map_err(|mut errors| errors.remove(0))
}

/// Parses a whole file, reporting several syntax errors when there are: brackets left open
/// where a new statement begins, and the errors of the statements after a failed one
/// (`recover.rs`), at most [`recover::MAX_SYNTAX_ERRORS`].
pub fn parse_all(source: &str) -> Result<File, Vec<Diagnostic>> {
    if source.len() > MAX_SOURCE_BYTES {
        return Err(vec![
            Diagnostic::error(Span::new(0, 0), "the file is too large")
                .note(format!("the limit is {MAX_SOURCE_BYTES} bytes")),
        ]);
    }
    check_control(source).map_err(|d| vec![d])?;
    check_comments(source).map_err(|d| vec![d])?;
    check_nesting(source).map_err(|d| vec![d])?;
    let mut pairs = SdfParser::parse(Rule::file, source).map_err(|e| {
        // Brackets left open where a statement begins are said first. (Only after a failed
        // parse: a statement keyword is never a name, so the parse fails whenever there are.)
        let open = recover::open_at_statements(source);
        if !open.is_empty() {
            return open;
        }
        let first = syntax_error(source, e);
        let later = recover::later_errors(source, &first);
        std::iter::once(first).chain(later).collect::<Vec<_>>()
    })?;
    let file = pairs.next().expect("the `file` rule matched");
    let items = file
        .into_inner()
        .filter(|p| p.as_rule() != Rule::EOI)
        .map(item)
        .collect();
    Ok(File { items })
}

pub(super) fn ident(p: Pair<Rule>) -> Ident {
    Ident {
        name: p.as_str().to_string(),
        span: p.as_span().into(),
    }
}

pub(super) fn expr(p: Pair<Rule>) -> Expr {
    PRATT
        .map_primary(primary)
        .map_prefix(|op, rhs| Expr {
            span: Span::from(op.as_span()).to(rhs.span),
            kind: ExprKind::Neg(Box::new(rhs)),
        })
        .map_postfix(|lhs, op| {
            let span = lhs.span.to(op.as_span().into());
            let lhs = Box::new(lhs);
            let kind = match op.as_rule() {
                Rule::pipe => {
                    let target = op.into_inner().next().expect("pipe target");
                    ExprKind::Pipe(lhs, call_or_name(target))
                }
                Rule::tag => ExprKind::Tag(lhs, ident(op.into_inner().next().expect("tag"))),
                Rule::component => {
                    ExprKind::Component(lhs, ident(op.into_inner().next().expect("component")))
                }
                Rule::annotation => {
                    let mut it = op.into_inner();
                    let name = ident(it.next().expect("annotation name"));
                    let args = it.next().map(arg_list).unwrap_or_default();
                    ExprKind::Annotation(lhs, name, args)
                }
                _ => {
                    let target = op.into_inner().nth(1).expect("at target");
                    ExprKind::At(lhs, Box::new(primary(target)))
                }
            };
            Expr { kind, span }
        })
        .map_infix(|lhs, op, rhs| {
            let op = match op.as_rule() {
                Rule::add => BinOp::Add,
                Rule::sub => BinOp::Sub,
                Rule::mul => BinOp::Mul,
                Rule::div => BinOp::Div,
                _ => BinOp::Pow,
            };
            Expr {
                span: lhs.span.to(rhs.span),
                kind: ExprKind::Binary(op, Box::new(lhs), Box::new(rhs)),
            }
        })
        .parse(p.into_inner())
}

fn primary(p: Pair<Rule>) -> Expr {
    let span: Span = p.as_span().into();
    let kind = match p.as_rule() {
        Rule::group => {
            let mut it = p.into_inner().map(expr);
            let first = it.next().expect("parenthesised expression");
            match (it.next(), it.next()) {
                (Some(y), Some(z)) => ExprKind::Vector(Box::new([first, y, z])),
                _ => return first,
            }
        }
        Rule::quantity => {
            let mut it = p.into_inner();
            let number = it.next().expect("number");
            // The grammar admits only digit strings that Rust's float parser accepts.
            let value = number.as_str().parse::<f64>().unwrap_or(f64::NAN);
            ExprKind::Number {
                value,
                unit: it.next().map(ident),
            }
        }
        Rule::color => ExprKind::Color(p.as_str().to_string()),
        Rule::call | Rule::name => return call_or_name_expr(p),
        rule => unreachable!("primary rule {rule:?}"),
    };
    Expr { kind, span }
}

fn call_or_name_expr(p: Pair<Rule>) -> Expr {
    let span: Span = p.as_span().into();
    let kind = match p.as_rule() {
        Rule::name => ExprKind::Name(ident(p.into_inner().next().expect("name"))),
        _ => ExprKind::Call(call_or_name(p)),
    };
    Expr { kind, span }
}

/// A call, or a bare name taken as a call with no arguments (`s |> complement`).
fn call_or_name(p: Pair<Rule>) -> Call {
    let span: Span = p.as_span().into();
    let mut it = p.into_inner();
    let name = ident(it.next().expect("called name"));
    let mut args = Vec::new();
    let mut block = None;
    for q in it {
        match q.as_rule() {
            Rule::args => args = arg_list(q.into_inner().next().expect("argument list")),
            _ => block = Some(q.into_inner().map(expr).collect()),
        }
    }
    Call {
        name,
        args,
        block,
        span,
    }
}

fn arg_list(p: Pair<Rule>) -> Vec<Arg> {
    p.into_inner()
        .map(|a| {
            let mut it = a.into_inner().peekable();
            let name = match it.peek().map(|q| q.as_rule()) {
                Some(Rule::ident) => it.next().map(ident),
                _ => None,
            };
            Arg {
                name,
                value: expr(it.next().expect("argument value")),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
