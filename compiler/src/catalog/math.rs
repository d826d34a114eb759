//! Math functions usable in expressions and `implicit` bodies: f64 value and interval partial
//! derivatives (for inferring an `implicit`'s Lipschitz bound).

use crate::interval::Interval;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A math function of the expression language.
pub struct MathFn {
    /// Name in the language.
    pub name: &'static str,
    /// Number of arguments.
    pub arity: usize,
    /// One line for the docs.
    pub doc: &'static str,
    /// Value in f64.
    pub eval: fn(&[f64]) -> f64,
    /// Range of the value over argument intervals.
    pub range: fn(&[Interval]) -> Interval,
    /// Ranges of the partial derivatives with respect to each argument.
    pub partials: fn(&[Interval]) -> Vec<Interval>,
    /// The naga math function computing it.
    pub lower: naga::MathFunction,
    /// How it treats angles.
    pub units: Units,
    /// Whether every value in the argument intervals is in the function's domain (a NaN field
    /// otherwise); the checker refuses an `implicit` where this cannot be shown.
    pub defined: fn(&[Interval]) -> bool,
}

/// Defined everywhere.
const EVERYWHERE: fn(&[Interval]) -> bool = |_| true;

/// How a math function treats angles (numbers with `deg`/`rad`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Plain numbers in, a plain number out.
    Plain,
    /// An angle or a plain number (radians) in, a plain number out (sin, cos).
    AngleIn,
    /// All arguments of one kind; the result is of that kind (abs, min, max).
    Same,
    /// Plain numbers in, an angle out (atan2).
    AngleOut,
}

fn unit() -> Interval {
    Interval::new(-1.0, 1.0)
}

/// ∂min(a, b)/∂a (or ∂max(b, a)/∂a): 1 where `a` is surely the one taken (a < b throughout),
/// 0 where surely not, the hull [0, 1] where either may be.
fn switch(taken: bool, other: bool) -> Interval {
    match (taken, other) {
        (true, _) => Interval::point(1.0),
        (_, true) => Interval::point(0.0),
        _ => Interval::new(0.0, 1.0),
    }
}

/// The sign of a: d|a|/da.
fn sign(a: Interval) -> Interval {
    if a.lo > 0.0 {
        Interval::point(1.0)
    } else if a.hi < 0.0 {
        Interval::point(-1.0)
    } else {
        unit()
    }
}

/// Every math function.
pub static MATH_FUNCTIONS: &[MathFn] = &[
    MathFn {
        name: "abs",
        defined: EVERYWHERE,
        units: Units::Same,
        lower: naga::MathFunction::Abs,
        arity: 1,
        doc: "|a|",
        eval: |a| a[0].abs(),
        range: |a| a[0].abs(),
        partials: |a| vec![sign(a[0])],
    },
    MathFn {
        name: "sqrt",
        defined: |a| a[0].lo >= 0.0,
        units: Units::Plain,
        lower: naga::MathFunction::Sqrt,
        arity: 1,
        doc: "√a (an argument that may be negative is an error)",
        eval: |a| a[0].sqrt(),
        range: |a| a[0].map_up(|x| x.max(0.0).sqrt()),
        partials: |a| {
            vec![
                a[0].map_up(|x| x.max(0.0).sqrt())
                    .recip()
                    .mul(Interval::point(0.5)),
            ]
        },
    },
    MathFn {
        name: "sin",
        defined: EVERYWHERE,
        units: Units::AngleIn,
        lower: naga::MathFunction::Sin,
        arity: 1,
        doc: "sine (radians)",
        eval: |a| a[0].sin(),
        range: |a| a[0].periodic(f64::sin, 0.0),
        partials: |a| vec![a[0].periodic(f64::cos, std::f64::consts::FRAC_PI_2)],
    },
    MathFn {
        name: "cos",
        defined: EVERYWHERE,
        units: Units::AngleIn,
        lower: naga::MathFunction::Cos,
        arity: 1,
        doc: "cosine (radians)",
        eval: |a| a[0].cos(),
        range: |a| a[0].periodic(f64::cos, std::f64::consts::FRAC_PI_2),
        partials: |a| vec![a[0].periodic(f64::sin, 0.0).neg()],
    },
    MathFn {
        name: "exp",
        defined: EVERYWHERE,
        units: Units::Plain,
        lower: naga::MathFunction::Exp,
        arity: 1,
        doc: "eᵃ",
        eval: |a| a[0].exp(),
        range: |a| a[0].map_up(f64::exp),
        partials: |a| vec![a[0].map_up(f64::exp)],
    },
    MathFn {
        name: "log",
        defined: |a| a[0].lo > 0.0,
        units: Units::Plain,
        lower: naga::MathFunction::Log,
        arity: 1,
        doc: "natural logarithm (an argument that may be ≤ 0 is an error)",
        eval: |a| a[0].ln(),
        range: |a| a[0].map_up(|x| x.max(0.0).ln()),
        partials: |a| vec![a[0].recip()],
    },
    MathFn {
        name: "min",
        defined: EVERYWHERE,
        units: Units::Same,
        lower: naga::MathFunction::Min,
        arity: 2,
        doc: "the smaller of a and b",
        eval: |a| a[0].min(a[1]),
        range: |a| Interval::new(a[0].lo.min(a[1].lo), a[0].hi.min(a[1].hi)),
        partials: |a| {
            let (below, above) = (a[0].hi < a[1].lo, a[0].lo > a[1].hi);
            vec![switch(below, above), switch(above, below)]
        },
    },
    MathFn {
        name: "max",
        defined: EVERYWHERE,
        units: Units::Same,
        lower: naga::MathFunction::Max,
        arity: 2,
        doc: "the larger of a and b",
        eval: |a| a[0].max(a[1]),
        range: |a| Interval::new(a[0].lo.max(a[1].lo), a[0].hi.max(a[1].hi)),
        partials: |a| {
            let (below, above) = (a[0].hi < a[1].lo, a[0].lo > a[1].hi);
            vec![switch(above, below), switch(below, above)]
        },
    },
    MathFn {
        name: "length",
        defined: EVERYWHERE,
        units: Units::Plain,
        lower: naga::MathFunction::Length,
        arity: 3,
        doc: "√(a² + b² + c²): the length of a vector (its partials are bounded by 1)",
        eval: |a| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt(),
        range: |a| {
            let s = a[0].powi(2).add(a[1].powi(2)).add(a[2].powi(2));
            s.map_up(|x| x.max(0.0).sqrt())
        },
        partials: |_| vec![unit(), unit(), unit()],
    },
    MathFn {
        name: "atan2",
        defined: EVERYWHERE,
        units: Units::AngleOut,
        lower: naga::MathFunction::Atan2,
        arity: 2,
        doc: "the angle of the point (b, a): atan2(a, b), in (−π, π]; it jumps by 2π where a crosses 0 with b < 0, so it needs an annotation there",
        eval: |a| a[0].atan2(a[1]),
        range: |_| Interval::new(-std::f64::consts::PI, std::f64::consts::PI),
        // ∂/∂a = b/(a²+b²), ∂/∂b = −a/(a²+b²): unbounded near the origin. Where a can be 0
        // while b is negative, the angle jumps by 2π across its branch cut: no finite bound.
        partials: |a| {
            if a[0].has_zero() && a[1].lo < 0.0 {
                return vec![Interval::ALL, Interval::ALL];
            }
            let r2 = a[0].powi(2).add(a[1].powi(2));
            vec![a[1].div(r2), a[0].neg().div(r2)]
        },
    },
    MathFn {
        name: "clamp",
        defined: EVERYWHERE,
        units: Units::Same,
        lower: naga::MathFunction::Clamp,
        arity: 3,
        doc: "a kept within [b, c]: min(max(a, b), c)",
        eval: |a| a[0].max(a[1]).min(a[2]),
        range: |a| {
            let m = Interval::new(a[0].lo.max(a[1].lo), a[0].hi.max(a[1].hi));
            Interval::new(m.lo.min(a[2].lo), m.hi.min(a[2].hi))
        },
        partials: |a| {
            let (x, lo, hi) = (a[0], a[1], a[2]);
            let inner = Interval::new(x.lo.max(lo.lo), x.hi.max(lo.hi));
            vec![
                switch(x.lo > lo.hi && x.hi < hi.lo, x.hi < lo.lo || x.lo > hi.hi),
                switch(lo.lo > x.hi && lo.hi < hi.lo, lo.hi < x.lo || lo.lo > hi.hi),
                switch(hi.hi < inner.lo, hi.lo > inner.hi),
            ]
        },
    },
    MathFn {
        name: "mix",
        defined: EVERYWHERE,
        units: Units::Plain,
        lower: naga::MathFunction::Mix,
        arity: 3,
        doc: "a·(1 − c) + b·c (with shapes, `mix(w) { a b }` is the operator)",
        eval: |a| a[0] * (1.0 - a[2]) + a[1] * a[2],
        range: |a| {
            let one = Interval::point(1.0);
            a[0].mul(one.sub(a[2])).add(a[1].mul(a[2]))
        },
        partials: |a| vec![Interval::point(1.0).sub(a[2]), a[2], a[1].sub(a[0])],
    },
    MathFn {
        name: "sign",
        defined: EVERYWHERE,
        units: Units::Plain,
        lower: naga::MathFunction::Sign,
        arity: 1,
        doc: "−1, 0 or 1 as a is negative, zero or positive (a jump at 0: no slope bound across it)",
        eval: |a| {
            if a[0] > 0.0 {
                1.0
            } else if a[0] < 0.0 {
                -1.0
            } else {
                0.0
            }
        },
        range: |a| sign(a[0]),
        partials: |a| vec![jump(a[0].lo > 0.0 || a[0].hi < 0.0, 0.0)],
    },
    MathFn {
        name: "floor",
        defined: EVERYWHERE,
        units: Units::Same,
        lower: naga::MathFunction::Floor,
        arity: 1,
        doc: "the largest whole number ≤ a (a jump at each whole number: no slope bound across one)",
        eval: |a| a[0].floor(),
        range: |a| Interval::new(a[0].lo.floor(), a[0].hi.floor()),
        partials: |a| vec![jump(a[0].lo.floor() == a[0].hi.floor(), 0.0)],
    },
    MathFn {
        name: "fract",
        defined: EVERYWHERE,
        units: Units::Same,
        lower: naga::MathFunction::Fract,
        arity: 1,
        doc: "a − floor(a), in [0, 1) (a jump at each whole number)",
        eval: |a| a[0] - a[0].floor(),
        range: |a| {
            if a[0].lo.floor() == a[0].hi.floor() {
                Interval::new(a[0].lo - a[0].lo.floor(), a[0].hi - a[0].lo.floor())
            } else {
                Interval::new(0.0, 1.0)
            }
        },
        partials: |a| vec![jump(a[0].lo.floor() == a[0].hi.floor(), 1.0)],
    },
    MathFn {
        name: "mod",
        // The divisor must keep its sign (b = 0 divides by zero).
        defined: |a| a[1].lo > 0.0 || a[1].hi < 0.0,
        units: Units::Same,
        // Lowered as a − b·floor(a / b) (`catalog::gpu::field::lower`).
        lower: naga::MathFunction::Floor,
        arity: 2,
        doc: "a − b·floor(a / b), GLSL's mod: in [0, b) for b > 0 (a jump where a / b is whole)",
        eval: |a| a[0] - a[1] * (a[0] / a[1]).floor(),
        range: |a| {
            let q = a[0].div(a[1]);
            let k = Interval::new(q.lo.floor(), q.hi.floor());
            if k.lo == k.hi {
                a[0].sub(a[1].mul(k))
            } else if a[1].lo > 0.0 {
                Interval::new(0.0, a[1].hi)
            } else {
                Interval::new(a[1].lo, 0.0)
            }
        },
        partials: |a| {
            let q = a[0].div(a[1]);
            let (lo, hi) = (q.lo.floor(), q.hi.floor());
            if lo == hi && lo.is_finite() {
                vec![Interval::point(1.0), Interval::point(-lo)]
            } else {
                vec![Interval::ALL, Interval::ALL]
            }
        },
    },
    MathFn {
        name: "smoothstep",
        // The edges must differ everywhere (b − a = 0 divides by zero).
        defined: |a| {
            let w = a[1].sub(a[0]);
            w.lo > 0.0 || w.hi < 0.0
        },
        units: Units::Plain,
        // Lowered as t²·(3 − 2t), t = clamp((c − a) / (b − a), 0, 1)
        // (`catalog::gpu::field::lower`).
        lower: naga::MathFunction::SmoothStep,
        arity: 3,
        doc: "t²·(3 − 2t) with t = clamp((c − a) / (b − a), 0, 1): from 0 at a to 1 at b, smoothly (slope ≤ 1.5/|b − a|)",
        eval: |a| {
            let t = ((a[2] - a[0]) / (a[1] - a[0])).clamp(0.0, 1.0);
            t * t * (3.0 - 2.0 * t)
        },
        range: |_| Interval::new(0.0, 1.0),
        partials: |a| {
            // ds/dt = 6t(1 − t) ∈ [0, 1.5] (0 where t is clamped); dt/dc = 1/w,
            // dt/da = (c − b)/w², dt/db = (a − c)/w², w = b − a.
            let w = a[1].sub(a[0]);
            let ds = Interval::new(0.0, 1.5);
            let w2 = w.powi(2);
            vec![
                ds.mul(a[2].sub(a[1]).div(w2)),
                ds.mul(a[0].sub(a[2]).div(w2)),
                ds.div(w),
            ]
        },
    },
];

/// A derivative of `slope` where the function is continuous over the interval (`smooth`), or
/// no bound where it may jump inside it.
fn jump(smooth: bool, slope: f64) -> Interval {
    if smooth {
        Interval::point(slope)
    } else {
        Interval::ALL
    }
}

/// A math function written in terms of the operators (the checker expands a call into them, so
/// its range, slope and lowering are theirs).
pub struct DerivedFn {
    /// Name in the language.
    pub name: &'static str,
    /// Number of arguments.
    pub arity: usize,
    /// One line for the docs: what it is, written with the parts.
    pub doc: &'static str,
}

/// The derived math functions.
pub static DERIVED_FUNCTIONS: &[DerivedFn] = &[DerivedFn {
    name: "pow",
    arity: 2,
    doc: "a ^ b (the `^` operator: a whole exponent takes any base, another needs a > 0)",
}];
