//! The confirmation of hits where f/λ is not a distance to first order (a loose λ): the
//! reference for `lower::careful`, step for step.

use super::variants::{regula_falsi, stop};
use super::{Threshold, Traced};
use crate::reference::eval;
use crate::scene::{Scene, Trace};
use glam::DVec3;

/// What [`careful`] asks of the scene at a point of the ray.
pub trait Confirm {
    /// Whether the part nearest the point at `t` is loose (`eval::loose`; one evaluation).
    fn loose(&mut self, t: f64) -> bool;
}

/// [`Confirm`] for a scene along the ray `ro + t·rd`.
#[derive(Clone, Copy)]
pub struct ByScene<'s> {
    pub(super) scene: &'s Scene,
    /// Where t = 0.
    pub(super) ro: DVec3,
    /// The direction (unit).
    pub(super) rd: DVec3,
}

impl Confirm for ByScene<'_> {
    fn loose(&mut self, t: f64) -> bool {
        eval::loose(self.scene, self.ro + self.rd * t)
    }
}

/// The hit confirmation of [`careful`] for a scene whose field is not a distance to first order
/// everywhere (`Node::unit_gradient` of its root).
pub(super) fn confirmation(scene: &Scene, ro: DVec3, rd: DVec3) -> Option<ByScene<'_>> {
    (!scene.root_node().unit_gradient).then_some(ByScene { scene, ro, rd })
}

/// The step across a zone of f < ε(t) over a loose part, as a fraction of ε(t) (at least f):
/// small enough to land inside a part a quarter of ε thick (the tests' thin ellipsoid and bent
/// slab: 0.5 left holes wider than a pixel), large enough to cross a zone (λ/|∇f|)·ε wide in
/// 4·λ/|∇f| steps.
pub const ZONE_STEP: f64 = 0.25;

/// Regula falsi iterations that place a crossing [`careful`] finds.
pub const CROSSING_REFINE: u32 = 2;

/// Confirms a hit where f/λ is not a distance to first order (a loose λ: a non-uniform scale,
/// a twist, a blend, an annotation…), so that a loose λ does not fatten silhouettes: the hit
/// test f < ε(t) accepts points up to (λ/|∇f|)·ε from the surface, and for fields like the thin
/// ellipsoid's, points far from any surface (its field is small all along the plane of the
/// disc). Where the part nearest the variant's hit is not loose (`eval::loose`, one
/// evaluation), the hit stands. Otherwise the march goes on as basic sphere tracing in which a
/// zone of f < ε(t) is crossed in steps of max(f, ε(t)/4) until the field turns negative — a crossing,
/// placed by [`CROSSING_REFINE`] regula falsi steps, is the hit — or rises above ε again (sphere
/// tracing resumes; on entering the next zone, a part that is not loose is a hit at once).
/// Only crossings count over loose parts, as for the f64 truth; a part thinner than ε(t)/4 can be
/// stepped over there (Liktor's fixed-step trade). The same on the GPU (`lower::careful`).
pub(super) fn careful(
    trace: &Trace,
    eps: &Threshold,
    found: Traced,
    f: &mut impl FnMut(f64) -> f64,
    confirm: &mut impl Confirm,
) -> Traced {
    let (mut t, mut steps) = (found.t, found.steps);
    // Where the nearest part is not loose, f/λ is the distance: the variant's hit stands.
    steps += 1;
    if !confirm.loose(t) {
        return stop(t, steps, true, false);
    }
    // (Known loose at the variant's hit: the first zone needs no second look.)
    let mut fresh = true;
    let mut in_zone = false;
    let (mut t_out, mut d_out) = (0.0, -1.0);
    loop {
        if steps >= trace.steps {
            return stop(t, steps, false, true);
        }
        let d = f(t);
        steps += 1;
        // On or inside the surface (a zero is a hit too: it would leave regula falsi 0/0).
        if d <= 0.0 {
            if d_out >= 0.0 {
                t = regula_falsi(f, (t_out, d_out), (t, d), CROSSING_REFINE, &mut steps);
            }
            return stop(t, steps, true, false);
        }
        let e = eps.at(t);
        let step = if d < e {
            if !in_zone && !fresh {
                steps += 1;
                if !confirm.loose(t) {
                    return stop(t, steps, true, false);
                }
            }
            in_zone = true;
            d.max(ZONE_STEP * e)
        } else {
            in_zone = false;
            d
        };
        fresh = false;
        (t_out, d_out) = (t, d);
        t += step;
        if t > trace.max_distance {
            return stop(t, steps, false, false);
        }
    }
}

/// |∇f| at `p` by tetrahedral differences of step `h` (four evaluations).
pub fn tetra_gradient(f: impl Fn(DVec3) -> f64, p: DVec3, h: f64) -> f64 {
    let k = [
        DVec3::new(1.0, -1.0, -1.0),
        DVec3::new(-1.0, -1.0, 1.0),
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, 1.0),
    ];
    let g: DVec3 = k.iter().map(|&k| k * f(p + k * h)).sum();
    (g / (4.0 * h)).length()
}
