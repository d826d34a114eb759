//! Diagnostics: errors and warnings with source spans, rendered with codespan-reporting.

pub mod json;

use crate::source::Sources;
pub use crate::source::Span;
use codespan_reporting::diagnostic as cs;
use codespan_reporting::files::SimpleFiles;
use codespan_reporting::term;

/// How bad a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// The scene cannot be compiled.
    Error,
    /// The scene compiles, but something is likely wrong.
    Warning,
}

/// One message about the source, with a primary span and optional extra labels and help.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// The headline.
    pub message: String,
    /// Where, and what to say under the caret.
    pub span: Span,
    /// Text under the caret (may be empty).
    pub label: String,
    /// Other places that explain this one.
    pub secondary: Vec<(Span, String)>,
    /// Lines printed after the source excerpt (`help: ...`, `note: ...`).
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            message: message.into(),
            span,
            label: String::new(),
            secondary: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(span, message)
        }
    }

    /// Sets the text under the caret.
    pub fn label(mut self, label: impl Into<String>) -> Diagnostic {
        self.label = label.into();
        self
    }

    /// Adds a secondary label elsewhere in the source.
    pub fn also(mut self, span: Span, label: impl Into<String>) -> Diagnostic {
        self.secondary.push((span, label.into()));
        self
    }

    /// Adds a `help: ...` line.
    pub fn help(mut self, text: impl Into<String>) -> Diagnostic {
        self.notes.push(format!("help: {}", text.into()));
        self
    }

    /// Adds a `note: ...` line.
    pub fn note(mut self, text: impl Into<String>) -> Diagnostic {
        self.notes.push(format!("note: {}", text.into()));
        self
    }

    /// Whether this is an error (not a warning).
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

/// Appends one rendered diagnostic to `out`, coloured or plain. (Writing to memory cannot
/// fail; a failure would only drop a message.)
fn emit(
    out: &mut String,
    config: &term::Config,
    files: &SimpleFiles<&str, String>,
    diagnostic: &cs::Diagnostic<usize>,
    color: bool,
) {
    if color {
        let mut buffer = term::termcolor::Buffer::ansi();
        let _ = term::emit_to_write_style(&mut buffer, config, files, diagnostic);
        out.push_str(&String::from_utf8_lossy(buffer.as_slice()));
    } else {
        let _ = term::emit_to_string(out, config, files, diagnostic);
    }
}

/// Renders diagnostics as the user sees them: `error: ...`, `--> file:line:col`, the source line
/// and a caret under the span.
pub fn render(diagnostics: &[Diagnostic], file_name: &str, source: &str) -> String {
    render_styled(diagnostics, file_name, source, false)
}

/// [`render`], with ANSI colours (codespan's styles) if `color`.
pub fn render_styled(
    diagnostics: &[Diagnostic],
    file_name: &str,
    source: &str,
    color: bool,
) -> String {
    render_sources(diagnostics, &Sources::single(file_name, source), color)
}

/// Renders diagnostics whose spans point into any of a scene's files (imports included), each
/// label shown in its own file.
pub fn render_sources(diagnostics: &[Diagnostic], sources: &Sources, color: bool) -> String {
    // Control characters are shown as `?` (same length, so spans still fit): echoed raw they
    // would act on the terminal.
    let mut files = SimpleFiles::new();
    for f in &sources.files {
        let shown: String = f
            .text
            .chars()
            .map(|c| {
                if c.is_control() && !matches!(c, '\t' | '\n' | '\r') && c.len_utf8() == 1 {
                    '?'
                } else {
                    c
                }
            })
            .collect();
        files.add(f.name.as_str(), shown);
    }
    if sources.files.is_empty() {
        files.add("<input>", String::new());
    }
    // A span as (file, range in that file), clamped to the file as the report needs.
    let place = |s: Span| {
        let (id, s) = sources.locate(s);
        (id, s.start..s.end)
    };
    let config = term::Config::default();
    let mut out = String::new();
    let (shown, totals) = shown(diagnostics);
    for d in shown.iter().copied() {
        let (id, range) = place(d.span);
        let (name, source) = match sources.files.get(id) {
            Some(f) => (f.name.as_str(), f.text.as_str()),
            None => ("<input>", ""),
        };
        if let Some(note) = long_line(name, source, range.clone(), &d.label) {
            // A line too long to echo (one error printed megabytes): the place and an excerpt.
            let diagnostic = match d.severity {
                Severity::Error => cs::Diagnostic::error(),
                Severity::Warning => cs::Diagnostic::warning(),
            }
            .with_message(shorten(&d.message))
            .with_notes(
                std::iter::once(note)
                    .chain(d.notes.iter().map(|n| shorten(n)))
                    .collect(),
            );
            emit(&mut out, &config, &files, &diagnostic, color);
            continue;
        }
        let mut labels = vec![cs::Label::primary(id, range).with_message(shorten(&d.label))];
        labels.extend(d.secondary.iter().map(|(s, m)| {
            let (id, range) = place(*s);
            cs::Label::secondary(id, range).with_message(shorten(m))
        }));
        let diagnostic = match d.severity {
            Severity::Error => cs::Diagnostic::error(),
            Severity::Warning => cs::Diagnostic::warning(),
        }
        .with_message(shorten(&d.message))
        .with_labels(labels)
        .with_notes(d.notes.iter().map(|n| shorten(n)).collect());
        emit(&mut out, &config, &files, &diagnostic, color);
    }
    if let Some(line) = totals.rest() {
        out += &line;
        out.push('\n');
    }
    out
}

/// What a report holds: how many errors and warnings there are and how many it shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Totals {
    /// Errors in all.
    pub errors: usize,
    /// Warnings in all.
    pub warnings: usize,
    /// Errors shown.
    pub errors_shown: usize,
    /// Warnings shown.
    pub warnings_shown: usize,
}

impl Totals {
    /// The line that counts what is not shown, if anything is not.
    pub fn rest(&self) -> Option<String> {
        let errors = self.errors - self.errors_shown;
        let warnings = self.warnings - self.warnings_shown;
        (errors + warnings > 0).then(|| {
            format!(
                "… and {} more ({errors} errors, {warnings} warnings) not shown",
                errors + warnings
            )
        })
    }
}

/// The diagnostics a report shows, in the order it shows them — every error before any
/// warning (a file of 19 700 warnings hid its one error behind the first hundred), each kind in
/// the order found — at most [`MAX_SHOWN`]; and the totals. Every format shows the same ones.
pub fn shown(diagnostics: &[Diagnostic]) -> (Vec<&Diagnostic>, Totals) {
    let errors = diagnostics.iter().filter(|d| d.is_error());
    let warnings = diagnostics.iter().filter(|d| !d.is_error());
    let shown: Vec<&Diagnostic> = errors.chain(warnings).take(MAX_SHOWN).collect();
    let errors_shown = shown.iter().filter(|d| d.is_error()).count();
    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    let totals = Totals {
        errors,
        warnings: diagnostics.len() - errors,
        errors_shown,
        warnings_shown: shown.len() - errors_shown,
    };
    (shown, totals)
}

/// A message, label or note cut to [`MAX_LINE`] characters (a 100 000-character name quoted
/// in a message is shown by its start and end).
fn shorten(text: &str) -> String {
    let n = text.chars().count();
    if n <= MAX_LINE {
        return text.to_string();
    }
    let head: String = text.chars().take(MAX_LINE * 2 / 3).collect();
    let tail: String = text.chars().skip(n - MAX_LINE / 4).collect();
    format!(
        "{head}… ({} characters) …{tail}",
        n - MAX_LINE * 2 / 3 - MAX_LINE / 4
    )
}

/// The longest line (in characters) a diagnostic echoes; a longer one is shown as an excerpt.
pub const MAX_LINE: usize = 2_000;

/// For a span on a line longer than [`MAX_LINE`]: a note with its place (`file:line:column`),
/// the label and an excerpt around it.
fn long_line(
    file: &str,
    source: &str,
    span: std::ops::Range<usize>,
    label: &str,
) -> Option<String> {
    let start = source[..span.start].rfind('\n').map_or(0, |i| i + 1);
    let end = source[span.start..]
        .find('\n')
        .map_or(source.len(), |i| span.start + i);
    let length = source[start..end].chars().count();
    if length <= MAX_LINE {
        return None;
    }
    let line = source[..start].matches('\n').count() + 1;
    let column = source[start..span.start].chars().count() + 1;
    let before: String = source[start..span.start]
        .chars()
        .rev()
        .take(40)
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    let after: String = source[span.start..end].chars().take(40).collect();
    let label = if label.is_empty() {
        String::new()
    } else {
        format!("{label}; ")
    };
    Some(format!(
        "at {file}:{line}:{column} ({label}a line of {length} characters, shown around the place): …{before}⟨here⟩{after}…"
    ))
}

/// The most diagnostics one report shows; the rest are counted (a file of 100 000 errors
/// printed 22 MB).
pub const MAX_SHOWN: usize = 100;

/// The longest name a "did you mean" suggests.
const MAX_SUGGESTED: usize = 256;

/// The closest of `candidates` to `name`, if one is close enough to be a likely typo.
pub fn did_you_mean<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    // Names whose lengths differ by more than the allowed distance cannot be close: skipped
    // before the quadratic comparison (100 000-character names took 90 s).
    let n = name.chars().count();
    candidates
        .into_iter()
        .filter(|c| {
            let m = c.chars().count();
            n.abs_diff(m) <= 2.max(m / 3) && m <= MAX_SUGGESTED
        })
        .map(|c| (strsim::damerau_levenshtein(name, c), c))
        .filter(|&(d, c)| d <= 2.max(c.len() / 3) && d < c.len().max(name.len()))
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}
