//! The grid a part is baked on: a box, one spacing for every axis, and its points sampled.

use glam::DVec3;

/// Points at `lo + (i, j, k)·h` for i < n[0], j < n[1], k < n[2]; `hi` is the last point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// The first point (the box's lowest corner).
    pub lo: DVec3,
    /// The last point (the box's highest corner).
    pub hi: DVec3,
    /// The spacing, the same along every axis.
    pub h: f64,
    /// Points per axis (at least 2).
    pub n: [usize; 3],
}

impl Grid {
    /// The grid over `lo`..`hi` grown by [`super::MARGIN_CELLS`] cells on every side, with
    /// `res` points along the longest side (at least 4) and as many at the same spacing on the
    /// others.
    pub fn around(lo: DVec3, hi: DVec3, res: usize) -> Grid {
        let res = res.clamp(super::MIN_RES, super::MAX_RES);
        let size = (hi - lo).max(DVec3::splat(1e-9));
        // h·(res − 1) = longest side + 2·margin·h.
        let h = size.max_element() / (res as f64 - 1.0 - 2.0 * super::MARGIN_CELLS);
        let centre = (lo + hi) / 2.0;
        let n = size.to_array().map(|s| {
            let cells = (s / h + 2.0 * super::MARGIN_CELLS).ceil() as usize;
            (cells + 1).clamp(2, res)
        });
        let extent = DVec3::new((n[0] - 1) as f64, (n[1] - 1) as f64, (n[2] - 1) as f64) * h;
        Grid {
            lo: centre - extent / 2.0,
            hi: centre + extent / 2.0,
            h,
            n,
        }
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.n[0] * self.n[1] * self.n[2]
    }

    /// Whether it has no points (never: at least 2 per axis).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The index of point `(i, j, k)` (x fastest).
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.n[0] * (j + self.n[1] * k)
    }

    /// The position of point `(i, j, k)`.
    pub fn point(&self, i: usize, j: usize, k: usize) -> DVec3 {
        self.lo + DVec3::new(i as f64, j as f64, k as f64) * self.h
    }

    /// `field` at every point, in index order (on all cores, a z-slice each).
    pub fn sample(&self, field: &(dyn Fn(DVec3) -> f64 + Sync)) -> Vec<f64> {
        let slices: Vec<usize> = (0..self.n[2]).collect();
        crate::parallel::par_map(&slices, |&k| {
            let mut out = Vec::with_capacity(self.n[0] * self.n[1]);
            for j in 0..self.n[1] {
                for i in 0..self.n[0] {
                    out.push(field(self.point(i, j, k)));
                }
            }
            out
        })
        .concat()
    }
}
