//! Short names for the math the shapes and shading use, on [`FnBuilder`], so that their
//! bodies read like their formulas.

use super::builder::{Ex, FnBuilder};
use naga::{MathFunction, VectorSize};

impl FnBuilder<'_> {
    /// |v| of a vector.
    pub fn length(&mut self, v: Ex) -> Ex {
        self.math(MathFunction::Length, &[v])
    }

    /// |x| componentwise.
    pub fn abs(&mut self, x: Ex) -> Ex {
        self.math(MathFunction::Abs, &[x])
    }

    /// min(a, b) componentwise.
    pub fn min(&mut self, a: Ex, b: Ex) -> Ex {
        self.math(MathFunction::Min, &[a, b])
    }

    /// max(a, b) componentwise.
    pub fn max(&mut self, a: Ex, b: Ex) -> Ex {
        self.math(MathFunction::Max, &[a, b])
    }

    /// clamp(x, lo, hi)
    pub fn clamp(&mut self, x: Ex, lo: Ex, hi: Ex) -> Ex {
        self.math(MathFunction::Clamp, &[x, lo, hi])
    }

    /// a · b
    pub fn dot(&mut self, a: Ex, b: Ex) -> Ex {
        self.math(MathFunction::Dot, &[a, b])
    }

    /// √x
    pub fn sqrt(&mut self, x: Ex) -> Ex {
        self.math(MathFunction::Sqrt, &[x])
    }

    /// Components 0, 1, 2 of a vector.
    pub fn xyz(&mut self, v: Ex) -> [Ex; 3] {
        [self.at(v, 0), self.at(v, 1), self.at(v, 2)]
    }

    /// `vec2(a, b)`
    pub fn vec2(&mut self, a: Ex, b: Ex) -> Ex {
        let ty = self.m.vec(VectorSize::Bi);
        self.compose(ty, vec![a, b])
    }

    /// The largest component of a `vec3`.
    pub fn max3(&mut self, v: Ex) -> Ex {
        let [x, y, z] = self.xyz(v);
        let yz = self.max(y, z);
        self.max(x, yz)
    }

    /// The smallest component of a `vec3`.
    pub fn min3(&mut self, v: Ex) -> Ex {
        let [x, y, z] = self.xyz(v);
        let yz = self.min(y, z);
        self.min(x, yz)
    }

    /// floor(x + 0.5): rounding half up, the same on the CPU and every GPU.
    pub fn round_half_up(&mut self, x: Ex, size: Option<VectorSize>) -> Ex {
        let mut half = self.f(0.5);
        if let Some(size) = size {
            half = self.splat(half, size);
        }
        let y = self.add(x, half);
        self.math(MathFunction::Floor, &[y])
    }

    /// A vec3 of one f32 literal.
    pub fn splat3(&mut self, x: f64) -> Ex {
        let s = self.f(x);
        self.splat(s, VectorSize::Tri)
    }
}
