//! The walks that tag a node's field: the material id a surface takes by the operators'
//! rules (`map_material`), whether its part is loose (`map_loose`), and the point in the own
//! coordinates of the shape whose material it takes (`map_texture`, for patterns).

use super::Walk;
use super::constant::{constant_looseness, constant_materials};
use super::pick::{pick_blend, pick_loose, pick_material};
use crate::ir::builder::{Ex, FnBuilder};
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
    /// Whether blending operators blend the tags (`map_blend`) rather than pick one.
    pub blends: bool,
    /// Whether the tag is looseness (`map_loose`): intersections and cuts pick it by
    /// [`pick_loose`].
    pub loose: bool,
    /// The nodes whose tag is one constant at every point (`constant.rs`); empty where
    /// the tag is not an id.
    pub constant: &'a [Option<u32>],
}

impl Walk<'_> {
    /// Material id (1-based; 0 the default; `None`: statically no material) of a node.
    pub(super) fn with_material(&self, b: &mut FnBuilder, id: NodeId, p: Ex) -> Option<Ex> {
        let scene = self.scene;
        let constant = constant_materials(scene);
        self.tag_of(
            b,
            id,
            p,
            &Tagging {
                zero: &|b| b.u(0),
                blends: false,
                loose: false,
                constant: &constant,
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

    /// Looseness of a node: 1 where the part the materials' rule picks is loose
    /// (`Scene::breaks_unit_gradient`, `eval::loose`), 0 or `None` where not.
    pub(super) fn with_loose(&self, b: &mut FnBuilder, id: NodeId, p: Ex) -> Option<Ex> {
        let scene = self.scene;
        let constant = constant_looseness(scene);
        self.tag_of(
            b,
            id,
            p,
            &Tagging {
                zero: &|b| b.u(0),
                blends: false,
                loose: true,
                constant: &constant,
                tag: &|b, id, _, inner| {
                    if scene.breaks_unit_gradient(id) {
                        Some(b.u(1))
                    } else {
                        inner
                    }
                },
            },
        )
    }

    /// Field and `vec4(q, 1)` of a node, q the point in the own coordinates of the node whose
    /// material the surface takes (`eval::surface`); `vec4(0)` where no material was given.
    /// The same picks as [`Walk::with_material`], so the point belongs to the same material.
    pub(super) fn with_texture(&self, b: &mut FnBuilder, id: NodeId, p: Ex) -> Option<Ex> {
        let scene = self.scene;
        self.tag_of(
            b,
            id,
            p,
            &Tagging {
                zero: &|b| {
                    let v4 = b.m.vec(naga::VectorSize::Quad);
                    let z = b.f(0.0);
                    b.compose(v4, vec![z, z, z, z])
                },
                blends: false,
                loose: false,
                constant: &[],
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

    /// Field and `vec3(first id, second id, weight of the second)` of a node: the materials a
    /// blending operator mixes (`crate::reference::blend`, `eval::blend`); `vec3(0)` where none was given.
    pub(super) fn with_blend(&self, b: &mut FnBuilder, id: NodeId, p: Ex) -> Option<Ex> {
        let scene = self.scene;
        self.tag_of(
            b,
            id,
            p,
            &Tagging {
                zero: &|b| b.splat3(0.0),
                blends: true,
                loose: false,
                constant: &[],
                tag: &|b, id, _, inner| {
                    let Some(m) = scene.nodes[id].material else {
                        return inner;
                    };
                    let own = b.f(m as f64 + 1.0);
                    Some(match inner {
                        None => {
                            let zero = b.f(0.0);
                            let v3 = b.m.vec3();
                            b.compose(v3, vec![own, own, zero])
                        }
                        // Parts without a material of their own take this one (`Blend::under`).
                        Some(v) => {
                            let [x, y, t] = b.xyz(v);
                            let zero = b.f(0.0);
                            let xe = b.bin(naga::BinaryOperator::Equal, x, zero);
                            let ye = b.bin(naga::BinaryOperator::Equal, y, zero);
                            let x = b.select(xe, own, x);
                            let y = b.select(ye, own, y);
                            let v3 = b.m.vec3();
                            b.compose(v3, vec![x, y, t])
                        }
                    })
                },
            },
        )
    }

    /// The tag of a node (a function's root): a constant where the node's parts leave it no
    /// choice (nothing walked), else [`Walk::with_tag`]'s.
    fn tag_of(&self, b: &mut FnBuilder, id: NodeId, p: Ex, tag: &Tagging) -> Option<Ex> {
        match tag.constant.get(id) {
            Some(&Some(c)) => (c != 0).then(|| b.u(c)),
            _ => self.with_tag(b, id, p, tag).1,
        }
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
        // A part whose tag is constant needs only its field. (Not under bounding-volume trees:
        // the tag walk takes every child's value, which the tree's field may not give.)
        if !self.any_tree
            && let Some(&Some(c)) = tag.constant.get(id)
        {
            let d = self.distance(b, id, p);
            return (d, (c != 0).then(|| b.u(c)));
        }
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
                // A baked shape's field is its map's: its tag is walked where the map is.
                let seen: Vec<(Ex, Option<Ex>)> = seen
                    .into_iter()
                    .enumerate()
                    .map(|(i, s)| s.unwrap_or_else(|| self.with_tag(b, children[i], p, tag)))
                    .collect();
                let picked = if tag.blends && op.materials.blends() {
                    pick_blend(b, op.materials, ctx, &seen)
                } else if tag.loose {
                    pick_loose(b, op.materials, ctx, &seen, tag.zero)
                } else {
                    pick_material(b, op.materials, ctx, &seen, tag.zero)
                };
                (d, picked)
            }
            _ => (self.distance(b, id, p), None),
        };
        (d, (tag.tag)(b, id, p, m))
    }
}
