//! A cell's polygon split along the creases that cross it without meeting inside it (two
//! parallel edges of a part, a chamfer or a cut narrower than a cell, a crease passing a
//! corner): one vertex cannot lie on two creases, and a fan around it would cut across one.

use glam::DVec3;

/// The cosine above which two normals count as one plane's (two crease points' planes here;
/// a face's crossings joined by `faces::segments`).
pub const SAME_PLANE: f64 = 0.999;

/// The crease's stretch within a cell (in cells) below which the cell's ring is split along
/// it even where no other crease crosses the cell.
const GRAZE: f64 = 0.1;

/// The cosine below which a sharp point's two planes meet at a crease (about 25°).
pub const CREASE: f64 = 0.9;

/// `ring` (a cell's polygon) cut into smaller rings along chords between its crease points that
/// lie on one crease — the faces' sharp points where two tangent lines met, `crease` giving
/// their planes' normals, which name the crease — where the ring crosses two creases or more
/// (or one, and a corner's creases end in the cell beside it; or one that only grazes the
/// cell, its chord shorter than [`GRAZE`]), no two chords cross and no chord
/// lies in one face of the cell from `lo` to `hi` (a neighbour could cut along it too). Each
/// part then lies along one side of each crease; the ring is given back whole otherwise.
pub fn split(
    ring: Vec<u32>,
    positions: &[DVec3],
    crease: impl Fn(u32) -> Option<(DVec3, DVec3)>,
    (lo, hi): (DVec3, DVec3),
) -> Vec<Vec<u32>> {
    // (index in the ring, the crease's two normals)
    let creases: Vec<(usize, DVec3, DVec3)> = (0..ring.len())
        .filter_map(|k| {
            let (a, b) = crease(ring[k])?;
            (a.dot(b) < CREASE).then_some((k, a, b))
        })
        .collect();
    if creases.len() < 2 {
        return vec![ring];
    }
    let same = |(_, a, b): (usize, DVec3, DVec3), (_, c, d): (usize, DVec3, DVec3)| {
        (a.dot(c) > SAME_PLANE && b.dot(d) > SAME_PLANE)
            || (a.dot(d) > SAME_PLANE && b.dot(c) > SAME_PLANE)
    };
    let on_one_face = |i: usize, j: usize| {
        let (p, q) = (positions[ring[i] as usize], positions[ring[j] as usize]);
        (0..3).any(|k| p[k] == q[k] && (p[k] == lo[k] || p[k] == hi[k]))
    };
    // Each crease's two points, if it has exactly two.
    let mut chords: Vec<(usize, usize)> = Vec::new();
    for (x, &s) in creases.iter().enumerate() {
        let others: Vec<usize> = (0..creases.len())
            .filter(|&y| y != x && same(s, creases[y]))
            .collect();
        // (Ends next to each other on the ring would cut off a part of two vertices.)
        let apart = |i: usize, j: usize| j - i > 1 && !(i == 0 && j == ring.len() - 1);
        if let [y] = others[..]
            && x < y
            && apart(s.0, creases[y].0)
            && !on_one_face(s.0, creases[y].0)
        {
            chords.push((s.0, creases[y].0));
        } else if others.len() > 1 {
            return vec![ring];
        }
    }
    let crossing = |(a, b): (usize, usize), (c, d): (usize, usize)| {
        let within = |k: usize| a < k && k < b;
        within(c) != within(d) && ![a, b].contains(&c) && ![a, b].contains(&d)
    };
    // One chord alone: a crease the QEF's line follows, unless the ring's other crease points
    // (a corner in the cell: a box's corner cut off by a plane) lie beside it, or the crease
    // only grazes the cell (past a grid edge by less than a tenth of a cell: a vertex on its
    // short stretch would meet its ends, and moved off them it leaves the crease).
    let others = creases.len() - 2 * chords.len();
    let short = |(i, j): (usize, usize)| {
        let (p, q) = (positions[ring[i] as usize], positions[ring[j] as usize]);
        (p - q).length() < GRAZE * (hi.x - lo.x)
    };
    if chords.is_empty()
        || (chords.len() == 1 && others < 2 && !short(chords[0]))
        || chords
            .iter()
            .enumerate()
            .any(|(i, &p)| chords[..i].iter().any(|&q| crossing(p, q)))
    {
        return vec![ring];
    }
    cut(&ring, &chords)
}

/// The parts of the cyclic `ring` cut along `chords` (pairs of its indices, none crossing).
fn cut(ring: &[u32], chords: &[(usize, usize)]) -> Vec<Vec<u32>> {
    // Innermost chords first: each cuts off the stretch between its ends, which no other
    // uncut chord lies in.
    let mut order: Vec<(usize, usize)> = chords.to_vec();
    order.sort_by_key(|&(a, b)| b - a);
    let mut alive = vec![true; ring.len()];
    let mut parts = Vec::with_capacity(chords.len() + 1);
    for (a, b) in order {
        let part: Vec<u32> = (a..=b).filter(|&k| alive[k]).map(|k| ring[k]).collect();
        alive[a + 1..b].fill(false);
        parts.push(part);
    }
    parts.push(
        (0..ring.len())
            .filter(|&k| alive[k])
            .map(|k| ring[k])
            .collect(),
    );
    parts
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ring crossing two parallel creases comes apart along both: three parts, every chord
    /// used once each way (so the mesh stays manifold).
    #[test]
    fn two_creases_make_three_parts() {
        // Crossings 0..6 on three planes, a (x), b (y), c (z); crease points 6..10.
        let (a, b, c) = (DVec3::X, DVec3::Y, DVec3::Z);
        let positions: Vec<DVec3> = (0..10).map(|i| DVec3::splat(i as f64 * 0.1)).collect();
        // a a | ab | b b | bc | c c | cb ... : creases ab (6, 9) and bc (7, 8)
        let ring = vec![0, 6, 2, 7, 4, 5, 8, 3, 9, 1];
        let crease = |v: u32| match v {
            6 | 9 => Some((a, b)),
            7 => Some((b, c)),
            8 => Some((c, b)),
            _ => None,
        };
        let cell = (DVec3::splat(-1.0), DVec3::splat(2.0));
        let parts = split(ring, &positions, crease, cell);
        assert_eq!(parts.len(), 3, "{parts:?}");
        let mut edges = std::collections::HashMap::new();
        for p in &parts {
            for k in 0..p.len() {
                *edges.entry((p[k], p[(k + 1) % p.len()])).or_insert(0) += 1;
            }
        }
        for (&(u, v), &count) in &edges {
            assert_eq!(count, 1);
            if [6, 7, 8, 9].contains(&u) && [6, 7, 8, 9].contains(&v) {
                assert_eq!(edges.get(&(v, u)), Some(&1), "chord {u}–{v} one way only");
            }
        }
    }
}
