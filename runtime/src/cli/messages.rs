//! How diagnostics reach the user: codespan's report, coloured on a terminal (`--color`,
//! honouring `NO_COLOR`), or one JSON object per diagnostic (`--message-format json`) for
//! editors and CI, then one `{"summary": …}` object with the totals; both show the same
//! diagnostics: errors first, at most `diag::MAX_SHOWN`. (Only the scene's diagnostics: other errors — a file that cannot be read,
//! a bad flag — stay `error: …` lines.) And the one line of success, unless `--quiet`.

use sdfc_compiler::diag::{self, Diagnostic, Severity, Span};
use sdfc_compiler::source::Sources;
use std::io::IsTerminal;
use std::sync::OnceLock;

/// `--message-format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// The report with the source line and a caret.
    Human,
    /// One JSON object per line and diagnostic.
    Json,
}

/// `--color`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Color {
    /// Colour when standard error is a terminal and `NO_COLOR` is not set.
    Auto,
    /// Always colour.
    Always,
    /// Never colour.
    Never,
}

static STYLE: OnceLock<(Format, bool)> = OnceLock::new();

/// Whether `-q/--quiet` was given.
static QUIET: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Prints a command's one line of success to standard error, unless `--quiet`.
pub fn done(line: &str) {
    if !QUIET.load(std::sync::atomic::Ordering::Relaxed) {
        say!("{line}");
    }
}

/// Chooses the format, whether to colour (once, from the flags and the environment) and
/// whether to be quiet.
pub fn configure(format: Format, color: Color, quiet: bool) {
    QUIET.store(quiet, std::sync::atomic::Ordering::Relaxed);
    let colored = match color {
        Color::Always => true,
        Color::Never => false,
        Color::Auto => {
            std::io::stderr().is_terminal()
                && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
        }
    };
    let _ = STYLE.set((format, colored));
}

/// The diagnostics of a scene's files as the user asked for them.
pub fn report(diagnostics: &[Diagnostic], sources: &Sources) -> String {
    let (format, colored) = STYLE.get().copied().unwrap_or((Format::Human, false));
    match format {
        Format::Human => diag::render_sources(diagnostics, sources, colored),
        Format::Json => {
            // The same diagnostics as the human report, in its order and with its cap, then a
            // summary object with the totals.
            let (shown, totals) = diag::shown(diagnostics);
            let mut out: String = shown
                .iter()
                .map(|d| json(d, sources).to_string() + "\n")
                .collect();
            if !diagnostics.is_empty() {
                let summary = serde_json::json!({"summary": {
                    "errors": totals.errors,
                    "warnings": totals.warnings,
                    "errors_shown": totals.errors_shown,
                    "warnings_shown": totals.warnings_shown,
                }});
                out += &(summary.to_string() + "\n");
            }
            out
        }
    }
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

fn place(source: &str, span: Span) -> serde_json::Value {
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
fn json(d: &Diagnostic, sources: &Sources) -> serde_json::Value {
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
