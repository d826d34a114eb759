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

    /// [`Grid::sample`] for a field with Lipschitz constant `lambda`, evaluated only where the
    /// sign may change: a block of points (an octree over blocks of [`BLOCK`]³ points, on all
    /// cores) whose centre value c has |c| > λ·(half its diagonal + h) has that sign at every
    /// point and every grid neighbour, so no edge touching it crosses the surface; its points
    /// get c. The sign at every point, and the value at every point beside a crossing, are
    /// [`Grid::sample`]'s — all the distance transform reads (`edt.rs`).
    pub fn sample_lipschitz(&self, field: &(dyn Fn(DVec3) -> f64 + Sync), lambda: f64) -> Vec<f64> {
        let starts = |n: usize| (0..n).step_by(BLOCK);
        let blocks: Vec<[usize; 3]> = starts(self.n[2])
            .flat_map(|k| {
                starts(self.n[1]).flat_map(move |j| starts(self.n[0]).map(move |i| [i, j, k]))
            })
            .collect();
        let parts = crate::parallel::par_map(&blocks, |&lo| {
            let hi = [0, 1, 2].map(|a| (lo[a] + BLOCK).min(self.n[a]));
            let mut out = Vec::new();
            self.fill(field, lambda, (lo, hi), &mut out);
            out
        });
        let mut values = vec![0.0; self.len()];
        for (at, v) in parts.into_iter().flatten() {
            values[at] = v;
        }
        values
    }

    /// The points `lo..hi` (per axis, `hi` excluded) with their values into `out`, as
    /// [`Grid::sample_lipschitz`] says.
    fn fill(
        &self,
        field: &(dyn Fn(DVec3) -> f64 + Sync),
        lambda: f64,
        (lo, hi): ([usize; 3], [usize; 3]),
        out: &mut Vec<(usize, f64)>,
    ) {
        let each = |out: &mut Vec<(usize, f64)>, f: &dyn Fn(DVec3) -> f64| {
            for k in lo[2]..hi[2] {
                for j in lo[1]..hi[1] {
                    for i in lo[0]..hi[0] {
                        out.push((self.index(i, j, k), f(self.point(i, j, k))));
                    }
                }
            }
        };
        let span = [0, 1, 2].map(|a| hi[a] - lo[a]);
        if span.iter().product::<usize>() <= 8 {
            return each(out, field);
        }
        let first = self.point(lo[0], lo[1], lo[2]);
        let last = self.point(hi[0] - 1, hi[1] - 1, hi[2] - 1);
        let c = field((first + last) / 2.0);
        let reach = lambda * ((last - first).length() / 2.0 + self.h);
        if c.abs() > reach * (1.0 + 1e-9) {
            return each(out, &|_| c);
        }
        let mid = [0, 1, 2].map(|a| lo[a] + span[a].div_ceil(2));
        let halves = |a: usize| {
            let mut v = vec![(lo[a], mid[a])];
            if mid[a] < hi[a] {
                v.push((mid[a], hi[a]));
            }
            v
        };
        for &(z0, z1) in &halves(2) {
            for &(y0, y1) in &halves(1) {
                for &(x0, x1) in &halves(0) {
                    self.fill(field, lambda, ([x0, y0, z0], [x1, y1, z1]), out);
                }
            }
        }
    }
}

/// Points per axis of [`Grid::sample_lipschitz`]'s blocks.
pub const BLOCK: usize = 16;
