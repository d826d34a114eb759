//! Lipschitz bounds beyond the catalog's rules: inference for `implicit` expressions by interval
//! arithmetic on the gradient (here), the check of `@lipschitz` annotations (`verify.rs`) and of
//! bounds too large for rays to arrive (`converge.rs`).

mod converge;
mod overflow;
mod ranges;
mod reach;
mod verify;

pub use overflow::may_overflow;
pub use ranges::{Values, too_small_at, verify_everywhere, verify_over_ranges};
pub use verify::{Effort, verify_annotations};

use crate::interval::Interval;
use crate::scene::Field;
use crate::syntax::BinOp;
use std::ops::{Add, Div, Mul, Neg, Sub};

pub use crate::catalog::field::MAX_WHOLE_POWER;

/// A bound on |∇f| over all of space for an `implicit` body, by forward-mode differentiation in
/// interval arithmetic (Liktor §2.2: the Lipschitz constant is the supremum of the gradient's
/// length). Infinite when no finite bound follows (e.g. `x*x`), and the checker then asks for an
/// annotation. An error names a function whose argument may leave its domain (`sqrt` of a
/// possibly negative value, `log` of a possibly non-positive one, a fractional power of a
/// possibly negative base, a division by a possibly zero divisor): the field would be NaN or
/// infinite there, which no annotation mends.
pub fn infer(field: &Field) -> Result<f64, String> {
    let mut undefined = None;
    let (_, g) = grad(field, &[Interval::ALL; 3], &mut undefined, &mut false);
    if let Some(what) = undefined {
        return Err(what);
    }
    let l = g.iter().map(|i| i.mag().powi(2)).sum::<f64>().sqrt();
    Ok(if l.is_nan() { f64::INFINITY } else { l })
}

/// The values an expression of parameters (no coordinates) takes over every value they may
/// take (their declared ranges, everything without one), and the first reason it may be
/// undefined there (as [`infer`] reports them).
pub fn value_range(field: &Field) -> (Interval, Option<String>) {
    let mut undefined = None;
    let (v, _) = grad(field, &[Interval::ALL; 3], &mut undefined, &mut false);
    (v, undefined)
}

/// Whether the body takes `atan2(a, b)` where a may cross 0 while b is negative: the angle
/// jumps by 2π there, so no slope bound holds across it (the reason an inference failed).
pub fn crosses_branch_cut(field: &Field) -> bool {
    let mut cut = false;
    grad(field, &[Interval::ALL; 3], &mut None, &mut cut);
    cut
}

/// A bound on |∇f| of an `implicit` body over the box `region` (interval arithmetic, as
/// [`infer`]); infinite where none follows.
pub fn bound_in(field: &Field, region: &[Interval; 3]) -> f64 {
    let (_, g) = grad(field, region, &mut None, &mut false);
    let l = g.iter().map(|i| i.mag().powi(2)).sum::<f64>().sqrt();
    if l.is_nan() { f64::INFINITY } else { l }
}

/// Value range and gradient ranges of a field over all of space.
fn grad(
    f: &Field,
    region: &[Interval; 3],
    undefined: &mut Option<String>,
    cut: &mut bool,
) -> (Interval, [Interval; 3]) {
    let r = grad_inner(f, region, undefined, cut);
    // A value surely beyond f32's range: the shader computes infinities (and NaN from them).
    let max = f64::from(f32::MAX);
    if r.0.lo > max || r.0.hi < -max {
        undefined.get_or_insert_with(|| {
            format!(
                "a part of it is always beyond f32's range (its value ranges over [{:e}, {:e}])",
                r.0.lo, r.0.hi
            )
        });
    }
    r
}

/// [`grad`] of one node, its parts' by [`grad`].
fn grad_inner(
    f: &Field,
    region: &[Interval; 3],
    undefined: &mut Option<String>,
    cut: &mut bool,
) -> (Interval, [Interval; 3]) {
    let zero = Interval::point(0.0);
    match f {
        Field::Const(c) => (Interval::point(*c), [zero; 3]),
        // Any value of its range (everything without one): a bound for every value the host
        // may set.
        Field::Param(r) => (Interval::new(r.lo, r.hi), [zero; 3]),
        Field::Coord(i) => {
            let mut g = [zero; 3];
            g[*i] = Interval::point(1.0);
            (region[*i], g)
        }
        Field::Neg(a) => {
            let (v, g) = grad(a, region, undefined, cut);
            (v.neg(), g.map(Interval::neg))
        }
        Field::Binary(op, a, b) => binary_grad(*op, a, b, region, undefined, cut),
        Field::Call(func, args) => call_grad(func, args, region, undefined, cut),
    }
}

/// [`grad`] of `a op b`.
fn binary_grad(
    op: BinOp,
    a: &Field,
    b: &Field,
    region: &[Interval; 3],
    undefined: &mut Option<String>,
    cut: &mut bool,
) -> (Interval, [Interval; 3]) {
    let ((va, ga), (vb, gb)) = (
        grad(a, region, undefined, cut),
        grad(b, region, undefined, cut),
    );
    let each = |f: &dyn Fn(Interval, Interval) -> Interval| [0, 1, 2].map(|i| f(ga[i], gb[i]));
    match op {
        BinOp::Add => (va.add(vb), each(&|x, y| x.add(y))),
        BinOp::Sub => (va.sub(vb), each(&|x, y| x.sub(y))),
        // a·a is a square: ≥ 0, which plain interval products cannot see.
        BinOp::Mul if a == b => (
            va.powi(2),
            each(&|x, _| x.mul(va).mul(Interval::point(2.0))),
        ),
        // −a·a (as `-x*x` parses) is minus a square: ≤ 0.
        BinOp::Mul if matches!(a, Field::Neg(n) if **n == *b) => {
            (vb.powi(2).neg(), each(&|x, y| x.mul(vb).add(va.mul(y))))
        }
        BinOp::Mul => (va.mul(vb), each(&|x, y| x.mul(vb).add(va.mul(y)))),
        BinOp::Div => {
            // A divisor that may be 0 makes the field infinite or NaN (0/0) there.
            if vb.has_zero() {
                undefined.get_or_insert_with(|| {
                    format!(
                        "`/` may divide by zero (the divisor ranges over [{}, {}])",
                        vb.lo, vb.hi
                    )
                });
            }
            let q = va.div(vb);
            (q, each(&|x, y| x.sub(q.mul(y)).div(vb)))
        }
        BinOp::Pow => pow_grad(b, va, ga, undefined),
    }
}

/// [`grad`] of `a ^ b` from a's value range `va` and gradient `ga`: a whole constant exponent
/// is differentiated; any other power has no bound, and is undefined for a base that may be
/// negative (or zero, for a negative exponent).
fn pow_grad(
    b: &Field,
    va: Interval,
    ga: [Interval; 3],
    undefined: &mut Option<String>,
) -> (Interval, [Interval; 3]) {
    let zero = Interval::point(0.0);
    match *b {
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
        Field::Const(n) if n < 0.0 && va.has_zero() => {
            undefined.get_or_insert_with(|| {
                format!(
                    "`^ {n}` may divide by zero (the base ranges over [{}, {}])",
                    va.lo, va.hi
                )
            });
            (Interval::ALL, [Interval::ALL; 3])
        }
        _ => {
            // A negative base is defined only for the whole exponents the
            // lowering multiplies out (|n| ≤ 64); `pow` is NaN or undefined there.
            let whole =
                matches!(*b, Field::Const(n) if n.fract() == 0.0 && n.abs() <= MAX_WHOLE_POWER);
            if va.lo < 0.0 && !whole {
                undefined.get_or_insert_with(|| {
                    format!("`^` may raise a negative base (as low as {}) to a power that is not a whole number from -64 to 64", va.lo)
                });
            }
            (Interval::ALL, [Interval::ALL; 3])
        }
    }
}

/// [`grad`] of a math function's call, by the chain rule over its partial derivatives;
/// undefined where an argument may leave its domain.
fn call_grad(
    func: &crate::catalog::MathFn,
    args: &[Field],
    region: &[Interval; 3],
    undefined: &mut Option<String>,
    cut: &mut bool,
) -> (Interval, [Interval; 3]) {
    let zero = Interval::point(0.0);
    let parts: Vec<(Interval, [Interval; 3])> = args
        .iter()
        .map(|a| grad(a, region, undefined, cut))
        .collect();
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
            format!(
                "`{}` may be given a value outside its domain (its argument ranges over {})",
                func.name,
                range.join(", ")
            )
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

/// `d` with the call that built `node` beside it, when a function's body did: each call
/// builds its own nodes, so the warning names the call whose arguments make it.
fn with_call(node: &crate::scene::Node, d: crate::diag::Diagnostic) -> crate::diag::Diagnostic {
    match node.call_site {
        Some(call) if !call.contains(node.span) => {
            d.also(call, "in this call: its arguments make the bound wrong")
        }
        _ => d,
    }
}

/// The annotated nodes the checks sample: reachable, annotated below the catalog's rule (one
/// at or above it is implied by the rule, a proof; one above it has the checker's own warning,
/// "looser than the inferred bound").
fn annotated(scene: &crate::scene::Scene) -> Vec<crate::scene::NodeId> {
    scene
        .reachable()
        .into_iter()
        .filter(|&id| scene.nodes[id].lambda < scene.nodes[id].inferred_lambda)
        .collect()
}

/// Whether the scene has `@lipschitz` annotations below their inferred bounds: those the
/// annotation check ([`verify_everywhere`]) samples; without any, it has nothing to do.
pub fn has_claims(scene: &crate::scene::Scene) -> bool {
    !annotated(scene).is_empty()
}

/// A small deterministic generator (xorshift), so the check says the same every run.
struct Rng(u64);

impl Rng {
    fn bits(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn unit(&mut self) -> f64 {
        (self.bits() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn vec(&mut self) -> glam::DVec3 {
        glam::DVec3::new(self.unit(), self.unit(), self.unit())
    }
}
