//! A part tree as the shader will read it: a post-order program of four-number words (one
//! `vec4<f32>` each on the GPU), run with a small stack by a generic evaluator — the form whose
//! code does not grow with the scene, only with the kinds of primitive it uses (issue 33 §1).
//! [`run`] is that evaluator in f64, the reference the shader's must match.
//!
//! Instructions (the first word's x is the opcode as bits of a u32):
//!
//! - `LEAF + kind`: `[op, words, factor, tag]` (tag: material + 1 or 0, and [`LOOSE`]), three
//!   words of the frame's rows
//!   (`m` row i in xyz, `t` component i in w), then one word per argument (a number in x, a
//!   vector in xyz). Pushes the primitive's field at the frame's point times the factor.
//! - `COMBINE`: `[op, flags, k, 0]` (flags: 1 = largest, 2 = negate the top first): pops the
//!   top (a child) and combines it into the one below (the fold's running result), picking the
//!   material as the fold does.
//! - `NEGATE`: `[op, 0, 0, 0]`: the top's value negated (a fold's first child, negated).
//! - `END`: `[op, 0, factor, tag]`: the fold's result seen by its parent; its material where
//!   it picked none, loose where it or what it picked is.

use super::{Part, PartKind, Way};
use crate::catalog::{Ctx, Primitive, Ty, Val};
use crate::scene::{NodeKind, Scene};
use glam::DVec3;

/// Opcode of a fold's combination step.
pub const COMBINE: u32 = 1;
/// Opcode negating the top value.
pub const NEGATE: u32 = 2;
/// Opcode ending a fold.
pub const END: u32 = 3;
/// Opcode of the first primitive kind; kind `i` of [`Program::kinds`] is `LEAF + i`.
pub const LEAF: u32 = 16;
/// The bit of a leaf's word count that says its frame only moves (`m` is the identity).
pub const MOVED: u32 = 1 << 30;
/// The deepest stack a program may need (the shader's arrays have this many entries).
pub const MAX_STACK: usize = 16;

/// A program and what runs it needs.
#[derive(Clone, Debug)]
pub struct Program {
    /// The words, four numbers each (bits of a u32 where a field is one).
    pub words: Vec<[f64; 4]>,
    /// The primitive kinds its leaves use, in opcode order.
    pub kinds: Vec<&'static Primitive>,
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
}

/// A u32 as a word's number (its bits, as the shader reads them with `bitcast`).
pub fn bits(x: u32) -> f64 {
    f64::from(f32::from_bits(x))
}

/// A word's number as the u32 whose bits it holds.
fn unbits(x: f64) -> u32 {
    (x as f32).to_bits()
}

/// `part` (of `scene`) as a program; `kinds` the primitive kinds opcodes already name (shared
/// by every cell's program of one scene), extended with new ones.
pub fn encode(
    scene: &Scene,
    part: &Part,
    kinds: &mut Vec<&'static Primitive>,
) -> Result<Program, Refused> {
    let mut words = Vec::new();
    let depth = emit(scene, part, kinds, &mut words)?;
    if depth > MAX_STACK {
        return Err(Refused::TooDeep(depth));
    }
    Ok(Program {
        words,
        kinds: kinds.clone(),
        depth,
    })
}

/// The bit of a tag that says the part is loose (its hit needs confirming); the rest is the
/// material + 1, or 0 for none.
pub const LOOSE: u32 = 1 << 31;

/// A part's tag word: its material + 1 (0: none) and its looseness bit.
fn tag_of(part: &Part) -> f64 {
    let m = part.material.map_or(0, |m| m + 1);
    bits(m | if part.loose { LOOSE } else { 0 })
}

/// Appends `part`'s instructions; returns the stack depth they reach.
fn emit(
    scene: &Scene,
    part: &Part,
    kinds: &mut Vec<&'static Primitive>,
    words: &mut Vec<[f64; 4]>,
) -> Result<usize, Refused> {
    match &part.kind {
        PartKind::Leaf => {
            let NodeKind::Primitive { prim, ctx } = &scene.nodes[part.node].kind else {
                return Err(Refused::NotPrimitive);
            };
            let kind = match kinds.iter().position(|k| std::ptr::eq(*k, *prim)) {
                Some(i) => i,
                None => {
                    kinds.push(prim);
                    kinds.len() - 1
                }
            };
            let n = 4 + prim.params.len();
            // A frame that only moves is applied as p + t: as the inline form's p − offset, to
            // the bit (`MOVED` in the word count's high bit).
            let moved = if part.frame.m == glam::DMat3::IDENTITY {
                MOVED
            } else {
                0
            };
            words.push([
                bits(LEAF + kind as u32),
                bits(n as u32 | moved),
                part.factor,
                tag_of(part),
            ]);
            let (m, t) = (part.frame.m, part.frame.t);
            for i in 0..3 {
                let row = m.row(i);
                words.push([row.x, row.y, row.z, t[i]]);
            }
            if ctx.args.iter().any(|v| matches!(v, Val::Word(_))) {
                return Err(Refused::WordArgument);
            }
            for (param, v) in prim.params.iter().zip(&ctx.args) {
                words.push(match vector(param.ty) {
                    true => v.vec().extend(0.0).to_array(),
                    false => [v.num(), 0.0, 0.0, 0.0],
                });
            }
            Ok(1)
        }
        PartKind::Fold { way, k, children } => {
            let mut depth = 0;
            for (i, (child, negate)) in children.iter().enumerate() {
                // The running result sits below each later child.
                depth = depth.max(emit(scene, child, kinds, words)? + usize::from(i > 0));
                if i == 0 && *negate {
                    words.push([bits(NEGATE), 0.0, 0.0, 0.0]);
                } else if i > 0 {
                    let flags = u32::from(*way == Way::Max) | (u32::from(*negate) << 1);
                    words.push([bits(COMBINE), bits(flags), *k, 0.0]);
                }
            }
            words.push([bits(END), 0.0, part.factor, tag_of(part)]);
            Ok(depth)
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

/// One entry of the stack: the value, the fold's nearest (or farthest) child value so far,
/// and its material.
#[derive(Clone, Copy)]
struct Entry {
    value: f64,
    best: f64,
    material: Option<u32>,
}

/// The program's value and material at `p`, as [`super::eval::sample`] gives them for its tree.
pub fn run(program: &Program, p: DVec3) -> (f64, Option<u32>) {
    let words = &program.words;
    let mut stack: Vec<Entry> = Vec::with_capacity(MAX_STACK);
    let mut pc = 0;
    // (The looseness bit is the shader's; this runner gives materials.)
    let tag = |x: f64| match unbits(x) & !LOOSE {
        0 => None,
        m => Some(m - 1),
    };
    while pc < words.len() {
        let w = words[pc];
        match unbits(w[0]) {
            COMBINE => {
                let flags = unbits(w[1]);
                let way = if flags & 1 == 1 { Way::Max } else { Way::Min };
                let (Some(c), Some(a)) = (stack.pop(), stack.pop()) else {
                    return (f64::NAN, None);
                };
                let v = if flags & 2 == 2 { -c.value } else { c.value };
                let better = match way {
                    Way::Min => v < a.best,
                    Way::Max => v > a.best,
                };
                let (best, material) = if better {
                    (v, c.material)
                } else {
                    (a.best, a.material)
                };
                let value = super::eval::combine(way, w[2], a.value, v);
                stack.push(Entry {
                    value,
                    best,
                    material,
                });
                pc += 1;
            }
            NEGATE => {
                if let Some(top) = stack.last_mut() {
                    (top.value, top.best) = (-top.value, -top.best);
                }
                pc += 1;
            }
            END => {
                if let Some(top) = stack.last_mut() {
                    let value = top.value * w[2];
                    *top = Entry {
                        value,
                        best: value,
                        material: top.material.or(tag(w[3])),
                    };
                }
                pc += 1;
            }
            op => {
                let Some(prim) = program.kinds.get(op.wrapping_sub(LEAF) as usize) else {
                    return (f64::NAN, None);
                };
                let rows = &words[pc + 1..pc + 4];
                let q = DVec3::new(
                    rows[0][0] * p.x + rows[0][1] * p.y + rows[0][2] * p.z + rows[0][3],
                    rows[1][0] * p.x + rows[1][1] * p.y + rows[1][2] * p.z + rows[1][3],
                    rows[2][0] * p.x + rows[2][1] * p.y + rows[2][2] * p.z + rows[2][3],
                );
                let args: Vec<Val> = prim
                    .params
                    .iter()
                    .zip(&words[pc + 4..pc + (unbits(w[1]) & !MOVED) as usize])
                    .map(|(param, a)| match vector(param.ty) {
                        true => Val::Vec3(DVec3::new(a[0], a[1], a[2])),
                        false => Val::Num(a[0]),
                    })
                    .collect();
                let value = (prim.eval)(&Ctx::of_args(args), q) * w[2];
                stack.push(Entry {
                    value,
                    best: value,
                    material: tag(w[3]),
                });
                pc += (unbits(w[1]) & !MOVED) as usize;
            }
        }
    }
    stack
        .last()
        .map_or((f64::NAN, None), |e| (e.value, e.material))
}

impl Program {
    /// The words as the shader's buffer holds them: every number as the bits of an f32 (a
    /// field that is a u32 is one already: see [`bits`]), read with `bitcast` — loads of u32
    /// are exact, where a float load might flush the small opcodes' bits (denormals) to zero.
    pub fn to_gpu(&self) -> Vec<[u32; 4]> {
        self.words.iter().map(|w| w.map(unbits)).collect()
    }

    /// The leaves it evaluates (primitive evaluations per point).
    pub fn leaves(&self) -> usize {
        let mut pc = 0;
        let mut n = 0;
        while pc < self.words.len() {
            let op = unbits(self.words[pc][0]);
            if op >= LEAF {
                n += 1;
                pc += (unbits(self.words[pc][1]) & !MOVED) as usize;
            } else {
                pc += 1;
            }
        }
        n
    }
}
