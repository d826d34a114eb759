//! Numbers and point maps that an entry's f64 body and its IR body (`gpu/`) both use, so that
//! the two compute the same thing from one definition.

use glam::DVec3;

/// Rodrigues' rotation of `v` by `angle` about the unit `axis`.
pub fn rotate(v: DVec3, axis: DVec3, angle: f64) -> DVec3 {
    let (s, co) = angle.sin_cos();
    v * co + axis.cross(v) * s + axis * axis.dot(v) * (1.0 - co)
}

/// The steepest slope of [`super::operators::falloff`], reached at s = 1/√5.
pub const FALLOFF_SLOPE: f64 = 1.717_300_316_677_839_6;

/// The six face normals of a dodecahedron: cyclic permutations of (0, ±1, φ), normalised.
pub fn dodecahedron_normals() -> [DVec3; 6] {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let n = |x: f64, y: f64, z: f64| DVec3::new(x, y, z).normalize();
    [
        n(0.0, 1.0, phi),
        n(0.0, -1.0, phi),
        n(1.0, phi, 0.0),
        n(-1.0, phi, 0.0),
        n(phi, 0.0, 1.0),
        n(-phi, 0.0, 1.0),
    ]
}

/// −√3/2, 1/2 and 1/√3: the hexagon's fold direction and its half side over its inradius.
pub const HEX_FOLD: (f64, f64, f64) = (-0.866_025_403_784_438_6, 0.5, 0.577_350_269_189_625_8);

/// Smallest semi-axis the ellipsoid uses: a zero radius is raised to it (a flat disc).
pub const ELLIPSOID_MIN_RADIUS: f64 = 1e-9;

/// Radius beyond which every point escapes: |z|^(n−1) > 2 (then |z₁| ≥ |z|ⁿ − |z| > |z|).
pub fn mandelbulb_radius(power: f64) -> f64 {
    2f64.powf(1.0 / (power - 1.0))
}
