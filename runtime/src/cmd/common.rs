//! What several commands share: writing their output and the progress bar.

use crate::cli::write_file;
use std::io::{IsTerminal, Write};
use std::path::Path;

/// Writes a command's output: to standard output without a path or for `-` (binary output
/// refused on a terminal; a closed pipe is not an error), else the whole file; the exit code.
pub fn write_output(path: Option<&Path>, bytes: &[u8], binary: bool) -> i32 {
    match path.filter(|p| *p != Path::new("-")) {
        Some(path) => write_whole(path, bytes),
        None => {
            if binary && std::io::stdout().is_terminal() {
                say!("error: the output is binary; write it to a file with `-o FILE`");
                return 1;
            }
            let mut stdout = std::io::stdout().lock();
            match stdout.write_all(bytes).and_then(|_| stdout.flush()) {
                Ok(()) => 0,
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => 0,
                Err(e) => {
                    say!("error: cannot write to standard output: {e}");
                    1
                }
            }
        }
    }
}

/// Whether `path` (a file, or `-` for standard output) can be written as far as can be known
/// before writing: its folder exists, and it is not a folder itself. The error says which.
pub fn writable(path: &Path) -> Result<(), String> {
    if path == Path::new("-") {
        return Ok(());
    }
    if path.is_dir() {
        return Err(format!(
            "error: cannot write `{}`: it is a folder",
            path.display()
        ));
    }
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(format!(
            "error: cannot write `{}`: the folder `{}` does not exist",
            path.display(),
            dir.display()
        )),
        _ => Ok(()),
    }
}

/// Writes a whole file, printing the error; the exit code.
pub fn write_whole(path: &Path, bytes: &[u8]) -> i32 {
    match write_file(path, bytes) {
        Ok(()) => 0,
        Err(e) => {
            say!("{e}");
            1
        }
    }
}

/// A progress bar on standard error, only when it is a terminal.
pub fn progress_bar(what: &str) -> Option<indicatif::ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = indicatif::ProgressBar::new(1);
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{{spinner}} {what} {{pos}}/{{len}} {{wide_bar}} {{elapsed}} {{msg}}"
        ))
        .ok()?,
    );
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    Some(bar)
}
