//! What a mesh is worth: whether it is closed, 2-manifold and consistently oriented, its
//! volume, and how far it lies from the surface it stands for.

use super::Mesh;
use super::field::Field;
use crate::parallel::par_map;
use glam::DVec3;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// The mesh's edges by how the triangles use them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Topology {
    /// Undirected edges.
    pub edges: usize,
    /// Edges used by one triangle only (holes).
    pub boundary: usize,
    /// Edges used by more than two triangles.
    pub non_manifold: usize,
    /// Edges two triangles use in the same direction (their orientations disagree).
    pub misoriented: usize,
    /// Triangles with a repeated vertex index.
    pub degenerate: usize,
    /// Vertices whose position, written as f32, another vertex has too (tools that join
    /// vertices by position, as STL readers must, would pinch the mesh there).
    pub shared_positions: usize,
}

impl Topology {
    /// Closed, every edge shared by exactly two triangles in opposite directions, and no two
    /// vertices at one position.
    pub fn is_closed_manifold(&self) -> bool {
        self.boundary == 0
            && self.non_manifold == 0
            && self.misoriented == 0
            && self.shared_positions == 0
    }
}

/// Counts how the triangles of `mesh` use their edges.
pub fn topology(mesh: &Mesh) -> Topology {
    let mut uses: HashMap<(u32, u32), (u32, u32)> =
        HashMap::with_capacity_and_hasher(mesh.triangles.len() * 3 / 2, Default::default());
    let mut degenerate = 0;
    for t in &mesh.triangles {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            degenerate += 1;
            continue;
        }
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = uses.entry((a.min(b), a.max(b))).or_default();
            if a < b {
                e.0 += 1;
            } else {
                e.1 += 1;
            }
        }
    }
    let mut seen = HashSet::with_capacity_and_hasher(mesh.positions.len(), Default::default());
    let shared_positions = mesh
        .positions
        .iter()
        .filter(|p| !seen.insert(p.as_vec3().to_array().map(f32::to_bits)))
        .count();
    let mut top = Topology {
        edges: uses.len(),
        degenerate,
        shared_positions,
        ..Topology::default()
    };
    for &(forward, backward) in uses.values() {
        match forward + backward {
            1 => top.boundary += 1,
            2 if forward != 1 => top.misoriented += 1,
            2 => {}
            _ => top.non_manifold += 1,
        }
    }
    top
}

/// The volume the mesh encloses (the divergence theorem over its triangles; positive for a
/// closed mesh oriented outwards).
pub fn volume(mesh: &Mesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// How far a mesh lies from the surface, in scene units.
#[derive(Clone, Copy, Debug, Default)]
pub struct Deviation {
    /// The largest distance of a vertex to the surface.
    pub vertex_max: f64,
    /// The root mean square of the vertices' distances.
    pub vertex_rms: f64,
    /// The largest distance between a triangle's centroid and the surface point its gradient
    /// leads to (both ways: that surface point is at most this far from the mesh).
    pub face_max: f64,
    /// Their root mean square.
    pub face_rms: f64,
    /// Vertices sampled (all, or an even stride of them).
    pub vertices_sampled: usize,
    /// Triangles sampled (all, or an even stride of them).
    pub faces_sampled: usize,
}

/// The most triangles, and the most vertices, [`deviation`] samples (an even stride of them).
pub const SAMPLES: usize = 50_000;

/// The distance from `p` to the surface of `field` found by Newton steps along the gradient
/// (p − d·∇d), an upper bound on the distance to the surface when they converge; |d| where they
/// do not (a lower bound for a field that is a bound, the distance for an exact one).
fn to_surface(field: &Field, p: DVec3, h: f64) -> f64 {
    let d0 = field.at(p);
    let mut q = p;
    let mut d = d0;
    for _ in 0..8 {
        if d.abs() < 1e-9 * h {
            return (q - p).length();
        }
        let n = field.normal(q, 1e-3 * h);
        if n == DVec3::ZERO {
            break;
        }
        q -= n * d;
        d = field.at(q);
    }
    if d.abs() < 1e-6 * h {
        (q - p).length()
    } else {
        d0.abs()
    }
}

/// The two-sided deviation of `mesh` from the surface of `field`: up to [`SAMPLES`] vertices
/// and the centroids of up to [`SAMPLES`] triangles; `h` is the cell size (sets the tolerances).
pub fn deviation(field: &Field, mesh: &Mesh, h: f64) -> Deviation {
    let stride = mesh.positions.len().div_ceil(SAMPLES).max(1);
    let points: Vec<DVec3> = mesh.positions.iter().step_by(stride).copied().collect();
    let vertices = par_map(&points, |&p| to_surface(field, p, h));
    let stride = mesh.triangles.len().div_ceil(SAMPLES).max(1);
    let sampled: Vec<[u32; 3]> = mesh.triangles.iter().step_by(stride).copied().collect();
    let faces = par_map(&sampled, |t| {
        let c = t.iter().map(|&v| mesh.positions[v as usize]).sum::<DVec3>() / 3.0;
        to_surface(field, c, h)
    });
    let stats = |d: &[f64]| {
        let max = d.iter().copied().fold(0.0, f64::max);
        let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len().max(1) as f64).sqrt();
        (max, rms)
    };
    let (vertex_max, vertex_rms) = stats(&vertices);
    let (face_max, face_rms) = stats(&faces);
    Deviation {
        vertex_max,
        vertex_rms,
        face_max,
        face_rms,
        vertices_sampled: points.len(),
        faces_sampled: sampled.len(),
    }
}
