//! `sdfc check`: a scene's summary or its diagnostics, or the catalog (`--list`).

use crate::cli::input::{compile, print_out, read_source};
use crate::cli::{CheckArgs, messages};
use sdfc_compiler::check::Checked;
use sdfc_compiler::diag::Diagnostic;
use sdfc_compiler::lipschitz::{self, Effort};
use std::path::Path;

/// Runs `sdfc check`; returns the exit code.
pub fn run(args: &CheckArgs) -> i32 {
    if args.list {
        return print_out(&sdfc_compiler::docs::catalog_table())
            .err()
            .unwrap_or(0);
    }
    let Some(file) = &args.file else {
        say!("error: give a scene file to check (or `-` for standard input)");
        return 1;
    };
    let effort = if args.lipschitz {
        Effort::Thorough
    } else {
        Effort::Fast
    };
    check(file, effort)
}

/// Checks the scene at `path` with `effort` for its `@lipschitz` annotations; prints the
/// diagnostics and the summary.
fn check(path: &Path, effort: Effort) -> i32 {
    let (name, source) = match read_source(path) {
        Ok(x) => x,
        Err(e) => {
            say!("{e}");
            return 1;
        }
    };
    let Checked {
        scene,
        mut diagnostics,
        sources,
    } = compile((path, &name), &source, &std::collections::HashMap::new());
    if let Some(scene) = &scene {
        let found = lipschitz::verify_annotations(scene, effort);
        let none = std::collections::HashMap::new();
        let at = |v: &_| compile((path, &name), &source, v).scene;
        let more = lipschitz::verify_over_ranges(&at, scene, effort, (&none, &found));
        diagnostics.extend(found);
        diagnostics.extend(more);
    }
    say_raw!("{}", messages::report(&diagnostics, &sources));
    let Some(scene) = scene else { return 1 };
    let warnings = diagnostics
        .iter()
        .filter(|d| !Diagnostic::is_error(d))
        .count();
    let summary = sdfc_compiler::docs::summary(&name, &scene, warnings);
    let options = sdfc_compiler::lower::tracer::Options::from_scene(&scene);
    let predicted = match crate::cli::driver::compute_module(&scene, &options) {
        Ok((_, predicted)) => predicted,
        Err(e) => {
            say!("{e}");
            return 2;
        }
    };
    let compile = format!(
        "  driver compile: {} predicted on lavapipe (up to {})",
        crate::cli::driver::seconds(predicted.seconds),
        crate::cli::driver::seconds(predicted.at_most)
    );
    print_out(&format!("{summary}\n{compile}\n"))
        .err()
        .unwrap_or(0)
}
