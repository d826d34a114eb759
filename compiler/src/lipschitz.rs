//! Lipschitz bounds beyond the catalog's rules: inference for `implicit` expressions by interval
//! arithmetic on the gradient, and an estimate of the true constant by sampling the CPU evaluator.

use crate::interval::Interval;
use crate::scene::Field;
use crate::syntax::BinOp;
use glam::DVec3;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A bound on |∇f| over all of space for an `implicit` body, by forward-mode differentiation in
/// interval arithmetic (Liktor §4: the Lipschitz constant is the supremum of the gradient's
/// length). Infinite when no finite bound follows (e.g. `x*x`), and the checker then asks for an
/// annotation.
pub fn infer(field: &Field) -> f64 {
    let (_, g) = grad(field);
    let l = g.iter().map(|i| i.mag().powi(2)).sum::<f64>().sqrt();
    if l.is_nan() { f64::INFINITY } else { l }
}

/// Value range and gradient ranges of a field over all of space.
fn grad(f: &Field) -> (Interval, [Interval; 3]) {
    let zero = Interval::point(0.0);
    match f {
        Field::Const(c) => (Interval::point(*c), [zero; 3]),
        Field::Coord(i) => {
            let mut g = [zero; 3];
            g[*i] = Interval::point(1.0);
            (Interval::ALL, g)
        }
        Field::Neg(a) => {
            let (v, g) = grad(a);
            (v.neg(), g.map(Interval::neg))
        }
        Field::Binary(op, a, b) => {
            let ((va, ga), (vb, gb)) = (grad(a), grad(b));
            let each =
                |f: &dyn Fn(Interval, Interval) -> Interval| [0, 1, 2].map(|i| f(ga[i], gb[i]));
            match op {
                BinOp::Add => (va.add(vb), each(&|x, y| x.add(y))),
                BinOp::Sub => (va.sub(vb), each(&|x, y| x.sub(y))),
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
                    _ => (Interval::ALL, [Interval::ALL; 3]),
                },
            }
        }
        Field::Call(func, args) => {
            let parts: Vec<(Interval, [Interval; 3])> = args.iter().map(grad).collect();
            let vals: Vec<Interval> = parts.iter().map(|p| p.0).collect();
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
