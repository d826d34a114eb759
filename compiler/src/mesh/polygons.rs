//! Each cell's polygons: its faces' segments chained into closed rings, one per surface sheet,
//! each fanned around a vertex the QEF places and a Newton step settles on the surface.

use super::bends::Planes;
use super::corners::{self, Corner};
use super::creases;
use super::faces::{self, Paths};
use super::facets::{self, Polygon};
use super::field::{Face, Field, Grid};
use super::qef;
use super::search;
use super::settle::{self, Settle};
use crate::parallel::par_map;
use glam::{DVec3, IVec3};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// The fans of every cell.
pub struct Fans {
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Field evaluations spent.
    pub evaluations: usize,
    /// Cells whose segments did not close into rings.
    pub broken: usize,
}

/// Fans every polygon of `cells` around its vertex, appended to `positions`; `segments` are
/// the faces' paths, `normals` the crossings' (vertex `v < normals.len()` is a crossing) and
/// `planes` the sharp points' after them (their creases' two planes, where they are a crease's).
/// Then moves apart vertices that came too near (`separate`).
pub fn fan(
    field: &Field,
    grid: &Grid,
    cells: &[IVec3],
    segments: &Paths,
    (normals, planes): (&[DVec3], &[Option<Planes>]),
    positions: &mut Vec<DVec3>,
    sharp: bool,
) -> Fans {
    let mut starts = {
        let positions = &*positions;
        par_map(cells, |&c| {
            let starts = cell_starts(grid, c, segments, (positions, normals, planes), sharp)?;
            Some((c, starts))
        })
    };
    let mut evaluations = match sharp {
        true => keep_corners(field, grid, cells, &mut starts),
        false => 0,
    };
    // Sharp vertices settle on the surface, all cells' searches in lockstep (but those at a
    // corner outside their cell, on it already).
    // (Sized first: grown by doubling, the lists were copied and their pages zeroed twice.)
    let mut starting: Vec<(DVec3, Option<DVec3>, DVec3)> = Vec::new();
    if sharp {
        let rings = starts.iter().flatten().map(|(_, rings)| rings.len()).sum();
        starting.reserve_exact(rings);
        starting.extend(starts.iter().flatten().flat_map(|(c, rings)| {
            let lo = grid.point(*c);
            rings
                .iter()
                .filter(|(_, s)| s.corner.is_none())
                .map(move |(_, s)| (s.p, s.or, lo))
        }));
    }
    let mut points = Vec::with_capacity(starting.len());
    let make =
        |&(p, or, lo): &(DVec3, Option<DVec3>, DVec3)| Settle::new(field, (p, or), lo, grid.h);
    evaluations += search::run_batched(field, &starting, make, |s: Settle| points.push(s.p));
    drop(starting);
    let mut settled = points.into_iter();
    let mut broken = 0;
    let mut polygons = Vec::new();
    for found in starts {
        let Some((cell, rings)) = found else {
            broken += 1;
            continue;
        };
        for (ring, start) in rings {
            let centre = match (sharp, start.corner) {
                (_, Some(corner)) => corner.at,
                (true, None) => settled.next().unwrap_or(start.p),
                (false, None) => start.p,
            };
            let centre = away(centre, &ring, positions, grid.h);
            polygons.push(Polygon { cell, ring, centre });
        }
    }
    if sharp {
        evaluations += facets::reveal(field, grid, &mut polygons, positions, (normals, planes));
    }
    let mut triangles = Vec::new();
    for Polygon { ring, centre, .. } in polygons {
        let vertex = positions.len() as u32;
        positions.push(centre);
        for k in 0..ring.len() {
            let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
            triangles.push([vertex, b, a]);
        }
    }
    separate(positions, faces::MIN_GAP * grid.h);
    Fans {
        triangles,
        evaluations,
        broken,
    }
}

/// Cell `c`'s rings (with `sharp`, split along creases: [`creases::split`]) and where each
/// one's vertex starts; `None` where its segments do not close.
fn cell_starts(
    grid: &Grid,
    c: IVec3,
    segments: &Paths,
    (positions, normals, planes): (&[DVec3], &[DVec3], &[Option<Planes>]),
    sharp: bool,
) -> Option<Vec<(Vec<u32>, Start)>> {
    let rings = polygons(c, segments)?;
    // A sharp point's crease: vertices after the crossings index `planes`.
    let crease = |v: u32| {
        let k = (v as usize).checked_sub(normals.len())?;
        planes.get(k).copied().flatten()
    };
    let cell = (grid.point(c), grid.point(c) + grid.h);
    let rings: Vec<Vec<u32>> = match sharp {
        true => rings
            .into_iter()
            .flat_map(|ring| creases::split(ring, positions, crease, cell))
            .collect(),
        false => rings,
    };
    // The ends of a chord a ring was split along lie in two parts, and on a plane beyond each:
    // their planes are not in the parts' QEFs.
    let mut parts: HashMap<u32, u32> = HashMap::default();
    for &v in rings.iter().flatten() {
        *parts.entry(v).or_default() += 1;
    }
    let within = |v: u32| crease(v).filter(|_| parts[&v] == 1);
    let starts = rings
        .into_iter()
        .map(|ring| {
            let centre = start(grid, c, &ring, (positions, normals, &within), sharp);
            (ring, centre)
        })
        .collect();
    Some(starts)
}

/// The planes of a sharp point's crease, by vertex (`None`: a crossing, or no crease's).
type CreaseOf<'a> = dyn Fn(u32) -> Option<Planes> + 'a;

/// Where a ring's vertex starts.
struct Start {
    /// The point.
    p: DVec3,
    /// Where to start again, should `p` not reach the surface ([`Settle`]'s `or`).
    or: Option<DVec3>,
    /// The corner outside the cell the vertex goes to instead, where [`corners`] allows it.
    corner: Option<Corner>,
}

/// A cell and its rings with their vertices' starts (`None`: its segments did not close).
type CellStarts = Option<(IVec3, Vec<(Vec<u32>, Start)>)>;

/// Keeps the corners outside their cells that [`corners::keep`] allows, of the rings in
/// `starts` (by cell, `cells`' order; `None`: a cell whose segments did not close, which
/// counts as drawn); returns the evaluations spent.
fn keep_corners(field: &Field, grid: &Grid, cells: &[IVec3], starts: &mut [CellStarts]) -> usize {
    let drawn: HashSet<IVec3> = cells
        .iter()
        .zip(starts.iter())
        .filter(|(_, s)| s.as_ref().is_none_or(|(_, rings)| !rings.is_empty()))
        .map(|(&c, _)| c)
        .collect();
    let mut claims: Vec<&mut Option<Corner>> = starts
        .iter_mut()
        .flatten()
        .flat_map(|(_, rings)| rings.iter_mut().map(|(_, s)| &mut s.corner))
        .collect();
    corners::keep(
        field,
        &mut claims,
        &drawn,
        settle::on_surface(field, grid.h),
    )
}

/// Where the vertex of `ring` (a polygon of cell `c`) starts: sharp, where the QEF of its
/// crossings' tangent planes and its sharp points' two planes puts it (around the mass point of
/// all its vertices: a face's sharp points lie on the creases inside the cell, so a crease's
/// line is followed to them), to be settled on the surface by a [`Settle`]; plain, the mean of
/// its crossings. Vertex `v` of `positions` is a crossing of normal `normals[v]` if
/// `v < normals.len()`, else a sharp point whose planes `crease(v)` gives, if it is a crease's.
/// (A corner whose third plane no crossing of the cell lies on — its trace on the cell's faces
/// runs between two sharp points — is still found: those points carry that plane.)
fn start(
    grid: &Grid,
    c: IVec3,
    ring: &[u32],
    (positions, normals, crease): (&[DVec3], &[DVec3], &CreaseOf<'_>),
    sharp: bool,
) -> Start {
    let lo = grid.point(c);
    let mut sheet: Vec<(DVec3, DVec3)> = ring
        .iter()
        .filter_map(|&v| normals.get(v as usize).map(|&n| (positions[v as usize], n)))
        .collect();
    if sharp {
        for &v in ring {
            if let Some((a, b)) = crease(v) {
                let p = positions[v as usize];
                sheet.extend([(p, a), (p, b)]);
            }
        }
        let mass = ring.iter().map(|&v| positions[v as usize]).sum::<DVec3>() / ring.len() as f64;
        let found = qef::solve(&sheet, mass);
        let corner = corners::outside(&found, &sheet, grid, c);
        let (p, or) = match found.crease {
            Some(along) => {
                let on = onto_crease(found.point, along, lo, lo + grid.h);
                (on, (on != found.point).then_some(found.point))
            }
            None => (found.point, None),
        };
        Start { p, or, corner }
    } else {
        let mean = sheet.iter().map(|s| s.0).sum::<DVec3>() / sheet.len().max(1) as f64;
        let p = mean.clamp(lo, lo + grid.h);
        Start {
            p,
            or: None,
            corner: None,
        }
    }
}

/// The point of the crease's line through `p` along `along` nearest `p` within the cell from
/// `lo` to `hi`, a twentieth of the line's stretch in the cell off its ends (`p` itself inside
/// them, or where the line misses the cell, for [`Settle`] to clamp). Clamped coordinate by
/// coordinate, a point outside would leave the crease, and the fan around it would cut across
/// the crease; moved along the line it stays on both planes.
fn onto_crease(p: DVec3, along: DVec3, lo: DVec3, hi: DVec3) -> DVec3 {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..3 {
        if along[k].abs() < 1e-12 {
            if p[k] < lo[k] || p[k] > hi[k] {
                return p;
            }
            continue;
        }
        let (a, b) = ((lo[k] - p[k]) / along[k], (hi[k] - p[k]) / along[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    if t0 > t1 {
        return p;
    }
    // Kept off the line's ends a little: an end on the cell's side is a face's sharp point of
    // the ring, which the vertex must not meet (`away` would move it off the crease).
    let margin = 0.05 * (t1 - t0);
    p + along * 0.0f64.clamp(t0 + margin, t1 - margin)
}

/// The polygons of cell `c`: its faces' segments, oriented as seen from outside the cell, chained
/// into closed rings of vertices; `None` if they do not close.
fn polygons(c: IVec3, segments: &Paths) -> Option<Vec<Vec<u32>>> {
    // The paths as they lie (borrowed), and whether this cell walks them backwards (a face on
    // its near side, seen from outside the cell, runs the other way).
    let mut paths: Vec<(&[u32], bool)> = Vec::with_capacity(8);
    for i in 0..6 {
        let (face, far) = Face::of_cell(c, i);
        for path in segments.of(face) {
            paths.push((path, !far));
        }
    }
    let start = |(p, back): (&[u32], bool)| if back { p[p.len() - 1] } else { p[0] };
    let mut used = vec![false; paths.len()];
    let mut rings = Vec::new();
    while let Some(first) = used.iter().position(|u| !u) {
        let mut ring = Vec::new();
        let mut at = first;
        loop {
            used[at] = true;
            let (path, back) = paths[at];
            // Every vertex but the last, which the next path starts with.
            let to = if back {
                ring.extend(path[1..].iter().rev());
                path[0]
            } else {
                ring.extend_from_slice(&path[..path.len() - 1]);
                path[path.len() - 1]
            };
            if to == start(paths[first]) {
                break;
            }
            at = (0..paths.len()).find(|&k| !used[k] && start(paths[k]) == to)?;
        }
        rings.push(ring);
    }
    Some(rings)
}

/// The polygon's vertex `centre`, moved toward the ring's mean while it lies within
/// `faces::MIN_GAP` cells of one of the ring's vertices (a corner of the shape on a cell's face
/// is both a face's sharp point and the QEF's answer), so that no two vertices share a position.
fn away(centre: DVec3, ring: &[u32], positions: &[DVec3], h: f64) -> DVec3 {
    let mean = ring.iter().map(|&v| positions[v as usize]).sum::<DVec3>() / ring.len() as f64;
    let gap = faces::MIN_GAP * h;
    let near = |c: DVec3| {
        ring.iter()
            .any(|&v| (positions[v as usize] - c).length() < gap)
    };
    let mut c = centre;
    for k in 1..=8 {
        if !near(c) {
            return c;
        }
        c = centre + (mean - centre) * (0.01 * k as f64);
    }
    mean
}

/// Moves apart vertices nearer each other than `gap`: two polygons' vertices clamped to one
/// cell corner, or two parts that touch at a point (the primitives example's octahedron tip on
/// its floor, where the two sheets' vertices came within 1e-8). (A polygon's vertex on its own
/// ring's vertices is moved off them first, by `away`: a cluster there is more than the few
/// moves here undo.) The mesh is manifold by its indices either way,
/// but a tool that joins vertices by position would pinch it there. Each move is about `gap`
/// (1e-4 of a cell); a vertex in a cluster of k moves about k times (at most [`MAX_MOVES`]).
fn separate(positions: &mut [DVec3], gap: f64) {
    const END: u32 = u32::MAX;
    // Vertices are looked up in buckets of 4 gaps (at most 2 a side cover the gap around a
    // point: 8 lookups, about 3 on average); among those nearer than the gap the first is the
    // one a search of the 27 buckets of one gap around the point's own would meet first (z,
    // then y, then x offset; the latest placed first), as before the coarse buckets.
    let fine = |p: DVec3| (p / gap).floor().as_i64vec3();
    let coarse = |p: DVec3| (p / (4.0 * gap)).floor().as_i64vec3();
    // Each bucket's latest vertex, and each vertex's predecessor in its bucket: lists without
    // an allocation per bucket.
    let mut head: HashMap<glam::I64Vec3, u32> =
        HashMap::with_capacity_and_hasher(positions.len(), Default::default());
    let mut before = vec![END; positions.len()];
    // The first vertex nearer `p` than the gap, among those placed.
    let near =
        |p: DVec3, positions: &[DVec3], head: &HashMap<glam::I64Vec3, u32>, before: &[u32]| {
            let home = fine(p);
            let (lo, hi) = (coarse(p - 1.01 * gap), coarse(p + 1.01 * gap));
            let mut first: Option<(Order, DVec3)> = None;
            for z in lo.z..=hi.z {
                for y in lo.y..=hi.y {
                    for x in lo.x..=hi.x {
                        let cell = glam::I64Vec3::new(x, y, z);
                        let mut j = head.get(&cell).copied().unwrap_or(END);
                        while j != END {
                            let q = positions[j as usize];
                            let d = fine(q) - home;
                            if (p - q).length() < gap && d.abs().max_element() <= 1 {
                                let order = (d.z, d.y, d.x, std::cmp::Reverse(j));
                                if first.is_none_or(|(o, _)| order < o) {
                                    first = Some((order, q));
                                }
                            }
                            j = before[j as usize];
                        }
                    }
                }
            }
            first.map(|(_, q)| q)
        };
    for i in 0..positions.len() {
        let mut p = positions[i];
        // Moved off one vertex, it may come near another: look again. A cluster of k vertices
        // at one point (a fractal's cells collapsing onto one spot) lines up along `AWAY`, the
        // k-th needing k moves: with 8 at most, the ninth of the sharp mandelbulb's cluster at
        // 96 cells stayed on the eighth's position.
        for k in 0..MAX_MOVES {
            let Some(q) = near(p, positions, &head, &before) else {
                break;
            };
            let away = (p - q).try_normalize().unwrap_or(AWAY);
            // After a few moves, turned and lengthened a little more each time: between two
            // vertices a gap apart, straight moves can shuttle back and forth and end on one of
            // them (three pairs within 1e-10 in the sharp mandelbulb on the GPU at 96 cells).
            let (dir, reach) = match k {
                0..4 => (away, 1.000_001),
                _ => (
                    (away + 0.5 * spiral(k)).try_normalize().unwrap_or(AWAY),
                    1.0 + k as f64 / 64.0,
                ),
            };
            p = q + dir * (gap * reach);
        }
        positions[i] = p;
        before[i] = head.insert(coarse(p), i as u32).unwrap_or(END);
    }
}

/// Which of two vertices near a point [`separate`] meets first: the smaller (z, y, x offset of
/// its bucket of one gap from the point's, then the later placed).
type Order = (i64, i64, i64, std::cmp::Reverse<u32>);

/// The k-th of a sequence of unit vectors spread over the sphere (the Fibonacci spiral).
fn spiral(k: usize) -> DVec3 {
    let z = 1.0 - 2.0 * ((k % 97) as f64 + 0.5) / 97.0;
    let r = (1.0 - z * z).sqrt();
    let a = k as f64 * 2.399_963_229_728_653;
    DVec3::new(r * a.cos(), r * a.sin(), z)
}

/// The moves [`separate`] makes at most for one vertex.
const MAX_MOVES: usize = 256;

/// The direction a vertex moves off another at its very position.
const AWAY: DVec3 = DVec3::new(
    0.267_261_241_912_424_4,
    0.534_522_483_824_848_8,
    0.801_783_725_737_273_2,
);

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pair of vertices ends at least the gap apart: a cluster of 40 at one point (more
    /// than the moves once allowed), and 40 more shuttled between two points a gap apart.
    #[test]
    fn clusters_come_apart() {
        let gap = 1e-6;
        let a = DVec3::new(0.3, -0.7, 0.1);
        let b = a + DVec3::X * gap * 1.000_001;
        let mut positions: Vec<DVec3> = std::iter::repeat_n(a, 40)
            .chain((0..40).map(|i| if i % 2 == 0 { a } else { b }))
            .collect();
        separate(&mut positions, gap);
        for i in 0..positions.len() {
            for j in 0..i {
                let d = (positions[i] - positions[j]).length();
                assert!(d >= gap, "{i} and {j} are {d:e} apart");
            }
        }
    }
}
