//! The field the mesher contours: the scene's distance bound clipped to the box being meshed,
//! so that a cut part is capped and the mesh stays closed; and the grid of cells over the box.

use crate::parallel::par_map;
use crate::reference::eval;
use crate::scene::Scene;
use glam::{DVec3, IVec3};

/// Evaluates the scene's field (f/λ, the root `map` of the same lowering) at many points at
/// once: the runtime's evaluates it on the GPU in f32.
pub trait Evaluator: Sync {
    /// The field at each of `points`, in order, or `None` when it cannot (the CPU evaluates
    /// them then).
    fn values(&self, points: &[DVec3]) -> Option<Vec<f64>>;
    /// The smallest difference of values or positions it resolves, in scene units (f32's
    /// rounding at the box's largest coordinate): searches stop there instead of at the
    /// CPU's f64 tolerances.
    fn resolution(&self) -> f64;
}

/// The scene's f/λ intersected with a box: max(f/λ, box distance). Both are 1-Lipschitz, so
/// the maximum is too, and |d(c)| > r proves that no surface crosses the ball of radius r at c.
#[derive(Clone, Copy)]
pub struct Field<'a> {
    scene: &'a Scene,
    lo: DVec3,
    hi: DVec3,
    /// Where batches are evaluated, if not on the CPU.
    evaluator: Option<&'a dyn Evaluator>,
}

impl<'a> Field<'a> {
    /// The scene's field clipped to the box from `lo` to `hi`, evaluated on the CPU (f64).
    pub fn new(scene: &'a Scene, lo: DVec3, hi: DVec3) -> Field<'a> {
        Field {
            scene,
            lo,
            hi,
            evaluator: None,
        }
    }

    /// The same field with its batches ([`Field::many`]) evaluated by `evaluator`, if given
    /// (else on the CPU).
    pub fn with_evaluator(self, evaluator: Option<&'a dyn Evaluator>) -> Field<'a> {
        Field { evaluator, ..self }
    }

    /// The same field with its batches on the CPU (for searches of a few points, where a
    /// batch would cost more than it saves).
    pub fn on_cpu(&self) -> Field<'a> {
        Field {
            evaluator: None,
            ..*self
        }
    }

    /// The clipped distance bound at `p` (NaN counts as outside where it is read), on the CPU.
    pub fn at(&self, p: DVec3) -> f64 {
        eval::distance(self.scene, p).max(self.outside(p))
    }

    /// The distance bound of the box at `p` (negative inside it).
    fn outside(&self, p: DVec3) -> f64 {
        let centre = 0.5 * (self.lo + self.hi);
        crate::catalog::primitives::sd_box(p - centre, 0.5 * (self.hi - self.lo))
    }

    /// The clipped field at every one of `points`: by the evaluator if there is one, else on
    /// all cores (each value then equals [`Field::at`]'s).
    pub fn many(&self, points: &[DVec3]) -> Vec<f64> {
        if let Some(values) = self.evaluator.and_then(|e| e.values(points))
            && values.len() == points.len()
        {
            return values
                .into_iter()
                .zip(points)
                .map(|(v, &p)| v.max(self.outside(p)))
                .collect();
        }
        par_map(points, |&p| self.at(p))
    }

    /// Whether batches go to an evaluator (the GPU) rather than the CPU.
    pub fn batched(&self) -> bool {
        self.evaluator.is_some()
    }

    /// The smallest difference the batches resolve (0 on the CPU: its own tolerances hold).
    pub fn resolution(&self) -> f64 {
        self.evaluator.map_or(0.0, |e| e.resolution())
    }

    /// The field's unit gradient at `p` from the four samples of `eval::TETRAHEDRON` at
    /// distance `h`, on the CPU; zero where it vanishes.
    pub fn normal(&self, p: DVec3, h: f64) -> DVec3 {
        eval::unit_gradient(|q| self.at(q), p, h)
    }

    /// The distance between the samples of a gradient for cells of size `h`: 1e-4 of a cell
    /// on the CPU; a hundredth of a cell where the batches are f32 (their values' rounding is
    /// relative to the magnitudes inside the field — a ball of radius 40 rounds at 2.4e-6 —
    /// and the difference of two samples nearer than that is noise, read as false creases).
    pub fn gradient_step(&self, h: f64) -> f64 {
        match self.evaluator {
            None => 1e-4 * h,
            Some(e) => (1e-2 * h).max(30.0 * e.resolution()),
        }
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

/// The index (0..8) of the cell corner at `offset` (each coordinate 0 or 1) from its lowest:
/// [`corner`]'s inverse.
pub fn local(offset: IVec3) -> usize {
    (offset.x + 2 * offset.y + 4 * offset.z) as usize
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
    /// A grid of `resolution` cells along the box's longest side (not always a whole number:
    /// the cell is that side over it), one more cell and a little around it (the clipped
    /// field's surface lies inside).
    pub fn over(lo: DVec3, hi: DVec3, resolution: f64) -> Grid {
        let size = hi - lo;
        let h = size.max_element() / resolution;
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

    /// The grid point whose [`Grid::key`] is `key`.
    pub fn unkey(&self, key: u64) -> IVec3 {
        let m = self.n.as_u64vec3() + 1;
        let (x, yz) = (key % m.x, key / m.x);
        IVec3::new(x as i32, (yz % m.y) as i32, (yz / m.y) as i32)
    }
}

/// A face of the grid: its lowest corner and the axis it is normal to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Face {
    /// The lowest corner.
    pub base: IVec3,
    /// The axis the face is normal to (0, 1, 2).
    pub axis: usize,
}

impl Face {
    /// The two axes spanning the face, in the order that makes them right-handed with its
    /// normal (u × v = the normal).
    pub fn span(self) -> (usize, usize) {
        ((self.axis + 1) % 3, (self.axis + 2) % 3)
    }

    /// The face's four corners, counter-clockwise seen from the normal's positive side.
    pub fn corners(self) -> [IVec3; 4] {
        let (u, v) = self.span();
        let (eu, ev) = (IVec3::AXES[u], IVec3::AXES[v]);
        [
            self.base,
            self.base + eu,
            self.base + eu + ev,
            self.base + ev,
        ]
    }

    /// Face `i` (0..6) of cell `c`, and whether it is the cell's far side along its axis (its
    /// outward normal is then the axis; else the opposite).
    pub fn of_cell(c: IVec3, i: i32) -> (Face, bool) {
        let axis = (i / 2) as usize;
        let far = i % 2 == 1;
        let base = if far { c + IVec3::AXES[axis] } else { c };
        (Face { base, axis }, far)
    }

    /// Its four edges in the same order (edge i from corner i to corner i + 1), each as the
    /// grid edge's lowest end and axis.
    pub fn edges(self) -> [(IVec3, usize); 4] {
        let (u, v) = self.span();
        let c = self.corners();
        [(c[0], u), (c[1], v), (c[3], u), (c[0], v)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`Grid::unkey`] undoes [`Grid::key`] at every corner of a small odd-sized grid, and a
    /// cell's corners come back by [`local`] from [`corner`].
    #[test]
    fn keys_and_corners_come_back() {
        let grid = Grid::over(DVec3::ZERO, DVec3::new(3.0, 2.0, 5.0), 7.3);
        for z in 0..=grid.n.z {
            for y in 0..=grid.n.y {
                for x in 0..=grid.n.x {
                    let p = IVec3::new(x, y, z);
                    assert_eq!(grid.unkey(grid.key(p)), p);
                }
            }
        }
        for i in 0..8 {
            assert_eq!(local(corner(i)), i as usize);
        }
    }
}
