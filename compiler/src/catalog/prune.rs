//! Bounding volumes inside `map`: a union's children grouped into a tree of boxes, so that an
//! evaluation skips every group whose box is farther than the nearest distance found so far.
//!
//! Only children whose f/λ is the distance to their surface outside it (`Node::exact`) and
//! whose box is finite are grouped. For such a child, at a point outside its box, f/λ is the
//! distance to a surface inside the box, so at least the distance to the box: when that is
//! already ≥ the running minimum d, min(d, f/λ) = d and the child need not be evaluated. The
//! pruned union is therefore the same function as the plain one, evaluated in less work; the
//! other children (loose fields, unbounded shapes, the ground plane) are evaluated first, in
//! their order, which also gives the running minimum a good start.

use super::{Bound, Ctx};
use glam::DVec3;

/// Fewest groupable children for a tree to be built.
pub const MIN_CHILDREN: usize = 3;

/// Most children in a leaf group. Measured by hand on the CPU evaluator (the f64 ground truth
/// of `sdfc bench` at 256×144; the village written as a flat union of 39 parts, and the
/// composition): with no tree 21.8 s and 3.4 s; leaves of 2, every group tested, 3.7 s and
/// 2.0 s; leaves of 4 or 8, or tests only on groups costing 4 or 8 primitive evaluations, no
/// better (3.6–4.5 s, 2.0–4.3 s). `cargo bench --bench eval` keeps the first comparison.
pub const LEAF: usize = 2;

/// Fewest grouped children for the shader to test a union's tree by default
/// (`BoundingVolumes::Large`). Measured on lavapipe (Mesa 25.0.7, which skips a branch no lane
/// takes), each example's trace with trees against its plain trace, alternating frames at
/// 320×180 (`sdfc bench … --reference plain.wgsl`, stop 19). With every tree tested, the
/// examples whose unions group 3 or 4 parts were up to 1.33× slower (the temple's platform and
/// columns, the dodecahedron's spheres, the jewel's setting, the lamp, domain_ops), and those
/// with a union of 5 or more 0.46–0.86× (textures, shapes, the village, primitives,
/// composition). With this threshold every example is either plain or faster (0.21–0.86×);
/// scattered scenes of 3–64 random parts measured 0.15–0.94× with every tree.
pub const GPU_MIN_GROUPED: usize = 5;

/// A union's evaluation plan.
#[derive(Clone, Debug, PartialEq)]
pub struct Tree {
    /// Children evaluated unconditionally, first, in order.
    pub first: Vec<usize>,
    /// Groups of the other children, each behind its box test.
    pub groups: Vec<Group>,
}

/// A box and what it holds.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The box's lowest corner.
    pub lo: DVec3,
    /// The box's highest corner.
    pub hi: DVec3,
    /// Children (a leaf) or groups.
    pub inside: Inside,
}

/// What a group holds.
#[derive(Clone, Debug, PartialEq)]
pub enum Inside {
    /// Child indices.
    Children(Vec<usize>),
    /// Smaller groups.
    Groups(Vec<Group>),
}

impl Tree {
    /// The plan for a union with these children, if grouping pays (enough exact children
    /// with finite boxes).
    pub fn build(ctx: &Ctx) -> Option<Tree> {
        let n = ctx.child_bound.len();
        let boxed = |i: usize| {
            let b: Bound = ctx.child_bound[i];
            ctx.child_exact[i] && b.lo.is_finite() && b.hi.is_finite()
        };
        let (grouped, first): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| boxed(i));
        if grouped.len() < MIN_CHILDREN {
            return None;
        }
        let group = split(ctx, grouped);
        let groups = match group.inside {
            Inside::Groups(g) => g,
            Inside::Children(_) => vec![group],
        };
        Some(Tree { first, groups })
    }

    /// How many children the groups hold (every child but `first`).
    pub fn grouped(&self) -> usize {
        self.groups.iter().map(Group::children).sum()
    }

    /// The union's value at `p` given each child's f/λ by `child`: the same as the minimum of
    /// all, evaluating only the children a box test does not rule out.
    pub fn min(&self, p: DVec3, child: &mut dyn FnMut(usize) -> f64) -> f64 {
        let mut d = f64::MAX;
        for &i in &self.first {
            d = d.min(child(i));
        }
        for g in &self.groups {
            d = g.min(p, d, child);
        }
        d
    }
}

impl Group {
    /// The running minimum `d` after this group at `p`.
    fn min(&self, p: DVec3, mut d: f64, child: &mut dyn FnMut(usize) -> f64) -> f64 {
        if !self.near(p, d) {
            return d;
        }
        match &self.inside {
            Inside::Children(c) => {
                for &i in c {
                    d = d.min(child(i));
                }
            }
            Inside::Groups(g) => {
                for g in g {
                    d = g.min(p, d, child);
                }
            }
        }
        d
    }

    /// Whether a child in the box can be below `d`: the box's distance is at most d, i.e.
    /// |max(|p − c| − h, 0)|² ≤ max(d, 0)². Where d ≤ 0 (p inside some part) only a part that
    /// also holds p can be lower, and then p is in its box. The shader tests the same.
    pub fn near(&self, p: DVec3, d: f64) -> bool {
        let (c, h) = (self.center(), self.half());
        let q = ((p - c).abs() - h).max(DVec3::ZERO);
        let m = d.max(0.0);
        q.dot(q) <= m * m
    }

    /// How many children the group holds, in all its groups.
    fn children(&self) -> usize {
        match &self.inside {
            Inside::Children(c) => c.len(),
            Inside::Groups(g) => g.iter().map(Group::children).sum(),
        }
    }

    /// The box's centre.
    pub fn center(&self) -> DVec3 {
        (self.lo + self.hi) * 0.5
    }

    /// The box's half extents.
    pub fn half(&self) -> DVec3 {
        (self.hi - self.lo) * 0.5
    }
}

/// Groups `children` by halving along the longest spread of their boxes' centres.
fn split(ctx: &Ctx, mut children: Vec<usize>) -> Group {
    let (lo, hi) = children
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &i| {
            (lo.min(ctx.child_bound[i].lo), hi.max(ctx.child_bound[i].hi))
        });
    if children.len() <= LEAF {
        return Group {
            lo,
            hi,
            inside: Inside::Children(children),
        };
    }
    let centre = |i: usize| (ctx.child_bound[i].lo + ctx.child_bound[i].hi) * 0.5;
    let (clo, chi) = children
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &i| {
            (lo.min(centre(i)), hi.max(centre(i)))
        });
    let spread = chi - clo;
    let axis = if spread.x >= spread.y && spread.x >= spread.z {
        0
    } else if spread.y >= spread.z {
        1
    } else {
        2
    };
    // A stable sort by the centre keeps the written order among equals (the same tree on
    // every run and machine).
    children.sort_by(|&a, &b| centre(a)[axis].total_cmp(&centre(b)[axis]));
    let right = children.split_off(children.len() / 2);
    Group {
        lo,
        hi,
        inside: Inside::Groups(vec![split(ctx, children), split(ctx, right)]),
    }
}
