//! Procedural textures (Liktor §4) in f64: the weight w ∈ [0, 1] of each pattern at a point of
//! the shape's own space, the reference the emitted code (`lower/texture.rs`) mirrors
//! operation for operation (the same products by reciprocals, the same integer hash); f32 and
//! f64 then differ by rounding only, and in the lattice cell only where a cell is narrower than
//! f32's spacing at the point.

use crate::scene::{Pattern, PatternKind};
use glam::DVec3;

/// Every pattern: its name in `color NAME(first, second, scale, octaves)`, and what it is.
pub const PATTERNS: &[(&str, PatternKind, &str)] = &[
    (
        "checker",
        PatternKind::Checker,
        "A solid 3D checker of cells `scale` wide.",
    ),
    (
        "tiles",
        PatternKind::Tiles,
        "A 2D checker of cells `scale` wide projected along the three axes, blended by the normal (triplanar).",
    ),
    (
        "noise",
        PatternKind::Noise,
        "Value noise of feature size `scale`, `octaves` octaves summed with halving amplitudes.",
    ),
    (
        "turbulence",
        PatternKind::Turbulence,
        "Perlin's turbulence: |2·noise − 1| summed over `octaves` octaves.",
    ),
    (
        "marble",
        PatternKind::Marble,
        "Bands along x, `scale` apart, bent by turbulence: 0.5 + 0.5·sin(2π·x/scale + 6·turbulence).",
    ),
    (
        "wood",
        PatternKind::Wood,
        "Rings around the y axis, `scale` apart, bent by noise: 0.5 + 0.5·sin(2π·(r/scale + 0.4·noise)).",
    ),
];

/// Most octaves of noise a pattern sums.
pub const MAX_OCTAVES: u32 = 8;

/// How far along the normal the second sample for a triplanar pattern's own-space normal lies,
/// relative to the pattern's scale (at least [`NORMAL_STEP_FLOOR`] of the point's distance from
/// the origin, which f32 resolves).
pub const NORMAL_STEP: f64 = 0.01;

/// The least step for a triplanar normal, relative to |p| (2⁻¹⁰: well above f32's 2⁻²³).
pub const NORMAL_STEP_FLOOR: f64 = 1.0 / 1024.0;

/// The noise lattice repeats every this many cells along each axis: lattice coordinates are
/// taken modulo it before they become integers, so they never leave the i32 range (and f32
/// and f64 agree on them while a cell is wider than f32's spacing at the point).
pub const LATTICE_PERIOD: f64 = 65536.0;

/// The step along the normal `n` at `p` for a triplanar pattern of scale `scale`.
pub fn normal_step(p: DVec3, scale: f64) -> f64 {
    (NORMAL_STEP * scale).max(NORMAL_STEP_FLOOR * p.length())
}

/// A lattice point's pseudo-random value in [0, 1): an integer hash of its coordinates (u32
/// arithmetic, so the shader computes the same bits), its top 24 bits over 2²⁴ (exact in f32).
pub fn hash(i: [i32; 3]) -> f64 {
    let mut h = (i[0] as u32).wrapping_mul(0x8da6_b343)
        ^ (i[1] as u32).wrapping_mul(0xd816_3841)
        ^ (i[2] as u32).wrapping_mul(0xcb1a_b31f);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    (h >> 8) as f64 / 16_777_216.0
}

/// Value noise in [0, 1): the lattice values around `q` interpolated with smoothstep weights.
pub fn noise(q: DVec3) -> f64 {
    let i = q.floor();
    let f = q - i;
    let u = f * f * (DVec3::splat(3.0) - 2.0 * f);
    // The lattice cell modulo the period: 0 ≤ c < 65536, whatever q.
    let cell = i - LATTICE_PERIOD * (i * (1.0 / LATTICE_PERIOD)).floor();
    let c = [cell.x as i32, cell.y as i32, cell.z as i32];
    let at = |dx: i32, dy: i32, dz: i32| hash([c[0] + dx, c[1] + dy, c[2] + dz]);
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let x00 = lerp(at(0, 0, 0), at(1, 0, 0), u.x);
    let x10 = lerp(at(0, 1, 0), at(1, 1, 0), u.x);
    let x01 = lerp(at(0, 0, 1), at(1, 0, 1), u.x);
    let x11 = lerp(at(0, 1, 1), at(1, 1, 1), u.x);
    lerp(lerp(x00, x10, u.y), lerp(x01, x11, u.y), u.z)
}

/// `octaves` octaves of `layer(noise)` at doubling frequencies and halving amplitudes,
/// normalised to [0, 1].
fn octaves(q: DVec3, octaves: u32, layer: impl Fn(f64) -> f64) -> f64 {
    let (mut sum, mut total, mut a, mut f) = (0.0, 0.0, 1.0, 1.0);
    for _ in 0..octaves {
        sum += a * layer(noise(q * f));
        total += a;
        a *= 0.5;
        f *= 2.0;
    }
    sum * (1.0 / total)
}

/// Fractal noise in [0, 1].
pub fn fbm(q: DVec3, n: u32) -> f64 {
    octaves(q, n, |v| v)
}

/// Turbulence in [0, 1].
pub fn turbulence(q: DVec3, n: u32) -> f64 {
    octaves(q, n, |v| (2.0 * v - 1.0).abs())
}

/// 1 on odd cells of the checker of cell size `s` in the given coordinates, else 0.
fn parity(coords: &[f64], s: f64) -> f64 {
    let inv = 1.0 / s;
    let sum: f64 = coords.iter().map(|c| (c * inv).floor()).sum();
    sum - 2.0 * (sum * 0.5).floor()
}

/// The pattern's weight at `q` (the shape's own coordinates), `nq` its normal there (for
/// triplanar projection).
pub fn weight(pattern: &Pattern, q: DVec3, nq: DVec3) -> f64 {
    let s = pattern.scale;
    let inv = 1.0 / s;
    let qs = q * inv;
    let k = pattern.octaves;
    match pattern.kind {
        PatternKind::Checker => parity(&[q.x, q.y, q.z], s),
        PatternKind::Tiles => {
            // Each axis's plane weighted by the normal's component to the fourth.
            let a = nq.abs();
            let w = a * a * a * a;
            let planes = [
                parity(&[q.y, q.z], s),
                parity(&[q.x, q.z], s),
                parity(&[q.x, q.y], s),
            ];
            let total = w.x + w.y + w.z;
            if total > 0.0 {
                (w.x * planes[0] + w.y * planes[1] + w.z * planes[2]) / total
            } else {
                planes[1]
            }
        }
        PatternKind::Noise => fbm(qs, k),
        PatternKind::Turbulence => turbulence(qs, k),
        PatternKind::Marble => {
            let t = turbulence(qs, k);
            0.5 + 0.5 * (std::f64::consts::TAU * q.x * inv + 6.0 * t).sin()
        }
        PatternKind::Wood => {
            let r = (q.x * q.x + q.z * q.z).sqrt() * inv;
            let n = fbm(qs, k);
            0.5 + 0.5 * (std::f64::consts::TAU * (r + 0.4 * n)).sin()
        }
    }
}
