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
    // (Grid i of m has cells SPLIT^(m − 1 − i) times the layout's: powers of two, exact.)
    let grids = super::cells::levels(layout.n);
    let coarser = |i: usize| (super::cells::SPLIT as f64).powi((grids.len() - 1 - i) as i32);
    let levels: Vec<([usize; 3], f64)> = grids
        .iter()
        .enumerate()
        .map(|(i, &n)| (n, layout.size * coarser(i)))
        .collect();
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

/// Words of room in the programs' buffer a host gives each cell of every level at first (more
/// where the counter says so).
pub const ROOM_PER_CELL: u64 = 24;

/// Cells a dispatch of the pre-pass prunes at first (they share the scratch, which the host
/// empties between dispatches).
pub const CHUNK: usize = 1 << 14;

/// Words of scratch a host gives each cell of a dispatch at first: its parent's program.
pub const SCRATCH_PER_CELL: u64 = 512;

/// Words of a level's uniform (`layout::PRUNE_LEVEL_FIELDS`).
pub const LEVEL_WORDS: usize = crate::layout::PRUNE_LEVEL_BYTES as usize / 4;

/// Where a level's uniform holds what the host fills in for each dispatch (its word, of
/// [`LEVEL_WORDS`]): the programs' room, the scratch's, the dispatch's first cell.
pub const ROOM_WORDS: [usize; 3] = [14, 17, 18];

impl Seed {
    /// The ranges buffer's first contents and each level's first entry: the header, the grid's
    /// cells (the last level's, as the tracer reads them), the outside program's range, the
    /// whole program's (the first level's parent), then every coarser level's cells.
    pub fn ranges(&self) -> (Vec<u32>, Vec<u32>) {
        let cells = self.cells();
        let mut words: Vec<u32> = self.header.iter().flatten().copied().collect();
        words.resize(2 * (HEADER + cells), 0);
        words.extend(self.outside);
        words.extend(self.whole);
        let mut bases = Vec::with_capacity(self.levels.len());
        let mut next = HEADER + cells + 2;
        for (l, (n, _)) in self.levels.iter().enumerate() {
            if l + 1 == self.levels.len() {
                bases.push(HEADER as u32);
            } else {
                bases.push(next as u32);
                next += n.iter().product::<usize>();
            }
        }
        words.resize(2 * next, 0);
        (words, bases)
    }

    /// Level `l`'s uniform (`layout::PRUNE_LEVEL_FIELDS`), its levels' first ranges entries
    /// `bases` ([`Seed::ranges`]), with the programs' and the scratch's room (words) and the
    /// dispatch's first cell at [`ROOM_WORDS`].
    pub fn level_words(
        &self,
        l: usize,
        bases: &[u32],
        (code, scratch, first): (u32, u32, u32),
    ) -> [u32; LEVEL_WORDS] {
        // (The words the host fills in are the uniform's fields of those names.)
        assert!(
            ["capacity", "scratch_capacity", "first_cell"]
                .iter()
                .zip(ROOM_WORDS)
                .all(|(name, at)| crate::layout::PRUNE_LEVEL_FIELDS
                    .iter()
                    .any(|&(n, offset)| n == *name && offset as usize == 4 * at))
        );
        let (n, size) = self.levels[l];
        let whole = (HEADER + self.cells() + 1) as u32;
        let (up, split, in_base) = match l {
            // The coarsest grid's cells all prune the whole program.
            0 => ([1, 1, 1], u32::MAX, whole),
            _ => {
                let up = self.levels[l - 1].0;
                let split = super::cells::SPLIT as u32;
                (up.map(|k| k as u32), split, bases[l - 1])
            }
        };
        let hi = self.lo + DVec3::from(n.map(|k| k as f64)) * size;
        let scale = self.lo.abs().max(hi.abs()).max_element() + (hi - self.lo).length();
        let f = |x: f64| (x as f32).to_bits();
        let last = l + 1 == self.levels.len();
        let cells = n.iter().product::<usize>() as u32;
        let [nx, ny, nz] = n.map(|k| k as u32);
        let (lo, s) = (self.lo, f(size));
        let mut words = [
            f(lo.x),
            f(lo.y),
            f(lo.z),
            s,
            nx,
            ny,
            nz,
            cells,
            up[0],
            up[1],
            up[2],
            split,
            in_base,
            bases[l],
            0,
            f(scale),
            u32::from(last),
            0,
            0,
            0,
        ];
        for (at, x) in ROOM_WORDS.into_iter().zip([code, scratch, first]) {
            words[at] = x;
        }
        words
    }
}
