//! What several commands share: writing their output, the progress bar, and the limit on the
//! shaders `render` and `bench` hand to the driver.

use crate::cli::{Error, write_file};
use sdfc_compiler::emit;
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
/// before writing: its folder exists. The error says which folder is missing.
pub fn writable(path: &Path) -> Result<(), String> {
    if path == Path::new("-") {
        return Ok(());
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

/// Most calls of distance functions in a shader `render` and `bench` hand to the driver
/// without `--allow-slow-compile`. Measured on lavapipe (a flat union of spheres at 32×18, the
/// driver's compile dominating): 256 calls 0.7 s, 1 024 5.9 s, 2 048 21.5 s, 4 096 113 s —
/// quadratic; 8 192 would take about 8 minutes. In `map` a shared `let` is one function and
/// costs little (4 096 evaluations through them: 2.4 s), but the material function writes its
/// body at each use; `sdfc emit` has no such limit.
pub const MAX_DRIVER_CALLS: usize = 4096;

/// Refuses, with the scene's span, a module too large for the driver to compile in
/// reasonable time (see [`MAX_DRIVER_CALLS`]); else its calls of distance functions.
pub fn check_driver_size(
    module: &naga::Module,
    (sources, scene): (
        &sdfc_compiler::source::Sources,
        &sdfc_compiler::scene::Scene,
    ),
    allow: bool,
) -> Result<usize, Error> {
    let calls = emit::distance_calls(module);
    if calls > MAX_DRIVER_CALLS && !allow {
        let d = sdfc_compiler::diag::Diagnostic::error(
            scene.root_node().span,
            "this scene's shader is too large for the GPU driver to compile in reasonable time",
        )
        .label(format!("its code calls distance functions {calls} times"))
        .note(format!(
            "sdfc renders at most {MAX_DRIVER_CALLS} calls: on lavapipe a flat union of 2 048 shapes took 21 s to compile and 4 096 took 113 s, growing quadratically"
        ))
        .help("share repeated shapes with `let` or `repeat`, or pass `--allow-slow-compile` to wait; `sdfc emit` writes the shader for other engines");
        say_raw!("{}", crate::cli::messages::report(&[d], sources));
        return Err(Error::Reported);
    }
    Ok(calls)
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
