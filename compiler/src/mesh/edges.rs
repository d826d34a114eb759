//! Where the surface crosses the grid's edges: once on an edge whose ends lie on different
//! sides (regula falsi), and — with sharp features asked for — twice on an edge whose ends lie
//! on the same side but between which the field's bound allows it to dip across (a crease
//! cutting the edge, a part thinner than a cell), found by a bound-guided search.

use super::edge_search::{Dip, Root, Stage, normal_step};
use super::field::{Face, Field, Grid, corner, inside, local};
use super::search;
use crate::parallel::{par_flat_map, par_map, par_sort_unstable_by_key};
use glam::{DVec3, IVec3};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// Where the surface crosses a grid edge: the vertex's index, position and unit normal.
#[derive(Clone, Copy, Debug)]
pub struct Crossing {
    /// The vertex's index in the mesh.
    pub vertex: u32,
    /// On the surface, on the edge.
    pub position: DVec3,
    /// The field's gradient there.
    pub normal: DVec3,
}

/// The crossings of one grid edge, in order along its axis: one where its ends lie on
/// different sides, two where the field dips across between ends on the same side.
#[derive(Clone, Copy, Debug)]
pub struct Crossed {
    /// The first (or only) crossing.
    pub first: Crossing,
    /// The second, on an edge crossed twice.
    pub second: Option<Crossing>,
}

impl Crossed {
    /// The crossings in order from the edge's lowest end.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = Crossing> {
        std::iter::once(self.first).chain(self.second)
    }

    /// How many there are (1 or 2).
    pub fn count(&self) -> usize {
        1 + self.second.is_some() as usize
    }
}

/// What [`crossings`] finds.
pub struct Crossings {
    /// Vertex positions and normals: the crossings, numbered first.
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    /// The crossings by edge key ([`edge_key`]).
    pub by_edge: HashMap<u64, Crossed>,
    /// Edges crossed twice.
    pub dipped: usize,
    /// Field evaluations spent.
    pub evaluations: usize,
}

/// A grid edge: its [`edge_key`], and the cell (its index) and the cell's edge (0..12) it is.
type KeyedEdge = (u64, (u32, u8));

/// The crossings on every edge of `cells` (`at` gives the field at a grid point): once on each
/// edge that changes side; with `dips`, twice on each edge whose ends lie on the same side but
/// where the field dips across between them, if all four cells around it are in `listed` (so
/// every face at the edge is drawn, and sees both).
pub fn crossings(
    field: &Field,
    grid: &Grid,
    (cells, listed): (&[IVec3], &HashSet<IVec3>),
    at: &(impl Fn(IVec3) -> f64 + Sync),
    dips: bool,
) -> Crossings {
    let (changes, same) = cell_edges(grid, cells, at, dips);

    let all_around = par_map(&same, |&(e, _)| {
        around(e).iter().all(|c| listed.contains(c))
    });
    let dipping: Vec<Ended> = (same.into_iter().zip(all_around))
        .filter_map(|(e, all)| all.then_some(e))
        .collect();
    // Where each dipping edge's field crosses to the other side, if it does.
    let mut found = Vec::new();
    let make_dip = |&((p, a), ends): &Ended| {
        let along = DVec3::AXES[a] * grid.h;
        Dip::new(field, grid.point(p), along, ends, (p, a))
    };
    let mut evaluations = search::run_batched(field, &dipping, make_dip, |dip: Dip| {
        if let Some((t, fm)) = dip.found {
            found.push((dip.edge, dip.ends, t, fm));
        }
    });
    // One search per crossing: a changing edge's, then each dipped edge's two halves (start,
    // field there, extent, field at its end; the edge's key).
    let mut spans: Vec<(DVec3, f64, DVec3, f64, u64)> = changes
        .iter()
        .map(|&((p, a), (fa, fb))| {
            let along = DVec3::AXES[a] * grid.h;
            (grid.point(p), fa, along, fb, edge_key(grid, p, a))
        })
        .collect();
    for &((p, a), (fa, fb), t, fm) in &found {
        let (start, along, key) = (grid.point(p), DVec3::AXES[a] * grid.h, edge_key(grid, p, a));
        spans.push((start, fa, along * t, fm, key));
        spans.push((start + along * t, fm, along * (1.0 - t), fb, key));
    }
    let dipped = found.len();
    let mut positions = Vec::with_capacity(spans.len() * 2);
    let mut normals = Vec::with_capacity(spans.len());
    let mut by_edge: HashMap<u64, Crossed> =
        HashMap::with_capacity_and_hasher(spans.len(), Default::default());
    let make_root = |&(start, fa, along, fb, _): &(DVec3, f64, DVec3, f64, u64)| {
        Root::new(field, grid.h, (start, fa), along, fb)
    };
    let mut keys = spans.iter().map(|s| s.4);
    evaluations += search::run_batched(field, &spans, make_root, |search: Root| {
        let Stage::Done(position, normal) = search.stage else {
            // (`run` ends every search.)
            unreachable!("a crossing's search ended unfinished");
        };
        let key = keys.next().expect("a key for every search");
        let vertex = positions.len() as u32;
        positions.push(position);
        normals.push(normal);
        let c = Crossing {
            vertex,
            position,
            normal,
        };
        by_edge
            .entry(key)
            .and_modify(|x| x.second = Some(c))
            .or_insert(Crossed {
                first: c,
                second: None,
            });
    });
    Crossings {
        positions,
        normals,
        by_edge,
        dipped,
        evaluations,
    }
}

/// An edge (lowest end and axis) and the field at its ends.
type Ended = ((IVec3, usize), (f64, f64));

/// Each edge of `cells`, once, with the field at its ends (`at`): those that change side, and
/// with `dips` apart those on one side that the field may dip across, |d(a)| + |d(b)| < h (d is
/// 1-Lipschitz) — the rest dropped before sorting (most edges of a fine grid).
fn cell_edges(
    grid: &Grid,
    cells: &[IVec3],
    at: &(impl Fn(IVec3) -> f64 + Sync),
    dips: bool,
) -> (Vec<Ended>, Vec<Ended>) {
    let values: Vec<[f64; 8]> = par_map(cells, |&c| {
        std::array::from_fn(|i| at(c + corner(i as i32)))
    });
    let ends = |(cell, i): (u32, u8)| {
        let c = cells[cell as usize];
        let (p, a) = cell_edge(c, i as i32);
        let value = &values[cell as usize];
        (
            (p, a),
            (value[local(p - c)], value[local(p - c + IVec3::AXES[a])]),
        )
    };
    let index: Vec<u32> = (0..cells.len() as u32).collect();
    let mut edges: Vec<KeyedEdge> = par_flat_map(&index, |&cell| {
        (0..12u8).filter_map(move |i| {
            let ((p, a), (fa, fb)) = ends((cell, i));
            let keep = inside(fa) != inside(fb) || (dips && fa.abs() + fb.abs() < grid.h);
            keep.then_some((edge_key(grid, p, a), (cell, i)))
        })
    });
    par_sort_unstable_by_key(&mut edges, |e| e.0);
    edges.dedup_by_key(|e| e.0);
    edges
        .into_iter()
        .map(|(_, e)| ends(e))
        .partition(|&(_, (fa, fb))| inside(fa) != inside(fb))
}

/// The cosine of the angle between two crossings' normals on one face above which neither is
/// taken again by [`sharpen`] (20°: a curved sheet turns less within a cell at any resolution
/// worth meshing; a crease or a corner's faces turn more).
const SHARPEN_COSINE: f64 = 0.94;

/// On a field whose gradients are coarse (the GPU's f32, sampled a hundredth of a cell apart),
/// the normals of the crossings of `faces` that differ by more than 20° from another crossing's
/// on one face, taken again in f64 on the CPU ([`normal_step`]): near a crease
/// the coarse gradient blends its two planes, and the faces' crease points and the cells' QEF
/// vertices are only as good as these normals. Returns the evaluations spent (none on the CPU).
pub fn sharpen(field: &Field, grid: &Grid, faces: &[Face], crossings: &mut Crossings) -> usize {
    if !field.batched() {
        return 0;
    }
    let cpu = field.on_cpu();
    let step = normal_step(&cpu, grid.h);
    let mut marked: HashSet<u32> = HashSet::default();
    for &f in faces {
        let on: Vec<Crossing> = f
            .edges()
            .into_iter()
            .filter_map(|(p, a)| crossings.by_edge.get(&edge_key(grid, p, a)))
            .flat_map(Crossed::iter)
            .collect();
        for (i, x) in on.iter().enumerate() {
            for y in &on[i + 1..] {
                if x.normal.dot(y.normal) < SHARPEN_COSINE {
                    marked.extend([x.vertex, y.vertex]);
                }
            }
        }
    }
    let list: Vec<u32> = marked.into_iter().collect();
    let positions = &crossings.positions;
    let fresh = crate::parallel::par_map(&list, |&v| cpu.normal(positions[v as usize], step));
    for (&v, n) in list.iter().zip(fresh) {
        crossings.normals[v as usize] = n;
    }
    let normals = &crossings.normals;
    for c in crossings.by_edge.values_mut() {
        c.first.normal = normals[c.first.vertex as usize];
        if let Some(s) = &mut c.second {
            s.normal = normals[s.vertex as usize];
        }
    }
    4 * list.len()
}

/// The four cells around the grid edge from `p` along `axis`.
fn around((p, axis): (IVec3, usize)) -> [IVec3; 4] {
    let (u, v) = (IVec3::AXES[(axis + 1) % 3], IVec3::AXES[(axis + 2) % 3]);
    [p, p - u, p - v, p - u - v]
}

/// A key for the grid edge from `p` along `axis` (or the face at `p` normal to it).
pub fn edge_key(grid: &Grid, p: IVec3, axis: usize) -> u64 {
    grid.key(p) * 3 + axis as u64
}

/// Edge `i` (0..12) of cell `c`: its lowest end and axis.
fn cell_edge(c: IVec3, i: i32) -> (IVec3, usize) {
    let axis = (i / 4) as usize;
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let p = c + IVec3::AXES[u] * (i & 1) + IVec3::AXES[v] * ((i >> 1) & 1);
    (p, axis)
}
