//! The source files of a scene — the main file and what it imports — each placed at its own
//! offset in one span space, so a [`Span`] (defined here; `crate::diag` re-exports it) alone
//! says which file it points into.

/// A byte range in the source text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// First byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

impl Span {
    /// The span from `start` to `end`.
    pub fn new(start: usize, end: usize) -> Span {
        Span { start, end }
    }

    /// Whether `other` lies within this span.
    pub fn contains(self, other: Span) -> bool {
        self.start <= other.start && other.end <= self.end
    }

    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }
}

impl From<pest::Span<'_>> for Span {
    /// pest spans of rules ending in an optional part include the whitespace before it; trim it.
    fn from(s: pest::Span<'_>) -> Span {
        let text = s.as_str();
        Span::new(s.start(), s.start() + text.trim_end().len())
    }
}

/// One file's text and where its spans begin.
#[derive(Clone, Debug, PartialEq)]
pub struct SourceFile {
    /// The name shown in diagnostics (`examples/lamp.sdf`, `std/arches.sdf`).
    pub name: String,
    /// The text.
    pub text: String,
    /// The offset of its first byte in the span space.
    pub base: usize,
}

/// The files of a scene; the first is the main file, at offset 0.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Sources {
    /// In the order they were read; bases increase.
    pub files: Vec<SourceFile>,
}

impl Sources {
    /// A scene of one file.
    pub fn single(name: &str, text: &str) -> Sources {
        let mut s = Sources::default();
        s.push(name, text);
        s
    }

    /// Adds a file after the others (one byte apart, so no span covers two files); its base.
    pub fn push(&mut self, name: &str, text: &str) -> usize {
        let base = self.files.last().map_or(0, |f| f.base + f.text.len() + 1);
        self.files.push(SourceFile {
            name: name.to_string(),
            text: text.to_string(),
            base,
        });
        base
    }

    /// The index of the file holding `offset` (the last whose base is at or before it).
    pub fn file_of(&self, offset: usize) -> usize {
        self.files
            .partition_point(|f| f.base <= offset)
            .saturating_sub(1)
    }

    /// The file a span points into (its index) and the span within that file, clamped to it.
    pub fn locate(&self, span: Span) -> (usize, Span) {
        let id = self.file_of(span.start);
        let (base, len) = self
            .files
            .get(id)
            .map_or((0, 0), |f| (f.base, f.text.len()));
        let end = span.end.saturating_sub(base).min(len);
        (id, Span::new(span.start.saturating_sub(base).min(end), end))
    }

    /// The main file's name.
    pub fn main_name(&self) -> &str {
        self.files.first().map_or("<input>", |f| f.name.as_str())
    }

    /// The 0-based line of `offset` counted over all files in order (for comparing lines;
    /// two files' lines never coincide).
    pub fn line_starts(&self) -> Vec<usize> {
        let mut out = Vec::new();
        for f in &self.files {
            out.push(f.base);
            out.extend(f.text.match_indices('\n').map(|(i, _)| f.base + i + 1));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_are_found_by_offset() {
        let mut s = Sources::single("a", "abc");
        let b = s.push("b", "de");
        assert_eq!(b, 4);
        assert_eq!(s.file_of(0), 0);
        assert_eq!(s.file_of(3), 0);
        assert_eq!(s.file_of(4), 1);
        assert_eq!(s.file_of(100), 1);
        assert_eq!(s.line_starts(), vec![0, 4]);
        assert_eq!(s.locate(Span::new(5, 9)), (1, Span::new(1, 2)));
    }
}
