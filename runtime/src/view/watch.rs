//! Following a scene file (and the files it imports) on disk: the viewer's reloads and the
//! `--watch` of `render` and `emit`.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Waits this long after the last write before reloading (editors write in bursts).
pub const SETTLE: Duration = Duration::from_millis(80);

/// What the file watcher reports.
#[derive(Debug)]
pub enum Watched {
    /// The scene file was written (or came back).
    Changed,
    /// The scene file is gone.
    Gone,
}

/// Watches the scene file and the files it imports: their directories (editors replace
/// files, and a deleted file may come back), reporting events about those files.
pub struct SceneWatcher {
    watcher: notify::RecommendedWatcher,
    /// Directories watched.
    dirs: HashSet<PathBuf>,
    /// Absolute paths of the imported files followed (the main file is always followed).
    imports: Arc<Mutex<HashSet<PathBuf>>>,
}

impl SceneWatcher {
    /// Follows the files `file` imports now (after a reload the set may have changed); a
    /// directory that cannot be watched is skipped with a message.
    pub fn follow(&mut self, file: &Path) {
        use notify::Watcher;
        let files: HashSet<PathBuf> = crate::cli::input::imported_files(file)
            .into_iter()
            .map(|f| std::path::absolute(&f).unwrap_or(f))
            .collect();
        for f in &files {
            let dir = parent(f);
            // (A directory that does not exist yet is looked for again after the next save.)
            if !self.dirs.contains(&dir) && dir.is_dir() {
                match self
                    .watcher
                    .watch(&dir, notify::RecursiveMode::NonRecursive)
                {
                    Ok(()) => {
                        self.dirs.insert(dir);
                    }
                    Err(e) => say!("cannot watch `{}`: {e}", dir.display()),
                }
            }
        }
        if let Ok(mut imports) = self.imports.lock() {
            *imports = files;
        }
    }
}

fn parent(file: &Path) -> PathBuf {
    file.parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."))
}

/// Starts watching `file` (and, through [`SceneWatcher::follow`], what it imports).
pub fn watch(
    file: &Path,
    report: impl Fn(Watched) + Send + 'static,
) -> notify::Result<SceneWatcher> {
    use notify::Watcher;
    let file = std::path::absolute(file).unwrap_or_else(|_| file.to_path_buf());
    let dir = parent(&file);
    let imports: Arc<Mutex<HashSet<PathBuf>>> = Arc::default();
    let followed = imports.clone();
    let target = file.clone();
    let mut watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
        let Ok(event) = event else { return };
        if event.kind.is_access() {
            return;
        }
        let ours = |p: &PathBuf| {
            let p = std::path::absolute(p).unwrap_or_else(|_| p.clone());
            p == target || followed.lock().is_ok_and(|f| f.contains(&p))
        };
        if event.paths.iter().any(ours) {
            let what = if target.exists() {
                Watched::Changed
            } else {
                Watched::Gone
            };
            report(what);
        }
    })?;
    watcher.watch(&dir, notify::RecursiveMode::NonRecursive)?;
    let mut w = SceneWatcher {
        watcher,
        dirs: HashSet::from([dir]),
        imports,
    };
    w.follow(&file);
    Ok(w)
}

/// `--watch` of `render` and `emit`: runs the command, then again after every save of `file`
/// (a burst of writes counts once), until interrupted; each run prints its own line or its
/// diagnostics. Returns only if the file cannot be watched.
pub fn watch_loop(file: &Path, mut run: impl FnMut() -> i32) -> i32 {
    let (tx, rx) = std::sync::mpsc::channel();
    let mut watcher = match watch(file, move |w| {
        let _ = tx.send(w);
    }) {
        Ok(w) => w,
        Err(e) => {
            say!("error: cannot watch `{}`: {e}", file.display());
            return 1;
        }
    };
    run();
    say!(
        "watching `{}`: every save runs the command again (Ctrl-C stops)",
        file.display()
    );
    loop {
        let Ok(event) = rx.recv() else { return 1 };
        if let Watched::Gone = event {
            say!(
                "`{}` was deleted or moved away; watching for it to come back",
                file.display()
            );
            continue;
        }
        // Let the burst of writes settle, then run once for all of it.
        std::thread::sleep(SETTLE);
        while rx.try_recv().is_ok() {}
        if file.exists() {
            run();
            watcher.follow(file);
        }
    }
}

/// A command once, or with `--watch` again after every save of `file` (not for standard input).
pub fn watching(file: &std::path::Path, watch: bool, mut once: impl FnMut() -> i32) -> i32 {
    if !watch {
        return once();
    }
    if file == std::path::Path::new("-") {
        say!("error: `--watch` needs a scene file, not standard input");
        return 1;
    }
    watch_loop(file, once)
}
