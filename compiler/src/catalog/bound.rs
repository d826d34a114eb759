//! Where a shape's surface lies: a bounding sphere and an axis-aligned box, kept together.

use glam::DVec3;

/// Where a shape's surface lies: a bounding sphere and an axis-aligned box, each of which holds
/// the whole surface (the box is the tighter along axes: a thin shape's sphere is not). Both are
/// infinite for unbounded shapes (planes, infinite repetition). Built only through the methods
/// below, so the two always describe the same shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bound {
    /// Sphere centre.
    pub center: DVec3,
    /// Sphere radius (may be infinite).
    pub radius: f64,
    /// The box's lowest corner (components may be −∞).
    pub lo: DVec3,
    /// The box's highest corner (components may be +∞).
    pub hi: DVec3,
}

impl Bound {
    /// The unbounded bound.
    pub const INFINITE: Bound = Bound {
        center: DVec3::ZERO,
        radius: f64::INFINITY,
        lo: DVec3::NEG_INFINITY,
        hi: DVec3::INFINITY,
    };

    /// A sphere at the origin (its box is the cube around it).
    pub fn origin(radius: f64) -> Bound {
        Bound::sphere(DVec3::ZERO, radius)
    }

    /// A sphere (its box is the cube around it).
    pub fn sphere(center: DVec3, radius: f64) -> Bound {
        if !radius.is_finite() {
            return Bound::INFINITE;
        }
        Bound {
            center,
            radius,
            lo: center - DVec3::splat(radius),
            hi: center + DVec3::splat(radius),
        }
    }

    /// A box centred at the origin with half extents `half`, and the sphere around it.
    pub fn centered_box(half: DVec3) -> Bound {
        Bound::sphere(DVec3::ZERO, half.length()).with_box(-half, half)
    }

    /// The same sphere with its box narrowed to `lo..hi` (where that is tighter).
    pub fn with_box(self, lo: DVec3, hi: DVec3) -> Bound {
        Bound {
            lo: self.lo.max(lo),
            hi: self.hi.min(hi),
            ..self
        }
    }

    /// Whether the surface lies in a finite region.
    pub fn is_finite(self) -> bool {
        self.radius.is_finite()
    }

    /// The bound moved by `offset`.
    pub fn moved(self, offset: DVec3) -> Bound {
        if !self.is_finite() {
            // The box may still be finite along some axes (a 2D shape: every z).
            return Bound {
                lo: self.lo + offset,
                hi: self.hi + offset,
                ..self
            };
        }
        Bound {
            center: self.center + offset,
            radius: self.radius,
            lo: self.lo + offset,
            hi: self.hi + offset,
        }
    }

    /// The bound under a distance-preserving linear map `f` (a rotation or reflection): the
    /// sphere moves, the box becomes the box around its moved corners, narrowed to the sphere's.
    pub fn isometry(self, f: impl Fn(DVec3) -> DVec3) -> Bound {
        if !self.is_finite() {
            return self.planar_isometry(f);
        }
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for i in 0..8 {
            let corner = DVec3::select(
                glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0),
                self.hi,
                self.lo,
            );
            let q = f(corner);
            lo = lo.min(q);
            hi = hi.max(q);
        }
        Bound::sphere(f(self.center), self.radius).with_box(lo, hi)
    }

    /// An isometry of a bound that is finite in x and y only (a 2D shape's): a turn about z
    /// moves its rectangle; anything else, or any other infinite bound, is unbounded.
    fn planar_isometry(self, f: impl Fn(DVec3) -> DVec3) -> Bound {
        let planar = self.lo.x.is_finite()
            && self.hi.x.is_finite()
            && self.lo.y.is_finite()
            && self.hi.y.is_finite()
            && !self.lo.z.is_finite()
            && !self.hi.z.is_finite();
        let ez = f(DVec3::Z);
        if !planar || (ez.z.abs() - 1.0).abs() > 1e-12 {
            return Bound::INFINITE;
        }
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for (x, y) in [
            (self.lo.x, self.lo.y),
            (self.lo.x, self.hi.y),
            (self.hi.x, self.lo.y),
            (self.hi.x, self.hi.y),
        ] {
            let q = f(DVec3::new(x, y, 0.0));
            lo = lo.min(q);
            hi = hi.max(q);
        }
        Bound {
            lo: DVec3::new(lo.x, lo.y, f64::NEG_INFINITY),
            hi: DVec3::new(hi.x, hi.y, f64::INFINITY),
            ..self
        }
    }

    /// The bound scaled by the positive factors `s` per axis.
    pub fn scaled(self, s: DVec3) -> Bound {
        if !self.is_finite() {
            return Bound {
                lo: self.lo * s,
                hi: self.hi * s,
                ..self
            };
        }
        Bound {
            center: self.center * s,
            radius: self.radius * s.max_element(),
            lo: self.lo * s,
            hi: self.hi * s,
        }
    }

    /// The bound grown by `by` in every direction.
    pub fn grown(self, by: f64) -> Bound {
        self.grown_box(DVec3::splat(by), by)
    }

    /// The box grown by `by` per axis and the sphere by `radius`.
    pub fn grown_box(self, by: DVec3, radius: f64) -> Bound {
        if !self.is_finite() {
            return Bound {
                lo: self.lo - by,
                hi: self.hi + by,
                ..self
            };
        }
        Bound {
            center: self.center,
            radius: self.radius + radius,
            lo: self.lo - by,
            hi: self.hi + by,
        }
    }

    /// What holds both (the sphere is not minimal, but tight enough).
    pub fn union(self, o: Bound) -> Bound {
        if !self.is_finite() || !o.is_finite() {
            // The boxes still hold both (finite along some axes for 2D shapes).
            return Bound {
                lo: self.lo.min(o.lo),
                hi: self.hi.max(o.hi),
                ..Bound::INFINITE
            };
        }
        let d = (o.center - self.center).length();
        let sphere = if d + o.radius <= self.radius {
            self
        } else if d + self.radius <= o.radius {
            o
        } else {
            let radius = (d + self.radius + o.radius) / 2.0;
            let center = if d > 0.0 {
                self.center + (o.center - self.center) * ((radius - self.radius) / d)
            } else {
                self.center
            };
            Bound::sphere(center, radius)
        };
        Bound {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
            ..sphere
        }
    }

    /// What holds the part common to both: the smaller sphere, the boxes' overlap.
    pub fn intersection(self, o: Bound) -> Bound {
        let sphere = if o.radius < self.radius { o } else { self };
        sphere.with_box(self.lo.max(o.lo), self.hi.min(o.hi))
    }

    /// Radius of the infinite cylinder around `axis` (through the origin) that contains the sphere.
    pub fn cylinder_radius(self, axis: DVec3) -> f64 {
        let perp = self.center - axis * self.center.dot(axis);
        perp.length() + self.radius
    }
}
