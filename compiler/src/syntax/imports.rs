//! Imports: reading the files a scene imports (relative to the importing file, or from the
//! standard library), once each, splicing their definitions in place of the `import`, with
//! cycles reported along their chain. The spans of every file share one space ([`Sources`]).

use super::{File, Item, parse_all, shift};
use crate::diag::{Diagnostic, Span};
use crate::source::Sources;
use std::collections::HashSet;
use std::path::{Component, Path, PathBuf};

/// Most files one scene may read (its imports, transitively, and itself).
pub const MAX_FILES: usize = 256;

/// The standard library: `import "std/NAME.sdf"` reads these, not the disk.
pub const STD: &[(&str, &str)] = &[
    ("std/arches.sdf", include_str!("../../std/arches.sdf")),
    ("std/stairs.sdf", include_str!("../../std/stairs.sdf")),
    ("std/columns.sdf", include_str!("../../std/columns.sdf")),
    ("std/gears.sdf", include_str!("../../std/gears.sdf")),
];

/// Where imported files come from.
pub trait Loader {
    /// The text of the file at `path` (the import joined to the importing file's directory),
    /// or why it cannot be read.
    fn read(&self, path: &Path) -> Result<String, String>;
}

/// Files on disk, at most [`super::MAX_SOURCE_BYTES`] each; a UTF-8 byte-order mark dropped.
pub struct FsLoader;

impl Loader for FsLoader {
    fn read(&self, path: &Path) -> Result<String, String> {
        let limit = super::MAX_SOURCE_BYTES;
        // Only regular files: a directory, a FIFO or a device (`/dev/stdin`) is refused before
        // it is opened (opening a FIFO blocks).
        let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
        if meta.is_dir() {
            return Err("it is a directory".into());
        }
        if !meta.is_file() {
            return Err("it is not a regular file".into());
        }
        let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
        match read_limited(file).map_err(|e| e.to_string())? {
            Some(bytes) => decode(bytes),
            None => Err(format!("it is larger than the limit of {limit} bytes")),
        }
    }
}

/// Reads a source: at most [`super::MAX_SOURCE_BYTES`] and one byte more (`/dev/zero` is
/// refused, not read until memory runs out); `None` when it is larger than the limit.
pub fn read_limited(reader: impl std::io::Read) -> std::io::Result<Option<Vec<u8>>> {
    use std::io::Read;
    let limit = super::MAX_SOURCE_BYTES;
    let mut bytes = Vec::new();
    reader.take(limit as u64 + 1).read_to_end(&mut bytes)?;
    Ok((bytes.len() <= limit).then_some(bytes))
}

/// A source's bytes as text: UTF-8, or why not with the place of the first invalid byte; a
/// UTF-8 byte-order mark, which Windows editors write, dropped.
pub fn decode(bytes: Vec<u8>) -> Result<String, String> {
    let text = String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let before = String::from_utf8_lossy(&e.as_bytes()[..at]);
        let line = before.matches('\n').count() + 1;
        let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        format!("it is not UTF-8 text (an invalid byte at {line}:{column}, offset {at})")
    })?;
    Ok(match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_string(),
        None => text,
    })
}

/// No files at all (the standard library only): what `check::compile` uses, which has no file
/// to be relative to.
pub struct NoFiles;

impl Loader for NoFiles {
    fn read(&self, _: &Path) -> Result<String, String> {
        Err("this source has no file to import relative to (check it as a file)".into())
    }
}

/// Files held in memory by path (tests and fuzzing: a virtual file system).
pub struct MapLoader(pub std::collections::HashMap<PathBuf, String>);

impl Loader for MapLoader {
    fn read(&self, path: &Path) -> Result<String, String> {
        self.0
            .get(&normalize(path))
            .cloned()
            .ok_or_else(|| "No such file or directory (os error 2)".to_string())
    }
}

/// The scene's files read and parsed, imports spliced in: the file to check (none when a file
/// failed to read or parse), every file read, and the errors found.
pub struct Loaded {
    /// The main file with its imports' definitions in place of each `import`.
    pub file: Option<File>,
    /// Every file read, the main one first.
    pub sources: Sources,
    /// Errors of reading and parsing (spans in the shared space).
    pub diagnostics: Vec<Diagnostic>,
    /// Files imported that could not be read (a watcher waits for them to appear).
    pub missing: Vec<PathBuf>,
}

/// Parses the main file (`name`, `text`) and every file it imports.
pub fn load(name: &str, text: &str, loader: &dyn Loader) -> Loaded {
    load_at(name, Path::new(name), text, loader)
}

/// [`load`] for the file at `main`, shown as `name`: imports are found beside `main` itself,
/// so a path that is not UTF-8 (`café` in Latin-1) is never made text on the way.
pub fn load_at(name: &str, main: &Path, text: &str, loader: &dyn Loader) -> Loaded {
    let mut l = Load {
        sources: Sources::single(name, text),
        diagnostics: Vec::new(),
        missing: Vec::new(),
        included: HashSet::new(),
        loader,
    };
    let file = match parse_all(text) {
        Ok(file) => file,
        Err(diagnostics) => {
            return Loaded {
                file: None,
                sources: l.sources,
                diagnostics,
                missing: l.missing,
            };
        }
    };
    let dir = main.parent().unwrap_or(Path::new("")).to_path_buf();
    let main = normalize(main);
    l.included.insert(main.clone());
    let mut chain = vec![(main, name.to_string())];
    let items = l.splice(file.items, &dir, &mut chain, None);
    let ok = l.diagnostics.is_empty();
    Loaded {
        file: ok.then_some(File { items }),
        sources: l.sources,
        diagnostics: l.diagnostics,
        missing: l.missing,
    }
}

struct Load<'l> {
    sources: Sources,
    diagnostics: Vec<Diagnostic>,
    missing: Vec<PathBuf>,
    /// Files read already (an import of one again adds nothing).
    included: HashSet<PathBuf>,
    loader: &'l dyn Loader,
}

impl Load<'_> {
    /// `items` with each `import` replaced by the imported file's definitions. `chain` holds
    /// the files being imported, outermost first; `imported_at` is where this file was
    /// imported (none for the main file, whose items may be anything).
    fn splice(
        &mut self,
        items: Vec<Item>,
        dir: &Path,
        chain: &mut Vec<(PathBuf, String)>,
        imported_at: Option<Span>,
    ) -> Vec<Item> {
        let mut out = Vec::new();
        for item in items {
            if let Item::Import {
                path,
                path_span,
                span,
            } = &item
            {
                out.extend(self.import(path, *path_span, *span, dir, chain));
                continue;
            }
            if let Some(at) = imported_at
                && let Some((span, what)) = not_a_definition(&item)
            {
                self.diagnostics.push(
                    Diagnostic::error(span, "an imported file holds definitions only")
                        .label(format!("{what} in an imported file"))
                        .also(at, "imported here")
                        .note("a library may hold `let`, `fn`, `material` and `import`; shapes, settings and parameters belong to the scene that imports it"),
                );
                continue;
            }
            out.push(item);
        }
        out
    }

    /// The items of the file `import "path"` names (at `path_span`, the statement at `span`),
    /// read relative to `dir` unless it is the standard library's, spliced in turn; nothing
    /// when it cannot or need not be read (read already), each problem reported.
    fn import(
        &mut self,
        path: &str,
        path_span: Span,
        span: Span,
        dir: &Path,
        chain: &mut Vec<(PathBuf, String)>,
    ) -> Vec<Item> {
        let std_text = STD.iter().find(|(n, _)| *n == path).map(|(_, t)| *t);
        let (resolved, shown) = resolve(path, std_text.is_some(), dir);
        if !self.admit(
            path,
            path_span,
            std_text.is_some(),
            &resolved,
            &shown,
            chain,
        ) {
            return Vec::new();
        }
        let text = match std_text {
            Some(t) => t.to_string(),
            None => match self.loader.read(&resolved) {
                Ok(t) => t,
                Err(why) => {
                    self.missing.push(resolved.clone());
                    self.diagnostics.push(
                        Diagnostic::error(path_span, format!("cannot import `{path}`"))
                            .label(why)
                            .note(format!("looked for `{shown}` (an import is relative to the file that writes it)")),
                    );
                    return Vec::new();
                }
            },
        };
        let base = self.sources.push(&shown, &text);
        let mut file = match parse_all(&text) {
            Ok(f) => f,
            Err(errors) => {
                for mut d in errors {
                    shift::diagnostic(&mut d, base);
                    self.diagnostics.push(d.also(span, "imported here"));
                }
                return Vec::new();
            }
        };
        shift::file(&mut file, base);
        let dir = resolved.parent().unwrap_or(Path::new("")).to_path_buf();
        chain.push((resolved, shown));
        let items = self.splice(file.items, &dir, chain, Some(span));
        chain.pop();
        items
    }

    /// Whether the import of `path` (resolved to `resolved`, shown as `shown`) is to be read:
    /// not when it names no file, a file the standard library lacks (`in_std`: it has it), one
    /// already being imported along `chain` (a cycle), one read already, or one file more
    /// than [`MAX_FILES`]; each but the one read already reported.
    fn admit(
        &mut self,
        path: &str,
        path_span: Span,
        in_std: bool,
        resolved: &Path,
        shown: &str,
        chain: &[(PathBuf, String)],
    ) -> bool {
        if path.is_empty() || path.ends_with('/') {
            self.diagnostics.push(
                Diagnostic::error(path_span, "an import names a file")
                    .label("no file name")
                    .help("write `import \"lib/furniture.sdf\"`, relative to this file"),
            );
            return false;
        }
        if path.starts_with("std/") && !in_std {
            self.diagnostics.push(not_in_std(path, path_span));
            return false;
        }
        if let Some(start) = chain.iter().position(|(p, _)| *p == resolved) {
            let names: Vec<&str> = chain[start..]
                .iter()
                .map(|(_, n)| n.as_str())
                .chain([shown])
                .collect();
            self.diagnostics.push(
                Diagnostic::error(path_span, "import cycle")
                    .label(format!("`{shown}` is already being imported"))
                    .note(format!("the chain: {}", names.join(" → ")))
                    .help("move what both files need into a third file that both import"),
            );
            return false;
        }
        if !self.included.insert(resolved.to_path_buf()) {
            return false;
        }
        if self.sources.files.len() >= MAX_FILES {
            self.diagnostics.push(
                Diagnostic::error(path_span, "too many imported files")
                    .label(format!("more than {MAX_FILES} files in one scene")),
            );
            return false;
        }
        true
    }
}

/// Where `import "path"` in a file of `dir` points (`in_std`: the standard library's file,
/// keyed apart from a file on disk of the same name), and the name shown for it.
fn resolve(path: &str, in_std: bool, dir: &Path) -> (PathBuf, String) {
    if in_std {
        return (PathBuf::from("<std>").join(path), path.to_string());
    }
    let p = normalize(&dir.join(path));
    let shown = match p.display().to_string() {
        s if s.is_empty() => ".".to_string(),
        s => s,
    };
    (p, shown)
}

/// `import "std/NAME.sdf"` of a file the standard library does not have.
fn not_in_std(path: &str, path_span: Span) -> Diagnostic {
    let names = STD.iter().map(|(n, _)| *n);
    let d = Diagnostic::error(path_span, format!("the standard library has no `{path}`"))
        .label("not in the standard library");
    match crate::diag::did_you_mean(path, names) {
        Some(s) => d.help(format!("did you mean `{s}`?")),
        None => d.note(format!(
            "it has {}",
            STD.iter()
                .map(|(n, _)| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// For a statement an imported file may not hold: its span and what it is.
fn not_a_definition(item: &Item) -> Option<(Span, &'static str)> {
    match item {
        Item::Let { .. } | Item::Fn(_) | Item::Import { .. } => None,
        Item::Block { keyword, .. } if keyword.name == "material" => None,
        Item::Block { keyword, .. } => Some((keyword.span, "a settings block")),
        Item::Param { name, .. } => Some((name.span, "a parameter")),
        Item::Value { keyword, .. } => Some((keyword.span, "a setting")),
        Item::Scene(e) => Some((e.span, "a shape of the scene")),
    }
}

/// `a/./b/../c` → `a/c`, without asking the file system (a key for "read already").
fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if matches!(out.components().next_back(), Some(Component::Normal(_))) {
                    out.pop();
                } else {
                    out.push("..");
                }
            }
            c => out.push(c),
        }
    }
    out
}
