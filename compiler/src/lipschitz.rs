//! Lipschitz bounds beyond the catalog's rules: inference for `implicit` expressions by interval
//! arithmetic on the gradient, and an estimate of the true constant by sampling the CPU evaluator.

use crate::interval::Interval;
use crate::scene::Field;
use crate::syntax::BinOp;
use glam::DVec3;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// The largest |n| for which `a ^ n` with a whole n is multiplied out (on the GPU as on the
/// CPU), so that it is defined for negative bases.
pub const MAX_WHOLE_POWER: f64 = 64.0;

/// A bound on |∇f| over all of space for an `implicit` body, by forward-mode differentiation in
/// interval arithmetic (Liktor §4: the Lipschitz constant is the supremum of the gradient's
/// length). Infinite when no finite bound follows (e.g. `x*x`), and the checker then asks for an
/// annotation. An error names a function whose argument may leave its domain (`sqrt` of a
/// possibly negative value, `log` of a possibly non-positive one, a fractional power of a
/// possibly negative base): the field would be NaN there, which no annotation mends.
pub fn infer(field: &Field) -> Result<f64, String> {
    let mut undefined = None;
    let (_, g) = grad(field, &mut undefined, &mut false);
    if let Some(what) = undefined {
        return Err(what);
    }
    let l = g.iter().map(|i| i.mag().powi(2)).sum::<f64>().sqrt();
    Ok(if l.is_nan() { f64::INFINITY } else { l })
}

/// Whether the body takes `atan2(a, b)` where a may cross 0 while b is negative: the angle
/// jumps by 2π there, so no slope bound holds across it (the reason an inference failed).
pub fn crosses_branch_cut(field: &Field) -> bool {
    let mut cut = false;
    grad(field, &mut None, &mut cut);
    cut
}

/// Value range and gradient ranges of a field over all of space.
fn grad(f: &Field, undefined: &mut Option<String>, cut: &mut bool) -> (Interval, [Interval; 3]) {
    let zero = Interval::point(0.0);
    match f {
        Field::Const(c) => (Interval::point(*c), [zero; 3]),
        Field::Coord(i) => {
            let mut g = [zero; 3];
            g[*i] = Interval::point(1.0);
            (Interval::ALL, g)
        }
        Field::Neg(a) => {
            let (v, g) = grad(a, undefined, cut);
            (v.neg(), g.map(Interval::neg))
        }
        Field::Binary(op, a, b) => {
            let ((va, ga), (vb, gb)) = (grad(a, undefined, cut), grad(b, undefined, cut));
            let each =
                |f: &dyn Fn(Interval, Interval) -> Interval| [0, 1, 2].map(|i| f(ga[i], gb[i]));
            match op {
                BinOp::Add => (va.add(vb), each(&|x, y| x.add(y))),
                BinOp::Sub => (va.sub(vb), each(&|x, y| x.sub(y))),
                // a·a is a square: ≥ 0, which plain interval products cannot see.
                BinOp::Mul if a == b => (
                    va.powi(2),
                    each(&|x, _| x.mul(va).mul(Interval::point(2.0))),
                ),
                BinOp::Mul => (va.mul(vb), each(&|x, y| x.mul(vb).add(va.mul(y)))),
                BinOp::Div => {
                    let q = va.div(vb);
                    (q, each(&|x, y| x.sub(q.mul(y)).div(vb)))
                }
                BinOp::Pow => match **b {
                    // xⁿ with a whole exponent: n·xⁿ⁻¹·x'.
                    Field::Const(n) if n.fract() == 0.0 && (0.0..=64.0).contains(&n) => {
                        let n = n as i32;
                        let d = if n == 0 {
                            zero
                        } else {
                            va.powi(n - 1).mul(Interval::point(n as f64))
                        };
                        (va.powi(n), ga.map(|x| d.mul(x)))
                    }
                    _ => {
                        // A negative base is defined only for the whole exponents the
                        // lowering multiplies out (|n| ≤ 64); `pow` is NaN or undefined there.
                        let whole = matches!(**b, Field::Const(n) if n.fract() == 0.0 && n.abs() <= MAX_WHOLE_POWER);
                        if va.lo < 0.0 && !whole {
                            undefined.get_or_insert_with(|| {
                                format!("`^` may raise a negative base (as low as {}) to a power that is not a whole number from -64 to 64", va.lo)
                            });
                        }
                        (Interval::ALL, [Interval::ALL; 3])
                    }
                },
            }
        }
        Field::Call(func, args) => {
            let parts: Vec<(Interval, [Interval; 3])> =
                args.iter().map(|a| grad(a, undefined, cut)).collect();
            let vals: Vec<Interval> = parts.iter().map(|p| p.0).collect();
            if func.name == "atan2" && vals[0].has_zero() && vals[1].lo < 0.0 {
                *cut = true;
            }
            if !(func.defined)(&vals) {
                let range: Vec<String> = vals
                    .iter()
                    .map(|v| format!("[{}, {}]", v.lo, v.hi))
                    .collect();
                undefined.get_or_insert_with(|| {
                    format!("`{}` may be given a value outside its domain (its argument ranges over {})", func.name, range.join(", "))
                });
            }
            let partials = (func.partials)(&vals);
            let mut g = [zero; 3];
            for (k, (_, ga)) in parts.iter().enumerate() {
                for i in 0..3 {
                    g[i] = g[i].add(partials[k].mul(ga[i]));
                }
            }
            ((func.range)(&vals), g)
        }
    }
}

/// Largest |∇f| seen by central differences at `samples` points spread over the cube of half
/// size `extent` around `center` (a low-discrepancy sequence, so repeatable). A lower estimate of
/// the true constant: if it exceeds an annotation, the annotation is wrong.
pub fn estimate(f: impl Fn(DVec3) -> f64, center: DVec3, extent: f64, samples: usize) -> f64 {
    let h = extent * 1e-5;
    let mut best: f64 = 0.0;
    for i in 0..samples {
        // R3 quasi-random sequence (plastic-number based), in [0, 1)³.
        let g = 1.220_744_084_605_759_5_f64;
        let a = DVec3::new(1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g));
        let u = (DVec3::splat(0.5) + a * i as f64).fract();
        let p = center + (u * 2.0 - DVec3::ONE) * extent;
        let grad = DVec3::new(
            f(p + DVec3::X * h) - f(p - DVec3::X * h),
            f(p + DVec3::Y * h) - f(p - DVec3::Y * h),
            f(p + DVec3::Z * h) - f(p - DVec3::Z * h),
        ) / (2.0 * h);
        if grad.is_finite() {
            best = best.max(grad.length());
        }
    }
    best
}

/// Samples every annotated node's field and warns where its slope exceeds the annotation (the
/// cause of overstepping artefacts). Unbounded nodes are sampled in a cube of half size 4 around
/// the origin.
pub fn verify_annotations(scene: &crate::scene::Scene) -> Vec<crate::diag::Diagnostic> {
    let mut out = Vec::new();
    for id in scene.reachable() {
        let n = &scene.nodes[id];
        if n.lambda == n.inferred_lambda {
            continue;
        }
        let (center, extent) = if n.bound.radius.is_finite() {
            (n.bound.center, n.bound.radius * 1.5 + 1e-3)
        } else {
            (DVec3::ZERO, 4.0)
        };
        let seen = estimate(|p| crate::eval::node(scene, id, p).d, center, extent, 4096);
        if seen > n.lambda * 1.01 {
            out.push(
                crate::diag::Diagnostic::warning(
                    n.span,
                    "the annotated Lipschitz bound is too small",
                )
                .label(format!(
                    "the slope reaches {seen:.3} here, above the annotated {}",
                    n.lambda
                ))
                .note("steps of f/λ may pass through the surface; raise the annotation"),
            );
        }
    }
    out
}
