//! Triangle meshes of a scene's surface: the cells the field's bound cannot rule out, one
//! polygon per surface sheet in each, sharp corners and creases from the gradients, on all cores.
//!
//! The steps: `cells` (an octree pruned by |f/λ| > half-diagonal), `contour` (corners,
//! crossings, `faces`' segments, polygons fanned around a `qef` vertex — or drawn as their
//! faces where a cell holds several corners, `facets`), then materials per
//! triangle; `measure` says how far the mesh is from the surface and whether it is closed and
//! manifold, `formats` writes STL, OBJ, PLY and glTF.

mod bends;
mod cells;
mod contour;
mod corners;
mod creases;
mod edge_search;
mod edges;
mod faces;
mod facets;
pub mod field;
pub mod formats;
pub mod measure;
mod plans;
mod polygons;
mod qef;
mod search;
mod settle;
mod trace;
mod walk;

use crate::parallel::par_map;
use crate::reference::eval;
use crate::scene::Scene;
use field::{Field, Grid};
use glam::DVec3;

/// What to mesh and how.
#[derive(Clone, Debug)]
pub struct Options {
    /// Cells along the longest side of the box: the cell is that side over it, so it need not
    /// be whole (a cell size asked for, a triangle count aimed at).
    pub resolution: f64,
    /// The box meshed (lowest and highest corner); the surface is clipped to it and capped.
    pub bounds: (DVec3, DVec3),
    /// Place each polygon's vertex by the QEF and add the faces' sharp points (corners and
    /// creases stay sharp); without, the vertex is the mean of the crossings (marching cubes'
    /// chamfer: the baseline the sharp method is measured against).
    pub sharp: bool,
    /// Drop the blocks the field's bound proves empty (the octree); without, every cell of the
    /// grid is contoured (the brute-force baseline the pruning is measured against).
    pub prune: bool,
    /// Refuse, as soon as the octree's coarse levels show it, a mesh whose estimated memory
    /// exceeds this many bytes.
    pub max_bytes: u64,
}

/// The largest resolution accepted (grid points must have 64-bit keys, and a grid this fine is
/// past any memory anyway).
pub const MAX_RESOLUTION: u32 = 65_536;

/// Bytes a mesh costs per active cell, from measurement (a ball at 1 000 cells a side: 5.2
/// million cells, a peak of 4.7 GiB with the STL written): the corner, crossing and face
/// tables, about 1.7 vertices and 3.5 triangles, the file's bytes.
const BYTES_PER_CELL: u64 = 1000;

/// Active cells expected per side² of an active block (a flat sheet crosses about side² of its
/// side³ cells, a block near it but not crossed holds none, the pruning's margin adds some).
const CELLS_PER_AREA: u64 = 2;

/// A triangle mesh with a material per triangle.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Each triangle's material id (0 the default, i + 1 the scene's i-th material).
    pub materials: Vec<u32>,
    /// What making it cost.
    pub stats: Stats,
}

/// What meshing cost.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    /// The cells' edge length.
    pub cell: f64,
    /// Cells along each axis.
    pub grid: [i32; 3],
    /// Cells along the box's longest side (the resolution asked for).
    pub resolution: f64,
    /// Cells the surface may cross (the rest were pruned by the bound).
    pub active_cells: usize,
    /// Cells the surface crosses that the bound had pruned, added back so that the mesh stays
    /// closed (0 where every bound holds).
    pub added_cells: usize,
    /// Field evaluations, all steps.
    pub evaluations: usize,
    /// Cells whose polygons did not close (see `contour::Contour::broken`).
    pub broken_cells: usize,
    /// Grid edges the surface crosses twice (a crease or a thin part between their ends).
    pub dipped_edges: usize,
}

/// Why a mesh was not made.
#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// The resolution is below 1, above [`MAX_RESOLUTION`] or not a number.
    Resolution(f64),
    /// The box is empty, inverted or not finite.
    Bounds,
    /// The estimated memory passes the limit: (estimate, limit) in bytes.
    Memory(u64, u64),
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Error::Resolution(r) => write!(
                f,
                "the resolution {r} is out of range: give 1 to {MAX_RESOLUTION} cells"
            ),
            Error::Bounds => write!(f, "the box to mesh is empty or not finite"),
            Error::Memory(need, limit) => write!(
                f,
                "the mesh would need about {} of memory, past the limit of {}: give a lower \
                 resolution (the memory grows with its square)",
                gib(*need),
                gib(*limit)
            ),
        }
    }
}

/// Bytes in GiB, for messages.
fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// The scene's own finite box, if it has one.
pub fn scene_bounds(scene: &Scene) -> Option<(DVec3, DVec3)> {
    let b = scene.root_node().bound;
    (b.lo.is_finite() && b.hi.is_finite()).then_some((b.lo, b.hi))
}

/// Meshes the surface of `scene` inside `options.bounds` on the CPU; `stage` is told what runs
/// next.
pub fn mesh(scene: &Scene, options: &Options, stage: &dyn Fn(&str)) -> Result<Mesh, Error> {
    mesh_with(scene, options, None, stage)
}

/// [`mesh`] with the field's batches evaluated by `evaluator` where one is given (the GPU);
/// the faces' few searches and the materials stay on the CPU.
pub fn mesh_with(
    scene: &Scene,
    options: &Options,
    evaluator: Option<&dyn field::Evaluator>,
    stage: &dyn Fn(&str),
) -> Result<Mesh, Error> {
    if !(options.resolution >= 1.0 && options.resolution <= f64::from(MAX_RESOLUTION)) {
        return Err(Error::Resolution(options.resolution));
    }
    let (lo, hi) = options.bounds;
    if !(lo.is_finite() && hi.is_finite() && lo.cmplt(hi).all()) {
        return Err(Error::Bounds);
    }
    let field = Field::new(scene, lo, hi).with_evaluator(evaluator);
    let grid = Grid::over(lo, hi, options.resolution);
    stage("finding the cells the surface crosses");
    // The memory `cells` cells would need, refused past the limit.
    let fits = |cells: u64| {
        let need = cells.saturating_mul(BYTES_PER_CELL);
        if need > options.max_bytes {
            Err(Error::Memory(need, options.max_bytes))
        } else {
            Ok(())
        }
    };
    let active = if !options.prune {
        let n = grid.n.as_u64vec3();
        fits(n.x * n.y * n.z)?;
        cells::every(&grid)
    } else {
        cells::active(&field, &grid, |blocks, side| {
            fits((blocks as u64).saturating_mul((side as u64).pow(2) * CELLS_PER_AREA))
        })?
    };
    stage("contouring");
    let c = contour::contour(&field, &grid, &active.cells, options.sharp);
    stage("materials");
    let materials = par_map(&c.triangles, |t| {
        let centroid = t.iter().map(|&v| c.positions[v as usize]).sum::<DVec3>() / 3.0;
        eval::surface(scene, centroid).0
    });
    Ok(Mesh {
        stats: Stats {
            cell: grid.h,
            grid: grid.n.to_array(),
            resolution: options.resolution,
            active_cells: active.cells.len(),
            added_cells: c.added,
            evaluations: active.evaluations + c.evaluations + c.triangles.len(),
            broken_cells: c.broken,
            dipped_edges: c.dipped,
        },
        positions: c.positions,
        triangles: c.triangles,
        materials,
    })
}
