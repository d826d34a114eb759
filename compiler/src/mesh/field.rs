//! The field the mesher contours: the scene's distance bound clipped to the box being meshed,
//! so that a cut part is capped and the mesh stays closed; and the grid of cells over the box.

use crate::reference::eval;
use crate::scene::Scene;
use glam::{DVec3, IVec3};

/// The scene's f/λ intersected with a box: max(f/λ, box distance). Both are 1-Lipschitz, so
/// the maximum is too, and |d(c)| > r proves that no surface crosses the ball of radius r at c.
pub struct Field<'a> {
    scene: &'a Scene,
    lo: DVec3,
    hi: DVec3,
}

impl<'a> Field<'a> {
    /// The scene's field clipped to the box from `lo` to `hi`.
    pub fn new(scene: &'a Scene, lo: DVec3, hi: DVec3) -> Field<'a> {
        Field { scene, lo, hi }
    }

    /// The clipped distance bound at `p` (NaN counts as outside where it is read).
    pub fn at(&self, p: DVec3) -> f64 {
        let centre = 0.5 * (self.lo + self.hi);
        let outside = crate::catalog::primitives::sd_box(p - centre, 0.5 * (self.hi - self.lo));
        eval::distance(self.scene, p).max(outside)
    }

    /// The field's unit gradient at `p` from the four samples of `eval::TETRAHEDRON` at
    /// distance `h`; zero where it vanishes.
    pub fn normal(&self, p: DVec3, h: f64) -> DVec3 {
        eval::unit_gradient(|q| self.at(q), p, h)
    }
}

/// Whether a field value counts as inside (NaN and 0 count as outside, so every value has
/// one side and the two cells at a face agree).
pub fn inside(d: f64) -> bool {
    d < 0.0
}

/// Corner `i` (0..8) of a cell (or of an octree block of side 1), relative to its lowest.
pub fn corner(i: i32) -> IVec3 {
    IVec3::new(i & 1, (i >> 1) & 1, i >> 2)
}

/// A regular grid of cubic cells: cell (i, j, k) spans origin + h·[i, i+1] × … .
#[derive(Clone, Copy, Debug)]
pub struct Grid {
    /// The lowest corner of cell (0, 0, 0).
    pub origin: DVec3,
    /// The cells' edge length.
    pub h: f64,
    /// Cells along each axis.
    pub n: IVec3,
}

/// How far the grid is shifted off the box, in cells: a fraction no round coordinate shares,
/// so that a plane at a round height (a floor at y = 0) does not pass exactly through corners.
const SHIFT: DVec3 = DVec3::new(0.013_1, 0.017_3, 0.010_9);

impl Grid {
    /// A grid of `resolution` cells along the box's longest side, one more cell and a little
    /// around it (the clipped field's surface lies inside).
    pub fn over(lo: DVec3, hi: DVec3, resolution: u32) -> Grid {
        let size = hi - lo;
        let h = size.max_element() / resolution as f64;
        let origin = lo - h * (DVec3::ONE + SHIFT);
        let n = ((size / h) + 2.0 + 2.0 * SHIFT).ceil().as_ivec3();
        Grid { origin, h, n }
    }

    /// The position of grid point `c` (a cell's lowest corner).
    pub fn point(&self, c: IVec3) -> DVec3 {
        self.origin + c.as_dvec3() * self.h
    }

    /// A key for grid point `c` (0 ≤ c ≤ n), unique over the grid.
    pub fn key(&self, c: IVec3) -> u64 {
        let m = self.n.as_u64vec3() + 1;
        c.x as u64 + m.x * (c.y as u64 + m.y * c.z as u64)
    }
}
