//! The limit on the GPU driver's compile: the module `render`, `bench` and `view` hand it.

use crate::cli::Error;
use sdfc_compiler::cost::{self, Predicted};
use sdfc_compiler::emit;

/// The scene's compute module for `render`, `bench` and `view`, in a form the driver compiles in
/// reasonable time (`sdfc_compiler::cost`): as `options` ask; else, when the default box trees
/// are what makes it too slow, without them (said in a note); else refused at once with the
/// scene's span and the predicted time, unless `allow` (`--allow-slow-compile`).
pub fn driver_module(
    scene: &sdfc_compiler::scene::Scene,
    sources: &sdfc_compiler::source::Sources,
    options: &mut sdfc_compiler::lower::tracer::Options,
    allow: bool,
) -> Result<(naga::Module, Predicted), Error> {
    use sdfc_compiler::lower::tracer::BoundingVolumes;
    let compile = |o: &sdfc_compiler::lower::tracer::Options| compute_module(scene, o);
    let (module, predicted) = compile(options)?;
    if !predicted.too_slow() || allow {
        return Ok((module, predicted));
    }
    if options.bounding_volumes == BoundingVolumes::Large {
        let plain = sdfc_compiler::lower::tracer::Options {
            bounding_volumes: BoundingVolumes::Off,
            ..*options
        };
        let (m, p) = compile(&plain)?;
        if !p.too_slow() {
            say!(
                "note: the unions' box trees are left out: with them the driver would take up to {} to compile the shader, without them up to {} (`--bvh` keeps them, with `--allow-slow-compile`)",
                seconds(predicted.at_most),
                seconds(p.at_most)
            );
            *options = plain;
            return Ok((m, p));
        }
    }
    let d = sdfc_compiler::diag::Diagnostic::error(
        scene.root_node().span,
        "this scene's shader is too large for the GPU driver to compile in reasonable time",
    )
    .label(format!(
        "predicted compile: {} on lavapipe, up to {}",
        seconds(predicted.seconds),
        seconds(predicted.at_most)
    ))
    .note(format!(
        "sdfc hands the driver shaders predicted to compile within {} (its model of lavapipe's compile time: docs/stability.md)",
        seconds(cost::MAX_COMPILE_SECONDS)
    ))
    .help("share repeated shapes with `let` or `repeat`, draw the scene as data (`--form data`, for unions, intersections and cuts of primitives), or pass `--allow-slow-compile` to wait; `sdfc emit` writes the shader for other engines");
    say_raw!("{}", crate::cli::messages::report(&[d], sources));
    Err(Error::Reported)
}

/// The scene's compute module (what `render` draws with) for `options`, and the driver's
/// compile predicted for it.
pub fn compute_module(
    scene: &sdfc_compiler::scene::Scene,
    options: &sdfc_compiler::lower::tracer::Options,
) -> Result<(naga::Module, Predicted), Error> {
    let (module, _) = emit::module(scene, sdfc_compiler::lower::Entry::Compute, options)
        .map_err(|e| Error::Compiler(e.0))?;
    let predicted = cost::predict_module(&module);
    Ok((module, predicted))
}

/// Seconds as a person reads them: `0.4 s`, `12 s`, `3 min`, `2.5 h`.
pub fn seconds(s: f64) -> String {
    if s < 1.0 {
        format!("{s:.1} s")
    } else if s < 120.0 {
        format!("{s:.0} s")
    } else if s < 7200.0 {
        format!("{:.0} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}
