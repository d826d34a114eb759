//! Distance maps (Liktor §3): a part's field sampled on a grid, turned into Euclidean distances
//! to the surface by vector propagation, and read back by trilinear interpolation.

pub mod cache;
mod edt;
pub mod file;
mod grid;

pub use grid::Grid;

use glam::DVec3;

/// Most grid points per axis (a 512³ volume of f32 is 512 MiB).
pub const MAX_RES: usize = 512;

/// The baking method's version, part of every cache key: a volume stored by an earlier method
/// is not read back as this one's.
pub const VERSION: u32 = 3;

/// Fewest grid points per axis: the margin's cells on both sides and two cells for the shape.
pub const MIN_RES: usize = 2 * MARGIN_CELLS as usize + 3;

/// Points per side when `bake` is not given `res`.
pub const DEFAULT_RES: usize = 64;

/// Bytes baking holds per grid point: the sample (8), the nearest surface point and its squared
/// distance (40), the distance (8) and the stored value (4), rounded up.
pub const BYTES_PER_POINT: u64 = 64;

/// Most bytes one bake may hold ([`BYTES_PER_POINT`] per point): 2 GiB, about 330 points on
/// every side of a cube.
pub const MAX_BYTES: u64 = 2 << 30;

/// Most evaluations of primitives sampling one bake may cost (grid points × the shape's
/// evaluations per point; the surface's points cost about forty more each): a blob of 300
/// balls at 128 points per side is 6e8 and bakes in about 10 s on two cores.
pub const MAX_WORK: f64 = 4e9;

/// The bytes baking `grid` holds while it runs (estimated before any work).
pub fn bytes_to_bake(grid: &Grid) -> u64 {
    grid.len() as u64 * BYTES_PER_POINT
}

/// Cells of margin around the part's bound: the surface stays inside the volume by this many
/// cells, so the interpolant near it never reads the outside rule.
pub const MARGIN_CELLS: f64 = 2.0;

/// A baked distance map: signed distances at the points of a grid, read by trilinear
/// interpolation inside it and by the distance to the grid's box plus the clamped value outside.
#[derive(Clone, PartialEq)]
pub struct Volume {
    /// The grid: its box, spacing and points per axis.
    pub grid: Grid,
    /// Signed distance at each grid point (x fastest, then y, then z), negative inside.
    pub values: Vec<f32>,
    /// A Lipschitz constant of [`Volume::field`], proven from the values (`lambda_of`,
    /// `total_lambda`).
    pub lambda: f64,
}

impl std::fmt::Debug for Volume {
    /// The grid and λ, not the values (millions of numbers in every scene's debug print).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Volume")
            .field("grid", &self.grid)
            .field("values", &self.values.len())
            .field("lambda", &self.lambda)
            .finish()
    }
}

impl Volume {
    /// A volume of stored values on `grid` (as baked, or read back from a file), with its
    /// Lipschitz constant proven from them.
    pub fn from_values(grid: Grid, values: Vec<f32>) -> Volume {
        let lambda = total_lambda(&grid, &values, lambda_of(&grid, &values));
        Volume {
            grid,
            values,
            lambda,
        }
    }

    /// How far outside its box the baked surface may reach: the field outside is v + d where
    /// the boundary value v is negative, so up to −v; 0 when every boundary value is positive.
    pub fn reach_outside(&self) -> f64 {
        let [nx, ny, nz] = self.grid.n;
        let mut least: f64 = 0.0;
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    if i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1 {
                        least = least.min(self.at(i, j, k));
                    }
                }
            }
        }
        -least
    }

    /// Bytes its values take on the GPU (one `f32` per point).
    pub fn bytes(&self) -> u64 {
        4 * self.values.len() as u64
    }

    /// Bakes `field` over the box `lo`..`hi` (grown by [`MARGIN_CELLS`]) with `res` points along
    /// its longest side: the field sampled at every grid point (the sign says inside or
    /// outside, the values place the surface between points), distances propagated from the
    /// surface's crossings on the grid's edges (`edt.rs`).
    pub fn bake(field: &(dyn Fn(DVec3) -> f64 + Sync), lo: DVec3, hi: DVec3, res: usize) -> Volume {
        let grid = Grid::around(lo, hi, res);
        let samples = grid.sample(field);
        Volume::from_samples(grid, &samples, field)
    }

    /// [`Volume::bake`] of a field whose Lipschitz constant is `lambda`: the same volume, with
    /// the field evaluated only near its surface ([`Grid::sample_lipschitz`]).
    pub fn bake_lipschitz(
        field: &(dyn Fn(DVec3) -> f64 + Sync),
        lambda: f64,
        lo: DVec3,
        hi: DVec3,
        res: usize,
    ) -> Volume {
        let grid = Grid::around(lo, hi, res);
        let samples = grid.sample_lipschitz(field, lambda);
        Volume::from_samples(grid, &samples, field)
    }

    /// The volume of `samples` (the field at `grid`'s points, in index order: any positive
    /// multiple of it) on `grid`: distances propagated from the surface's crossings, the feet
    /// found with `field` itself.
    pub fn from_samples(
        grid: Grid,
        samples: &[f64],
        field: &(dyn Fn(DVec3) -> f64 + Sync),
    ) -> Volume {
        let values: Vec<f32> = edt::signed_distances(&grid, samples, field)
            .into_iter()
            .map(|d| d as f32)
            .collect();
        Volume::from_values(grid, values)
    }

    /// The stored value at grid point `(i, j, k)`.
    fn at(&self, i: usize, j: usize, k: usize) -> f64 {
        f64::from(self.values[self.grid.index(i, j, k)])
    }

    /// The trilinear interpolation of the values at `p` clamped into the box.
    pub fn inside(&self, p: DVec3) -> f64 {
        let g = &self.grid;
        let [nx, ny, nz] = g.n;
        let u = ((p.clamp(g.lo, g.hi) - g.lo) / g.h).to_array();
        let cell = |u: f64, n: usize| (u.floor().max(0.0) as usize).min(n - 2);
        let (i, j, k) = (cell(u[0], nx), cell(u[1], ny), cell(u[2], nz));
        let (tx, ty, tz) = (u[0] - i as f64, u[1] - j as f64, u[2] - k as f64);
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        let x00 = lerp(self.at(i, j, k), self.at(i + 1, j, k), tx);
        let x10 = lerp(self.at(i, j + 1, k), self.at(i + 1, j + 1, k), tx);
        let x01 = lerp(self.at(i, j, k + 1), self.at(i + 1, j, k + 1), tx);
        let x11 = lerp(self.at(i, j + 1, k + 1), self.at(i + 1, j + 1, k + 1), tx);
        lerp(lerp(x00, x10, ty), lerp(x01, x11, ty), tz)
    }

    /// The baked field: inside the box the interpolated distance; outside it, with d the
    /// distance to the box and v the interpolated value at the nearest point of the box,
    /// √(d² + v²) where v > 0 and v + d elsewhere (both continuous across the box's faces).
    pub fn field(&self, p: DVec3) -> f64 {
        let g = &self.grid;
        let d = (p - p.clamp(g.lo, g.hi)).length();
        let v = self.inside(p);
        if d == 0.0 {
            v
        } else if v > 0.0 {
            (d * d + v * v).sqrt()
        } else {
            v + d
        }
    }
}

/// The Lipschitz constant of [`Volume::field`] given the interpolant's, `inner`: outside the
/// box d's gradient is normal to the face, edge or corner region it is in, and v's (through the
/// projection onto the box) lies in its tangent space, so the two are orthogonal: √(d² + v²)
/// has |∇|² = (d² + v²|∇v|²)/(d² + v²) ≤ max(1, inner²), and v + d has |∇|² ≤ 1 + inner². The
/// first holds everywhere outside when every value on the box's boundary is positive (the
/// interpolant on a face is bilinear in them, so it is positive on the whole boundary).
fn total_lambda(grid: &Grid, values: &[f32], inner: f64) -> f64 {
    let [nx, ny, nz] = grid.n;
    let on_boundary = |i: usize, j: usize, k: usize| {
        i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1
    };
    let positive = (0..nz).all(|k| {
        (0..ny).all(|j| (0..nx).all(|i| !on_boundary(i, j, k) || values[grid.index(i, j, k)] > 0.0))
    });
    if positive {
        inner.max(1.0)
    } else {
        (1.0 + inner * inner).sqrt()
    }
}

/// A Lipschitz constant of the trilinear interpolant of `values` on `grid`: within a cell,
/// ∂F/∂x is the bilinear interpolation (in y and z) of the cell's four x-edge differences over
/// h, so its largest magnitude is the largest of those four; likewise for y and z. |∇F| is then
/// at most √(mx² + my² + mz²) in that cell, and the constant is the largest over the cells. (For
/// exact distances each edge difference is at most h, so at most √3; in practice about 1.)
pub fn lambda_of(grid: &Grid, values: &[f32]) -> f64 {
    let [nx, ny, nz] = grid.n;
    let v = |i: usize, j: usize, k: usize| f64::from(values[grid.index(i, j, k)]);
    let mut worst: f64 = 0.0;
    for k in 0..nz - 1 {
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let mut m = [0.0f64; 3];
                for a in 0..2 {
                    for b in 0..2 {
                        m[0] = m[0].max((v(i + 1, j + a, k + b) - v(i, j + a, k + b)).abs());
                        m[1] = m[1].max((v(i + a, j + 1, k + b) - v(i + a, j, k + b)).abs());
                        m[2] = m[2].max((v(i + a, j + b, k + 1) - v(i + a, j + b, k)).abs());
                    }
                }
                worst = worst.max((m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt());
            }
        }
    }
    worst / grid.h
}
