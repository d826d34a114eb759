//! The checks of the whole scene once its statements are checked: an absolute ε and the
//! scene's coordinates against what f32 resolves, and `bound auto` against an unbounded scene.

use super::Checker;
use super::settings::F32_RESOLUTION;
use crate::diag::Diagnostic;
use crate::scene::NodeId;

/// Image height the resolution warning assumes for a pixel's footprint.
const NOMINAL_LINES: f64 = 1080.0;
/// Coordinates above this overflow f32 when squared and summed (√(f32::MAX / 3) ≈ 1.06e19).
const F32_SQUARE_LIMIT: f64 = 1e19;

impl Checker<'_> {
    /// Warns when an absolute ε is below what f32 positions resolve at the camera's distance
    /// (the tracers then use that floor, `EPSILON_FLOOR`·|eye − target|).
    pub(super) fn check_epsilon(&mut self) {
        let Some((trace, span)) = &self.settings.trace else {
            return;
        };
        let crate::scene::Epsilon::Absolute(e) = trace.epsilon else {
            return;
        };
        let floor = self.settings.camera().epsilon_floor();
        if e < floor {
            self.diags.push(
                Diagnostic::warning(*span, format!("ε = {e} is below what f32 positions resolve at this camera distance"))
                    .label(format!("the tracers use ε = {floor:.3e} instead"))
                    .note("a hit threshold under about 1e-5 of the camera's distance to its target cannot be met in f32: rays would spend their budget at the surface"),
            );
        }
    }

    /// Warns when the scene's coordinates are larger than f32 resolves at its pixel footprint
    /// (positions round to more than a pixel of a 1080-line image at the camera's distance to
    /// its target), or so large that squared lengths overflow f32.
    pub(super) fn check_f32_range(&mut self, root: NodeId) {
        let camera = self.settings.camera();
        let b = self.nodes[root].bound;
        let scene_size = if b.radius.is_finite() {
            b.center.length() + b.radius
        } else {
            0.0
        };
        let camera_size = camera.eye.length().max(camera.target.length());
        let size = scene_size.max(camera_size);
        let ulp = size * F32_RESOLUTION;
        let footprint =
            (camera.eye - camera.target).length() * 2.0 * (camera.fov / 2.0).tan() / NOMINAL_LINES;
        let overflow = size > F32_SQUARE_LIMIT;
        // (No footprint: the camera is invalid, which is reported on its own.)
        if (ulp <= footprint || footprint <= 0.0) && !overflow {
            return;
        }
        let span = match self.settings.camera {
            Some((_, span)) if camera_size >= scene_size => span,
            _ => self.nodes[root].span,
        };
        let mut d = Diagnostic::warning(
            span,
            format!("coordinates reach {size:.3e}, beyond what f32 resolves here"),
        );
        d = if overflow {
            d.label(format!(
                "above {F32_SQUARE_LIMIT:.0e}, squared lengths overflow f32 on the GPU"
            ))
        } else {
            d.label(format!(
                "f32 rounds positions there to {ulp:.3e}, more than a pixel ({footprint:.3e}) at this camera distance"
            ))
        };
        self.diags.push(
            d.note("the GPU computes in f32: surfaces will be placed wrongly or missed")
                .help("model the scene near the origin, at a scale between about 1e-4 and 1e4"),
        );
    }

    /// Checks that `bound auto` has a finite sphere to use.
    pub(super) fn check_bound(&mut self, root: NodeId) {
        if let Some(((None, _), span)) = self.settings.bound
            && !self.nodes[root].bound.radius.is_finite()
        {
            self.diags.push(
                Diagnostic::error(span, "`bound auto` needs a bounded scene")
                    .label("the scene reaches infinity")
                    .note("an infinite surface (a plane, an infinite repetition) has no bounding sphere; give `bound sphere { .. }` or `bound box { .. }` to enclose the part to trace"),
            );
        }
    }
}
