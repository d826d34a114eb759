//! Arguments as the catalog takes them: a value (a number or a vector), its type with its
//! range, a parameter of an entry, and the magnitudes the GPU can carry.

use glam::DVec3;

/// The magnitudes a number in a scene may have besides 0: within f32, with room for a square or
/// a reciprocal (the shader computes 1/s, s², n·s…), so that nothing the lowering derives from
/// it overflows f32 (about 3.4e38) or vanishes.
pub const GPU_RANGE: (f64, f64) = (1e-18, 1e18);

/// Whether `x` is 0 or within [`GPU_RANGE`] in magnitude.
pub fn fits_gpu(x: f64) -> bool {
    x == 0.0 || (GPU_RANGE.0..=GPU_RANGE.1).contains(&x.abs())
}

/// A checked argument value. Colours and axes are vectors; counts are numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Val {
    /// A plain number (lengths and angles in radians included).
    Num(f64),
    /// A vector, colour (linear 0..1 RGB) or unit axis.
    Vec3(DVec3),
    /// The index of a word in a [`Ty::PositiveOr`] list (e.g. `epsilon pixel`).
    Word(usize),
}

impl Val {
    /// The number (0 for non-numbers; the checker guarantees types).
    pub fn num(self) -> f64 {
        match self {
            Val::Num(x) => x,
            _ => 0.0,
        }
    }

    /// The vector (a number is broadcast).
    pub fn vec(self) -> DVec3 {
        match self {
            Val::Vec3(v) => v,
            Val::Num(x) => DVec3::splat(x),
            Val::Word(_) => DVec3::ZERO,
        }
    }

    /// Whether every component is 0 or within [`GPU_RANGE`] (see [`fits_gpu`]; words fit).
    pub fn fits_gpu(self) -> bool {
        match self {
            Val::Num(x) => fits_gpu(x),
            Val::Vec3(v) => v.to_array().into_iter().all(fits_gpu),
            Val::Word(_) => true,
        }
    }
}

/// The type of a parameter, with the range the checker enforces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ty {
    /// Any finite number.
    Number,
    /// A finite number ≥ 0.
    Length,
    /// A finite number > 0.
    Positive,
    /// A number in [0, 1].
    Fraction,
    /// An angle: a number with a unit (`30deg`, `0.5rad`), stored in radians.
    Angle,
    /// A whole number ≥ 1.
    Count,
    /// A whole number from 1 to the limit.
    CountTo(u32),
    /// A whole number from 0 to the limit.
    UpTo(u32),
    /// A whole number from the first limit to the second.
    WholeIn(u32, u32),
    /// 0, or a number ≥ the limit.
    ZeroOrAtLeast(f64),
    /// Any finite vector.
    Vec3,
    /// A size: one number ≥ 0 for all three axes, or a vector of them.
    Size,
    /// A scale factor: one number > 0, or a vector of them.
    Scale,
    /// Whole numbers ≥ 0 per axis: one number or a vector of them.
    Counts,
    /// A direction: `x`, `y`, `z` or a non-zero vector; normalised.
    Axis,
    /// A colour: `#rrggbb`, `#rgb` or a vector of 0..1 components.
    Color,
    /// A number > 0, or one of the listed words.
    PositiveOr(&'static [&'static str]),
    /// A number in [lo, hi).
    Range(f64, f64),
    /// One of the listed words.
    Word(&'static [&'static str]),
}

impl Ty {
    /// How the type is named in messages and docs.
    pub fn describe(self) -> String {
        match self {
            Ty::Number => "a number".into(),
            Ty::Length => "a length (≥ 0)".into(),
            Ty::Positive => "a number > 0".into(),
            Ty::Fraction => "a number in [0, 1]".into(),
            Ty::Angle => "an angle (e.g. `30deg`)".into(),
            Ty::Count => "a whole number ≥ 1".into(),
            Ty::CountTo(n) => format!("a whole number from 1 to {n}"),
            Ty::UpTo(n) => format!("a whole number from 0 to {n}"),
            Ty::WholeIn(lo, hi) => format!("a whole number from {lo} to {hi}"),
            Ty::ZeroOrAtLeast(lo) => format!("0 or a number ≥ {lo}"),
            Ty::Vec3 => "a vector `(x, y, z)`".into(),
            Ty::Size => "a size (number or vector, ≥ 0)".into(),
            Ty::Scale => "a scale (number or vector, > 0)".into(),
            Ty::Counts => "whole numbers ≥ 0 (number or vector)".into(),
            Ty::Axis => "an axis (`x`, `y`, `z` or a vector)".into(),
            Ty::Color => "a colour (`#rrggbb` or `(r, g, b)`)".into(),
            Ty::PositiveOr(words) => {
                let w: Vec<String> = words.iter().map(|w| format!("`{w}`")).collect();
                format!("a number > 0 or {}", w.join(" or "))
            }
            Ty::Range(lo, hi) => format!("a number in [{lo}, {hi})"),
            Ty::Word(words) => {
                let w: Vec<String> = words.iter().map(|w| format!("`{w}`")).collect();
                format!("one of {}", w.join(", "))
            }
        }
    }

    /// Whether a plain number is a value of this type (false for the vector-valued types,
    /// which the checker converts separately, and for NaN).
    pub fn accepts_number(self, x: f64) -> bool {
        let whole = x.fract() == 0.0;
        match self {
            Ty::Number => x.is_finite(),
            Ty::Length => x >= 0.0 && x.is_finite(),
            Ty::Positive | Ty::PositiveOr(_) => x > 0.0 && x.is_finite(),
            Ty::Fraction => (0.0..=1.0).contains(&x),
            Ty::Range(lo, hi) => x >= lo && x < hi,
            Ty::Count => x >= 1.0 && whole,
            Ty::CountTo(n) => x >= 1.0 && x <= n as f64 && whole,
            Ty::UpTo(n) => x >= 0.0 && x <= n as f64 && whole,
            Ty::WholeIn(lo, hi) => x >= f64::from(lo) && x <= f64::from(hi) && whole,
            Ty::ZeroOrAtLeast(lo) => x == 0.0 || (x >= lo && x.is_finite()),
            _ => false,
        }
    }
}

/// One parameter of a primitive, operator or settings block.
#[derive(Clone, Copy, Debug)]
pub struct Param {
    /// Its name, for named arguments.
    pub name: &'static str,
    /// Its type.
    pub ty: Ty,
    /// The default; `None` makes the parameter required.
    pub default: Option<Val>,
}

/// A parameter with a default.
pub const fn opt(name: &'static str, ty: Ty, default: Val) -> Param {
    Param {
        name,
        ty,
        default: Some(default),
    }
}

/// A required parameter.
pub const fn req(name: &'static str, ty: Ty) -> Param {
    Param {
        name,
        ty,
        default: None,
    }
}
