//! Syntax errors said as what was meant, where the text around them makes it plain.

use crate::diag::{Diagnostic, Span};

/// Syntax errors whose cause is plain from the text around them, said as what was meant: a
/// unit after a space (`30 deg`), a second decimal point (`1.2.3`), a degree sign (`30°`), a
/// named argument with `:` (`sphere(radius: 2)`).
pub(super) fn meant(source: &str, span: Span) -> Option<Diagnostic> {
    let before = &source[..span.start];
    let after = &source[span.start..];
    unit_after_space(before, after, span)
        .or_else(|| two_decimal_points(before, after, span))
        .or_else(|| degree_sign(after, span))
        .or_else(|| colon_argument(before))
}

/// `30 deg`: a unit after a space.
fn unit_after_space(before: &str, after: &str, span: Span) -> Option<Diagnostic> {
    let number_before = |text: &str| {
        text.trim_end()
            .chars()
            .next_back()
            .is_some_and(|c| c.is_ascii_digit() || c == '.')
    };
    let word: String = after
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    if !(["deg", "rad"].contains(&word.as_str())
        && before.ends_with(char::is_whitespace)
        && number_before(before))
    {
        return None;
    }
    let number: String = before
        .trim_end()
        .chars()
        .rev()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    let gap = before.len() - before.trim_end().len();
    Some(
        Diagnostic::error(
            Span::new(span.start - gap, span.start + word.len()),
            "a unit is written right after its number",
        )
        .label("no space before the unit")
        .help(format!("write `{number}{word}`")),
    )
}

/// `1.2.3`: a second decimal point (read as a component after the number `1.2`).
fn two_decimal_points(before: &str, after: &str, span: Span) -> Option<Diagnostic> {
    if !(before.ends_with('.') && after.starts_with(|c: char| c.is_ascii_digit())) {
        return None;
    }
    let number: String = before[..before.len() - 1]
        .chars()
        .rev()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    if !number.contains('.') {
        return None;
    }
    let start = span.start - 1 - number.len();
    let end = span.start + after.chars().take_while(char::is_ascii_digit).count();
    Some(
        Diagnostic::error(Span::new(start, end), "a number has one decimal point")
            .label("two decimal points")
            .help("write one number, or separate numbers with `,`"),
    )
}

/// `30°`: a degree sign.
fn degree_sign(after: &str, span: Span) -> Option<Diagnostic> {
    if !after.starts_with('°') {
        return None;
    }
    Some(
        Diagnostic::error(
            Span::new(span.start, span.start + '°'.len_utf8()),
            "angles are written with a unit, not `°`",
        )
        .label("a degree sign")
        .help("write the number with `deg` after it, e.g. `30deg`"),
    )
}

/// `name: value` inside a call's parentheses: `:` gives a shape its material.
fn colon_argument(before: &str) -> Option<Diagnostic> {
    let colon = before.trim_end();
    let rest = colon.strip_suffix(':')?;
    let name: String = rest
        .trim_end()
        .chars()
        .rev()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    let head = rest.trim_end()[..rest.trim_end().len() - name.len()].trim_end();
    if name.is_empty() || !(head.ends_with('(') || head.ends_with(',')) {
        return None;
    }
    let at = colon.len() - 1;
    Some(
        Diagnostic::error(
            Span::new(at, at + 1),
            "a named argument is written with `=`",
        )
        .label("`:` gives a shape its material")
        .help(format!("write `{name} = …`")),
    )
}
