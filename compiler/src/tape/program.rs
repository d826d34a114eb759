//! A part tree as the shader reads it (issue 33 §1): a [`Table`] of the whole tree's parts —
//! each leaf's primitive kind, frame and arguments, each fold's factor and material, and how
//! each part enters its parent fold — and, per cell, a [`Code`] of one u32 per part its pruned
//! tree evaluates, in post-order. A generic evaluator runs it with a running value in
//! registers and a small stack for nested folds; [`run`] is that evaluator in f64, the
//! reference the shader's must match. Parts are stored once, so a cell's program costs four
//! bytes a part, not the part's words (Barbier, Sanchez et al. 2025 keep per-cell lists of
//! active nodes the same way).
//!
//! A part's entry in the table (words of four numbers; a field that is a u32 is its bits):
//!
//! - head `[kind | flags << 8, k, factor, tag]`: `kind` the leaf's primitive kind (its index in
//!   [`Table::kinds`]); flags [`LARGEST`] (the parent fold keeps the larger value), [`NEGATED`]
//!   (the parent negates this part), for a leaf [`MOVED`] (its frame only moves), for a fold
//!   [`OWN_LARGEST`] (it keeps the larger value itself); `k` the
//!   parent's blend radius; `factor` what the part's raw value is multiplied by; `tag` its
//!   material + 1 (0 for none) and [`LOOSE`].
//! - a leaf's frame: one word `[t, 0]` if it only moves (applied as p + t, as the inline form's
//!   p − offset, to the bit), else three words, `m`'s row i in xyz and `t` component i in w;
//!   then one word per argument (a number in x, a vector in xyz).
//!
//! An instruction is a part's word offset in the table, with [`END`] for a fold (its children
//! came before it) and [`FIRST`] for the first child its fold keeps. A first part starts its
//! fold's running value; a later one is combined into it; a later fold's end combines its
//! result into the value it takes off the stack, which the first leaf under it put there
//! ([`SPILL`]). A tree of one fold of leaves needs no stack at all.

use super::{Part, PartKind, Way};
use crate::catalog::{Ctx, Primitive, Ty, Val};
use crate::scene::{NodeKind, Scene};
use glam::DVec3;

/// An instruction's bit: the part is a fold, whose children are done.
pub const END: u32 = 1 << 31;
/// An instruction's bit: the part is the first its fold keeps.
pub const FIRST: u32 = 1 << 30;
/// An instruction's bit: the leaf (a first one) puts the running value on the stack first,
/// for the later fold above it that will take it back at its end.
pub const SPILL: u32 = 1 << 29;
/// The bits of an instruction that hold the part's word offset.
pub const OFFSET: u32 = SPILL - 1;
/// A head's flag: the parent fold keeps the larger value.
pub const LARGEST: u32 = 1;
/// A head's flag: the parent fold negates this part (a subtraction's cutters).
pub const NEGATED: u32 = 2;
/// A head's flag: the leaf's frame only moves (`m` is the identity; one frame word).
pub const MOVED: u32 = 4;
/// A head's flag: the fold itself keeps the larger value (an intersection or a cut), so its
/// end decides looseness by [`ALL_LOOSE`] and [`OUT_LOOSE`].
pub const OWN_LARGEST: u32 = 8;
/// The shift of a head's flags above its kind.
pub const FLAGS_SHIFT: u32 = 8;
/// The deepest stack a program may need (the shader's arrays have this many entries).
pub const MAX_STACK: usize = 16;
/// The bit of a tag that says the part is loose (its hit needs confirming); the rest is the
/// material + 1, or 0 for none.
pub const LOOSE: u32 = 1 << 31;
/// A running tag's bit while a largest fold runs: every child so far is loose.
pub const ALL_LOOSE: u32 = 1 << 30;
/// A running tag's bit while a largest fold runs: a loose child is positive where it is (the
/// point is outside it, as the fold sees it).
pub const OUT_LOOSE: u32 = 1 << 29;
/// The bits of a tag that hold the material + 1. At a largest fold's end, the fold is loose
/// where every child is or a loose child is positive — `MatRule::pick_loose`, as the inline
/// form decides it — over the children its cell kept.
pub const MATERIAL: u32 = !(LOOSE | ALL_LOOSE | OUT_LOOSE);

/// The rounding [`Table::meta`] allows each part of a subtree, relative to the magnitudes its
/// value is made of: 2⁻²⁰, sixteen times f32's 2⁻²⁴ (an argument rounded to f32, a few
/// operations, and a fold's step each round at about that).
pub const ROUNDING_PER_PART: f64 = 1.0 / 1_048_576.0;

/// A part's parent in [`Table::meta`] where it has none (the root).
pub const NO_PARENT: u32 = u32::MAX;

/// Every part of a tree, stored once.
#[derive(Clone, Debug)]
pub struct Table {
    /// The words, four numbers each (bits of a u32 where a field is one).
    pub words: Vec<[f64; 4]>,
    /// Each part's first word, by its id.
    pub at: Vec<u32>,
    /// The primitive kinds its leaves use, in the order their heads number them.
    pub kinds: Vec<&'static Primitive>,
}

/// One cell's program.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Code {
    /// The instructions.
    pub words: Vec<u32>,
    /// The leaves it evaluates (primitive evaluations per point).
    pub leaves: usize,
    /// The deepest its stack gets.
    pub depth: usize,
}

/// Why a tree cannot be a program.
#[derive(Clone, Debug, PartialEq)]
pub enum Refused {
    /// Its folds nest deeper than [`MAX_STACK`] values.
    TooDeep(usize),
    /// A leaf is not a primitive.
    NotPrimitive,
    /// A primitive has an argument that is a word, not a number.
    WordArgument,
    /// The table would need more words than an instruction can address.
    TooLarge,
}

/// A u32 as a word's number (its bits, as the shader reads them with `bitcast`).
pub fn bits(x: u32) -> f64 {
    f64::from(f32::from_bits(x))
}

/// A word's number as the u32 whose bits it holds.
fn unbits(x: f64) -> u32 {
    (x as f32).to_bits()
}

/// A part's tag word: its material + 1 (0: none) and its looseness bit.
fn tag_of(part: &Part) -> f64 {
    let m = part.material.map_or(0, |m| m + 1);
    bits(m | if part.loose { LOOSE } else { 0 })
}

impl Table {
    /// The table of `tree` (of `scene`), whose parts are numbered `0..tree.size()`.
    pub fn new(scene: &Scene, tree: &Part) -> Result<Table, Refused> {
        let mut table = Table {
            words: Vec::new(),
            at: vec![0; tree.size()],
            kinds: Vec::new(),
        };
        table.add(scene, tree, (Way::Min, 0.0, false))?;
        if table.words.len() > OFFSET as usize {
            return Err(Refused::TooLarge);
        }
        Ok(table)
    }

    /// Adds `part` and everything in it; `(way, k, negated)`: how its parent takes it.
    fn add(
        &mut self,
        scene: &Scene,
        part: &Part,
        (way, k, negated): (Way, f64, bool),
    ) -> Result<(), Refused> {
        let flags = (u32::from(way == Way::Max) * LARGEST) | (u32::from(negated) * NEGATED);
        self.at[part.id] = self.words.len() as u32;
        match &part.kind {
            PartKind::Leaf => {
                let NodeKind::Primitive { prim, ctx } = &scene.nodes[part.node].kind else {
                    return Err(Refused::NotPrimitive);
                };
                if ctx.args.iter().any(|v| matches!(v, Val::Word(_))) {
                    return Err(Refused::WordArgument);
                }
                let kind = match self.kinds.iter().position(|k| std::ptr::eq(*k, *prim)) {
                    Some(i) => i,
                    None => {
                        self.kinds.push(prim);
                        self.kinds.len() - 1
                    }
                };
                let (m, t) = (part.frame.m, part.frame.t);
                let moved = m == glam::DMat3::IDENTITY;
                let flags = flags | if moved { MOVED } else { 0 };
                self.words.push([
                    bits(kind as u32 | flags << FLAGS_SHIFT),
                    k,
                    part.factor,
                    tag_of(part),
                ]);
                if moved {
                    self.words.push(t.extend(0.0).to_array());
                } else {
                    for i in 0..3 {
                        let row = m.row(i);
                        self.words.push([row.x, row.y, row.z, t[i]]);
                    }
                }
                for (param, v) in prim.params.iter().zip(&ctx.args) {
                    self.words.push(match vector(param.ty) {
                        true => v.vec().extend(0.0).to_array(),
                        false => [v.num(), 0.0, 0.0, 0.0],
                    });
                }
            }
            PartKind::Fold {
                way: inner,
                k: inner_k,
                children,
            } => {
                let flags = flags | if *inner == Way::Max { OWN_LARGEST } else { 0 };
                self.words
                    .push([bits(flags << FLAGS_SHIFT), k, part.factor, tag_of(part)]);
                for (c, negate) in children {
                    self.add(scene, c, (*inner, *inner_k, *negate))?;
                }
            }
        }
        Ok(())
    }

    /// What the pre-pass on the GPU (`lower/data/prune.rs`) knows of each part besides its
    /// entry, at the entry's word offset (other words zero): `[parent, proven, zoom, rounding]`
    /// — the word offset of the fold it is a child of ([`NO_PARENT`] for the root), 1 where its
    /// value is proven 1-Lipschitz (`Part::proven`: only those are pruned), the parent fold's
    /// zoom as f32 bits (how far the parent's point moves when the world point moves by 1), and
    /// as f32 bits how far f32's rounding may move the part's value, relative to the magnitudes
    /// it is made of: [`ROUNDING_PER_PART`] for each part in it and a few more.
    pub fn meta(&self, tree: &Part) -> Vec<[u32; 4]> {
        let mut meta = vec![[0; 4]; self.words.len()];
        let mut walk = vec![(tree, NO_PARENT, 1.0)];
        while let Some((part, parent, zoom)) = walk.pop() {
            let at = self.at[part.id];
            let rounding = (part.size() + 8) as f64 * ROUNDING_PER_PART;
            let f = |x: f64| (x as f32).to_bits();
            meta[at as usize] = [parent, u32::from(part.proven), f(zoom), f(rounding)];
            if let PartKind::Fold { children, .. } = &part.kind {
                walk.extend(children.iter().map(|(c, _)| (c, at, part.zoom)));
            }
        }
        meta
    }

    /// The words as the shader's buffer holds them: every number as the bits of an f32 (a
    /// field that is a u32 is one already: see [`bits`]), read with `bitcast` — loads of u32
    /// are exact, where a float load might flush the small kinds' bits (denormals) to zero.
    pub fn to_gpu(&self) -> Vec<[u32; 4]> {
        self.words.iter().map(|w| w.map(unbits)).collect()
    }
}

/// `part` (a tree numbered as `table`'s, or a pruning of it) as a program.
pub fn encode(table: &Table, part: &Part) -> Result<Code, Refused> {
    let mut code = Code {
        words: Vec::new(),
        leaves: 0,
        depth: 0,
    };
    let mut height = 0;
    emit(table, part, (true, false), &mut code, &mut height);
    if code.depth > MAX_STACK {
        return Err(Refused::TooDeep(code.depth));
    }
    Ok(code)
}

/// Appends `part`'s instructions; `first`: it is the first its fold keeps, `save`: (for a
/// first part) the running value below it must be kept for a fold's end; `height` is the
/// stack's.
fn emit(
    table: &Table,
    part: &Part,
    (first, save): (bool, bool),
    code: &mut Code,
    height: &mut usize,
) {
    let first_bit = if first { FIRST } else { 0 };
    let at = table.at[part.id];
    match &part.kind {
        PartKind::Leaf => {
            let spill = first && save;
            if spill {
                *height += 1;
                code.depth = code.depth.max(*height);
            }
            code.leaves += 1;
            code.words
                .push(at | first_bit | if spill { SPILL } else { 0 });
        }
        PartKind::Fold { children, .. } => {
            // A later fold's end takes a value off the stack: its first leaf puts it there.
            let save = !first || save;
            for (i, (c, _)) in children.iter().enumerate() {
                emit(table, c, (i == 0, save), code, height);
            }
            code.words.push(at | END | first_bit);
            if !first {
                *height -= 1;
            }
        }
    }
}

/// How many folds deep `part` nests (0: a leaf): the open folds a walk of its program holds
/// at once at most.
pub fn height(part: &Part) -> usize {
    match &part.kind {
        PartKind::Leaf => 0,
        PartKind::Fold { children, .. } => {
            1 + children.iter().map(|(c, _)| height(c)).max().unwrap_or(0)
        }
    }
}

/// Whether an argument of type `ty` is a vector in its word.
pub fn vector(ty: Ty) -> bool {
    matches!(
        ty,
        Ty::Vec3 | Ty::Size | Ty::Scale | Ty::Axis | Ty::Color | Ty::Counts
    )
}

/// A value being folded: the value, the fold's nearest (or farthest) child value so far, and
/// its material.
#[derive(Clone, Copy)]
struct Running {
    value: f64,
    best: f64,
    material: Option<u32>,
}

/// `v` (with `material`) folded into `a` as a head's flags and `k` say.
fn fold_in(a: Running, (v, material): (f64, Option<u32>), head: [f64; 4]) -> Running {
    let flags = unbits(head[0]) >> FLAGS_SHIFT;
    let way = if flags & LARGEST != 0 {
        Way::Max
    } else {
        Way::Min
    };
    let v = if flags & NEGATED != 0 { -v } else { v };
    let better = match way {
        Way::Min => v < a.best,
        Way::Max => v > a.best,
    };
    let (best, material) = if better {
        (v, material)
    } else {
        (a.best, a.material)
    };
    Running {
        value: super::eval::combine(way, head[1], a.value, v),
        best,
        material,
    }
}

/// A first part's value starting its fold: negated if its head says.
fn start(v: f64, material: Option<u32>, head: [f64; 4]) -> Running {
    let v = match unbits(head[0]) >> FLAGS_SHIFT & NEGATED {
        0 => v,
        _ => -v,
    };
    Running {
        value: v,
        best: v,
        material,
    }
}

/// The program's value and material at `p`, as [`super::eval::sample`] gives them for its
/// tree; an empty program gives [`crate::ir::FAR`] and no material.
pub fn run(table: &Table, code: &Code, p: DVec3) -> (f64, Option<u32>) {
    let words = &table.words;
    // (The looseness bit is the shader's; this runner gives materials.)
    let tag = |x: f64| match unbits(x) & MATERIAL {
        0 => None,
        m => Some(m - 1),
    };
    let mut running = Running {
        value: crate::ir::FAR,
        best: crate::ir::FAR,
        material: None,
    };
    let mut stack: Vec<Running> = Vec::with_capacity(MAX_STACK);
    for &ins in &code.words {
        let at = (ins & OFFSET) as usize;
        let head = words[at];
        let first = ins & FIRST != 0;
        if ins & END != 0 {
            let v = running.value * head[2];
            let material = running.material.or(tag(head[3]));
            running = if first {
                start(v, material, head)
            } else {
                let Some(below) = stack.pop() else {
                    return (f64::NAN, None);
                };
                fold_in(below, (v, material), head)
            };
        } else {
            let v = leaf(table, at, p) * head[2];
            let material = tag(head[3]);
            if first {
                if ins & SPILL != 0 {
                    stack.push(running);
                }
                running = start(v, material, head);
            } else {
                running = fold_in(running, (v, material), head);
            }
        }
    }
    (running.value, running.material)
}

/// The raw field of the leaf whose entry starts at word `at`, at `p`.
fn leaf(table: &Table, at: usize, p: DVec3) -> f64 {
    let words = &table.words;
    let head = unbits(words[at][0]);
    let Some(prim) = table.kinds.get((head & 0xff) as usize) else {
        return f64::NAN;
    };
    let (q, args) = if head >> FLAGS_SHIFT & MOVED != 0 {
        let t = words[at + 1];
        (p + DVec3::new(t[0], t[1], t[2]), at + 2)
    } else {
        let r = &words[at + 1..at + 4];
        let row = |i: usize| r[i][0] * p.x + r[i][1] * p.y + r[i][2] * p.z + r[i][3];
        (DVec3::new(row(0), row(1), row(2)), at + 4)
    };
    let args: Vec<Val> = prim
        .params
        .iter()
        .zip(&words[args..])
        .map(|(param, a)| match vector(param.ty) {
            true => Val::Vec3(DVec3::new(a[0], a[1], a[2])),
            false => Val::Num(a[0]),
        })
        .collect();
    (prim.eval)(&Ctx::of_args(args), q)
}
