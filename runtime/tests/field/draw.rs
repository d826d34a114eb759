//! The random draws of `field.rs`: a deterministic generator, the points a scene is evaluated
//! at, and primitive arguments of each type, all exact in f32.

use super::POINTS;
use glam::DVec3;
use sdfc_compiler::catalog::Ty;

/// A small deterministic generator (SplitMix64): the same points and arguments on every run.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    pub fn sign(&mut self) -> f64 {
        if self.next() & 1 == 0 { 1.0 } else { -1.0 }
    }
    /// 10^e with e uniform in [lo, hi), rounded to f32.
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        f32x(10f64.powf(lo + (hi - lo) * self.unit()))
    }
    /// A magnitude for an argument: a round value from 0 to 1e4, or any from 1e-6 to 1e4.
    pub fn magnitude(&mut self) -> f64 {
        const ROUND: [f64; 13] = [
            0.0, 1e-6, 1e-4, 0.01, 0.1, 0.3, 0.5, 1.0, 1.5, 2.0, 7.0, 100.0, 1e4,
        ];
        match self.below(2) {
            0 => f32x(ROUND[self.below(ROUND.len())]),
            _ => self.log_uniform(-6.0, 4.0),
        }
    }
}

/// `x` rounded to the nearest f32 (so that the GPU receives exactly what the CPU evaluates).
pub fn f32x(x: f64) -> f64 {
    x as f32 as f64
}

/// The points a scene is evaluated at: wide ones (each coordinate ±10^[−6, 4)), ordinary ones
/// in [−3, 3]³, ones near the origin (±10^[−6, −2)), mixtures with zero coordinates, and some
/// at up to twice `size` from the origin in a random direction (near a primitive's surface);
/// plus the origin, the unit axes and the corners of the range. All exact in f32.
pub fn points(r: &mut Rng, size: f64) -> Vec<DVec3> {
    let mut v: Vec<DVec3> = [
        DVec3::ZERO,
        DVec3::X,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::new(-1e4, 1e4, -1e4),
        DVec3::new(1e-6, -1e-6, 1e-6),
    ]
    .map(|p| p.to_array().map(f32x).into())
    .into();
    while v.len() < POINTS {
        let coordinate = |r: &mut Rng, kind: usize| match kind {
            0 => r.sign() * r.log_uniform(-6.0, 4.0),
            1 => f32x(6.0 * r.unit() - 3.0),
            2 => r.sign() * r.log_uniform(-6.0, -2.0),
            _ => 0.0,
        };
        let p = match r.below(20) {
            0..=6 => DVec3::new(coordinate(r, 0), coordinate(r, 0), coordinate(r, 0)),
            7..=11 => DVec3::new(coordinate(r, 1), coordinate(r, 1), coordinate(r, 1)),
            12..=13 => DVec3::new(coordinate(r, 2), coordinate(r, 2), coordinate(r, 2)),
            14..=16 => {
                let k = [r.below(4), r.below(4), r.below(4)];
                DVec3::new(
                    coordinate(r, k[0]),
                    coordinate(r, k[1]),
                    coordinate(r, k[2]),
                )
            }
            _ => {
                let d = DVec3::new(r.unit() - 0.5, r.unit() - 0.5, r.unit() - 0.5);
                let d = d.try_normalize().unwrap_or(DVec3::X);
                (d * size * 2.0 * r.unit()).to_array().map(f32x).into()
            }
        };
        v.push(p);
    }
    v
}

/// A number of type `ty` for a primitive's argument, exact in f32.
pub fn number_value(r: &mut Rng, ty: Ty) -> f64 {
    let m = r.magnitude();
    match ty {
        Ty::Number => r.sign() * m,
        Ty::Positive | Ty::Scale if m == 0.0 => 0.5,
        Ty::Fraction => f32x(r.unit()),
        Ty::Count => 1.0 + r.below(6) as f64,
        Ty::CountTo(n) => 1.0 + r.below(n as usize) as f64,
        Ty::WholeIn(lo, hi) => f64::from(lo) + r.below((hi - lo + 1) as usize) as f64,
        Ty::UpTo(n) => r.below(n as usize + 1) as f64,
        Ty::ZeroOrAtLeast(_) if r.below(2) == 0 => 0.0,
        Ty::ZeroOrAtLeast(lo) => f32x(lo.max(m)),
        Ty::Range(lo, hi) => {
            let x = f32x(lo + (hi - lo) * r.unit());
            if x < hi { x } else { lo }
        }
        _ => m,
    }
}

/// A number of type `ty` for a primitive's argument, as source text.
pub fn number(r: &mut Rng, ty: Ty) -> String {
    let x = number_value(r, ty);
    match ty {
        Ty::Angle => format!("{x:e}rad"),
        _ => format!("{x:e}"),
    }
}

/// A value of type `ty` for a primitive's argument, as source text.
pub fn value(r: &mut Rng, ty: Ty) -> String {
    let vector = |r: &mut Rng, inner: Ty| {
        let c: Vec<String> = (0..3).map(|_| number(r, inner)).collect();
        format!("({})", c.join(", "))
    };
    match ty {
        Ty::Vec3 => vector(r, Ty::Number),
        Ty::Size if r.below(2) == 0 => vector(r, Ty::Length),
        Ty::Scale if r.below(2) == 0 => vector(r, Ty::Positive),
        Ty::Counts if r.below(2) == 0 => vector(r, Ty::UpTo(3)),
        Ty::Size => number(r, Ty::Length),
        Ty::Counts => number(r, Ty::UpTo(3)),
        Ty::Axis => match r.below(3) {
            0 => ["x", "y", "z", "-y"][r.below(4)].to_string(),
            _ => loop {
                let v = [(); 3].map(|_| number_value(r, Ty::Number));
                if v.iter().any(|&c| c != 0.0) {
                    break format!("({:e}, {:e}, {:e})", v[0], v[1], v[2]);
                }
            },
        },
        Ty::Color => "#f80".to_string(),
        Ty::PositiveOr(words) | Ty::Word(words) => words[r.below(words.len())].to_string(),
        t => number(r, t),
    }
}
