//! Scans of the source before and beside the parser: control characters, unclosed comments,
//! nesting past the limit, clearer messages for unbalanced brackets, and where a statement
//! keyword begins.

use super::{BLOCK_KEYWORDS, DEFINITION_KEYWORDS, MAX_NESTING, VALUE_KEYWORDS};
use crate::diag::{Diagnostic, Span};

/// The length of the comment `rest` starts with, if it starts with one: `Some(None)` for a
/// `/*` that is never closed.
fn comment_at(rest: &[u8]) -> Option<Option<usize>> {
    if rest.starts_with(b"//") {
        Some(Some(
            rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len()),
        ))
    } else if rest.starts_with(b"/*") {
        Some(rest[2..].windows(2).position(|w| w == b"*/").map(|p| p + 4))
    } else {
        None
    }
}

/// The length of the quoted string (`import "…"`) `rest` starts with, if it does: to its
/// closing quote, or to the end of its line when it has none.
fn string_at(rest: &[u8]) -> Option<usize> {
    if rest.first() != Some(&b'"') {
        return None;
    }
    let end = rest[1..]
        .iter()
        .position(|&b| b == b'"' || b == b'\n')
        .map_or(rest.len(), |p| p + 1);
    Some(if rest.get(end) == Some(&b'"') {
        end + 1
    } else {
        end
    })
}

/// Positions and bytes of the code outside comments and quoted strings (an unclosed comment
/// runs to the end).
pub(super) fn code_bytes(source: &str) -> impl Iterator<Item = (usize, u8)> + '_ {
    let bytes = source.as_bytes();
    let mut i = 0;
    std::iter::from_fn(move || {
        while i < bytes.len() {
            let rest = &bytes[i..];
            if let Some(len) = string_at(rest) {
                i += len;
                continue;
            }
            match comment_at(rest) {
                Some(len) => i += len.unwrap_or(rest.len()),
                None => {
                    i += 1;
                    return Some((i - 1, bytes[i - 1]));
                }
            }
        }
        None
    })
}

/// A control character other than a tab or a line break (a NUL byte, an escape…) is an error at
/// its place, named, rather than a syntax error with an invisible caret.
pub(super) fn check_control(source: &str) -> Result<(), Diagnostic> {
    let Some((at, c)) = source
        .char_indices()
        .find(|&(_, c)| c.is_control() && !matches!(c, '\t' | '\n' | '\r'))
    else {
        return Ok(());
    };
    let name = match c {
        '\0' => " (NUL)".to_string(),
        '\u{1b}' => " (escape)".to_string(),
        '\u{7f}' => " (delete)".to_string(),
        _ => String::new(),
    };
    Err(Diagnostic::error(
        Span::new(at, at + c.len_utf8()),
        format!(
            "a control character U+{:04X}{name} is not allowed in a scene",
            c as u32
        ),
    )
    .label("here")
    .note("scene files are text: only tabs and line breaks of the control characters may appear"))
}

/// A `/*` comment that is never closed is an error at its opening, saying so (it was a syntax
/// error expecting an expression where the comment began).
pub(super) fn check_comments(source: &str) -> Result<(), Diagnostic> {
    let bytes = source.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if let Some(len) = string_at(&bytes[i..]) {
            i += len;
            continue;
        }
        match comment_at(&bytes[i..]) {
            Some(Some(len)) => i += len,
            Some(None) => {
                return Err(
                    Diagnostic::error(Span::new(i, i + 2), "this comment is never closed")
                        .label("opened here")
                        .help("close it with `*/`"),
                );
            }
            None => i += 1,
        }
    }
    Ok(())
}

/// Refuses input nested deeper than [`MAX_NESTING`] brackets, or with longer runs of prefix
/// minus signs, before the recursive parser sees it.
pub(super) fn check_nesting(source: &str) -> Result<(), Diagnostic> {
    let mut depth = 0usize;
    let mut minus_run = 0usize;
    for (i, b) in code_bytes(source) {
        match b {
            b'(' | b'{' => depth += 1,
            b')' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        minus_run = match b {
            b'-' => minus_run + 1,
            b' ' | b'\t' | b'\r' | b'\n' => minus_run,
            _ => 0,
        };
        if depth > MAX_NESTING || minus_run > MAX_NESTING {
            return Err(
                Diagnostic::error(Span::new(i, i + 1), "nesting is too deep")
                    .label(format!("more than {MAX_NESTING} levels deep here"))
                    .help("split the scene into `let` bindings"),
            );
        }
    }
    Ok(())
}

/// A clearer message than the expected-token list for unbalanced brackets: an unclosed opener
/// when the parser stopped at the end, an unmatched closer where it stopped on one.
pub(super) fn bracket_error(source: &str, at: usize) -> Option<Diagnostic> {
    let mut open: Vec<(usize, u8)> = Vec::new();
    for (i, b) in code_bytes(source) {
        let want = match b {
            b'(' | b'{' => {
                open.push((i, b));
                continue;
            }
            b')' => b'(',
            b'}' => b'{',
            _ => continue,
        };
        let closer = b as char;
        match open.pop() {
            Some((_, o)) if o == want => {}
            Some((j, o)) => {
                return Some(
                    Diagnostic::error(
                        Span::new(i, i + 1),
                        format!("`{closer}` does not match `{}`", o as char),
                    )
                    .label("closes the wrong bracket")
                    .also(Span::new(j, j + 1), "opened here"),
                );
            }
            None => {
                return Some(
                    Diagnostic::error(Span::new(i, i + 1), format!("unmatched `{closer}`"))
                        .label("nothing to close here"),
                );
            }
        }
    }
    let rest_is_blank = code_bytes(source).all(|(i, b)| i < at || b.is_ascii_whitespace());
    match open.last() {
        Some(&(j, o)) if rest_is_blank => {
            let closer = if o == b'(' { ')' } else { '}' };
            Some(
                Diagnostic::error(Span::new(j, j + 1), format!("unclosed `{}`", o as char))
                    .label(format!("this `{}` is never closed", o as char))
                    .also(
                        Span::new(source.len(), source.len()),
                        format!("expected `{closer}` before the end of the file"),
                    ),
            )
        }
        _ => None,
    }
}

/// Whether a statement keyword (a block's, or `let`, `param`, `fn`, `import`, `background`)
/// begins the text at `at`, at the start of its line; one inside brackets means the brackets
/// before it were never closed.
pub(super) fn statement_at(source: &str, at: usize) -> bool {
    if !source.is_char_boundary(at) {
        return false;
    }
    let line_start = at == 0 || source.as_bytes()[at - 1] == b'\n';
    let words = BLOCK_KEYWORDS
        .iter()
        .chain(DEFINITION_KEYWORDS)
        .chain(VALUE_KEYWORDS);
    line_start && keyword_at(&source[at..], words)
}

/// Whether `rest` begins with one of `words` as a whole word.
pub(super) fn keyword_at<'w>(rest: &str, mut words: impl Iterator<Item = &'w &'w str>) -> bool {
    words.any(|w| {
        rest.strip_prefix(w)
            .is_some_and(|r| !r.starts_with(|c: char| c.is_ascii_alphanumeric() || c == '_'))
    })
}
