//! Diagnostics as JSON: one object per diagnostic (file, severity, message, span with line and
//! column, labels, notes) and a summary with the totals — what `--message-format json` prints
//! and what the playground underlines.

use super::{Diagnostic, Severity, Span};
use crate::source::Sources;
use serde_json::Value;

/// The diagnostics as the human report shows them (errors first, at most `diag::MAX_SHOWN`),
/// one JSON object per line, then a `{"summary": …}` line with the totals; empty when there
/// are none.
pub fn lines(diagnostics: &[Diagnostic], sources: &Sources) -> String {
    let (shown, totals) = super::shown(diagnostics);
    let mut out: String = shown
        .iter()
        .map(|d| one(d, sources).to_string() + "\n")
        .collect();
    if !diagnostics.is_empty() {
        out += &(summary(&totals).to_string() + "\n");
    }
    out
}

/// The summary object: errors and warnings, and how many of each are shown.
pub fn summary(totals: &super::Totals) -> Value {
    serde_json::json!({"summary": {
        "errors": totals.errors,
        "warnings": totals.warnings,
        "errors_shown": totals.errors_shown,
        "warnings_shown": totals.warnings_shown,
    }})
}

/// The file a span points into: its name, its text, and the span within it.
fn locate(sources: &Sources, span: Span) -> (&str, &str, Span) {
    let (id, span) = sources.locate(span);
    match sources.files.get(id) {
        Some(f) => (f.name.as_str(), f.text.as_str(), span),
        None => ("<input>", "", span),
    }
}

/// Line and column (1-based; the column in characters) of byte `offset`.
fn line_column(source: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(source.len());
    while !source.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &source[..offset];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

fn place(source: &str, span: Span) -> Value {
    // Clamped to the source, as the report clamps it.
    let end = span.end.min(source.len());
    let span = Span::new(span.start.min(end), end);
    let (line, column) = line_column(source, span.start);
    let (end_line, end_column) = line_column(source, span.end);
    serde_json::json!({
        "start": span.start, "end": span.end,
        "line": line, "column": column, "end_line": end_line, "end_column": end_column,
    })
}

/// One diagnostic as JSON: file, severity, message, its span (bytes, line and column), the
/// label under the caret, the other places with their labels, and the notes.
pub fn one(d: &Diagnostic, sources: &Sources) -> Value {
    let (name, source, span) = locate(sources, d.span);
    serde_json::json!({
        "file": name,
        "severity": match d.severity { Severity::Error => "error", Severity::Warning => "warning" },
        "message": d.message,
        "span": place(source, span),
        "label": d.label,
        "secondary": d.secondary.iter().map(|(s, l)| {
            let (file, source, span) = locate(sources, *s);
            serde_json::json!({ "file": file, "span": place(source, span), "label": l })
        }).collect::<Vec<_>>(),
        "notes": d.notes,
    })
}
