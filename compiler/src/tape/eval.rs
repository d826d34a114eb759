//! Running a part tree at a point in f64: its value, material and blended materials, as the
//! reference evaluator gives them for the scene it came from (`reference::eval::sample`,
//! `reference::eval::blend`).

use super::{Part, PartKind, Way};
use crate::catalog::operators::{smax, smin};
use crate::reference::blend::{Blend, smin_weight};
use crate::scene::{NodeKind, Scene};
use glam::DVec3;

/// The value (as the part's parent sees it; for the root, the scene's distance bound) and the
/// material of `part` at world point `p`.
pub fn sample(scene: &Scene, part: &Part, p: DVec3) -> (f64, Option<u32>) {
    let (raw, inner) = match &part.kind {
        PartKind::Leaf => match &scene.nodes[part.node].kind {
            NodeKind::Primitive { prim, ctx } => ((prim.eval)(ctx, part.frame.apply(p)), None),
            // (`build` makes leaves of primitives only.)
            _ => (f64::NAN, None),
        },
        PartKind::Fold { way, k, children } => fold(scene, (*way, *k), children, p),
    };
    (raw * part.factor, inner.or(part.material))
}

/// The value of `part` at `p` (see [`sample`]).
pub fn value(scene: &Scene, part: &Part, p: DVec3) -> f64 {
    sample(scene, part, p).0
}

/// A fold's raw field and picked material at `p`: its children's values (negated where the fold
/// says) combined in order as the catalog's operators fold them, the material of the nearest
/// (Min) or farthest (Max) child value as `MatRule::pick` picks it.
fn fold(
    scene: &Scene,
    (way, k): (Way, f64),
    children: &[(Part, bool)],
    p: DVec3,
) -> (f64, Option<u32>) {
    let signed = |(c, negate): &(Part, bool)| {
        let (v, m) = sample(scene, c, p);
        (if *negate { -v } else { v }, m)
    };
    let Some(first) = children.first() else {
        return (f64::NAN, None);
    };
    let (mut acc, mut material) = signed(first);
    let mut best = acc;
    for child in &children[1..] {
        let (v, m) = signed(child);
        acc = combine(way, k, acc, v);
        let better = match way {
            Way::Min => v < best,
            Way::Max => v > best,
        };
        if better {
            (best, material) = (v, m);
        }
    }
    (acc, material)
}

/// Two values combined as the fold's operator does: `min`/`max` as the sharp operators call
/// them, IQ's quadratic smooth minimum and maximum with radius `k` > 0.
pub fn combine(way: Way, k: f64, a: f64, b: f64) -> f64 {
    match (way, k > 0.0) {
        (Way::Min, false) => a.min(b),
        (Way::Max, false) => a.max(b),
        (Way::Min, true) => smin(a, b, k),
        (Way::Max, true) => smax(a, b, k),
    }
}

/// The value and blended materials (`reference::blend::Blend`: ids as material + 1, 0 for
/// none) of `part` at `p`, by `reference::blend::pick`'s rule on each fold's running value: the
/// f64 twin of the shader's `tape_blend` (`lower/data/blend.rs`).
pub fn blend(scene: &Scene, part: &Part, p: DVec3) -> (f64, Blend) {
    let own = part.material.map_or(0, |m| m + 1);
    let (raw, inner) = match &part.kind {
        PartKind::Leaf => return (value(scene, part, p), Blend::plain(own)),
        PartKind::Fold { way, k, children } => {
            let signed = |(c, negate): &(Part, bool)| {
                let (v, b) = blend(scene, c, p);
                (if *negate { -v } else { v }, b)
            };
            let Some(first) = children.first() else {
                return (f64::NAN, Blend::plain(own));
            };
            let (mut acc, mut running) = signed(first);
            for child in &children[1..] {
                let (v, b) = signed(child);
                let (x, y) = match way {
                    Way::Min => (acc, v),
                    Way::Max => (-acc, -v),
                };
                running = if (x - y).abs() >= *k {
                    if x <= y { running } else { b }
                } else {
                    Blend {
                        a: running.dominant(),
                        b: b.dominant(),
                        t: smin_weight(x, y, *k),
                    }
                };
                acc = combine(*way, *k, acc, v);
            }
            (acc, running.under(own))
        }
    };
    (raw * part.factor, inner)
}
