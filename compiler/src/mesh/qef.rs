//! Where a cell's vertex goes: the point nearest every tangent plane of its surface sheet (the
//! quadratic error function of dual contouring, Ju et al. 2002 §2.3), solved by hand with a
//! 3×3 Jacobi eigendecomposition (no linear-algebra crate needed for one small matrix).

use glam::{DMat3, DVec3};

/// Eigenvalues below this fraction of the largest are dropped (a flat or creased sheet leaves
/// one or two directions free; the mass point decides those). Ju et al. truncate singular
/// values below 0.1 of the largest: eigenvalues of AᵀA are their squares.
const TRUNCATE: f64 = 0.01;

/// What [`solve`] finds.
#[derive(Clone, Copy, Debug)]
pub struct Solution {
    /// The point.
    pub point: DVec3,
    /// Where the planes leave exactly one direction free (a crease), that direction: every
    /// point of the line through `point` along it is as good.
    pub crease: Option<DVec3>,
    /// Whether the planes leave no direction free (three independent normals): `point` is
    /// then their one common point, a corner.
    pub corner: bool,
}

/// The point minimising Σ (nᵢ·(x − pᵢ))² over the sheet's surface points `pᵢ` and unit normals
/// `nᵢ`, nearest `mass` among the minimisers (the pseudo-inverse around the mass point). A
/// corner where three planes meet is found exactly, a crease's line is kept and the point
/// slides along it to the mass point, a flat sheet gives the mass point.
pub fn solve(points: &[(DVec3, DVec3)], mass: DVec3) -> Solution {
    let mut ata = DMat3::ZERO;
    let mut atb = DVec3::ZERO;
    for &(p, n) in points {
        if !n.is_finite() || n == DVec3::ZERO {
            continue;
        }
        // Rows nᵀ with right-hand side n·(p − mass): solve for x − mass.
        ata += outer(n, n);
        atb += n * n.dot(p - mass);
    }
    let (values, vectors) = eigen(ata);
    let largest = values.abs().max_element();
    let mut x = DVec3::ZERO;
    // The directions left free: how many, and the last.
    let (mut free, mut along) = (0, DVec3::ZERO);
    for i in 0..3 {
        let v = vectors.col(i);
        if largest > 0.0 && values[i].abs() > TRUNCATE * largest {
            x += v * (v.dot(atb) / values[i]);
        } else {
            (free, along) = (free + 1, v);
        }
    }
    Solution {
        point: mass + x,
        crease: (free == 1).then_some(along),
        corner: free == 0,
    }
}

/// The matrix a·bᵀ.
fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// Eigenvalues and eigenvectors (columns) of a symmetric 3×3 matrix by cyclic Jacobi rotations.
fn eigen(m: DMat3) -> (DVec3, DMat3) {
    let mut a = m.to_cols_array_2d();
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..32 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        if off < 1e-30 * (a[0][0].powi(2) + a[1][1].powi(2) + a[2][2].powi(2)) || off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            rotate(&mut a, &mut v, p, q, c, s);
        }
    }
    let values = DVec3::new(a[0][0], a[1][1], a[2][2]);
    // `v` holds the eigenvectors as its columns in column-major order.
    (values, DMat3::from_cols_array_2d(&v))
}

/// One Jacobi rotation in the (p, q) plane: A ← JᵀAJ, V ← VJ (arrays are column-major).
#[allow(clippy::needless_range_loop)] // (Rows and columns by index read as the formulas do.)
fn rotate(a: &mut [[f64; 3]; 3], v: &mut [[f64; 3]; 3], p: usize, q: usize, c: f64, s: f64) {
    for k in 0..3 {
        let (akp, akq) = (a[p][k], a[q][k]);
        a[p][k] = c * akp - s * akq;
        a[q][k] = s * akp + c * akq;
    }
    for k in 0..3 {
        let (apk, aqk) = (a[k][p], a[k][q]);
        a[k][p] = c * apk - s * aqk;
        a[k][q] = s * apk + c * aqk;
    }
    for row in 0..3 {
        let (vp, vq) = (v[p][row], v[q][row]);
        v[p][row] = c * vp - s * vq;
        v[q][row] = s * vp + c * vq;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mean(points: &[(DVec3, DVec3)]) -> DVec3 {
        points.iter().map(|p| p.0).sum::<DVec3>() / points.len() as f64
    }

    #[test]
    fn eigen_reconstructs_a_symmetric_matrix() {
        let m = DMat3::from_cols(
            DVec3::new(4.0, 1.0, -2.0),
            DVec3::new(1.0, 3.0, 0.5),
            DVec3::new(-2.0, 0.5, 1.0),
        );
        let (values, vectors) = eigen(m);
        let back = vectors * DMat3::from_diagonal(values) * vectors.transpose();
        assert!((back - m).abs_diff_eq(DMat3::ZERO, 1e-12), "{back:?}");
        let ortho = vectors.transpose() * vectors;
        assert!(ortho.abs_diff_eq(DMat3::IDENTITY, 1e-12));
    }

    #[test]
    fn three_planes_meet_at_their_corner() {
        let corner = DVec3::new(0.3, -0.2, 0.7);
        let points = [
            (corner + DVec3::new(0.0, 0.1, 0.05), DVec3::X),
            (corner + DVec3::new(0.08, 0.0, 0.02), DVec3::Y),
            (corner + DVec3::new(0.01, 0.04, 0.0), DVec3::Z),
            (corner + DVec3::new(0.0, 0.02, 0.09), DVec3::X),
        ];
        let found = solve(&points, mean(&points));
        assert!(found.point.abs_diff_eq(corner, 1e-12) && found.crease.is_none() && found.corner);
    }

    #[test]
    fn a_crease_keeps_its_line_and_a_plane_its_mean() {
        let n1 = DVec3::new(1.0, 1.0, 0.0).normalize();
        let n2 = DVec3::new(-1.0, 1.0, 0.0).normalize();
        // Two planes through the z axis at y = 1: the crease is (0, 1, z).
        let on = |x: f64, z: f64| DVec3::new(x, 1.0 - x.abs(), z);
        let pts = [(on(0.2, 0.1), n1), (on(-0.3, 0.5), n2)];
        let found = solve(&pts, mean(&pts));
        let x = found.point;
        assert!(
            found
                .crease
                .is_some_and(|d| d.cross(DVec3::Z).length() < 1e-12)
        );
        assert!((x.x).abs() < 1e-12 && (x.y - 1.0).abs() < 1e-12, "{x}");
        assert!((x.z - 0.3).abs() < 1e-12);
        let pts = [(DVec3::new(0.0, 0.0, 0.0), DVec3::Y), (DVec3::X, DVec3::Y)];
        let flat = solve(&pts, mean(&pts)).point;
        assert!(flat.abs_diff_eq(DVec3::new(0.5, 0.0, 0.0), 1e-12));
    }
}
