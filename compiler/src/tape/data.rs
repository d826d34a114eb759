//! What the data form's shader reads (issue 33 §1–2): the table of the scene's parts, the
//! program of every cell of a grid over the scene (one u32 a part it evaluates) concatenated in
//! a second buffer, each cell's range in a third, and a last range for points outside the grid.
//! The [`Layout`] — the primitive kinds and the grid — is compiled into the shader; the [`Data`]
//! is the host's to upload, and to make again when parameters change.

use super::cells::map_grid;
use super::program::{self, Code, Refused, Table};
use super::{Part, Unsupported};
use crate::catalog::Primitive;
use crate::scene::Scene;
use glam::DVec3;

/// The fewest and the most cells along the grid's longest side.
pub const CELLS: (usize, usize) = (8, 128);

/// Cells the grid has for every leaf, about (see [`cells_for`]).
const CELLS_PER_LEAF: f64 = 256.0;

/// Leaves from which `--form auto` draws a scene as data (where it can): measured on unions of
/// spheres (`scripts/scale_bench.py`, docs/data-form.md), the data form's trace is as fast as
/// the inline one at about 30 smoothly blended or 100 hard-united spheres, and its first frame
/// costs a shader compile of about 1–3 s whatever the parts, where the inline one's grows
/// with them.
pub const AUTO_FROM: usize = 100;

/// Leaves from which `--prepass auto` prunes on the device: measured on lavapipe (two cores,
/// docs/data-form.md), the device's pre-pass is 2.0× faster than the CPU's for 1000 blended
/// spheres and 2.3× for 10 000, as fast for 1000 hard-united ones, slower below (100 spheres:
/// 42 against 22 ms; the paper's trees, 186 boxes: 131 against 92 ms).
pub const GPU_PREPASS_FROM: usize = 1000;

/// Whether `--form auto` draws `scene` as data: it has a data form of at least
/// [`AUTO_FROM`] leaves (the caller checks what else the data form refuses).
pub fn prefer(scene: &Scene) -> bool {
    super::build(scene).is_ok_and(|tree| tree.leaves() >= AUTO_FROM)
}

/// Cells along the grid's longest side for a tree of `leaves` leaves: about
/// [`CELLS_PER_LEAF`] cells a leaf, within [`CELLS`]. Measured on 1000 smoothly blended
/// spheres (`docs/data-form.md`): 32 cells a side keep 13 leaves a cell, 64 keep 5.7, 128 keep
/// 3.2, and a frame's trace takes 97, 53 and 49 ms; the pre-pass and the buffers grow with the
/// cells.
pub fn cells_for(leaves: usize) -> usize {
    let side = (CELLS_PER_LEAF * leaves as f64).cbrt().round() as usize;
    side.clamp(CELLS.0, CELLS.1)
}

/// What the shader is compiled with: the opcodes' kinds and the grid.
#[derive(Clone, Debug)]
pub struct Layout {
    /// The primitive kinds, in the order the table's heads number them.
    pub kinds: Vec<&'static Primitive>,
    /// The grid's lowest corner.
    pub lo: DVec3,
    /// The cells' edge length.
    pub size: f64,
    /// Cells along x, y and z (0 cells: no grid, every point runs the whole program).
    pub n: [usize; 3],
    /// The deepest stack a program needs (the whole tree's; a pruned one needs no more): the
    /// shader's stack has this many entries, none for a single fold of leaves.
    pub depth: usize,
    /// Where the parts left out of the program outside the grid lie at least this far inside
    /// it: outside, the distance to the grid's box plus this is a distance bound for them, the
    /// proxy the evaluator takes the smaller of with that program (none: nothing is left out).
    pub proxy: Option<f64>,
}

/// The buffers: the parts, the programs and their ranges.
#[derive(Clone, Debug)]
pub struct Data {
    /// The table of the tree's parts (`program::Table`), as the shader reads it.
    pub nodes: Vec<[u32; 4]>,
    /// Every cell's program, then the one outside the grid.
    pub code: Vec<u32>,
    /// The grid ([`HEADER`] entries: its lowest corner, cell size, cells along x, y and z and
    /// the proxy's margin, as f32 bits where not counts), then each cell's program (first
    /// instruction, count), x fastest, then y, then z; then the one outside the grid.
    pub ranges: Vec<[u32; 2]>,
    /// The mean leaves a cell's program evaluates.
    pub mean_leaves: f64,
}

impl Data {
    /// The grid's cells.
    pub fn cells(&self) -> usize {
        self.ranges.len().saturating_sub(HEADER + 1)
    }

    /// The bytes of the three buffers.
    pub fn bytes(&self) -> usize {
        self.nodes.len() * 16 + self.code.len() * 4 + self.ranges.len() * 8
    }

    /// The three buffers as a host uploads them, in [`BUFFERS`]' order: little-endian u32s,
    /// each at least 16 bytes (a binding cannot be empty; the shader never reads the padding).
    pub fn buffers(&self) -> [Vec<u8>; 3] {
        let bytes = |words: &mut dyn Iterator<Item = u32>| -> Vec<u8> {
            let mut b: Vec<u8> = words.flat_map(u32::to_le_bytes).collect();
            b.resize(b.len().max(16), 0);
            b
        };
        [
            bytes(&mut self.nodes.iter().flatten().copied()),
            bytes(&mut self.code.iter().copied()),
            bytes(&mut self.ranges.iter().flatten().copied()),
        ]
    }

    /// The grid the ranges buffer's header holds: lowest corner, cell size, cells along x, y
    /// and z (0: no grid).
    pub fn grid(&self) -> ([f32; 3], f32, [u32; 3]) {
        let h = &self.ranges;
        let f = f32::from_bits;
        (
            [f(h[0][0]), f(h[0][1]), f(h[1][0])],
            f(h[1][1]),
            [h[2][0], h[2][1], h[3][0]],
        )
    }
}

/// A range's count bit: the cell is far from every surface (far-field culling, Barbier, Sanchez
/// et al. 2025 §4.3): the field over the whole cell is at least a clearance the count holds,
/// which the camera's trace steps by instead of running the program (`lower/data/far.rs`);
/// shading runs the program.
pub const FAR: u32 = 1 << 31;

/// The bits of a far cell's count that hold its program's length (a cell whose program is
/// longer is not marked).
pub const FAR_LENGTH: u32 = 0xffff;

/// Where a far cell's clearance starts in its count: the clearance in 64ths of the cell's edge,
/// at most [`FAR_MOST`].
pub const FAR_SHIFT: u32 = 16;

/// Steps of a far cell's clearance in a cell's edge.
pub const FAR_STEPS: f64 = 64.0;

/// The largest clearance a count holds, in 64ths of the cell's edge.
pub const FAR_MOST: u32 = 0x7fff;

/// A cell's count: its program's length `len`, marked [`FAR`] with its clearance where `lower`
/// (a lower bound of the field over the cell, none where the tree is not proven) is at least
/// the cell's half-diagonal (cells of edge `size`) — there a step of the clearance crosses the
/// cell in a few — and the program is short enough to share the count.
pub fn far_count(len: u32, lower: Option<f64>, size: f64) -> u32 {
    let radius = size * 3f64.sqrt() / 2.0;
    match lower {
        Some(lower) if lower >= radius && len <= FAR_LENGTH => {
            let steps = ((lower / size) * FAR_STEPS)
                .floor()
                .min(f64::from(FAR_MOST)) as u32;
            FAR | steps << FAR_SHIFT | len
        }
        _ => len,
    }
}

/// A range's program length and, for a far cell, the clearance (a lower bound of the field over
/// the cell) for cells of edge `size`.
pub fn unpack_count(count: u32, size: f64) -> (u32, Option<f64>) {
    if count & FAR == 0 {
        return (count, None);
    }
    let steps = (count >> FAR_SHIFT) & FAR_MOST;
    (
        count & FAR_LENGTH,
        Some(f64::from(steps) / FAR_STEPS * size),
    )
}

/// The data form's buffers by name, in the order of `layout::TAPE_BINDINGS` and
/// [`Data::buffers`], with the type of their elements as WGSL spells it.
pub const BUFFERS: [(&str, &str); 3] = [
    ("nodes", "vec4<u32>"),
    ("code", "u32"),
    ("ranges", "vec2<u32>"),
];

/// The file `emit --form data` writes buffer `name` (of [`BUFFERS`]) of a shader named
/// `stem` to: `STEM.NAME.u32`.
pub fn file_name(stem: &str, name: &str) -> String {
    format!("{stem}.{name}.u32")
}

/// The parameters (indices into `scene.params`) the shapes' arguments read: what the data's
/// buffers are made at, so that a host changing one needs new buffers.
pub fn follows(scene: &Scene) -> Vec<usize> {
    use crate::scene::NodeKind;
    let mut read = vec![false; scene.params.len()];
    for n in &scene.nodes {
        let syms = match &n.kind {
            NodeKind::Primitive { ctx, .. } | NodeKind::Operator { ctx, .. } => &ctx.sym,
            NodeKind::Implicit { .. } => continue,
        };
        for f in syms.iter().flatten().flatten() {
            f.params(&mut |r| read[r.index] = true);
        }
    }
    (0..read.len()).filter(|&i| read[i]).collect()
}

impl Layout {
    /// Whether a shader compiled for this layout runs `other`'s data: the same kinds, a stack
    /// as deep, and a grid and a proxy where this one has them (their values are data).
    pub fn holds(&self, other: &Layout) -> bool {
        let grid = |l: &Layout| l.n.iter().product::<usize>() > 0;
        self.kinds.len() == other.kinds.len()
            && self
                .kinds
                .iter()
                .zip(&other.kinds)
                .all(|(a, b)| std::ptr::eq(*a, *b))
            && other.depth <= self.depth
            && grid(self) == grid(other)
            && self.proxy.is_some() == other.proxy.is_some()
    }
}

/// Entries of the ranges buffer before the cells': the grid, read by the shader at run time
/// (so that parameters may move the parts without a new shader): `[lo.x, lo.y]`,
/// `[lo.z, size]`, `[nx, ny]`, `[nz, margin]`.
pub const HEADER: usize = 4;

/// The grid's header entries of the ranges buffer (see [`HEADER`]).
pub(super) fn header(layout: &Layout) -> [[u32; 2]; HEADER] {
    let f = |x: f64| (x as f32).to_bits();
    let [nx, ny, nz] = layout.n.map(|n| n as u32);
    [
        [f(layout.lo.x), f(layout.lo.y)],
        [f(layout.lo.z), f(layout.size)],
        [nx, ny],
        [nz, f(layout.proxy.unwrap_or(0.0))],
    ]
}

/// Why a scene has no data form.
#[derive(Clone, Debug, PartialEq)]
pub enum Why {
    /// A node the tree cannot hold.
    Node(Unsupported),
    /// The program cannot be made.
    Program(Refused),
}

/// The scene's tree and layout, `cells` (by default [`cells_for`] its leaves) along the
/// longest side of the box the scene's finite parts lie in.
pub fn layout(scene: &Scene, cells: Option<usize>) -> Result<(Part, Layout), Why> {
    let tree = super::build(scene).map_err(Why::Node)?;
    let table = Table::new(scene, &tree).map_err(Why::Program)?;
    let whole = program::encode(&table, &tree).map_err(Why::Program)?;
    let (lo, size, n, proxy) = match finite_box(scene, &tree) {
        Some((lo, hi, grow)) => {
            let cells = cells.unwrap_or_else(|| cells_for(tree.leaves())).max(1);
            let size = (hi - lo).max_element() / cells as f64;
            let n = ((hi - lo) / size).ceil().max(DVec3::ONE);
            let proxy = outside(scene, &tree).is_none_or(|o| o.leaves() < tree.leaves());
            let n = [n.x as usize, n.y as usize, n.z as usize];
            (lo, size, n, proxy.then_some(grow))
        }
        None => (DVec3::ZERO, 1.0, [0; 3], None),
    };
    let layout = Layout {
        kinds: table.kinds,
        lo,
        size,
        n,
        depth: whole.depth,
        proxy,
    };
    Ok((tree, layout))
}

/// What runs outside the grid besides the proxy: nothing where every surface is inside it
/// (every leaf is finite: the grid holds their boxes seen through their frames, even where
/// a parameter in a turn leaves the scene's own box unknown), else a root union's children
/// that have an unbounded part (a ground plane), else the whole tree.
pub fn outside(scene: &Scene, tree: &Part) -> Option<Part> {
    let root = scene.root_node().bound;
    if (root.lo.is_finite() && root.hi.is_finite()) || all_finite(scene, tree) {
        return None;
    }
    let super::PartKind::Fold {
        way: super::Way::Min,
        k,
        children,
    } = &tree.kind
    else {
        return Some(tree.clone());
    };
    let kept: Vec<(Part, bool)> = children
        .iter()
        .filter(|(c, _)| !all_finite(scene, c))
        .cloned()
        .collect();
    // (A smooth union blends near the grid's parts: those stay, the whole tree runs.)
    if *k > 0.0 || kept.is_empty() {
        return Some(tree.clone());
    }
    Some(Part {
        kind: super::PartKind::Fold {
            way: super::Way::Min,
            k: *k,
            children: kept,
        },
        ..tree.clone()
    })
}

/// Whether every leaf of `part` has a finite box (its surfaces are then inside the grid's).
fn all_finite(scene: &Scene, part: &Part) -> bool {
    let mut all = true;
    leaves(part, &mut |p: &Part| {
        let b = scene.nodes[p.node].bound;
        all &= b.lo.is_finite() && b.hi.is_finite();
    });
    all
}

/// The box of the tree's finite leaves, grown on every side by a twentieth of its extent
/// (none when no leaf is finite), and that growth: where cells pay.
fn finite_box(scene: &Scene, tree: &Part) -> Option<(DVec3, DVec3, f64)> {
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
        // A smooth union's surface lies up to its blend radius beyond its parts (a chain of
        // IQ's quadratic minimum stays above the smallest − k): every fold's radius added.
        let slack = DVec3::splat(blend_slack(tree));
        (lo - slack, hi + slack)
    };
    let grow = (hi - lo).max_element() / 20.0 + 1e-6;
    (lo.is_finite() && hi.is_finite() && lo.cmple(hi).all())
        .then(|| (lo - DVec3::splat(grow), hi + DVec3::splat(grow), grow))
}

/// The blend radii of every fold of `part`, summed: how far beyond its leaves' boxes its
/// surface can reach at most.
fn blend_slack(part: &Part) -> f64 {
    match &part.kind {
        super::PartKind::Leaf => 0.0,
        super::PartKind::Fold { k, children, .. } => {
            k + children.iter().map(|(c, _)| blend_slack(c)).sum::<f64>()
        }
    }
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
    let table = Table::new(scene, tree).map_err(Why::Program)?;
    let grid = (layout.lo, layout.size, [nx, ny, nz]);
    // A cell far from every surface is marked with a bound of the field over it (for the
    // camera's trace, `far_count`): the root fold's result's bounds, as the pruning ends with
    // them.
    let codes = map_grid(scene, tree, grid, |part, _, lower| {
        Ok::<_, Refused>((program::encode(&table, &part)?, lower))
    });
    let count = codes.len();
    let mut code = Vec::new();
    let mut ranges = Vec::with_capacity(HEADER + count + 1);
    ranges.extend(header(layout));
    let mut leaves = 0;
    // Cells with the same program (neighbours that keep the same parts) share it.
    let mut seen: std::collections::HashMap<Vec<u32>, [u32; 2]> = std::collections::HashMap::new();
    for p in codes {
        let (p, lower): (Code, Option<f64>) = p.map_err(Why::Program)?;
        leaves += p.leaves;
        let [start, len] = *seen.entry(p.words).or_insert_with_key(|words| {
            let range = [code.len() as u32, words.len() as u32];
            code.extend_from_slice(words);
            range
        });
        ranges.push([start, far_count(len, lower, layout.size)]);
    }
    let beyond = beyond(scene, tree, layout, &table)?;
    ranges.push([code.len() as u32, beyond.len() as u32]);
    code.extend(beyond);
    Ok(Data {
        nodes: table.to_gpu(),
        code,
        ranges,
        mean_leaves: leaves as f64 / count.max(1) as f64,
    })
}

/// The program outside the grid: the parts it does not hold, with the proxy for the rest
/// (empty where it holds them all).
pub(super) fn beyond(
    scene: &Scene,
    tree: &Part,
    layout: &Layout,
    table: &Table,
) -> Result<Vec<u32>, Why> {
    let part = match (layout.proxy, outside(scene, tree)) {
        (Some(_), None) => return Ok(Vec::new()),
        (_, Some(o)) => o,
        (None, None) => tree.clone(),
    };
    let p = program::encode(table, &part).map_err(Why::Program)?;
    Ok(p.words)
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
        Why::Program(Refused::TooLarge) => format!(
            "its parts need more than {} words of data, what a program can address",
            program::OFFSET
        ),
    }
}
