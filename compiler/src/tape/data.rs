//! What the data form's shader reads (issue 33 §1–2): the program of every cell of a grid over
//! the scene, concatenated in one buffer of words, each cell's range in a second buffer, and a
//! last range for points outside the grid (the whole tree). The [`Layout`] — the primitive kinds'
//! opcodes and the grid — is compiled into the shader; the [`Data`] is the host's to upload, and
//! to make again when parameters change.

use super::cells::Cells;
use super::program::{self, Program, Refused};
use super::{Part, Unsupported};
use crate::catalog::Primitive;
use crate::scene::Scene;
use glam::DVec3;

/// Cells along the grid's longest side, by default.
pub const CELLS: usize = 32;

/// What the shader is compiled with: the opcodes' kinds and the grid.
#[derive(Clone, Debug)]
pub struct Layout {
    /// The primitive kinds, in opcode order (`program::LEAF + i`).
    pub kinds: Vec<&'static Primitive>,
    /// The grid's lowest corner.
    pub lo: DVec3,
    /// The cells' edge length.
    pub size: f64,
    /// Cells along x, y and z (0 cells: no grid, every point runs the whole program).
    pub n: [usize; 3],
}

/// The buffers: programs and ranges.
#[derive(Clone, Debug)]
pub struct Data {
    /// Every cell's program, then the whole tree's: words as the shader reads them.
    pub words: Vec<[u32; 4]>,
    /// Each cell's program (first word, words), x fastest, then y, then z; then the whole's.
    pub ranges: Vec<[u32; 2]>,
    /// The mean leaves a cell's program evaluates.
    pub mean_leaves: f64,
}

/// Why a scene has no data form.
#[derive(Clone, Debug, PartialEq)]
pub enum Why {
    /// A node the tree cannot hold.
    Node(Unsupported),
    /// The program cannot be made.
    Program(Refused),
}

/// The scene's tree and layout, `cells` along the longest side of the box the scene's finite
/// parts lie in.
pub fn layout(scene: &Scene, cells: usize) -> Result<(Part, Layout), Why> {
    let tree = super::build(scene).map_err(Why::Node)?;
    let mut kinds = Vec::new();
    program::encode(scene, &tree, &mut kinds).map_err(Why::Program)?;
    let (lo, size, n) = match finite_box(scene, &tree) {
        Some((lo, hi)) => {
            let size = (hi - lo).max_element() / cells.max(1) as f64;
            let n = ((hi - lo) / size).ceil().max(DVec3::ONE);
            (lo, size, [n.x as usize, n.y as usize, n.z as usize])
        }
        None => (DVec3::ZERO, 1.0, [0; 3]),
    };
    Ok((tree, Layout { kinds, lo, size, n }))
}

/// The box of the tree's finite leaves, grown by a hundredth (none when none is finite): where
/// cells pay; beyond it the whole program runs.
fn finite_box(scene: &Scene, tree: &Part) -> Option<(DVec3, DVec3)> {
    let root = scene.root_node().bound;
    let (lo, hi) = if root.lo.is_finite() && root.hi.is_finite() {
        (root.lo, root.hi)
    } else {
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        leaves(tree, &mut |p: &Part| {
            let b = scene.nodes[p.node].bound;
            if b.lo.is_finite() && b.hi.is_finite() {
                // The leaf's box in world coordinates: its corners through the frame's inverse.
                let inv = p.frame.m.inverse();
                for i in 0..8 {
                    let c = DVec3::new(
                        if i & 1 == 0 { b.lo.x } else { b.hi.x },
                        if i & 2 == 0 { b.lo.y } else { b.hi.y },
                        if i & 4 == 0 { b.lo.z } else { b.hi.z },
                    );
                    let w = inv * (c - p.frame.t);
                    (lo, hi) = (lo.min(w), hi.max(w));
                }
            }
        });
        (lo, hi)
    };
    let grow = (hi - lo).max_element() / 100.0 + 1e-6;
    (lo.is_finite() && hi.is_finite() && lo.cmple(hi).all())
        .then(|| (lo - DVec3::splat(grow), hi + DVec3::splat(grow)))
}

fn leaves(part: &Part, f: &mut impl FnMut(&Part)) {
    match &part.kind {
        super::PartKind::Leaf => f(part),
        super::PartKind::Fold { children, .. } => children.iter().for_each(|(c, _)| leaves(c, f)),
    }
}

/// The buffers for `tree` on `layout`'s grid: each cell's pruned program, then the whole's.
pub fn data(scene: &Scene, tree: &Part, layout: &Layout) -> Result<Data, Why> {
    let [nx, ny, nz] = layout.n;
    let cells = Cells::new(scene, tree, layout.lo, layout.size, [nx, ny, nz]);
    let mut words = Vec::new();
    let mut ranges = Vec::with_capacity(cells.parts.len() + 1);
    let mut kinds = layout.kinds.clone();
    let mut leaves = 0;
    for part in cells.parts.iter().chain(std::iter::once(tree)) {
        let p: Program = program::encode(scene, part, &mut kinds).map_err(Why::Program)?;
        ranges.push([words.len() as u32, p.words.len() as u32]);
        leaves += p.leaves();
        words.extend(p.to_gpu());
    }
    let cells_leaves = leaves - tree.leaves();
    Ok(Data {
        words,
        ranges,
        mean_leaves: cells_leaves as f64 / cells.parts.len().max(1) as f64,
    })
}

/// Why the scene has no data form, in words for the user.
pub fn say(scene: &Scene, why: &Why) -> String {
    match why {
        Why::Node(u) => format!(
            "its `{}` is not a primitive, a move, turn or scale, or a union, intersection or \
             subtraction (hard or smooth) of those — what the data form holds so far",
            scene.nodes[u.node].kind_name()
        ),
        Why::Program(Refused::TooDeep(d)) => format!(
            "its folds nest {d} values deep, and the evaluator's stack holds {}",
            program::MAX_STACK
        ),
        Why::Program(Refused::NotPrimitive | Refused::WordArgument) => {
            "a part has an argument the data cannot carry".to_string()
        }
    }
}
