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
    check(file, effort, args.bake.bake_res)
}

/// Checks the scene at `path` (every `bake` at `bake_res`, if given) with `effort` for its
/// `@lipschitz` annotations; prints the
/// diagnostics and the summary.
fn check(path: &Path, effort: Effort, bake_res: Option<u32>) -> i32 {
    let base = crate::cli::input::ParamArgs {
        bake_res,
        ..Default::default()
    }
    .base();
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
    } = compile((path, &name), &source, &base);
    if let Some(scene) = &scene {
        let at = |v: &std::collections::HashMap<String, Vec<f64>>| {
            let mut v = v.clone();
            v.extend(base.clone());
            compile((path, &name), &source, &v).scene
        };
        let none = std::collections::HashMap::new();
        diagnostics.extend(lipschitz::verify_everywhere(&at, scene, effort, &none));
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
