//! The CPU reference evaluator: the scene's field and material at a point, in f64. It is the
//! ground truth the GPU output is checked against.

use crate::catalog::{Ctx, MatRule, Sample};
use crate::reference::blend::Blend;
use crate::scene::{Node, NodeId, NodeKind, Scene};
use glam::DVec3;

/// The scene's distance bound at `p`: the root's field divided by its λ, so that stepping by it
/// never passes a surface (Liktor §2.2, f/λ).
pub fn distance(scene: &Scene, p: DVec3) -> f64 {
    // No materials: a union's bounding-volume tree may leave children unevaluated.
    raw(&scene.nodes, scene.root, p) / scene.root_node().lambda
}

/// Distance bound and material at `p`.
pub fn sample(scene: &Scene, p: DVec3) -> Sample {
    let s = node(scene, scene.root, p);
    Sample {
        d: s.d / scene.root_node().lambda,
        mat: s.mat,
    }
}

/// The raw field of one node (not divided by its λ).
pub fn node(scene: &Scene, id: NodeId, p: DVec3) -> Sample {
    node_seen(scene, id, p, &mut |_, _| {})
}

/// The raw field of node `id` of `nodes` (a scene's nodes, or those being checked) at `p`.
pub fn raw(nodes: &[Node], id: NodeId, p: DVec3) -> f64 {
    let no_tag = |_: NodeId, _: DVec3, _: Option<u32>| None;
    node_with(nodes, id, p, &mut |_, _| {}, &no_tag, false).0
}

/// [`node`], calling `seen(id, q)` for every node evaluated on the way, with the point in that
/// node's own coordinates (how the annotation check finds where rays evaluate a node).
pub fn node_seen<F: FnMut(NodeId, DVec3)>(
    scene: &Scene,
    id: NodeId,
    p: DVec3,
    seen: &mut F,
) -> Sample {
    let (d, mat) = node_with(
        &scene.nodes,
        id,
        p,
        seen,
        &|n, _, inner| inner.or(scene.nodes[n].material),
        true,
    );
    Sample { d, mat }
}

/// A tag the walk carries up the graph, picked at each operator by its material rule.
pub trait Tag: Copy {
    /// The tag of an operator's result from its children's raw fields and tags.
    fn pick(rule: MatRule, ctx: &Ctx, children: &[(f64, Option<Self>)]) -> Option<Self>;
}

impl Tag for u32 {
    fn pick(rule: MatRule, ctx: &Ctx, children: &[(f64, Option<u32>)]) -> Option<u32> {
        rule.pick(ctx, children)
    }
}

impl Tag for (u32, DVec3) {
    fn pick(rule: MatRule, ctx: &Ctx, children: &[(f64, Option<Self>)]) -> Option<Self> {
        rule.pick(ctx, children)
    }
}

/// A part whose hit needs confirming (`loose`), picked by [`MatRule::pick_loose`].
#[derive(Clone, Copy)]
struct Loose;

impl Tag for Loose {
    fn pick(rule: MatRule, ctx: &Ctx, children: &[(f64, Option<Loose>)]) -> Option<Loose> {
        rule.pick_loose(ctx, children)
    }
}

impl Tag for Blend {
    fn pick(rule: MatRule, ctx: &Ctx, children: &[(f64, Option<Blend>)]) -> Option<Blend> {
        crate::reference::blend::pick(rule, ctx, children)
    }
}

/// The materials blended at `p` by the smooth operators and `mix` (`crate::reference::blend`); one
/// material where none blends.
pub fn blend(scene: &Scene, p: DVec3) -> Blend {
    let tag = |n: NodeId, _: DVec3, inner: Option<Blend>| match scene.nodes[n].material {
        None => inner,
        Some(m) => Some(inner.map_or(Blend::plain(m + 1), |b| b.under(m + 1))),
    };
    node_with(&scene.nodes, scene.root, p, &mut |_, _| {}, &tag, true)
        .1
        .unwrap_or(Blend::plain(0))
}

/// The material id at `p` (0 the default, i + 1 the i-th declared) and the point in the own
/// coordinates of the node that gave it (where a material's pattern is evaluated, so that it
/// follows the shape's transforms); `p` itself for the default material.
pub fn surface(scene: &Scene, p: DVec3) -> (u32, DVec3) {
    let tag = |n: NodeId, q: DVec3, inner: Option<(u32, DVec3)>| {
        inner.or(scene.nodes[n].material.map(|m| (m + 1, q)))
    };
    node_with(&scene.nodes, scene.root, p, &mut |_, _| {}, &tag, true)
        .1
        .unwrap_or((0, p))
}

/// Whether the surface nearest `p` (as the materials pick it: the nearest part of a union…;
/// at an intersection or a cut, any loose operand `p` is outside of, or all being loose:
/// [`MatRule::pick_loose`]) belongs to a part whose f/λ is not a distance to first order
/// (`Scene::breaks_unit_gradient`): where a hit needs confirming (`trace::careful`).
pub fn loose(scene: &Scene, p: DVec3) -> bool {
    let tag = |id: NodeId, _: DVec3, inner: Option<Loose>| {
        if scene.breaks_unit_gradient(id) {
            Some(Loose)
        } else {
            inner
        }
    };
    node_with(&scene.nodes, scene.root, p, &mut |_, _| {}, &tag, true)
        .1
        .is_some()
}

/// The walk of [`node_seen`] with the tag a node gives its result (`tag(node, its point, the
/// tag its operator picked from the children)`): the material, whether the part is loose, or
/// the material with the point where it was given. With `tags`, the children a union's
/// bounding-volume tree skipped are evaluated after all, so that the tag is picked from every
/// child as without the tree. Returns the raw field and the tag.
fn node_with<F: FnMut(NodeId, DVec3), T: Tag>(
    nodes: &[Node],
    id: NodeId,
    p: DVec3,
    seen: &mut F,
    tag: &impl Fn(NodeId, DVec3, Option<T>) -> Option<T>,
    tags: bool,
) -> (f64, Option<T>) {
    seen(id, p);
    let n = &nodes[id];
    let (d, inner) = match &n.kind {
        NodeKind::Primitive { prim, ctx } => ((prim.eval)(ctx, p), None),
        NodeKind::Implicit { field } => (field.eval(p), None),
        NodeKind::Operator { op, ctx, children } => {
            let mut nearest: Vec<Option<(f64, Option<T>)>> = vec![None; children.len()];
            // A child evaluated more than once (the copies of a `repeat`) gives the material
            // of its nearest evaluation.
            let mut child = |i: usize, q: DVec3| {
                let s = node_with(nodes, children[i], q, seen, tag, tags);
                if nearest[i].is_none_or(|old| s.0 < old.0) {
                    nearest[i] = Some(s);
                }
                s.0
            };
            let d = (op.eval)(ctx, p, &mut child);
            if tags && (ctx.prune.is_some() || ctx.baked.is_some()) {
                // A union evaluates its children at its own point, and a baked shape is where
                // its map is.
                for (i, s) in nearest.iter_mut().enumerate() {
                    if s.is_none() {
                        *s = Some(node_with(nodes, children[i], p, seen, tag, tags));
                    }
                }
            }
            let nearest: Vec<(f64, Option<T>)> = nearest
                .into_iter()
                .map(|s| s.unwrap_or((d, None)))
                .collect();
            (d, T::pick(op.materials, ctx, &nearest))
        }
    };
    (d, tag(id, p, inner))
}

/// The corners of the tetrahedron whose samples give the normal: they sum to zero and
/// Σ kᵢkᵢᵀ = 4I, so Σ kᵢ·f(p + e·kᵢ) = 4e·∇f(p) + 4e²·(H_yz, H_xz, H_xy) + O(e³) (the third
/// moment Σ kₓk_yk_z = 4): the gradient's error is O(e) where the Hessian has mixed terms,
/// against central differences' O(e²) — four evaluations instead of six.
pub const TETRAHEDRON: [DVec3; 4] = [
    DVec3::new(1.0, -1.0, -1.0),
    DVec3::new(-1.0, -1.0, 1.0),
    DVec3::new(-1.0, 1.0, -1.0),
    DVec3::new(1.0, 1.0, 1.0),
];

/// The scene field's gradient from four samples at distance `h` around `p` (the corners of
/// [`TETRAHEDRON`] scaled by h/√3), normalised; a zero gradient (at a cusp or the centre of
/// a sphere) gives the zero vector rather than NaN. The shader's `normal` does the same.
pub fn normal(scene: &Scene, p: DVec3, h: f64) -> DVec3 {
    unit_gradient(|q| distance(scene, q), p, h)
}

/// The unit gradient of any field `f` at `p` by the same four samples as [`normal`] (the
/// mesher's clipped field uses it); the zero vector where it vanishes.
pub fn unit_gradient(f: impl Fn(DVec3) -> f64, p: DVec3, h: f64) -> DVec3 {
    unit_gradient_of(&gradient_points(p, h).map(f))
}

/// The four points [`unit_gradient`] samples at distance `h` around `p`.
pub fn gradient_points(p: DVec3, h: f64) -> [DVec3; 4] {
    let e = h / 3f64.sqrt();
    TETRAHEDRON.map(|k| p + k * e)
}

/// The unit gradient from the field's values at [`gradient_points`], in their order (for a
/// caller that evaluates them in a batch); the zero vector where it vanishes.
pub fn unit_gradient_of(values: &[f64]) -> DVec3 {
    let g: DVec3 = TETRAHEDRON.iter().zip(values).map(|(&k, &v)| k * v).sum();
    g.try_normalize().unwrap_or(DVec3::ZERO)
}
