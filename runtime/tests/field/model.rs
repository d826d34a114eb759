//! The f32 error model of `field.rs`: forward error bounds of `implicit` bodies and the error
//! Vulkan allows the built-ins a module calls (the derivation is in `field.rs`'s module doc).

use super::f32x;
use glam::DVec3;
use sdfc_compiler::scene::Field;
use sdfc_compiler::syntax::BinOp;
use std::f64::consts::{LN_2, PI};

/// Unit roundoff of f32: a correctly rounded result is within u·|v| of the exact one.
pub const U: f64 = 1.0 / (1u64 << 24) as f64;
/// One ulp of f32, relative: ulp(v) ≤ ULP·|v|.
pub const ULP: f64 = 2.0 * U;
/// The smallest normal f32: a smaller result may be flushed to zero.
pub const TINY: f64 = f32::MIN_POSITIVE as f64;
/// The largest finite f32.
pub const MAX: f64 = f32::MAX as f64;

/// A value with an absolute error bound for its f32 evaluation.
#[derive(Clone, Copy)]
pub struct Est {
    /// The f64 value.
    pub v: f64,
    /// Its f32 evaluation's error bound (∞: none).
    pub e: f64,
    /// An intermediate (or this value) is beyond f32's range while finite in f64, or an input
    /// is where Vulkan leaves the result undefined.
    pub off: bool,
}

/// Half an ulp of `v` (and a possible flush to zero): a correctly rounded result's error.
fn rounded(v: f64) -> f64 {
    U * v.abs() + TINY
}

/// `n` ulps of `v`.
fn ulps(n: f64, v: f64) -> f64 {
    n * ULP * v.abs() + TINY
}

/// The error Vulkan allows `log2(a)`, a > 0: 3 ulp outside [0.5, 2], 2⁻²¹ absolute inside.
fn log2_error(a: f64) -> f64 {
    if (0.5..=2.0).contains(&a) {
        2f64.powi(-21)
    } else {
        ulps(3.0, a.log2())
    }
}

/// The relative error Vulkan allows `pow(a, y)` = `exp2(y·log2 a)`, a > 0: log2's error times
/// |y|·ln 2, the product's rounding, and exp2's 3 + 2|t| ulp.
fn pow_relative(a: f64, y: f64) -> f64 {
    let t = y * a.log2();
    LN_2 * (y.abs() * log2_error(a) + U * t.abs()) + (3.0 + 2.0 * t.abs()) * ULP
}

/// The f32 error bound of an `implicit` body at `p` (see the module doc).
pub fn estimate(f: &Field, p: DVec3) -> Est {
    let est = |v: f64, e: f64, off: bool| Est {
        v,
        e: if e.is_nan() { f64::INFINITY } else { e },
        off: off || (v.is_finite() && v.abs() > MAX),
    };
    match f {
        Field::Const(c) => est(*c, (c - f32x(*c)).abs(), false),
        Field::Coord(i) => est(p[*i], 0.0, false),
        // The uniform holds the value rounded to f32.
        Field::Param(r) => est(r.value, (r.value - f32x(r.value)).abs(), false),
        Field::Neg(a) => {
            let a = estimate(a, p);
            est(-a.v, a.e, a.off)
        }
        Field::Binary(op, a, b) => {
            let (x, y) = (estimate(a, p), estimate(b, p));
            let off = x.off || y.off;
            let v = sdfc_compiler::scene::binary(*op, x.v, y.v);
            let e = match op {
                BinOp::Add | BinOp::Sub => x.e + y.e + rounded(v),
                BinOp::Mul => y.v.abs() * x.e + x.v.abs() * y.e + x.e * y.e + rounded(v),
                BinOp::Div if y.v.abs() > y.e => {
                    (x.e + v.abs() * y.e) / (y.v.abs() - y.e) + ulps(2.5, v)
                }
                BinOp::Div => f64::INFINITY,
                BinOp::Pow => match **b {
                    Field::Const(n) if n.fract() == 0.0 => {
                        // Through the derivative n·aⁿ⁻¹, then the larger of multiplying out
                        // (each of ≤ |n| roundings of the power: ≤ |n|·u relative, squaring
                        // doubling an error as often as it halves the count) and of `pow`.
                        let through = if x.v == 0.0 {
                            if n == 1.0 { x.e } else { 0.0 }
                        } else {
                            (n * v / x.v).abs() * x.e
                        };
                        let multiplied = n.abs() * U + if n < 0.0 { 2.5 * ULP } else { 0.0 };
                        let pow = if x.v == 0.0 {
                            0.0
                        } else {
                            pow_relative(x.v.abs(), n)
                        };
                        through + multiplied.max(pow) * v.abs() + TINY
                    }
                    _ if x.v > 0.0 => {
                        let through = (y.v * v / x.v).abs() * x.e + (v * x.v.ln()).abs() * y.e;
                        through + pow_relative(x.v, y.v) * v.abs() + TINY
                    }
                    _ => f64::INFINITY,
                },
            };
            est(v, e, off)
        }
        Field::Call(func, args) => {
            let a: Vec<Est> = args.iter().map(|a| estimate(a, p)).collect();
            let off = a.iter().any(|a| a.off);
            let x: Vec<f64> = a.iter().map(|a| a.v).collect();
            let v = (func.eval)(&x);
            let e = match func.name {
                "abs" => a[0].e,
                "min" | "max" => a[0].e.max(a[1].e),
                "sqrt" => {
                    // √ of a value known to ±e: off by at most √e, or e/(2√s) away from 0.
                    let (e, s) = (a[0].e, x[0]);
                    let through = if e == 0.0 {
                        0.0
                    } else if s > 0.0 {
                        (e / (2.0 * v)).min(e.sqrt())
                    } else {
                        e.sqrt()
                    };
                    // inversesqrt's 2 ulp, then the reciprocal's 2.5.
                    through + ulps(4.5, v)
                }
                "exp" => v * a[0].e.exp_m1() + ulps(3.0 + 2.0 * x[0].abs(), v),
                "log" if x[0] > a[0].e => {
                    let through = -(1.0 - a[0].e / x[0]).ln();
                    through
                        + if (0.5..=2.0).contains(&x[0]) {
                            2f64.powi(-21)
                        } else {
                            ulps(3.0, v)
                        }
                }
                "log" => f64::INFINITY,
                "sin" | "cos" => {
                    let reduce = if x[0].abs() > PI {
                        ULP * x[0].abs()
                    } else {
                        0.0
                    };
                    a[0].e.min(2.0) + 2f64.powi(-11) + reduce
                }
                "length" => {
                    // dot: a product and two sums of non-negative terms, ≤ 3u relative; the
                    // square root halves it, then sqrt's own 4.5 ulp; squares below 2⁻¹²⁶
                    // may be flushed (≤ √(3·2⁻¹²⁶) after the root).
                    let squares = x.iter().map(|c| c * c).sum::<f64>();
                    let through: f64 = a.iter().map(|a| a.e).sum();
                    let e = through + 1.5 * U * v + ulps(4.5, v) + (3.0 * TINY).sqrt();
                    return est(v, e, off || squares > MAX);
                }
                "atan2" => {
                    let (y, x0) = (x[0], x[1]);
                    if y == 0.0 && x0 == 0.0 {
                        // Vulkan leaves atan2(0, 0) undefined.
                        return est(v, f64::INFINITY, true);
                    }
                    let r2 = y * y + x0 * x0;
                    let mut through = (x0.abs() * a[0].e + y.abs() * a[1].e) / r2;
                    // On the branch cut (y within its error of 0, x < 0) the angle may be
                    // either ±π: Vulkan does not promise a zero's sign.
                    if x0 < 0.0 && y.abs() <= a[0].e {
                        through = 2.0 * PI;
                    }
                    through.min(2.0 * PI) + ulps(4096.0, v)
                }
                // One of the arguments, unchanged.
                "clamp" => a[0].e.max(a[1].e).max(a[2].e),
                // Through each argument, then the products and sum (or a + t(b − a)).
                "mix" => {
                    let (ea, eb, et) = (a[0].e, a[1].e, a[2].e);
                    let through = ea * (1.0 - x[2]).abs()
                        + eb * x[2].abs()
                        + (x[1] - x[0]).abs() * et
                        + et * (ea + eb);
                    through
                        + 4.0 * U * (x[0].abs() + x[1].abs()) * (1.0 + x[2].abs())
                        + ulps(2.0, v)
                }
                // Exact, unless the argument may be on the other side of 0 (or at it).
                "sign" if x[0].abs() > a[0].e => 0.0,
                "sign" => 2.0,
                // Exact, unless a whole number lies within the argument's error.
                "floor" | "fract" if (x[0] - a[0].e).floor() != (x[0] + a[0].e).floor() => {
                    1.0 + a[0].e
                }
                "floor" => 0.0,
                // a − b·k, k = floor(a / b): a jump of |b| where a / b may cross a whole number
                // within its error; else through a and b (times k), the quotient's 2.5 ulp
                // moving k only as above, and the product and difference rounded.
                "mod" => {
                    let q = x[0] / x[1];
                    let eq = (a[0].e + q.abs() * a[1].e) / x[1].abs() + ulps(2.5, q);
                    let k = q.floor();
                    if (q - eq).floor() != (q + eq).floor() {
                        x[1].abs() + a[1].e + a[0].e + rounded(v) + U * x[0].abs()
                    } else {
                        a[0].e + k.abs() * a[1].e + 2.0 * U * (x[0].abs() + (k * x[1]).abs())
                    }
                }
                // Through t (slope 1.5 in t), t through its arguments (the division's 2.5 ulp),
                // then the polynomial's few roundings.
                "smoothstep" => {
                    let w = x[1] - x[0];
                    let et = (a[2].e + a[0].e) / w.abs()
                        + ((x[2] - x[0]) / (w * w)).abs() * (a[1].e + a[0].e)
                        + 3.0 * U * ((x[2] - x[0]) / w).abs();
                    1.5 * et + 4.0 * U
                }
                "fract" => a[0].e + rounded(v) + U * x[0].abs(),
                other => panic!("no f32 error model for `{other}`: add one to tests/field.rs"),
            };
            est(v, e, off)
        }
    }
}

/// The largest error, in ulps of a unit value, that Vulkan allows a built-in the module calls
/// (0 when it calls only exact or correctly rounded ones, `sqrt` and `/`; see the module doc).
pub fn builtin_ulps(module: &naga::Module) -> f64 {
    use naga::MathFunction as M;
    let functions = module.functions.iter().map(|(_, f)| f);
    let entries = module.entry_points.iter().map(|e| &e.function);
    functions
        .chain(entries)
        .flat_map(|f| f.expressions.iter())
        .map(|(_, e)| match e {
            naga::Expression::Math { fun, .. } => match fun {
                M::Sin | M::Cos | M::Tan | M::Atan2 | M::Atan | M::Asin | M::Acos => 4096.0,
                M::Exp | M::Exp2 | M::Log | M::Log2 | M::Pow => 255.0,
                _ => 0.0,
            },
            _ => 0.0,
        })
        .fold(0.0, f64::max)
}
