//! Materials through smooth operators (issue 17, item 6): where a smooth union, intersection or
//! subtraction blends two shapes' fields, or `mix` morphs one into the other, the surface's
//! colour and highlight blend too, by the same weight the field uses.
//!
//! The rule (no peer specifies one): a blending operator gives its surface two materials and
//! the weight t of the second. For the smooth minimum of radius k (IQ's quadratic polynomial,
//! `catalog::operators::smin`) t is IQ's mix factor of that very smin: with h = max(k − |a − b|,
//! 0)/k, t = h²/2 where the first shape is nearer and 1 − h²/2 where the second is — 0 or 1
//! outside the seam, ½ on the line where the fields are equal, continuous across it, so the
//! colour changes exactly where and as fast as the shape does. The smooth maximum and
//! subtraction are the smooth minimum of negated fields and take its factor; `mix(w)` takes t
//! = w (Liktor's metamorphosis: shape and colour morph together). Children are folded left to
//! right as the field is; a child that is itself a blend enters with its dominant material
//! (the one with weight above ½, the first at ½), so one surface point blends two materials
//! at most. Colour (patterns included) and specular blend; the material channel, reflection,
//! transparency and index of refraction follow the one material the sharp rule picks
//! (`MatRule::pick`).

use crate::catalog::operators::{smax, smin};
use crate::catalog::{Ctx, MatRule};
use crate::scene::{NodeKind, Scene};

/// Two material ids (0 the default, i + 1 the i-th declared) and the weight of the second.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    /// The first material.
    pub a: u32,
    /// The second material.
    pub b: u32,
    /// The weight of the second, 0..1.
    pub t: f64,
}

impl Blend {
    /// One material.
    pub fn plain(m: u32) -> Blend {
        Blend { a: m, b: m, t: 0.0 }
    }

    /// The material with weight above ½ (the first at ½).
    pub fn dominant(self) -> u32 {
        if self.t <= 0.5 { self.a } else { self.b }
    }

    /// The blend under an outer tag `m`: parts without a material of their own take it (as a
    /// tag applies to the parts of its subtree that have none).
    pub fn under(self, m: u32) -> Blend {
        Blend {
            a: if self.a == 0 { m } else { self.a },
            b: if self.b == 0 { m } else { self.b },
            t: self.t,
        }
    }
}

/// IQ's mix factor of the quadratic smooth minimum of `a` and `b` with radius `k`: the weight
/// of `b` (a sharp 0 or 1 for k = 0).
pub fn smin_weight(a: f64, b: f64, k: f64) -> f64 {
    if k <= 0.0 {
        return if a <= b { 0.0 } else { 1.0 };
    }
    let h = (k - (a - b).abs()).max(0.0) / k;
    let m = 0.5 * h * h;
    if a <= b { m } else { 1.0 - m }
}

/// The blend an operator with material rule `rule` gives its surface from its children's raw
/// fields and blends (the sharp rules pick one child's, as `MatRule::pick`).
pub fn pick(rule: MatRule, ctx: &Ctx, children: &[(f64, Option<Blend>)]) -> Option<Blend> {
    if !rule.blends() {
        return rule.pick(ctx, children);
    }
    if children.iter().all(|c| c.1.is_none()) {
        return None;
    }
    let tag = |i: usize| children[i].1.map_or(0, |b| b.dominant());
    if rule == MatRule::Weighted {
        return Some(Blend {
            a: tag(0),
            b: tag(1),
            t: ctx.num(0),
        });
    }
    let k = ctx.num(0);
    let norm = |i: usize| children[i].0 / ctx.child_lambda[i];
    let mut d = norm(0);
    let mut blend = children[0].1.unwrap_or(Blend::plain(0));
    for (i, child) in children.iter().enumerate().skip(1) {
        let di = norm(i);
        // smax(a, b) = −smin(−a, −b); the cut is smax(d, −dᵢ).
        let (x, y, next) = match rule {
            MatRule::SmoothNearest => (d, di, smin(d, di, k)),
            MatRule::SmoothFarthest => (-d, -di, smax(d, di, k)),
            _ => (-d, di, smax(d, -di, k)),
        };
        let t = smin_weight(x, y, k);
        // Outside the seam (|x − y| ≥ k) one side is whole, blend included; in it, two
        // dominants.
        blend = if (x - y).abs() >= k {
            if x <= y {
                blend
            } else {
                child.1.unwrap_or(Blend::plain(0))
            }
        } else {
            Blend {
                a: blend.dominant(),
                b: tag(i),
                t,
            }
        };
        d = next;
    }
    Some(blend)
}

/// Whether some blending operator the scene reaches has two different materials below it
/// that can surface (then shading blends: `eval::blend`, the shader's `map_blend`): a blend
/// tagged as a whole, or whose parts all carry one material, has one material and needs none.
pub fn has_blends(scene: &Scene) -> bool {
    // The materials given below `id`, and whether a leaf is reached without one (it then
    // surfaces with what is given at or above `id`: one more material).
    let surfacing = |id: usize| {
        let mut given = std::collections::BTreeSet::new();
        let mut bare = false;
        let mut stack: Vec<(usize, bool)> = scene.nodes[id]
            .children()
            .iter()
            .map(|&c| (c, false))
            .collect();
        while let Some((n, tagged)) = stack.pop() {
            let node = &scene.nodes[n];
            if let Some(m) = node.material {
                given.insert(m);
            }
            let tagged = tagged || node.material.is_some();
            let children = node.children();
            if children.is_empty() && !tagged {
                bare = true;
            }
            stack.extend(children.iter().map(|&c| (c, tagged)));
        }
        given.len() + usize::from(bare)
    };
    scene.reachable().into_iter().any(|n| {
        matches!(&scene.nodes[n].kind, NodeKind::Operator { op, .. } if op.materials.blends())
            && surfacing(n) > 1
    })
}
