//! The tracing variants' loop bodies in IR, one function per variant, each the same step for
//! step as its CPU reference in `crate::reference::trace` (whose doc comments cite the seeds).

use super::march::{Cx, EXHAUSTED, HIT, is_hit, var};
use crate::ir::builder::{Ex, FnBuilder};
use crate::reference::trace::{AUTO_MAX_OMEGA, CONE_PIXELS, ENHANCED_GUARD};
use crate::scene::Method;
use naga::BinaryOperator as B;

/// The chosen variant's loop, then discontinuity reduction if asked.
pub(super) fn body(b: &mut FnBuilder, cx: &Cx) {
    match cx.trace.method {
        Method::Basic => basic(b, cx),
        Method::Relaxed => relaxed(b, cx),
        Method::Enhanced => enhanced(b, cx),
        Method::Hybrid => super::hybrid::hybrid(b, cx),
        Method::Auto => auto(b, cx),
    }
    if let Some(loose) = cx.loose {
        super::careful::careful(b, cx, loose);
    }
    if cx.trace.discontinuity > 0 {
        discontinuity(b, cx);
    }
}

/// Hart; Bálint Alg. 1; Munini Fig. 9, with cone anti-aliasing if asked (Munini §2.4; see
/// `crate::reference::trace::basic` and `Cone`).
fn basic(b: &mut FnBuilder, cx: &Cx) {
    // The open run of near misses: its nearest t and d/r (−1: none open).
    let run = cx
        .cover
        .map(|_| (var(b, "run_t", 0.0), var(b, "run_q", -1.0)));
    b.loop_(|b| {
        cx.budget(b, EXHAUSTED, |_| {});
        let (t, d) = cx.here(b, "d");
        let e = cx.eps(b, t);
        let close = b.lt(d, e);
        cx.stop_if(b, close, HIT);
        if let (Some(run), Some(pixel)) = (run, cx.pixel()) {
            let at = cx.absolute(b, t);
            let k = b.f(CONE_PIXELS);
            let r = b.mul(k, pixel);
            let r = b.mul(r, at);
            let near = b.bin(B::LessEqual, d, r);
            b.if_(
                near,
                |b| {
                    let q = b.div(d, r);
                    let rq = b.load(run.1);
                    let zero = b.f(0.0);
                    let none = b.lt(rq, zero);
                    let closer = b.lt(q, rq);
                    let better = b.bin(B::LogicalOr, none, closer);
                    b.if_(
                        better,
                        |b| {
                            b.store(run.0, at);
                            b.store(run.1, q);
                        },
                        |_| {},
                    );
                },
                |b| close_run(b, cx, run),
            );
        }
        let nt = cx.advance(b, t, d);
        let far = cx.far(b);
        let gone = b.gt(nt, far);
        cx.stop_if(b, gone, 0);
    });
    if let Some(run) = run {
        // A run still open at a hit is the hit surface's own approach.
        let fl = b.load(cx.flags);
        let hit = is_hit(b, fl);
        b.if_(hit, |_| {}, |b| close_run(b, cx, run));
    }
}

/// Ends the open run of near misses, keeping it if it covers more than the best so far.
fn close_run(b: &mut FnBuilder, cx: &Cx, (run_t, run_q): (Ex, Ex)) {
    let Some((best_t, best)) = cx.cover else {
        return;
    };
    let q = b.load(run_q);
    let zero = b.f(0.0);
    let open = b.ge(q, zero);
    b.if_(
        open,
        |b| {
            let a = coverage(b, q);
            let prev = b.load(best);
            let more = b.gt(a, prev);
            b.if_(
                more,
                |b| {
                    let t = b.load(run_t);
                    b.store(best_t, t);
                    b.store(best, a);
                },
                |_| {},
            );
            let none = b.f(-1.0);
            b.store(run_q, none);
        },
        |_| {},
    );
}

/// Hart's coverage α(q) (see `crate::reference::trace::coverage`).
fn coverage(b: &mut FnBuilder, q: Ex) -> Ex {
    let zero = b.f(0.0);
    let one = b.f(1.0);
    let q = b.clamp(q, zero, one);
    let qq = b.mul(q, q);
    let rest = b.sub(one, qq);
    let root = b.sqrt(rest);
    let chord = b.mul(q, root);
    let arc = b.math(naga::MathFunction::Asin, &[q]);
    let sum = b.add(chord, arc);
    let inv_pi = b.f(std::f64::consts::FRAC_1_PI);
    let sum = b.mul(sum, inv_pi);
    let half = b.f(0.5);
    b.sub(half, sum)
}

/// Keinert §3.1–3.2, Listing 2 (see `crate::reference::trace::relaxed`).
fn relaxed(b: &mut FnBuilder, cx: &Cx) {
    let omega = var(b, "omega", cx.trace.omega);
    let step = var(b, "step", 0.0);
    let prev_radius = var(b, "prev_radius", 0.0);
    // `fallback keep`: the field where the last step stood (the safe point is t₋ + r₋).
    let keep = cx.trace.keep_relaxation;
    let prev_r = keep.then(|| var(b, "prev_r", 0.0));
    let candidate_t = var(b, "candidate_t", 0.0);
    // −1: no candidate yet (the first evaluation always makes one, so a ray whose budget runs
    // out has a candidate).
    let candidate_error = var(b, "candidate_error", -1.0);
    let candidate = (candidate_t, candidate_error);
    let vars = Relaxation {
        omega,
        step,
        prev_radius,
        prev_r,
    };
    b.loop_(|b| {
        cx.budget(b, EXHAUSTED | HIT, |b| {
            // The best candidate is the hit (Keinert §3.2).
            let ct = b.load(candidate_t);
            b.store(cx.t, ct);
        });
        let (t, r) = cx.here(b, "r");
        let radius = b.abs(r);
        let (fail, new_step, e) = vars.step(b, cx, (t, r, radius));
        let ok = b.expr(naga::Expression::Unary {
            op: naga::UnaryOperator::LogicalNot,
            expr: fail,
        });
        b.if_(
            ok,
            |b| candidate_or_stop(b, cx, candidate, (t, r, radius, e)),
            |_| {},
        );
        let back = b.neg(t);
        let new_step = b.max(new_step, back);
        b.store(step, new_step);
        cx.advance(b, t, new_step);
    });
}

/// The variables of relaxed sphere tracing's step: ω, the last step, the last radius, and with
/// `fallback keep` the last field value.
struct Relaxation {
    omega: Ex,
    step: Ex,
    prev_radius: Ex,
    prev_r: Option<Ex>,
}

impl Relaxation {
    /// The relaxed step from t (field `r`, `radius` = |r|) — back to the safe point where the
    /// unbounding spheres fail to overlap, else ahead by ω·r — stored in `step`: (whether it
    /// failed, the step, ε at t).
    fn step(&self, b: &mut FnBuilder, cx: &Cx, (t, r, radius): (Ex, Ex, Ex)) -> (Ex, Ex, Ex) {
        let (omega, step, prev_radius) = (self.omega, self.step, self.prev_radius);
        let (om, st, pr) = (b.load(omega), b.load(step), b.load(prev_radius));
        let one = b.f(1.0);
        let relaxing = b.gt(om, one);
        // ε here serves the overlap test and, if the step stands, the hit test.
        let e = cx.eps(b, t);
        let apart = cx.apart(b, st, (radius, pr), e);
        let fail = b.bin(B::LogicalAnd, relaxing, apart);
        b.name(fail, "fail");
        let back = match self.prev_r {
            // Back to t₋ + r₋ with ω kept (Bálint & Valasek Alg. 2).
            Some(prev_r) => {
                let pr = b.load(prev_r);
                b.sub(pr, st)
            }
            // Keinert's listing: step −= ω·step, ω = 1 from now on.
            None => {
                let back = b.mul(om, st);
                b.sub(st, back)
            }
        };
        let ahead = b.mul(r, om);
        let new_step = b.select(fail, back, ahead);
        b.store(step, new_step);
        match self.prev_r {
            Some(prev_r) => {
                let kept = b.select(fail, pr, radius);
                b.store(prev_radius, kept);
                let old = b.load(prev_r);
                let kept = b.select(fail, old, r);
                b.store(prev_r, kept);
            }
            None => {
                let new_omega = b.select(fail, one, om);
                b.store(omega, new_omega);
                b.store(prev_radius, radius);
            }
        }
        (fail, new_step, e)
    }
}

/// Where the step stands: t becomes the candidate if its error |r|/ε is the smallest yet, and
/// the ray stops on a hit (or inside at its start) or past the far limit.
fn candidate_or_stop(
    b: &mut FnBuilder,
    cx: &Cx,
    (candidate_t, candidate_error): (Ex, Ex),
    (t, r, radius, e): (Ex, Ex, Ex, Ex),
) {
    let error = b.div(radius, e);
    let ce = b.load(candidate_error);
    let smaller = b.lt(error, ce);
    let zero = b.f(0.0);
    let none = b.lt(ce, zero);
    let better = b.bin(B::LogicalOr, smaller, none);
    b.if_(
        better,
        |b| {
            b.store(candidate_t, t);
            b.store(candidate_error, error);
        },
        |_| {},
    );
    let near = b.lt(radius, e);
    let zero = b.f(0.0);
    let below = b.lt(r, zero);
    let at_start = b.bin(B::LessEqual, t, zero);
    let stuck = b.bin(B::LogicalAnd, below, at_start);
    let close = b.bin(B::LogicalOr, near, stuck);
    cx.stop_if(b, close, HIT);
    let far = cx.far(b);
    let gone = b.gt(t, far);
    cx.stop_if(b, gone, 0);
}

/// Bálint Alg. 3 (see `crate::reference::trace::enhanced`).
fn enhanced(b: &mut FnBuilder, cx: &Cx) {
    let d = var(b, "d", 0.0);
    let r_prev = var(b, "r_prev", 0.0);
    let r = var(b, "r", 0.0);
    b.loop_(|b| {
        cx.budget(b, EXHAUSTED, |_| {});
        let (t, dv, rp, rv) = (b.load(cx.t), b.load(d), b.load(r_prev), b.load(r));
        let zero = b.f(0.0);
        let plain = b.bin(B::Equal, dv, zero);
        // r + ω·r·(d − r₋ + r) / max(d + r₋ − r, guard·d)
        let den = b.add(dv, rp);
        let den = b.sub(den, rv);
        let g = b.f(ENHANCED_GUARD);
        let guard = b.mul(g, dv);
        let den = b.max(den, guard);
        let one = b.f(1.0);
        let den = b.select(plain, one, den);
        let num = b.sub(dv, rp);
        let num = b.add(num, rv);
        let w = b.f(cx.trace.omega);
        let wr = b.mul(w, rv);
        let q = b.div(num, den);
        let extra = b.mul(wr, q);
        let inferred = b.add(rv, extra);
        let dn = b.select(plain, rv, inferred);
        b.name(dn, "step");
        // ε at the current point is computed again in the overlap test rather than carried from
        // the last step's hit test: carried in a variable, it measured 5% slower on the
        // composition (llvmpipe; issue 14).
        let (at, point, rn, fail) = cx.probe(b, t, (rv, dn), None);
        b.if_(
            fail,
            |b| {
                let zero = b.f(0.0);
                b.store(d, zero);
            },
            |b| {
                b.store(cx.t, at);
                b.store(cx.p, point);
                b.store(d, dn);
                b.store(r_prev, rv);
                b.store(r, rn);
                let e = cx.eps(b, at);
                let close = b.lt(rn, e);
                cx.stop_if(b, close, HIT);
                let far = cx.far(b);
                let gone = b.gt(at, far);
                cx.stop_if(b, gone, 0);
            },
        );
    });
}

/// Bán & Valasek 2023 (see `crate::reference::trace::auto`).
fn auto(b: &mut FnBuilder, cx: &Cx) {
    let start = b.f(0.0);
    let r0 = cx.field_at(b, cx.ro, start);
    let f32t = b.m.f32();
    let r = b.local("dist", f32t, Some(r0));
    let z = b.local("stride", f32t, Some(r0));
    let m = var(b, "m", -1.0);
    b.loop_(|b| {
        let (t, rv) = (b.load(cx.t), b.load(r));
        let e = cx.eps(b, t);
        let close = b.lt(rv, e);
        cx.stop_if(b, close, HIT);
        let far = cx.far(b);
        let gone = b.gt(t, far);
        cx.stop_if(b, gone, 0);
        cx.budget(b, EXHAUSTED, |_| {});
        let (zv, mv) = (b.load(z), b.load(m));
        let (tn, point, rn, back) = cx.probe(b, t, (rv, zv), Some(e));
        b.name(back, "back");
        let rise = b.sub(rn, rv);
        let slope = b.div(rise, zv);
        let diff = b.sub(slope, mv);
        let beta = b.f(cx.trace.beta);
        let moved = b.mul(beta, diff);
        let moved = b.add(mv, moved);
        let reset = b.f(-1.0);
        let m2 = b.select(back, reset, moved);
        b.store(m, m2);
        let t2 = b.select(back, t, tn);
        let r2 = b.select(back, rv, rn);
        b.store(cx.t, t2);
        let p = b.load(cx.p);
        let p2 = b.select(back, p, point);
        b.store(cx.p, p2);
        b.store(r, r2);
        let one = b.f(1.0);
        let gap = b.sub(one, m2);
        let least = b.f(2.0 / AUTO_MAX_OMEGA);
        let gap = b.max(gap, least);
        let two = b.f(2.0);
        let omega = b.div(two, gap);
        let omega = b.max(omega, one);
        let step = b.mul(r2, omega);
        let e2 = cx.eps(b, t2);
        let step = b.max(step, e2);
        b.store(z, step);
    });
}

/// Keinert §3.4, Eq. 3 after a hit: `t ← max(t + f(t) − ε(t), 0)`, a fixed number of times.
fn discontinuity(b: &mut FnBuilder, cx: &Cx) {
    let fl = b.load(cx.flags);
    let bit = b.u(HIT);
    let masked = b.bin(B::And, fl, bit);
    let zero_u = b.u(0);
    let hit = b.bin(B::NotEqual, masked, zero_u);
    b.if_(
        hit,
        |b| {
            let limit = b.u(cx.trace.discontinuity);
            b.repeat("i", limit, |b, _| {
                let t = b.load(cx.t);
                let d = cx.field(b, t);
                let e = cx.eps(b, t);
                let nt = b.add(t, d);
                let nt = b.sub(nt, e);
                let zero = b.f(0.0);
                let nt = b.max(nt, zero);
                b.store(cx.t, nt);
            });
        },
        |_| {},
    );
}
