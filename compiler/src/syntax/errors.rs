//! Syntax errors: the parser's failure turned into one diagnostic that says what was expected
//! where, in the user's words, with the hints for mistakes seen often.

use super::scan::bracket_error;
use super::{DEFINITION_KEYWORDS, Rule, SdfParser, hints};
use crate::diag::{Diagnostic, Span};
use pest::Parser as _;

pub(super) fn syntax_error(source: &str, e: pest::error::Error<Rule>) -> Diagnostic {
    use pest::error::{ErrorVariant, InputLocation};
    let span = match e.location {
        InputLocation::Pos(p) => Span::new(p, p),
        InputLocation::Span((a, b)) => Span::new(a, b),
    };
    if let Some(d) = bracket_error(source, span.start) {
        return d;
    }
    if let Some(d) = ended_early(source, span.start) {
        return d;
    }
    if let Some(d) = inside_statement(source, span.start) {
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

/// A statement that ends with an operator (`let a = 1 +`), so that the parser stopped at the
/// next statement's keyword: the error belongs after the operator, not on the next line.
fn ended_early(source: &str, at: usize) -> Option<Diagnostic> {
    if !super::scan::statement_at(source, at) {
        return None;
    }
    // The last character of code before it (comments skipped).
    let (end, last) = super::scan::code_bytes(&source[..at])
        .filter(|(_, b)| !b.is_ascii_whitespace())
        .last()?;
    let before = &source[..=end];
    let last = last as char;
    let op = match last {
        '+' | '-' | '*' | '/' | '^' | '=' | ',' | '(' | ':' | '@' => last.to_string(),
        '>' if before.ends_with("|>") => "|>".to_string(),
        _ => return None,
    };
    let end = end + 1;
    Some(
        Diagnostic::error(Span::new(end, end), "syntax error")
            .label(format!("expected an expression after `{op}`"))
            .note("the next line begins a new statement"),
    )
}

/// For a syntax error at a statement's keyword (`fn`, `import`, `let`, `param`): the error
/// inside that statement, parsed alone (the file's parser reports only "expected a statement"
/// at its start).
fn inside_statement(source: &str, at: usize) -> Option<Diagnostic> {
    let rest = &source[at..];
    let keyword = super::scan::keyword_at(rest, DEFINITION_KEYWORDS.iter());
    // Only a keyword that begins its line begins a statement (`let let = 1` is a name missing).
    let line_start = source[..at]
        .rsplit('\n')
        .next()
        .unwrap_or("")
        .trim()
        .is_empty();
    if !keyword || !line_start {
        return None;
    }
    // The text before is blanked (same length, line breaks kept), so positions stay the file's.
    let blank: String = source[..at]
        .bytes()
        .map(|b| if b == b'\n' { '\n' } else { ' ' })
        .collect();
    let text = blank + rest;
    // pest tracks the literal tokens it tried only with its error detail on (a global switch,
    // so only for this parse; other threads' parses at worst get more detail).
    pest::set_error_detail(true);
    let parsed = SdfParser::parse(Rule::lone_stmt, &text);
    pest::set_error_detail(false);
    let attempts = parsed.err()?.parse_attempts()?;
    let pos = attempts.max_position;
    if pos <= at || pos > source.len() {
        return None;
    }
    // The literal tokens tried there (`=`, `)`…); pest does not export their type, so read
    // through their Display: ranges and built-ins are left out.
    let mut expected: Vec<String> = attempts
        .expected_tokens()
        .into_iter()
        .map(|t| t.to_string())
        .filter(|t| !t.trim().is_empty() && !t.contains("..") && t != "BUILTIN_RULE")
        .map(|t| format!("`{t}`"))
        .collect();
    expected.sort();
    expected.dedup();
    let list = match expected.as_slice() {
        [] => return None,
        [one] => one.clone(),
        [init @ .., last] => format!("{}, or {}", init.join(", "), last),
    };
    let span = Span::new(pos, pos);
    if let Some(d) = hints::meant(source, span) {
        return Some(d);
    }
    Some(Diagnostic::error(span, "syntax error").label(format!("expected {list}")))
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
pub(super) fn rule_name(rule: Rule) -> &'static str {
    match rule {
        Rule::EOI => "end of file",
        Rule::ident | Rule::name => "a name",
        Rule::number | Rule::quantity => "a number",
        Rule::unit => "a unit",
        Rule::color => "a colour",
        Rule::group | Rule::call | Rule::neg | Rule::expr | Rule::arg => "an expression",
        Rule::add | Rule::sub | Rule::mul | Rule::div | Rule::pow => "an operator",
        Rule::component | Rule::component_name => "a component (`.x`, `.y`, `.z`)",
        Rule::pipe | Rule::tag | Rule::annotation | Rule::at | Rule::at_kw => {
            "`|>`, `:`, `@`, `at`"
        }
        Rule::args | Rule::arg_list => "`(`",
        Rule::block => "`{`",
        Rule::settings_body => "`{`",
        Rule::setting => "a setting",
        Rule::in_kw => "`in`",
        Rule::string => "a quoted path",
        Rule::fn_params | Rule::fn_param => "a parameter",
        Rule::import_stmt | Rule::import_kw | Rule::fn_stmt | Rule::fn_kw | Rule::lone_stmt => {
            "a statement"
        }
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
        Rule::WHITESPACE => "a space",
        Rule::statement => "a statement",
        Rule::term | Rule::infix | Rule::prefix | Rule::postfix | Rule::primary => "an expression",
        Rule::ident_char => "a letter or digit",
    }
}
