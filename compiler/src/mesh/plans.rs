//! Which planes meet where in a cell whose polygon is flat between its crease points: the
//! plans `facets` tries, each a set of corners of three planes and, for each plane, the corners
//! that close its polygon.

/// Which planes meet where: each corner's three planes, and for each plane the corners that
/// close its polygon after its stretch (from the one on the crease its stretch ends on).
pub struct Plan {
    /// Each corner's three planes (by index).
    pub corners: Vec<[usize; 3]>,
    /// Each plane's corners after its stretch, in order.
    pub back: Vec<Vec<usize>>,
}

/// The plan of k planes around a hidden one (plane k): each crease ends on it.
pub fn around(k: usize) -> Plan {
    let corners = (0..k).map(|j| [(j + k - 1) % k, j, k]).collect();
    let mut back: Vec<Vec<usize>> = (0..k).map(|j| vec![(j + 1) % k, j]).collect();
    back.push((0..k).collect());
    Plan { corners, back }
}

/// Every triangulation of the convex polygon `vs` (its triangles as vertex triples).
pub fn triangulations(vs: &[usize]) -> Vec<Vec<[usize; 3]>> {
    if vs.len() < 3 {
        return vec![Vec::new()];
    }
    let (a, b) = (vs[0], vs[vs.len() - 1]);
    let mut out = Vec::new();
    for i in 1..vs.len() - 1 {
        for left in triangulations(&vs[..=i]) {
            for right in triangulations(&vs[i..]) {
                let mut t = left.clone();
                t.extend(right);
                t.push([a, vs[i], b]);
                out.push(t);
            }
        }
    }
    out
}

/// The plan of k planes whose corners are the triangles of a triangulation of their polygon
/// (plane j beside j ± 1): plane j's corners are its triangles, from the one on its side to
/// j + 1 round to the one on its side to j − 1.
pub fn meeting(k: usize, triangles: Vec<[usize; 3]>) -> Plan {
    let back = (0..k)
        .map(|j| {
            let mut beside: Vec<usize> = triangles
                .iter()
                .filter(|t| t.contains(&j))
                .flatten()
                .copied()
                .filter(|&u| u != j)
                .collect();
            beside.sort_by_key(|&u| (u + k - j) % k);
            beside.dedup();
            (beside.windows(2))
                .filter_map(|w| {
                    triangles
                        .iter()
                        .position(|t| t.contains(&j) && t.contains(&w[0]) && t.contains(&w[1]))
                })
                .collect()
        })
        .collect();
    Plan {
        corners: triangles,
        back,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// The polygons a plan draws, with each stretch cut to its two crease points (vertex j for
    /// crease point j, k + c for corner c), fit together: every edge but the ring's own is
    /// walked once each way, the ring's once, forwards (a closed, oriented disk).
    fn fits(k: usize, plan: &Plan) {
        let mut walked: HashMap<(usize, usize), usize> = HashMap::new();
        for (j, back) in plan.back.iter().enumerate() {
            let mut part: Vec<usize> = if j < k {
                vec![j, (j + 1) % k]
            } else {
                Vec::new()
            };
            part.extend(back.iter().map(|&c| k + c));
            for i in 0..part.len() {
                *walked
                    .entry((part[i], part[(i + 1) % part.len()]))
                    .or_default() += 1;
            }
        }
        for (&(u, v), &n) in &walked {
            assert_eq!(n, 1, "{k}: edge {u}–{v} walked {n} times");
            let ring = u < k && v == (u + 1) % k;
            assert_eq!(walked.contains_key(&(v, u)), !ring, "{k}: edge {u}–{v}");
        }
        for j in 0..k {
            assert!(walked.contains_key(&(j, (j + 1) % k)), "{k}: stretch {j}");
        }
    }

    /// Triangulations number as the Catalan numbers, and every plan (each triangulation's, and
    /// the hidden face's) fits together.
    #[test]
    fn plans_fit_together() {
        for (k, count) in [(3, 1), (4, 2), (5, 5), (6, 14)] {
            let all = triangulations(&(0..k).collect::<Vec<_>>());
            assert_eq!(all.len(), count, "{k} planes");
            for t in all {
                assert_eq!(t.len(), k - 2);
                fits(k, &meeting(k, t));
            }
            fits(k, &around(k));
        }
    }
}
