//! Reporting several syntax errors at once: brackets left open when a new statement begins,
//! and, after a syntax error, parsing again with the failed statement blanked out (its text
//! replaced by spaces, line breaks kept, so positions stay the file's).

use super::scan::{code_bytes, statement_at};
use super::{Rule, SdfParser, errors::syntax_error};
use crate::diag::{Diagnostic, Span};
use pest::Parser as _;

/// Largest file whose syntax errors after the first are looked for.
pub const RECOVERY_BYTES: usize = 256 << 10;

/// Most syntax errors one file reports.
pub const MAX_SYNTAX_ERRORS: usize = 20;

/// Brackets still open where a statement keyword begins a line: each reported at its opening,
/// with the place it should have closed by (the outermost open one; the scan goes on as if it
/// had closed there).
pub(super) fn open_at_statements(source: &str) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let mut open: Vec<(usize, u8)> = Vec::new();
    for (i, b) in code_bytes(source) {
        if !open.is_empty() && statement_at(source, i) {
            let (j, o) = open[0];
            let closer = if o == b'(' { ')' } else { '}' };
            out.push(
                Diagnostic::error(Span::new(j, j + 1), format!("unclosed `{}`", o as char))
                    .label(format!("this `{}` is never closed", o as char))
                    .also(
                        Span::new(i, i),
                        format!("expected `{closer}` before this statement"),
                    ),
            );
            open.clear();
        }
        match b {
            b'(' | b'{' => open.push((i, b)),
            b')' | b'}' => {
                let want = if b == b')' { b'(' } else { b'{' };
                match open.pop() {
                    Some((_, o)) if o == want => {}
                    // A closer of the wrong kind or of nothing: `bracket_error` says which.
                    _ => return Vec::new(),
                }
            }
            _ => {}
        }
    }
    out
}

/// After the syntax error `first`, the errors of the statements after it: the failed
/// statement is blanked and the file parsed again, until it parses or no new error is found.
pub(super) fn later_errors(source: &str, first: &Diagnostic) -> Vec<Diagnostic> {
    if source.len() > RECOVERY_BYTES {
        // Each error costs a parse of the whole file: past this size, the first error only.
        return Vec::new();
    }
    let mut text = source.to_string();
    let mut out = Vec::new();
    let mut at = first.span.start;
    while out.len() + 1 < MAX_SYNTAX_ERRORS {
        let (from, to) = statement_around(&text, at);
        if to <= from {
            break;
        }
        blank(&mut text, from, to);
        let Err(e) = SdfParser::parse(Rule::file, &text) else {
            break;
        };
        let d = syntax_error(&text, e);
        if d.span.start < to {
            // Nothing new after the blanked statement.
            break;
        }
        at = d.span.start;
        out.push(d);
    }
    out
}

/// The statement holding `at`: from the last line start at or before it that begins a
/// statement (a letter at the start of the line) to the next one after it where its brackets
/// are closed again (or a statement keyword begins a line).
fn statement_around(text: &str, at: usize) -> (usize, usize) {
    let starts_statement = |i: usize| {
        (i == 0 || text.as_bytes()[i - 1] == b'\n')
            && text[i..].starts_with(|c: char| c.is_ascii_alphabetic() || c == '#')
    };
    let at = at.min(text.len());
    let from = (0..=at)
        .rev()
        .find(|&i| text.is_char_boundary(i) && starts_statement(i))
        .unwrap_or(0);
    let mut depth = 0i64;
    let mut to = text.len();
    for (i, b) in code_bytes(text).filter(|&(i, _)| i >= from) {
        if i > at
            && text.is_char_boundary(i)
            && starts_statement(i)
            && (depth <= 0 || statement_at(text, i))
        {
            to = i;
            break;
        }
        match b {
            b'(' | b'{' => depth += 1,
            b')' | b'}' => depth -= 1,
            _ => {}
        }
    }
    (from, to)
}

/// Replaces `text[from..to]` with spaces, line breaks kept.
fn blank(text: &mut String, from: usize, to: usize) {
    let blanked: String = text[from..to]
        .chars()
        .map(|c| {
            if c == '\n' {
                "\n".to_string()
            } else {
                " ".repeat(c.len_utf8())
            }
        })
        .collect();
    text.replace_range(from..to, &blanked);
}
