//! What the data form's pre-pass on the GPU starts from (issue 33 §2): what grows with the
//! parts, not with the cells — the table, what the pre-pass knows of its parts, the whole and
//! the outside programs, the grid's header and levels; the device writes every cell's program.

use super::Part;
use super::data::{HEADER, Layout, Why, beyond, header};
use super::program::{self, Table};
use crate::scene::Scene;
use glam::DVec3;

/// What the pre-pass on the GPU starts from (`lower/data/prune.rs` prunes, the runtime's
/// `gpu/prune.rs` runs it): the table and what the pre-pass knows of its parts, the whole
/// tree's program and the one outside the grid, the grid's header and the grids pruned in
/// turn. The GPU writes every cell's program after these.
#[derive(Clone, Debug)]
pub struct Seed {
    /// The table of the tree's parts, as [`Data::nodes`].
    pub nodes: Vec<[u32; 4]>,
    /// Each part's parent, provenness and parent's zoom (`Table::meta`).
    pub meta: Vec<[u32; 4]>,
    /// The whole tree's program, then the one outside the grid.
    pub code: Vec<u32>,
    /// The whole program's range in `code`.
    pub whole: [u32; 2],
    /// The outside program's range in `code`.
    pub outside: [u32; 2],
    /// The grid's header entries of the ranges buffer ([`HEADER`]).
    pub header: [[u32; 2]; HEADER],
    /// The grids pruned in turn (`cells::levels`), coarsest first, the layout's last, each
    /// with its cells' edge length; all from the layout's lowest corner.
    pub levels: Vec<([usize; 3], f64)>,
    /// The grid's lowest corner.
    pub lo: DVec3,
    /// How many folds deep the tree nests (`program::height`): the open folds the pre-pass
    /// holds at once.
    pub height: usize,
}

impl Seed {
    /// The cells of the layout's grid (its last level).
    pub fn cells(&self) -> usize {
        self.levels.last().map_or(0, |(n, _)| n.iter().product())
    }
}

/// The pre-pass's seed for `tree` on `layout`'s grid (see [`Seed`]); none where the layout
/// has no grid (every point runs the whole program: nothing to prune).
pub fn seed(scene: &Scene, tree: &Part, layout: &Layout) -> Result<Option<Seed>, Why> {
    if layout.n.iter().product::<usize>() == 0 {
        return Ok(None);
    }
    let table = Table::new(scene, tree).map_err(Why::Program)?;
    let whole = program::encode(&table, tree).map_err(Why::Program)?.words;
    let beyond = beyond(scene, tree, layout, &table)?;
    let w = whole.len() as u32;
    let mut size = layout.size * (super::cells::SPLIT as f64).powi(-1);
    let mut levels: Vec<([usize; 3], f64)> = super::cells::levels(layout.n)
        .into_iter()
        .rev()
        .map(|n| {
            size *= super::cells::SPLIT as f64;
            (n, size)
        })
        .collect();
    levels.reverse();
    Ok(Some(Seed {
        nodes: table.to_gpu(),
        meta: table.meta(tree),
        whole: [0, w],
        outside: [w, beyond.len() as u32],
        code: whole.into_iter().chain(beyond).collect(),
        header: header(layout),
        levels,
        lo: layout.lo,
        height: program::height(tree),
    }))
}
