//! The tags a node gives at every point where its parts leave no choice: what the tag walks
//! (`tags.rs`) need not walk.

use crate::scene::{NodeId, NodeKind, Scene};

/// The tag (an id, 0 for none) each node's walk gives at every point, where its parts leave it
/// no choice: a part loose as a whole, a group in one material. Operators pick their tag among
/// their children's (`MatRule::pick`), so children that all tag alike tag their parent alike;
/// `own(node, inner)` is the node's own rule applied to the tag picked from its children (as
/// `Tagging::tag` in `tags.rs`, 0 standing for none). A function whose root is constant needs
/// no walk.
fn constant_tags(scene: &Scene, own: &dyn Fn(NodeId, u32) -> u32) -> Vec<Option<u32>> {
    /// The node's constant tag (`None`: it varies), each node worked out once (`memo`).
    fn visit(
        scene: &Scene,
        id: NodeId,
        own: &dyn Fn(NodeId, u32) -> u32,
        memo: &mut [Option<Option<u32>>],
    ) -> Option<u32> {
        if let Some(known) = memo[id] {
            return known;
        }
        let inner = match &scene.nodes[id].kind {
            NodeKind::Operator { children, .. } => {
                let mut tags = children.iter().map(|&c| visit(scene, c, own, memo));
                let first = tags.next().flatten();
                // Every child is visited (the memo is filled for all of them).
                tags.fold(first, |acc, t| if acc == t { acc } else { None })
            }
            _ => Some(0),
        };
        let tag = inner.map(|c| own(id, c));
        memo[id] = Some(tag);
        tag
    }
    let mut memo = vec![None; scene.nodes.len()];
    (0..scene.nodes.len())
        .map(|id| visit(scene, id, own, &mut memo))
        .collect()
}

/// [`constant_tags`] of the material id (1-based, 0 the default): a node in one material.
pub fn constant_materials(scene: &Scene) -> Vec<Option<u32>> {
    constant_tags(scene, &|id, inner| match scene.nodes[id].material {
        Some(k) if inner == 0 => k + 1,
        _ => inner,
    })
}

/// [`constant_tags`] of looseness (1 loose, 0 not; `eval::loose`): a node loose as a whole.
pub fn constant_looseness(scene: &Scene) -> Vec<Option<u32>> {
    constant_tags(scene, &|id, inner| {
        if scene.breaks_unit_gradient(id) {
            1
        } else {
            inner
        }
    })
}
