//! Whether rays can arrive within their step budget: an annotation far above the field's slope
//! makes every step of f/λ that many times too short (Hart's sphere tracing converges in about
//! λ/|∇f|·ln(1/ε) steps near a surface), so the budget runs out before any surface is reached
//! and the picture is blank (issue 31: λ from 2.4·10³ to 10¹⁸ accepted silently).

use crate::diag::Diagnostic;
use crate::scene::{Epsilon, NodeId, Scene};

/// Slope ratios below this are never reported: a bound a few times loose costs steps, not the
/// picture.
const LOOSE: f64 = 4.0;

/// The relative hit threshold rays must reach: ε over the far distance, or one pixel of a
/// 720-line image for ε `pixel`.
fn relative_epsilon(scene: &Scene) -> f64 {
    match scene.trace.epsilon {
        Epsilon::Absolute(e) => (e / scene.trace.max_distance).clamp(1e-12, 0.5),
        Epsilon::Pixel => ((scene.camera.fov / 2.0).tan() / 720.0).clamp(1e-12, 0.5),
    }
}

/// A warning when the node `id`'s bound λ is so far above `slope` (the steepest slope sampled
/// where rays go) that rays near it need more steps than the budget. `proven`: an interval
/// bound on the slope over that region (an `implicit`), which a smaller annotation it suggests
/// must not go below: sampling may have missed a thin steep part.
pub fn too_loose(scene: &Scene, id: NodeId, slope: f64, proven: Option<f64>) -> Option<Diagnostic> {
    let node = &scene.nodes[id];
    let ratio = node.lambda / slope;
    if !(slope > 0.0 && ratio.is_finite() && ratio > LOOSE) {
        return None;
    }
    let per_fold = (1.0 / relative_epsilon(scene)).ln().max(1.0);
    let needed = ratio * per_fold;
    let budget = f64::from(scene.trace.steps);
    if needed <= budget {
        return None;
    }
    let d = Diagnostic::warning(
        node.span,
        "this Lipschitz bound is so large that rays cannot arrive within their step budget",
    )
    .label(format!(
        "λ {} is {}× the steepest slope sampled, {}",
        short(node.lambda),
        short(ratio),
        short(slope)
    ))
    .note(format!(
        "each step is f/λ: near it a ray needs about {} steps to reach ε, and the budget is {}",
        short(needed.ceil()),
        scene.trace.steps
    ));
    let steps = short(needed.ceil());
    let d = match proven.filter(|b| b.is_finite()) {
        // Proven below the annotation: that bound is safe.
        Some(b) if b < node.lambda => d.help(format!(
            "annotate the interval bound where rays go, `@lipschitz({})`, or raise `steps` above {steps}",
            short(b * 1.001)
        )),
        // The region may be as steep as the annotation somewhere sampling did not see.
        Some(b) => d.help(format!(
            "raise `steps` above {steps}; the interval bound where rays go is {}, so a smaller annotation is not proven",
            short(b)
        )),
        None => d.help(format!(
            "raise `steps` above {steps}, or, if the field is nowhere steeper than sampled, annotate `@lipschitz({})`",
            short(slope * 1.1)
        )),
    };
    Some(super::with_call(node, d))
}

/// A number printed with three significant digits, in e-notation from 10⁵.
fn short(x: f64) -> String {
    if !x.is_finite() || x.abs() >= 1e5 {
        return format!("{x:.2e}");
    }
    let digits = (2 - x.abs().max(1e-300).log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{x:.digits$}");
    match s.contains('.') {
        true => s.trim_end_matches('0').trim_end_matches('.').to_string(),
        false => s,
    }
}
