//! Triangles from the active cells: the field at their corners, the crossings on their edges,
//! the segments on their faces chained into one closed polygon per surface sheet in each cell,
//! and each polygon fanned around a vertex the QEF places (Cubical Marching Squares, Ho et al.
//! 2005: crossings and face segments shared by neighbours make the mesh closed and 2-manifold
//! by construction; the QEF vertex and the faces' sharp points keep corners and creases).

use super::bends::{self, Planes, Sharp};
use super::edges;
use super::faces::{self, Segment};
use super::field::Face;
use super::field::{Field, Grid, corner, inside, local};
use super::polygons;
use super::search;
use super::trace::{self, Bracket};
use crate::parallel::{par_flat_map, par_map, par_sort_unstable_by_key};
use glam::{DVec3, IVec3};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// The mesh of the active cells.
pub struct Contour {
    /// Vertex positions: the crossings first, then the faces' sharp points, then the cells'.
    pub positions: Vec<DVec3>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Field evaluations spent.
    pub evaluations: usize,
    /// Cells the surface crosses that the pruning had dropped (a bound wrong there).
    pub added: usize,
    /// Grid edges the surface crosses twice between ends on the same side.
    pub dipped: usize,
    /// Cells whose segments did not close into polygons (0 unless the field is not a function:
    /// NaN flickering between calls; such cells are left out and the mesh has a hole there).
    pub broken: usize,
}

/// Contours the surface of `field` through `cells` of `grid`.
pub fn contour(field: &Field, grid: &Grid, cells: &[IVec3], sharp: bool) -> Contour {
    let given = cells.len();
    let Closed {
        cells,
        listed,
        value,
        mut evaluations,
    } = closed(field, grid, cells);
    let added = cells.len() - given;
    let cells = &cells[..];
    let at = |p: IVec3| value.get(&grid.key(p)).copied().unwrap_or(f64::NAN);

    // Each face of an active cell once: a cell's near faces, and its far ones where no active
    // cell lies beyond.
    let listed_ref = &listed;
    let face_list: Vec<Face> = par_flat_map(cells, |&c| {
        (0..6)
            .map(move |i| Face::of_cell(c, i))
            .filter(move |&(f, far)| !far || !listed_ref.contains(&(c + IVec3::AXES[f.axis])))
            .map(|(f, _)| f)
    });
    // Where the surface crosses every edge of an active cell.
    let mut crossings = edges::crossings(field, grid, (cells, &listed), &at, sharp);
    // Only the faces with a crossing on an edge draw anything.
    let on_face = par_map(&face_list, |&f| {
        faces::crossings_on(f, |(p, a)| {
            crossings.by_edge.get(&edges::edge_key(grid, p, a)).copied()
        })
    });
    let (face_list, on_face): (Vec<Face>, Vec<usize>) = (face_list.into_iter().zip(on_face))
        .filter(|&(_, n)| n > 0)
        .unzip();
    if sharp {
        evaluations += edges::sharpen(field, grid, &face_list, &mut crossings);
    }
    let edges::Crossings {
        mut positions,
        normals,
        by_edge,
        dipped,
        evaluations: spent,
    } = crossings;
    evaluations += spent;
    let crossing_at = |(p, a): (IVec3, usize)| by_edge.get(&edges::edge_key(grid, p, a)).copied();

    // The segments on every face drawn.
    // The centres of the faces of more than two crossings, in one batch.
    let mut centres: Vec<(Face, f64)> = face_list.iter().map(|&f| (f, f64::NAN)).collect();
    let ambiguous: Vec<usize> = (0..face_list.len()).filter(|&i| on_face[i] > 2).collect();
    let points: Vec<DVec3> = ambiguous
        .iter()
        .map(|&i| faces::centre(grid, face_list[i]))
        .collect();
    evaluations += points.len();
    for (&i, v) in ambiguous.iter().zip(field.many(&points)) {
        centres[i].1 = v;
    }
    let mut drawn = par_map(&centres, |&f| {
        faces::segments(field, grid, f, at, crossing_at, sharp)
    });
    // The faces' sharp points inside them, in lockstep batches.
    evaluations += settle_pending(field, grid, &face_list, &mut drawn);
    let mut planes: Vec<Option<Planes>> = Vec::new();
    let mut segments = faces::Paths::with_capacity(face_list.len());
    for (&f, (list, spent)) in face_list.iter().zip(drawn) {
        evaluations += spent;
        if list.is_empty() {
            continue;
        }
        for s in &list {
            segments.push(path(s, &mut positions, &mut planes));
        }
        segments.finish(f);
    }
    // One polygon per sheet in each cell, fanned around its QEF vertex.
    let fans = polygons::fan(
        field,
        grid,
        cells,
        &segments,
        (&normals, &planes),
        &mut positions,
        sharp,
    );
    evaluations += fans.evaluations;
    Contour {
        positions,
        triangles: fans.triangles,
        evaluations,
        added,
        dipped,
        broken: fans.broken,
    }
}

/// The cells `cells` with every neighbour across a face the surface crosses, until no face
/// the surface crosses leads out of the set, and the field at all their corners; and the
/// evaluations spent. With a correct bound the pruning already keeps every such cell; a bound
/// that is wrong somewhere (an annotation too small, a fractal's estimate) would otherwise leave
/// a hole in the mesh where it pruned a cell the surface crosses.
fn closed(field: &Field, grid: &Grid, cells: &[IVec3]) -> Closed {
    let mut active: HashSet<IVec3> = cells.iter().copied().collect();
    // (Sized once: this machine's page faults made the tables' growth a third of the time.)
    let mut value: HashMap<u64, f64> =
        HashMap::with_capacity_and_hasher(cells.len() * 3 / 2, Default::default());
    let mut frontier = cells.to_vec();
    let mut evaluations = 0;
    while !frontier.is_empty() {
        // The corners not yet known, each once.
        let mut points: Vec<u64> = par_map(&frontier, |&c| {
            std::array::from_fn::<_, 8, _>(|i| grid.key(c + corner(i as i32)))
        })
        .into_flattened();
        par_sort_unstable_by_key(&mut points, |&k| k);
        points.dedup();
        points.retain(|k| !value.contains_key(k));
        let at: Vec<DVec3> = par_map(&points, |&k| grid.point(grid.unkey(k)));
        let values = field.many(&at);
        evaluations += points.len();
        value.extend(points.into_iter().zip(values));
        // Which faces of each cell the surface crosses (bit i: face i).
        let crossed = par_map(&frontier, |&c| {
            let sides: [bool; 8] =
                std::array::from_fn(|i| inside(value[&grid.key(c + corner(i as i32))]));
            (0..6).fold(0u8, |bits, i| {
                let corners = Face::of_cell(c, i).0.corners().map(|p| sides[local(p - c)]);
                let mixed = corners.iter().any(|&s| s != corners[0]);
                bits | ((mixed as u8) << i)
            })
        });
        let mut next = Vec::new();
        for (&c, bits) in frontier.iter().zip(crossed) {
            for i in (0..6).filter(|i| bits & (1 << i) != 0) {
                let (face, far) = Face::of_cell(c, i);
                let step = IVec3::AXES[face.axis];
                let across = if far { c + step } else { c - step };
                if across.cmpge(IVec3::ZERO).all()
                    && across.cmplt(grid.n).all()
                    && active.insert(across)
                {
                    next.push(across);
                }
            }
        }
        frontier = next;
    }
    let mut cells: Vec<IVec3> = active.iter().copied().collect();
    cells.sort_unstable_by_key(|&c| grid.key(c));
    Closed {
        cells,
        listed: active,
        value,
        evaluations,
    }
}

/// What [`closed`] finds.
struct Closed {
    /// The cells, in grid order.
    cells: Vec<IVec3>,
    /// The same cells, to ask whether one is among them.
    listed: HashSet<IVec3>,
    /// The field at every corner of them, by grid point key.
    value: HashMap<u64, f64>,
    /// Field evaluations spent.
    evaluations: usize,
}

/// Runs the faces' pending searches for their sharp points in lockstep batches and puts what
/// they find (kept [`faces::MIN_GAP`] off the segments' ends) in their segments; returns the
/// evaluations spent.
fn settle_pending(
    field: &Field,
    grid: &Grid,
    faces: &[Face],
    drawn: &mut [(Vec<Segment>, usize)],
) -> usize {
    let mut owners = Vec::new();
    let mut pending: Vec<Bracket> = Vec::new();
    for (i, (list, _)) in drawn.iter_mut().enumerate() {
        for (j, s) in list.iter_mut().enumerate() {
            if let Some(b) = s.pending.take() {
                owners.push((i, j));
                pending.push(*b);
            }
        }
    }
    let mut evaluations = search::run(field, &mut pending);
    for ((i, j), b) in owners.into_iter().zip(pending) {
        let (a, e) = b.ends;
        let found = match (b.found, b.planes) {
            // The tangent lines' meeting point on the surface: a crease.
            (Some(at), planes) if trace::at_meet(at, b.from, grid) => vec![Sharp { at, planes }],
            // A surface point short of it: the trace bends more than once (a corner).
            (Some(at), Some((na, nb))) if !b.only_crease && na.dot(nb) <= bends::CORNER_COSINE => {
                let ends = ((a, na), at, (e, nb));
                let depth = bends::DEPTH - 1;
                let found =
                    bends::either_side(field, grid, faces[i], ends, depth, &mut evaluations);
                bends::untangled(faces[i], a, found, e)
            }
            // A point of a smooth trace, or too little turned to follow.
            (Some(at), _) if !b.only_crease => vec![Sharp { at, planes: None }],
            _ => Vec::new(),
        };
        drawn[i].0[j].sharp = faces::apart(a, found, e, grid.h);
    }
    evaluations
}

/// A segment as a path of vertices (from, its sharp points given indices, to).
/// A sharp point's planes go to `planes` (by its index less the crossings' count).
fn path<'a>(
    s: &'a Segment,
    positions: &'a mut Vec<DVec3>,
    planes: &'a mut Vec<Option<Planes>>,
) -> impl Iterator<Item = u32> + 'a {
    let sharp = s.sharp.iter().map(|p| {
        positions.push(p.at);
        planes.push(p.planes);
        positions.len() as u32 - 1
    });
    std::iter::once(s.from).chain(sharp).chain([s.to])
}
