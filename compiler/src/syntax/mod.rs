//! Syntax: the pest parser of `grammar/sdf.pest` and the typed AST it produces, every node with its span.

use crate::diag::{Diagnostic, Span};
use pest::Parser as _;
use pest::iterators::Pair;
use pest::pratt_parser::{Assoc, Op, PrattParser};
use std::sync::LazyLock;

mod hints;
mod scan;
use scan::{bracket_error, check_comments, check_control, check_nesting};

#[derive(pest_derive::Parser)]
#[grammar = "../../grammar/sdf.pest"]
struct SdfParser;

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
            | Op::postfix(Rule::at))
});

/// Parses a whole file. Syntax errors come back as one diagnostic with the expected tokens.
pub fn parse(source: &str) -> Result<File, Diagnostic> {
    if source.len() > MAX_SOURCE_BYTES {
        return Err(Diagnostic::error(Span::new(0, 0), "the file is too large")
            .note(format!("the limit is {MAX_SOURCE_BYTES} bytes")));
    }
    check_control(source)?;
    check_comments(source)?;
    check_nesting(source)?;
    let mut pairs = SdfParser::parse(Rule::file, source).map_err(|e| syntax_error(source, e))?;
    let file = pairs.next().expect("the `file` rule matched");
    let items = file
        .into_inner()
        .filter(|p| p.as_rule() != Rule::EOI)
        .map(item)
        .collect();
    Ok(File { items })
}

fn syntax_error(source: &str, e: pest::error::Error<Rule>) -> Diagnostic {
    use pest::error::{ErrorVariant, InputLocation};
    let span = match e.location {
        InputLocation::Pos(p) => Span::new(p, p),
        InputLocation::Span((a, b)) => Span::new(a, b),
    };
    if let Some(d) = bracket_error(source, span.start) {
        return d;
    }
    let (message, label) = match &e.variant {
        ErrorVariant::ParsingError { positives, .. } => {
            let mut names: Vec<&str> = positives.iter().map(|r| rule_name(*r)).collect();
            names.sort();
            names.dedup();
            // Colours, names and numbers are expressions; units are noise after a number.
            if names.contains(&"an expression") {
                names.retain(|n| !["a colour", "a name", "a number"].contains(n));
            }
            names.retain(|n| *n != "a unit");
            let expected = match names.as_slice() {
                [] => "something else".to_string(),
                [one] => one.to_string(),
                [init @ .., last] => format!("{}, or {}", init.join(", "), last),
            };
            ("syntax error".to_string(), format!("expected {expected}"))
        }
        ErrorVariant::CustomError { message } => (message.clone(), String::new()),
    };
    if let Some(d) = hints::meant(source, span) {
        return d;
    }
    let mut d = Diagnostic::error(span, message).label(label);
    if source[span.start..].starts_with(')') && vector_of_two(source, span.start) {
        d = d.help("a vector has three components: `(x, y, z)`");
    }
    d
}

/// Whether the parenthesis closing at `close` holds exactly one top-level comma.
fn vector_of_two(source: &str, close: usize) -> bool {
    let mut depth = 0;
    let mut commas = 0;
    for &b in source.as_bytes()[..close].iter().rev() {
        match b {
            b')' | b'}' => depth += 1,
            b'(' | b'{' if depth == 0 => return commas == 1,
            b'(' | b'{' => depth -= 1,
            b',' if depth == 0 => commas += 1,
            _ => {}
        }
    }
    false
}

/// Words a user understands for the grammar's rules.
fn rule_name(rule: Rule) -> &'static str {
    match rule {
        Rule::EOI => "end of file",
        Rule::ident | Rule::name => "a name",
        Rule::number | Rule::quantity => "a number",
        Rule::unit => "a unit",
        Rule::color => "a colour",
        Rule::group | Rule::call | Rule::neg | Rule::expr | Rule::arg => "an expression",
        Rule::add | Rule::sub | Rule::mul | Rule::div | Rule::pow => "an operator",
        Rule::pipe | Rule::tag | Rule::annotation | Rule::at | Rule::at_kw => {
            "`|>`, `:`, `@`, `at`"
        }
        Rule::args | Rule::arg_list => "`(`",
        Rule::block => "`{`",
        Rule::settings_body => "`{`",
        Rule::setting => "a setting",
        Rule::in_kw => "`in`",
        Rule::let_stmt
        | Rule::param_stmt
        | Rule::param_kw
        | Rule::block_stmt
        | Rule::block_kw
        | Rule::value_stmt
        | Rule::value_kw
        | Rule::scene_expr
        | Rule::file => "a statement",
        Rule::keyword => "a keyword",
        Rule::WHITESPACE | Rule::COMMENT => "a space",
        Rule::statement => "a statement",
        Rule::term | Rule::infix | Rule::prefix | Rule::postfix | Rule::primary => "an expression",
        Rule::ident_char => "a letter or digit",
    }
}

fn ident(p: Pair<Rule>) -> Ident {
    Ident {
        name: p.as_str().to_string(),
        span: p.as_span().into(),
    }
}

fn item(p: Pair<Rule>) -> Item {
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

fn expr(p: Pair<Rule>) -> Expr {
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
