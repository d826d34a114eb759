//! The CPU reference tracers in f64: every variant the shader can inline, with the same hit
//! conditions, fallbacks and evaluation counting, for checking the GPU and as ground truth.
//!
//! Each variant marches a one-dimensional function `f(t)` (the field along the ray), so the
//! same code traces scenes and the closed-form cases of the tests (the grazing plane).

mod careful;
mod variants;
pub use careful::{ByScene, CROSSING_REFINE, Confirm, ZONE_STEP, tetra_gradient};
use careful::{careful, confirmation};
pub use variants::hybrid_linear;
use variants::stop;

use crate::reference::eval;
use crate::scene::{Convex, Epsilon, Method, Scene, Trace};
use glam::DVec3;

/// Where a ray went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Traced {
    /// Distance along the ray where it stopped (the hit, or the selected candidate).
    pub t: f64,
    /// Evaluations of the field, all of them (failed relaxed steps and refinement included).
    pub steps: u32,
    /// Whether the ray is taken to have hit a surface.
    pub hit: bool,
    /// Whether the step budget ran out before the ray hit or left (a relaxed ray then still
    /// hits at its best candidate, Keinert §3.2).
    pub exhausted: bool,
    /// With cone anti-aliasing: where the ray passed closest to a surface in front of what it
    /// hit (the nearest approach of one near miss), and that surface's coverage of the pixel
    /// (0: none).
    pub cover_t: f64,
    /// The coverage α there (Munini §2.4), 0 to 1/2.
    pub cover: f64,
}

/// Hart's coverage of a pixel's cone section of radius r by a surface at distance d from its
/// centre (the disc area beyond a chord at d), as a function of q = d/r ∈ [0, 1]
/// (Munini §2.4): α = 1/2 − q·√(1 − q²)/π − asin(q)/π; 1/2 at q = 0, 0 at q = 1.
pub fn coverage(q: f64) -> f64 {
    let q = q.clamp(0.0, 1.0);
    0.5 - q * (1.0 - q * q).sqrt() / std::f64::consts::PI - q.asin() / std::f64::consts::PI
}

/// The cone radius for anti-aliasing at distance t: one pixel's width (Munini §2.4:
/// r = 2·tan(fov/2)/N_H · t, twice the half-pixel footprint).
pub const CONE_PIXELS: f64 = 2.0;

/// Smallest denominator of the enhanced step, relative to the previous step length: keeps the
/// inferred radius finite when the field grows as fast as the Lipschitz bound allows.
pub const ENHANCED_GUARD: f64 = 1e-5;

/// Relative margin of the overlap test of consecutive unbounding spheres (relaxed, enhanced,
/// auto): spheres whose gap is below this fraction of their radii, and below ε, count as
/// touching (see [`apart`]). On a plane the auto step makes consecutive spheres exactly
/// tangent, so without a margin rounding decides each fallback, differently in f32 and f64.
pub const TOUCH: f64 = 1e-5;

/// Whether the unbounding spheres of radii `r` and `rn`, `step` apart, fail to overlap: the gap
/// must exceed the [`TOUCH`] margin, which is kept below `eps` (ε at the tracer's current point:
/// where the step starts for enhanced and auto, where it ends for relaxed). A
/// margin relative to the radii alone let a step of 7·10⁵ leap a sphere of radius 1 (the
/// extremes suite, "leaving a wall head-on, ω = 1.99", enhanced).
pub fn apart(step: f64, r: f64, rn: f64, eps: f64) -> bool {
    let reach = r.abs() + rn.abs();
    step > reach + (TOUCH * reach).min(eps)
}

/// Largest over-relaxation the auto tracer infers (its ω = 2 / (1 − m) grows without bound as
/// the slope average m approaches 1, a ray leaving a surface head-on).
pub const AUTO_MAX_OMEGA: f64 = 1000.0;

/// The hit threshold ε(t): absolute, or the pixel footprint `pixel·t` kept above `floor`.
#[derive(Clone, Copy, Debug)]
pub struct Threshold {
    /// The scene's ε mode.
    pub epsilon: Epsilon,
    /// The pixel footprint per unit distance.
    pub pixel: f64,
    /// The smallest ε in pixel mode.
    pub floor: f64,
    /// Distance from the ray's origin of the point where the marched `t` is 0.
    pub offset: f64,
}

impl Threshold {
    /// The scene's threshold for a camera with pixel footprint `pixel`.
    pub fn new(scene: &Scene, trace: &Trace, pixel: f64) -> Threshold {
        Threshold {
            epsilon: trace.epsilon,
            pixel,
            floor: scene.camera.epsilon_floor(),
            offset: 0.0,
        }
    }

    /// ε at distance `t` (from where the march started).
    pub fn at(&self, t: f64) -> f64 {
        match self.epsilon {
            Epsilon::Pixel => (self.pixel * (t + self.offset)).max(self.floor),
            // Below the floor f32 positions cannot resolve the surface (the check warns).
            Epsilon::Absolute(e) => e.max(self.floor),
        }
    }
}

/// Traces `ro + t·rd` from t = 0 with an absolute hit threshold and no floor, ignoring the
/// scene's bound: for f64 references (the ground truth, the fine checks of the tests), which
/// resolve far below the f32 floor the shader's mirrors keep.
pub fn ray_exact(scene: &Scene, trace: &Trace, epsilon: f64, ro: DVec3, rd: DVec3) -> Traced {
    let eps = Threshold {
        epsilon: Epsilon::Absolute(epsilon),
        pixel: 0.0,
        floor: 0.0,
        offset: 0.0,
    };
    march(trace, &eps, |t| eval::distance(scene, ro + rd * t))
}

/// The part of a ray a trace searches, with its budget: the whole ray, the part inside a
/// convex bound, or what a multi-resolution pass leaves (mirrors `lower::march::Inputs`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Where the search starts.
    pub start: f64,
    /// Where it gives up.
    pub end: f64,
    /// Evaluations it may spend.
    pub budget: u32,
    /// Bálint's cone slope α (§4, Remark 1): the field is traced as F = (f − α·t)/(1 + α), so
    /// the trace stops before any surface enters the cone of radius α·t. 0: the ray itself.
    pub cone: f64,
}

impl Segment {
    /// The whole ray, `[0, max_distance]`, with the full budget.
    pub fn whole(trace: &Trace) -> Segment {
        Segment {
            start: 0.0,
            end: trace.max_distance,
            budget: trace.steps,
            cone: 0.0,
        }
    }
}

/// Traces the ray `ro + t·rd` through the scene with its chosen variant (inside its bound).
pub fn ray(scene: &Scene, trace: &Trace, ro: DVec3, rd: DVec3, pixel: f64) -> Traced {
    ray_segment(scene, trace, ro, rd, pixel, Segment::whole(trace))
}

/// Traces a segment of the ray `ro + t·rd`, clipped to the scene's bound if it has one.
pub fn ray_segment(
    scene: &Scene,
    trace: &Trace,
    ro: DVec3,
    rd: DVec3,
    pixel: f64,
    segment: Segment,
) -> Traced {
    let eps = Threshold::new(scene, trace, pixel);
    let f = |t| eval::distance(scene, ro + rd * t);
    match &scene.bound {
        None => march_segment(trace, &eps, segment, f, confirmation(scene, ro, rd)),
        Some(bound) => bounded(scene, trace, bound, &eps, (ro, rd), segment),
    }
}

/// Keinert §3.5: a ray is traced only inside the convex bound, from where it enters (case 1)
/// or from its start if that is inside (case 2); a ray missing the bound is culled (t stays at
/// the segment's start, no step spent). With `convex yes`, a start inside the object (one
/// evaluation finds out) is traced backwards from the bound's far side, so the hit is where
/// the ray leaves the object (case 3); ε is then measured from that far side. In a cone pass
/// such a ray stays where it is.
fn bounded(
    scene: &Scene,
    trace: &Trace,
    bound: &Convex,
    eps: &Threshold,
    (ro, rd): (DVec3, DVec3),
    segment: Segment,
) -> Traced {
    let culled = stop(segment.start, 0, false, false);
    let Some((near, far)) = bound.shape.interval(ro, rd) else {
        return culled;
    };
    let (lo, hi) = (near.max(segment.start), far.min(segment.end));
    if lo > hi {
        return culled;
    }
    let clipped = Segment {
        start: lo,
        end: hi,
        ..segment
    };
    let f = |t| eval::distance(scene, ro + rd * t);
    if !bound.convex || near > segment.start {
        return march_segment(trace, eps, clipped, f, confirmation(scene, ro, rd));
    }
    if f(lo) >= 0.0 {
        let mut r = march_segment(trace, eps, clipped, f, confirmation(scene, ro, rd));
        r.steps += 1;
        return r;
    }
    if segment.cone > 0.0 {
        return stop(segment.start, 1, false, false);
    }
    let exit = ro + rd * hi;
    let back = Segment {
        start: 0.0,
        end: hi - lo,
        ..segment
    };
    let eps_back = Threshold {
        offset: 0.0,
        ..*eps
    };
    let r = march_segment(
        trace,
        &eps_back,
        back,
        |s| eval::distance(scene, exit - rd * s),
        confirmation(scene, exit, -rd),
    );
    Traced {
        t: if r.hit { hi - r.t } else { lo },
        steps: r.steps + 1,
        hit: true,
        cover: 0.0,
        ..r
    }
}

/// Marches the segment of `f` with the variant of `trace`: t runs from 0 at `segment.start`,
/// ε and the cone are measured from the ray's origin.
pub fn march_segment(
    trace: &Trace,
    eps: &Threshold,
    segment: Segment,
    mut f: impl FnMut(f64) -> f64,
    confirm: Option<ByScene>,
) -> Traced {
    // Over a scene with loose parts the hybrid's linear step is capped in every pass, confirmed
    // or not (as the shader's, whose tracer knows the scene, not the pass).
    let inner = Trace {
        steps: segment.budget,
        max_distance: segment.end - segment.start,
        linear: variants::hybrid_linear(trace, confirm.is_some()),
        ..*trace
    };
    let shifted = Threshold {
        offset: eps.offset + segment.start,
        ..*eps
    };
    let alpha = segment.cone;
    // A coarse pass stops short of surfaces by design: nothing to confirm there.
    let confirm = confirm.filter(|_| alpha == 0.0).map(|c| ByScene {
        ro: c.ro + c.rd * segment.start,
        ..c
    });
    let mut r = march_confirmed(
        &inner,
        &shifted,
        |s| {
            let t = segment.start + s;
            let d = f(t);
            if alpha > 0.0 {
                (d - alpha * t) / (1.0 + alpha)
            } else {
                d
            }
        },
        confirm,
    );
    r.t += segment.start;
    r
}

/// Marches `f` (the field along a ray, already divided by its Lipschitz bound) with the
/// variant of `trace`, then applies discontinuity reduction if asked.
pub fn march(trace: &Trace, eps: &Threshold, f: impl FnMut(f64) -> f64) -> Traced {
    march_confirmed(trace, eps, f, None::<ByScene>)
}

/// [`march`], with each hit confirmed by [`careful`] when `confirm` is given.
pub fn march_confirmed(
    trace: &Trace,
    eps: &Threshold,
    mut f: impl FnMut(f64) -> f64,
    confirm: Option<impl Confirm>,
) -> Traced {
    let mut r = match trace.method {
        Method::Basic => variants::basic(trace, eps, &mut f),
        Method::Relaxed => variants::relaxed(trace, eps, &mut f),
        Method::Enhanced => variants::enhanced(trace, eps, &mut f),
        Method::Hybrid => variants::hybrid(trace, eps, &mut f),
        Method::Auto => variants::auto(trace, eps, &mut f),
    };
    if let Some(mut c) = confirm
        && r.hit
        && !r.exhausted
    {
        r = careful(trace, eps, r, &mut f, &mut c);
    }
    if r.hit {
        for _ in 0..trace.discontinuity {
            // Keinert §3.4, Eq. 3: t ← t + (f(t) − err(t)), towards the level set f = ε(t).
            let d = f(r.t);
            r.steps += 1;
            r.t = (r.t + d - eps.at(r.t)).max(0.0);
        }
    }
    r
}
