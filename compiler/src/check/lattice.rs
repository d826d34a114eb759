//! Copies of one shape written out on a lattice in a union become one `repeat` of the shape:
//! the same field, evaluated at the few copies the repeat's plan looks at instead of at every
//! copy (on a GPU that runs both sides of a branch, as Mesa 22.3's lavapipe does, the only way a
//! large union costs less; with branches that skip, it still beats a box tree over the copies).

use super::{Checker, MAX_NODES};
use crate::catalog::Val;
use crate::catalog::repeat::{MAX_COPIES, Plan};
use crate::catalog::traits::Motion;
use crate::diag::Span;
use crate::scene::{NodeId, NodeKind};
use glam::DVec3;
use std::collections::HashMap;

/// How nodes are written: a small number per node, equal for nodes written the same way (the
/// same primitive or operator, arguments, material, λ and children written the same way), kept
/// for the whole check so that each node is numbered once.
#[derive(Debug, Default)]
pub(super) struct Forms {
    /// Each numbered node's form.
    of: HashMap<NodeId, u32>,
    /// The forms by what they are made of: the node's own part and its children's forms.
    ids: HashMap<(String, Vec<u32>), u32>,
}

impl Forms {
    /// Forgets the form of node `id`, whose slot now holds another node.
    pub(super) fn forget(&mut self, id: NodeId) {
        self.of.remove(&id);
    }
}

/// Fewest copies of one shape a union must hold to be grouped.
const MIN_COPIES: usize = 3;

/// Relative tolerance for equal spacings along an axis (offsets written as decimals, such as
/// −5.6 and −2.4, differ by their spacing only up to rounding).
const SPACING_TOLERANCE: f64 = 1e-9;

/// One axis of a lattice: the first offset, the spacing (0 for one value) and the count.
#[derive(Clone, Copy, Debug)]
struct Axis {
    first: f64,
    spacing: f64,
    count: usize,
}

impl Axis {
    /// The axis of evenly spaced `values` (sorted, distinct), if they are.
    fn of(values: &[f64]) -> Option<Axis> {
        let (first, last) = (values[0], *values.last()?);
        let count = values.len();
        if count == 1 {
            return Some(Axis {
                first,
                spacing: 0.0,
                count,
            });
        }
        let spacing = (last - first) / (count - 1) as f64;
        let tol = SPACING_TOLERANCE * first.abs().max(last.abs()).max(spacing);
        let even = values
            .iter()
            .enumerate()
            .all(|(k, &v)| (v - (first + k as f64 * spacing)).abs() <= tol);
        (even && spacing > 0.0).then_some(Axis {
            first,
            spacing,
            count,
        })
    }

    /// The index of `v` on this axis.
    fn index(&self, v: f64) -> usize {
        if self.spacing == 0.0 {
            0
        } else {
            ((v - self.first) / self.spacing).round() as usize
        }
    }

    /// The middle of the axis: where the `repeat` is moved to.
    fn centre(&self) -> f64 {
        self.first + self.spacing * (self.count - 1) as f64 / 2.0
    }
}

/// The lattice `offsets` fill exactly (every combination of one value per axis, once), if any.
fn lattice(offsets: &[DVec3]) -> Option<[Axis; 3]> {
    let axes = [0, 1, 2].map(|i| {
        let mut v: Vec<f64> = offsets.iter().map(|o| o[i]).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        Axis::of(&v)
    });
    let axes = [axes[0]?, axes[1]?, axes[2]?];
    let cells: usize = axes.iter().map(|a| a.count).product();
    if cells != offsets.len() {
        return None;
    }
    let mut seen = vec![false; cells];
    for o in offsets {
        let k = [0, 1, 2].map(|i| axes[i].index(o[i]));
        let at = k[0] + axes[0].count * (k[1] + axes[1].count * k[2]);
        if std::mem::replace(&mut seen[at], true) {
            return None;
        }
    }
    Some(axes)
}

impl Checker<'_> {
    /// A union's children with each group of [`MIN_COPIES`] or more moved copies of one shape
    /// that exactly fill a lattice replaced by `repeat(spacing, count) { shape } at centre`,
    /// where the repeat's plan looks at fewer copies than the group holds. A copy is a move by a
    /// constant vector of a shape written the same way (the same `let`, or the same primitives,
    /// operators, arguments and materials), without a material or name of its own; the shape
    /// must be exact (its field, divided by λ, the distance outside it) with a finite bound.
    /// The repeat's field is then the union of its copies (see `catalog::repeat`), so the
    /// union's field is unchanged up to rounding of the offsets.
    pub(super) fn lattices(&mut self, children: Vec<NodeId>) -> Vec<NodeId> {
        if children.len() < MIN_COPIES {
            return children;
        }
        // Groups by the shape's written form, in the order of their first copy.
        let mut groups: Vec<(NodeId, Vec<(usize, DVec3)>)> = Vec::new();
        let mut group_of: HashMap<u32, usize> = HashMap::new();
        for (k, &c) in children.iter().enumerate() {
            let node = &self.nodes[c];
            let NodeKind::Operator {
                op,
                ctx,
                children: inner,
            } = &node.kind
            else {
                continue;
            };
            // (A copy's own annotation, `(s at v) @lipschitz(3)`, is a λ of its own.)
            if op.traits.motion != Motion::Move
                || ctx.sym.iter().any(Option::is_some)
                || node.material.is_some()
                || node.name.is_some()
                || node.lambda != node.inferred_lambda
            {
                continue;
            }
            let (shape, offset) = (inner[0], ctx.vec(0));
            // Exact shapes only: for those the repeat's plan gives the union of its copies
            // (the nearest copy is among those it looks at); for a bound it gives another,
            // still valid, bound.
            if !self.nodes[shape].bound.is_finite() || !self.nodes[shape].exact {
                continue;
            }
            let key = self.form(shape);
            match group_of.get(&key) {
                Some(&g) => groups[g].1.push((k, offset)),
                None => {
                    group_of.insert(key, groups.len());
                    groups.push((shape, vec![(k, offset)]));
                }
            }
        }
        let mut replaced: Vec<Option<NodeId>> = children.iter().map(|&c| Some(c)).collect();
        for (shape, copies) in groups {
            // (Each group adds two nodes; never past the limit the scene did not reach.)
            if copies.len() < MIN_COPIES || self.nodes.len() + 2 >= MAX_NODES {
                continue;
            }
            let offsets: Vec<DVec3> = copies.iter().map(|c| c.1).collect();
            let Some(axes) = lattice(&offsets) else {
                continue;
            };
            let spacing = DVec3::from_array(axes.map(|a| a.spacing));
            let count = DVec3::from_array(axes.map(|a| a.count as f64));
            let args = vec![Val::Vec3(spacing), Val::Vec3(count)];
            let ctx = self.ctx_over((args.clone(), vec![None, None]), &[shape]);
            let looked_at = Plan::new(&ctx).copies();
            if looked_at >= copies.len() as f64 || looked_at > MAX_COPIES as f64 {
                continue;
            }
            let span: Span = self.nodes[children[copies[0].0]].span;
            let Some(repeat) =
                self.operator_node("repeat", (args, vec![None, None]), vec![shape], span)
            else {
                continue;
            };
            let centre = Val::Vec3(DVec3::from_array(axes.map(|a| a.centre())));
            let Some(moved) =
                self.operator_node("translate", (vec![centre], vec![None]), vec![repeat], span)
            else {
                continue;
            };
            for (i, &(k, _)) in copies.iter().enumerate() {
                replaced[k] = (i == 0).then_some(moved);
            }
        }
        replaced.into_iter().flatten().collect()
    }
}

impl Checker<'_> {
    /// The form of node `id` (see [`Forms`]), numbering it and the nodes below it that have
    /// none yet, children first, without recursion (a chain of `let`s may be deep).
    fn form(&mut self, id: NodeId) -> u32 {
        let mut stack = vec![id];
        while let Some(&n) = stack.last() {
            if self.forms.of.contains_key(&n) {
                stack.pop();
                continue;
            }
            let node = &self.nodes[n];
            let children = node.children();
            let missing: Vec<NodeId> = children
                .iter()
                .copied()
                .filter(|c| !self.forms.of.contains_key(c))
                .collect();
            if !missing.is_empty() {
                stack.extend(missing);
                continue;
            }
            let (mat, lambda) = (node.material, node.lambda.to_bits());
            let own = match &node.kind {
                NodeKind::Primitive { prim, ctx } if ctx.sym.iter().all(Option::is_none) => {
                    format!("{}{:?}:{mat:?}:{lambda}", prim.name, ctx.args)
                }
                NodeKind::Operator { op, ctx, .. } if ctx.sym.iter().all(Option::is_none) => {
                    format!("{}{:?}:{mat:?}:{lambda}", op.name, ctx.args)
                }
                // The same node (a `let`) is the same shape, whatever it reads.
                _ => format!("#{n}:{mat:?}:{lambda}"),
            };
            let kids: Vec<u32> = children.iter().map(|c| self.forms.of[c]).collect();
            let next = self.forms.ids.len() as u32;
            let f = *self.forms.ids.entry((own, kids)).or_insert(next);
            self.forms.of.insert(n, f);
            stack.pop();
        }
        self.forms.of[&id]
    }
}
