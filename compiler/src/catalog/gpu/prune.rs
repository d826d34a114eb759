//! A union's bounding-volume tree in IR (`catalog::prune`): the parts outside the tree first,
//! then each group of parts behind a test of its box against the running minimum.

use super::{ChildLower, norm};
use crate::catalog::Ctx;
use crate::catalog::prune::{Group, Inside, Tree};
use crate::ir::{Ex, FnBuilder};

/// The union by `tree`: `d` starts at [`crate::ir::FAR`] and takes the minimum with each child
/// evaluated.
pub fn union(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower, tree: &Tree) -> Ex {
    let f32t = b.m.f32();
    let start = b.f(crate::ir::FAR);
    let d = b.local("d", f32t, Some(start));
    for &i in &tree.first {
        lower_into(b, c, p, child, d, i);
    }
    for g in &tree.groups {
        group(b, c, p, child, d, g);
    }
    b.load(d)
}

/// `d = min(d, child i)`.
fn lower_into(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower, d: Ex, i: usize) {
    let v = norm(b, c, child, i, p);
    let m = b.load(d);
    let m = b.min(m, v);
    b.store(d, m);
}

/// `if` the group's box is nearer than `d`: its children or groups, each lowering `d`.
fn group(b: &mut FnBuilder, c: &Ctx, p: Ex, child: ChildLower, d: Ex, g: &Group) {
    let body = |b: &mut FnBuilder| match &g.inside {
        Inside::Children(list) => {
            for &i in list {
                lower_into(b, c, p, child, d, i);
            }
        }
        Inside::Groups(list) => {
            for g in list {
                group(b, c, p, child, d, g);
            }
        }
    };
    // |max(|p − c| − h, 0)|² ≤ max(d, 0)², as `Group::near`, with the box grown by a few f32
    // ulps of its size so that rounding its corners cannot cut into a part.
    let (c, h) = (g.center(), g.half());
    let margin = 1e-6 * (c.abs().max_element() + h.max_element());
    let centre = b.vec3_lit(c);
    let half = b.vec3_lit(h + glam::DVec3::splat(margin));
    let q = b.sub(p, centre);
    let q = b.abs(q);
    let q = b.sub(q, half);
    let zero = b.splat3(0.0);
    let q = b.max(q, zero);
    let qq = b.dot(q, q);
    let dv = b.load(d);
    let zero = b.f(0.0);
    let m = b.max(dv, zero);
    let mm = b.mul(m, m);
    let near = b.bin(naga::BinaryOperator::LessEqual, qq, mm);
    b.if_(near, body, |_| {});
}
