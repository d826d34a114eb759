//! The walks that tag a node's field: the material id a surface takes by the operators'
//! rules (`map_material`), whether its part is loose (`map_loose`), and the point in the own
//! coordinates of the shape whose material it takes (`map_texture`, for patterns).

use super::Walk;
use super::builder::{Ex, FnBuilder};
use super::ops;
use crate::catalog::MatRule;
use crate::scene::{NodeId, NodeKind};

/// The tag a node gives its field: `(node, its point, the tag picked from its children)`.
pub(super) type TagFn<'a> = dyn Fn(&mut FnBuilder, NodeId, Ex, Option<Ex>) -> Option<Ex> + 'a;

/// The value a tag has where no part gave one.
pub(super) type Zero<'a> = dyn Fn(&mut FnBuilder) -> Ex + 'a;

/// How a walk tags: `tag(node, its point, the tag picked from its children)`, and the value of
/// an absent tag among present ones.
pub(super) struct Tagging<'a> {
    /// The tag a node gives its field.
    pub tag: &'a TagFn<'a>,
    /// An absent tag's value.
    pub zero: &'a Zero<'a>,
}

impl Walk<'_> {
    /// Field and material id (1-based; 0 the default; `None`: statically no material) of a node.
    pub(super) fn with_material(&self, b: &mut FnBuilder, id: NodeId, p: Ex) -> (Ex, Option<Ex>) {
        let scene = self.scene;
        self.with_tag(
            b,
            id,
            p,
            &Tagging {
                zero: &|b| b.u(0),
                tag: &|b, id, _, inner| match (scene.nodes[id].material, inner) {
                    (None, m) => m,
                    (Some(k), None) => Some(b.u(k + 1)),
                    (Some(k), Some(inner)) => {
                        let own = b.u(k + 1);
                        let zero = b.u(0);
                        let has = b.bin(naga::BinaryOperator::NotEqual, inner, zero);
                        Some(b.select(has, inner, own))
                    }
                },
            },
        )
    }

    /// Field and `vec4(q, 1)` of a node, q the point in the own coordinates of the node whose
    /// material the surface takes (`eval::surface`); `vec4(0)` where no material was given.
    /// The same picks as [`Walk::with_material`], so the point belongs to the same material.
    pub(super) fn with_texture(&self, b: &mut FnBuilder, id: NodeId, p: Ex) -> (Ex, Option<Ex>) {
        let scene = self.scene;
        self.with_tag(
            b,
            id,
            p,
            &Tagging {
                zero: &|b| {
                    let v4 = b.m.vec(naga::VectorSize::Quad);
                    let z = b.f(0.0);
                    b.compose(v4, vec![z, z, z, z])
                },
                tag: &|b, id, q, inner| {
                    if scene.nodes[id].material.is_none() {
                        return inner;
                    }
                    let [x, y, z] = b.xyz(q);
                    let one = b.f(1.0);
                    let v4 = b.m.vec(naga::VectorSize::Quad);
                    let own = b.compose(v4, vec![x, y, z, one]);
                    Some(match inner {
                        None => own,
                        Some(inner) => {
                            let w = b.at(inner, 3);
                            let zero = b.f(0.0);
                            let has = b.gt(w, zero);
                            b.select(has, inner, own)
                        }
                    })
                },
            },
        )
    }

    /// Field and tag of a node: the tag its operator picks from the children by the materials'
    /// rule, passed through `tag(node, picked)` (as `eval::node_with`).
    pub(super) fn with_tag(
        &self,
        b: &mut FnBuilder,
        id: NodeId,
        p: Ex,
        tag: &Tagging,
    ) -> (Ex, Option<Ex>) {
        let node = &self.scene.nodes[id];
        let (d, m) = match &node.kind {
            NodeKind::Operator { op, ctx, children } => {
                // Every child's field and tag: without a union's bounding-volume tree.
                let ctx = &*self.ctx_for(ctx, true);
                let mut seen: Vec<Option<(Ex, Option<Ex>)>> = vec![None; children.len()];
                // A child lowered more than once (the copies of a `repeat`) gives the material
                // of its nearest evaluation, as in `eval::node`.
                let mut child = |b: &mut FnBuilder, i: usize, q: Ex| {
                    let (d, m) = self.with_tag(b, children[i], q, tag);
                    seen[i] = Some(match seen[i] {
                        None => (d, m),
                        Some((d0, m0)) => {
                            let nearer = b.lt(d, d0);
                            let m = match (m, m0) {
                                (None, None) => None,
                                (m, m0) => {
                                    let m = m.unwrap_or_else(|| (tag.zero)(b));
                                    let m0 = m0.unwrap_or_else(|| (tag.zero)(b));
                                    Some(b.select(nearer, m, m0))
                                }
                            };
                            (b.select(nearer, d, d0), m)
                        }
                    });
                    d
                };
                let d = (op.lower)(b, ctx, p, &mut child);
                let seen: Vec<(Ex, Option<Ex>)> = seen
                    .into_iter()
                    .map(|s| s.expect("every child lowered"))
                    .collect();
                (d, pick_material(b, op.materials, ctx, &seen, tag.zero))
            }
            _ => (self.distance(b, id, p), None),
        };
        (d, (tag.tag)(b, id, p, m))
    }
}

/// The material rule of `catalog::MatRule::pick`, in IR.
fn pick_material(
    b: &mut FnBuilder,
    rule: MatRule,
    ctx: &crate::catalog::Ctx,
    seen: &[(Ex, Option<Ex>)],
    zero: &Zero,
) -> Option<Ex> {
    if seen.iter().all(|(_, m)| m.is_none()) {
        return None;
    }
    let mat = |b: &mut FnBuilder, i: usize| seen[i].1.unwrap_or_else(|| zero(b));
    match rule {
        MatRule::Pass => seen[0].1,
        MatRule::Weighted => Some(mat(b, usize::from(ctx.num(0) >= 0.5))),
        MatRule::Nearest | MatRule::Farthest | MatRule::Cut => {
            let sign = if rule == MatRule::Cut { -1.0 } else { 1.0 };
            let mut d = ops::scale_by(b, seen[0].0, 1.0 / ctx.child_lambda[0]);
            let mut m = mat(b, 0);
            for (i, &(di, _)) in seen.iter().enumerate().skip(1) {
                let di = ops::scale_by(b, di, sign / ctx.child_lambda[i]);
                let better = if rule == MatRule::Nearest {
                    b.lt(di, d)
                } else {
                    b.gt(di, d)
                };
                let mi = mat(b, i);
                m = b.select(better, mi, m);
                d = b.select(better, di, d);
            }
            Some(m)
        }
    }
}
