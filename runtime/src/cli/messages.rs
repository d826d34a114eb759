//! How diagnostics reach the user: codespan's report, coloured on a terminal (`--color`,
//! honouring `NO_COLOR`), or one JSON object per diagnostic (`--message-format json`) for
//! editors and CI, then one `{"summary": …}` object with the totals; both show the same
//! diagnostics: errors first, at most `diag::MAX_SHOWN`. (Only the scene's diagnostics: other errors — a file that cannot be read,
//! a bad flag — stay `error: …` lines.) And the one line of success, unless `--quiet`.

use sdfc_compiler::diag::{self, Diagnostic};
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
        // The same diagnostics as the human report, in its order and with its cap, then a
        // summary object with the totals.
        Format::Json => diag::json::lines(diagnostics, sources),
    }
}
