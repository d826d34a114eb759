//! The f32 range of `implicit` fields where rays reach: a part whose value may pass ±3.4e38
//! there is an error (the shader would compute an infinity, and NaN from it).

use super::Checker;
use crate::catalog::traits::Motion;
use crate::diag::Diagnostic;
use crate::interval::Interval;
use crate::scene::{NodeId, NodeKind};

impl Checker<'_> {
    /// Walks the scene from `root` with the radius about the origin that rays can reach — the
    /// eye's distance from the origin plus `max_distance` — carried into each node's own
    /// coordinates (a move adds its length, a scale divides by its smallest factor; turns,
    /// mirrors, repeats and the other domain operations keep a point no farther out, or are
    /// taken so), and checks every `implicit` over the box of that radius.
    pub(super) fn check_implicit_overflow(&mut self, root: NodeId) {
        let camera = self.settings.camera();
        let far = self.settings.trace.as_ref().map_or_else(
            || super::tracer::default_trace().max_distance,
            |(t, _)| t.max_distance,
        );
        let reach = camera.eye.length() + far;
        let mut stack = vec![(root, reach)];
        let mut seen = std::collections::HashSet::new();
        while let Some((n, r)) = stack.pop() {
            if !seen.insert((n, r.to_bits())) {
                continue;
            }
            match &self.nodes[n].kind {
                NodeKind::Implicit { field } => {
                    let region = [Interval::new(-r, r); 3];
                    if let Some((what, v)) = crate::lipschitz::may_overflow(field, &region) {
                        let span = self.nodes[n].span;
                        let d = Diagnostic::error(span, format!("{what} in this field may pass f32's range where rays reach"))
                            .label(format!("it ranges over [{:.3e}, {:.3e}] for |x|, |y|, |z| ≤ {r:.4}", v.lo, v.hi))
                            .note("the GPU computes in f32 (at most about ±3.4e38): past it the value is infinite, and NaN where infinities meet, so the picture is wrong there")
                            .help("keep it in range where rays go (e.g. `exp(min(a, 80))`), or bring the camera and `max_distance` closer");
                        let d = self.with_call_site(d, n);
                        self.diags.push(d);
                    }
                }
                NodeKind::Primitive { .. } => {}
                NodeKind::Operator { op, ctx, children } => {
                    let inner = match op.traits.motion {
                        Motion::Move => r + ctx.vec(0).length(),
                        Motion::Scale => r / ctx.vec(0).abs().min_element().max(f64::MIN_POSITIVE),
                        Motion::Turn | Motion::None => r,
                    };
                    stack.extend(children.iter().map(|&c| (c, inner)));
                }
            }
        }
    }
}
