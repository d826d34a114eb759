//! Parameters: what the host sets at run time (`param`, `time`) and their uses in expressions.

use crate::diag::Span;
use glam::DVec3;

/// What kind of value a parameter holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamKind {
    /// A plain number.
    Number,
    /// An angle, in radians.
    Angle,
    /// A vector.
    Vector,
    /// A colour (sRGB, 0..1).
    Color,
}

impl ParamKind {
    /// Components: 1 for numbers and angles, 3 for vectors and colours.
    pub fn components(self) -> usize {
        match self {
            ParamKind::Number | ParamKind::Angle => 1,
            _ => 3,
        }
    }

    /// How the manifest and `sdfc check` name it.
    pub fn name(self) -> &'static str {
        match self {
            ParamKind::Number => "number",
            ParamKind::Angle => "angle",
            ParamKind::Vector => "vector",
            ParamKind::Color => "color",
        }
    }
}

/// A declared parameter (`param name = default in lo..hi`) or the built-in `time`.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamDecl {
    /// Its name (a field of the `Params` uniform).
    pub name: String,
    /// Number, angle, vector or colour.
    pub kind: ParamKind,
    /// The declared default (numbers in `x`).
    pub default: DVec3,
    /// The value the scene was checked at: the default unless another was asked for.
    pub value: DVec3,
    /// The declared range, each end included (per component).
    pub range: Option<(DVec3, DVec3)>,
    /// Where it was declared (the whole file's start for the built-in `time`).
    pub span: Span,
}

impl ParamDecl {
    /// The values of its components, in order.
    pub fn values(&self) -> Vec<f64> {
        self.value.to_array()[..self.kind.components()].to_vec()
    }
}
