//! What a mesh is worth: whether it is closed, 2-manifold and consistently oriented, its
//! volume, and how far it lies from the surface it stands for.

use super::Mesh;
use super::field::Field;
use super::search::{self, Search};
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

/// The search for the distance from `p` to the surface by Newton steps along the gradient
/// (p − d·∇d), an upper bound on the distance to the surface when they converge; |d| where they
/// do not (a lower bound for a field that is a bound, the distance for an exact one).
struct Probe {
    /// Where it started and the field there.
    p: DVec3,
    d0: f64,
    /// Where it is and the field there.
    q: DVec3,
    d: f64,
    steps: usize,
    /// Cells' size, the gradient's sample distance and the batches' resolution.
    h: f64,
    step: f64,
    res: f64,
    phase: Phase,
    /// The distance found.
    found: f64,
}

/// What a [`Probe`] asks for next.
#[derive(Clone, Copy)]
enum Phase {
    Value,
    Normal,
    Done,
}

/// The Newton steps a [`Probe`] takes at most.
const PROBE_STEPS: usize = 8;

impl Probe {
    fn new(field: &Field, p: DVec3, h: f64) -> Probe {
        Probe {
            p,
            d0: f64::NAN,
            q: p,
            d: f64::NAN,
            steps: 0,
            h,
            step: (1e-3 * h).max(field.gradient_step(h)),
            res: field.resolution(),
            phase: Phase::Value,
            found: f64::NAN,
        }
    }

    /// Ends the search: the distance travelled if it reached the surface, else |d| at `p`.
    fn end(&mut self) {
        let on = self.d.abs() < (1e-6 * self.h).max(self.res);
        self.found = if on {
            (self.q - self.p).length()
        } else {
            self.d0.abs()
        };
        self.phase = Phase::Done;
    }
}

impl Search for Probe {
    fn ask(&self, points: &mut Vec<DVec3>) {
        match self.phase {
            Phase::Value => points.push(self.q),
            Phase::Normal => search::gradient_points(self.q, self.step, points),
            Phase::Done => {}
        }
    }

    fn tell(&mut self, values: &[f64]) {
        match self.phase {
            Phase::Value => {
                self.d = values[0];
                if self.steps == 0 {
                    self.d0 = self.d;
                }
                if self.d.abs() < (1e-9 * self.h).max(self.res) {
                    self.found = (self.q - self.p).length();
                    self.phase = Phase::Done;
                } else if self.steps == PROBE_STEPS {
                    self.end();
                } else {
                    self.phase = Phase::Normal;
                }
            }
            Phase::Normal => {
                let n = search::unit_gradient(values);
                if n == DVec3::ZERO {
                    self.end();
                } else {
                    self.q -= n * self.d;
                    self.steps += 1;
                    self.phase = Phase::Value;
                }
            }
            Phase::Done => {}
        }
    }
}

/// The two-sided deviation of `mesh` from the surface of `field`: up to [`SAMPLES`] vertices
/// and the centroids of up to [`SAMPLES`] triangles; `h` is the cell size (sets the tolerances).
pub fn deviation(field: &Field, mesh: &Mesh, h: f64) -> Deviation {
    let stride = mesh.positions.len().div_ceil(SAMPLES).max(1);
    let points: Vec<DVec3> = mesh.positions.iter().step_by(stride).copied().collect();
    let stride = mesh.triangles.len().div_ceil(SAMPLES).max(1);
    let sampled: Vec<[u32; 3]> = mesh.triangles.iter().step_by(stride).copied().collect();
    let centroids = sampled
        .iter()
        .map(|t| t.iter().map(|&v| mesh.positions[v as usize]).sum::<DVec3>() / 3.0);
    let mut probes: Vec<Probe> = points
        .iter()
        .copied()
        .chain(centroids)
        .map(|p| Probe::new(field, p, h))
        .collect();
    search::run(field, &mut probes);
    let found: Vec<f64> = probes.iter().map(|p| p.found).collect();
    let (vertices, faces) = found.split_at(points.len());
    let stats = |d: &[f64]| {
        let max = d.iter().copied().fold(0.0, f64::max);
        let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len().max(1) as f64).sqrt();
        (max, rms)
    };
    let (vertex_max, vertex_rms) = stats(vertices);
    let (face_max, face_rms) = stats(faces);
    Deviation {
        vertex_max,
        vertex_rms,
        face_max,
        face_rms,
        vertices_sampled: points.len(),
        faces_sampled: sampled.len(),
    }
}
