//! The five variants of the CPU reference, each marching `f(t)` from t = 0 (see [`super::march`]).

use super::{AUTO_MAX_OMEGA, CONE_PIXELS, ENHANCED_GUARD, Threshold, Traced, apart, coverage};
use crate::scene::Trace;

/// A finished march at `t` after `steps` evaluations.
pub(super) fn stop(t: f64, steps: u32, hit: bool, exhausted: bool) -> Traced {
    Traced {
        t,
        steps,
        hit,
        exhausted,
        cover_t: 0.0,
        cover: 0.0,
    }
}

/// Hart's cone anti-aliasing bookkeeping (Munini §2.4): each run of consecutive steps where
/// the field is within the cone radius (d ≤ r) is one near miss, counted once at its
/// smallest d/r; a run still open when the ray hits is the hit surface's own approach and is
/// not counted. The near miss with the largest coverage is kept.
#[derive(Clone, Copy, Debug)]
struct Cone {
    best: (f64, f64),
    run: Option<(f64, f64)>,
}

impl Cone {
    fn new() -> Cone {
        Cone {
            best: (0.0, 0.0),
            run: None,
        }
    }

    /// Records the field d at t (cone radius r).
    fn see(&mut self, t: f64, d: f64, r: f64) {
        if d <= r {
            let q = d / r;
            if self.run.is_none_or(|(_, best)| q < best) {
                self.run = Some((t, q));
            }
        } else {
            self.close();
        }
    }

    /// Ends the current run, keeping it if it covers more than the best so far.
    fn close(&mut self) {
        if let Some((t, q)) = self.run.take() {
            let a = coverage(q);
            if a > self.best.1 {
                self.best = (t, a);
            }
        }
    }

    fn into(mut self, mut r: Traced) -> Traced {
        if !r.hit {
            self.close();
        }
        (r.cover_t, r.cover) = self.best;
        r
    }
}

/// Basic sphere tracing (Hart; Bálint Alg. 1; Munini Fig. 9): t += f until f < ε(t),
/// t > t_max or the budget runs out.
/// With `antialias cone`, also Hart's cone anti-aliasing (Munini §2.4, see [`Cone`]); the
/// offset of a segment's t is added back so it reports distances from the ray's origin.
pub(super) fn basic(trace: &Trace, eps: &Threshold, f: &mut impl FnMut(f64) -> f64) -> Traced {
    let mut t = 0.0;
    let mut steps = 0;
    let mut cone = Cone::new();
    let result = loop {
        if steps >= trace.steps {
            break stop(t, steps, false, true);
        }
        let d = f(t);
        steps += 1;
        if d < eps.at(t) {
            break stop(t, steps, true, false);
        }
        if trace.antialias {
            let at = t + eps.offset;
            cone.see(at, d, CONE_PIXELS * eps.pixel * at);
        }
        t += d;
        if t > trace.max_distance {
            break stop(t, steps, false, false);
        }
    };
    cone.into(result)
}

/// Over-relaxed sphere tracing as in Keinert §3.1–3.2, Listing 2: steps of ω·f. When two
/// consecutive unbounding spheres stop overlapping, with `fallback reset` (the default) the
/// step is taken back by the listing's `step −= ω·step` and ω drops to 1 for the rest of the
/// ray; with `fallback keep` the ray goes back to the last safe point t₋ + r₋ and keeps ω, as
/// Bálint & Valasek's Algorithm 2 does (its re-evaluation there is the next iteration's). The
/// candidate with the smallest f/ε(t) (f/t in pixel mode: radius in screen space) is the hit
/// if the budget runs out.
pub(super) fn relaxed(trace: &Trace, eps: &Threshold, f: &mut impl FnMut(f64) -> f64) -> Traced {
    let mut omega = trace.omega;
    let (mut t, mut step, mut prev_radius) = (0.0, 0.0, 0.0);
    // The field at the last point whose step stood (signed: the safe point is t₋ + r₋).
    let mut prev_r = 0.0;
    let (mut candidate_t, mut candidate_error) = (0.0, f64::INFINITY);
    let mut steps = 0;
    loop {
        if steps >= trace.steps {
            // The first evaluation always makes a candidate, and the budget is at least 1.
            return stop(candidate_t, steps, true, true);
        }
        let r = f(t);
        steps += 1;
        let radius = r.abs();
        let fail = omega > 1.0 && apart(step, radius, prev_radius, eps.at(t));
        if fail && trace.keep_relaxation {
            // Back to t₋ + r₋: inside the last sphere, so the next point needs no test.
            step = prev_r - step;
        } else if fail {
            step -= omega * step;
            omega = 1.0;
            prev_radius = radius;
        } else {
            step = r * omega;
            prev_radius = radius;
            prev_r = r;
        }
        if !fail {
            let e = eps.at(t);
            if radius / e < candidate_error {
                candidate_t = t;
                candidate_error = radius / e;
            }
            // Listing 2 tests |r|: a point an over-relaxed step put inside a surface (its
            // spheres still overlapped) is left by the negative step r·ω; only at the start of
            // the ray, where there is no way back, does r < 0 count as the hit.
            if radius < e || (r < 0.0 && t <= 0.0) {
                return stop(t, steps, true, false);
            }
            if t > trace.max_distance {
                return stop(t, steps, false, false);
            }
        }
        step = step.max(-t);
        t += step;
    }
}

/// Enhanced (planar) sphere tracing, Bálint Alg. 3: the next radius is inferred from the last
/// two as if the surface were a plane, r·(d − r₋ + r)/(d + r₋ − r), scaled by ω; if the new
/// unbounding sphere does not overlap the current one the step is not taken and the next one
/// is a plain sphere-tracing step (the failed evaluation counts).
pub(super) fn enhanced(trace: &Trace, eps: &Threshold, f: &mut impl FnMut(f64) -> f64) -> Traced {
    let (mut t, mut d, mut r_prev, mut r) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    let mut steps = 0;
    loop {
        if steps >= trace.steps {
            return stop(t, steps, false, true);
        }
        let dn = if d == 0.0 {
            r
        } else {
            let den = (d + r_prev - r).max(ENHANCED_GUARD * d);
            r + trace.omega * r * (d - r_prev + r) / den
        };
        let rn = f(t + dn);
        steps += 1;
        if apart(dn, r, rn, eps.at(t)) {
            d = 0.0;
            continue;
        }
        t += dn;
        d = dn;
        r_prev = r;
        r = rn;
        if r < eps.at(t) {
            return stop(t, steps, true, false);
        }
        if t > trace.max_distance {
            return stop(t, steps, false, false);
        }
    }
}

/// Auto-relaxed sphere tracing (Bán & Valasek 2023): the slope m of f along the ray is kept
/// as a moving average with weight β, the step is f·ω with ω = 2/(1 − m) (at least 1), and a
/// step whose unbounding spheres do not overlap is taken back with m reset to −1.
pub(super) fn auto(trace: &Trace, eps: &Threshold, f: &mut impl FnMut(f64) -> f64) -> Traced {
    let mut t = 0.0;
    let mut r = f(t);
    let mut steps = 1;
    let mut z = r;
    let mut m = -1.0;
    loop {
        if r < eps.at(t) {
            return stop(t, steps, true, false);
        }
        if t > trace.max_distance {
            return stop(t, steps, false, false);
        }
        if steps >= trace.steps {
            return stop(t, steps, false, true);
        }
        let tn = t + z;
        let rn = f(tn);
        steps += 1;
        let back = apart(z, r, rn, eps.at(t));
        let slope = (rn - r) / z;
        if back {
            m = -1.0;
        } else {
            m += trace.beta * (slope - m);
            t = tn;
            r = rn;
        }
        let omega = (2.0 / (1.0 - m).max(2.0 / AUTO_MAX_OMEGA)).max(1.0);
        z = (r * omega).max(eps.at(t));
    }
}

/// The hybrid's linear step in units of ε(t): `trace.linear`, but at most the careful march's
/// [`super::ZONE_STEP`] in a scene with loose parts (`loose`): a fixed step longer than the
/// sphere step can hop over a loose part thinner than it before the hit test f < ε ever sees
/// it (a 0.01-thick ellipsoid disc lost 2.5% of its pixels in bands with `linear` 4), where the
/// careful march guarantees parts down to ε/4.
pub fn hybrid_linear(trace: &Trace, loose: bool) -> f64 {
    if loose {
        trace.linear.min(super::ZONE_STEP)
    } else {
        trace.linear
    }
}

/// Sphere tracing / linear search hybrid, Liktor §5.4: sphere steps while f is above
/// `linear`·ε(t), fixed steps of that length below it (longer than sphere steps near the
/// surface; see [`hybrid_linear`] for a scene with loose parts), a hit when f < ε(t); when a
/// step lands inside (f < 0) the crossing is refined by a fixed number of regula falsi
/// iterations between the last outside and the inside point.
pub(super) fn hybrid(trace: &Trace, eps: &Threshold, f: &mut impl FnMut(f64) -> f64) -> Traced {
    let (mut t, mut t_out, mut f_out) = (0.0, 0.0, 0.0);
    let mut steps = 0;
    loop {
        if steps >= trace.steps {
            return stop(t, steps, false, true);
        }
        let d = f(t);
        steps += 1;
        if d < 0.0 && steps > 1 {
            let root = regula_falsi(f, (t_out, f_out), (t, d), trace.refine, &mut steps);
            return stop(root, steps, true, false);
        }
        let e = eps.at(t);
        if d < e {
            return stop(t, steps, true, false);
        }
        if t >= trace.max_distance {
            return stop(t, steps, false, false);
        }
        (t_out, f_out) = (t, d);
        // The last step is clamped to t_max so that a long linear step cannot skip the end of
        // the ray, where ε(t) is largest.
        t = (t + d.max(trace.linear * e)).min(trace.max_distance);
    }
}

/// The crossing between an outside point (a, f(a) > 0) and an inside one (c, f(c) ≤ 0) after
/// `iterations` regula falsi steps, each an evaluation counted in `steps`.
pub(super) fn regula_falsi(
    f: &mut impl FnMut(f64) -> f64,
    (mut a, mut fa): (f64, f64),
    (mut c, mut fc): (f64, f64),
    iterations: u32,
    steps: &mut u32,
) -> f64 {
    for _ in 0..iterations {
        let tm = a + (c - a) * fa / (fa - fc);
        let fm = f(tm);
        *steps += 1;
        if fm > 0.0 {
            (a, fa) = (tm, fm);
        } else {
            (c, fc) = (tm, fm);
        }
    }
    a + (c - a) * fa / (fa - fc)
}
