//! Interval arithmetic on f64, used to bound an `implicit` expression's gradient.

/// A closed interval [lo, hi]; the bounds may be infinite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
}

/// Magnitude above which [`Interval::periodic`] gives [-1, 1] without looking for extremes.
const PERIODIC_LIMIT: f64 = 1e15;

impl Interval {
    /// Everything.
    pub const ALL: Interval = Interval {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };

    /// [lo, hi]; NaN bounds widen to everything.
    pub fn new(lo: f64, hi: f64) -> Interval {
        if lo.is_nan() || hi.is_nan() {
            return Interval::ALL;
        }
        Interval { lo, hi }
    }

    /// The single point x.
    pub fn point(x: f64) -> Interval {
        Interval::new(x, x)
    }

    /// The largest absolute value.
    pub fn mag(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// Whether 0 is inside.
    pub fn has_zero(self) -> bool {
        self.lo <= 0.0 && self.hi >= 0.0
    }

    /// Smallest interval holding both.
    pub fn hull(self, o: Interval) -> Interval {
        Interval::new(self.lo.min(o.lo), self.hi.max(o.hi))
    }

    /// Reciprocal (everything if 0 is inside).
    pub fn recip(self) -> Interval {
        if self.has_zero() {
            return Interval::ALL;
        }
        Interval::new(1.0 / self.hi, 1.0 / self.lo)
    }

    /// Image under a monotonically increasing function.
    pub fn map_up(self, f: impl Fn(f64) -> f64) -> Interval {
        Interval::new(f(self.lo), f(self.hi))
    }

    /// |x|.
    pub fn abs(self) -> Interval {
        if self.has_zero() {
            Interval::new(0.0, self.mag())
        } else {
            Interval::new(self.lo.abs().min(self.hi.abs()), self.mag())
        }
    }

    /// Image of sin or cos (`phase` 0 for sin, π/2 for cos): exact extremes when the interval is
    /// narrower than a period, else [-1, 1].
    pub fn periodic(self, f: fn(f64) -> f64, phase: f64) -> Interval {
        // Past 2⁵⁰ the extremes' spacing (π) is near f64's resolution and the search below
        // would not advance (k + 1 == k beyond 2⁵³): there, the whole range.
        let width = self.hi - self.lo;
        if width.is_nan() || width >= std::f64::consts::TAU || self.mag() > PERIODIC_LIMIT {
            return Interval::new(-1.0, 1.0);
        }
        let mut r = Interval::point(f(self.lo)).hull(Interval::point(f(self.hi)));
        // Extremes of sin(x + phase) at x + phase = π/2 + kπ.
        let half_pi = std::f64::consts::FRAC_PI_2;
        let mut k = ((self.lo + phase - half_pi) / std::f64::consts::PI).ceil();
        while half_pi + k * std::f64::consts::PI - phase <= self.hi {
            let x = half_pi + k * std::f64::consts::PI - phase;
            r = r.hull(Interval::point(f(x)));
            k += 1.0;
        }
        r
    }

    /// xⁿ for a whole n ≥ 0.
    pub fn powi(self, n: i32) -> Interval {
        if n == 0 {
            return Interval::point(1.0);
        }
        if n % 2 == 1 {
            return self.map_up(|x| x.powi(n));
        }
        let a = self.abs();
        a.map_up(|x| x.powi(n))
    }
}

impl std::ops::Add for Interval {
    type Output = Interval;
    fn add(self, o: Interval) -> Interval {
        Interval::new(self.lo + o.lo, self.hi + o.hi)
    }
}

impl std::ops::Sub for Interval {
    type Output = Interval;
    fn sub(self, o: Interval) -> Interval {
        self + -o
    }
}

impl std::ops::Mul for Interval {
    type Output = Interval;
    fn mul(self, o: Interval) -> Interval {
        let c = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        if c.iter().any(|x| x.is_nan()) {
            // 0 × ∞: one factor may be exactly zero; the product is zero only if it is a point.
            if self == Interval::point(0.0) || o == Interval::point(0.0) {
                return Interval::point(0.0);
            }
            return Interval::ALL;
        }
        Interval::new(
            c.iter().copied().fold(f64::INFINITY, f64::min),
            c.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    }
}

impl std::ops::Div for Interval {
    type Output = Interval;
    fn div(self, o: Interval) -> Interval {
        #[allow(clippy::suspicious_arithmetic_impl)]
        let q = self * o.recip();
        q
    }
}

impl std::ops::Neg for Interval {
    type Output = Interval;
    fn neg(self) -> Interval {
        Interval::new(-self.hi, -self.lo)
    }
}
