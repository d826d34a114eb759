//! A non-uniform `scale` taken into the primitive it scales (`catalog::absorb`), through the
//! turns and moves between them: an exact field where the scale alone gives a bound.

use super::{Checker, MAX_NODES};
use crate::catalog::absorb::{comps, times3, to_arg};
use crate::catalog::traits::Motion;
use crate::catalog::{self, ArgSyms, Val};
use crate::diag::Span;
use crate::scene::Field;
use crate::scene::{Node, NodeId, NodeKind};

/// A node's arguments: values where the scene is checked, and parameter expressions.
type Args = (Vec<Val>, ArgSyms);

/// A step between the scale and the primitive: its operator, its arguments once scaled, its
/// node.
type Step = (&'static str, Args, NodeId);

impl Checker<'_> {
    /// `scale(v)` of `child` rewritten as the primitive with scaled arguments under the same
    /// turns and moves, where every step between allows it: a turn about a coordinate axis k
    /// commutes with a scale whose other two factors are equal (any turn with a uniform
    /// scale), and a move by t becomes a move by t·v; `v` and the arguments may read
    /// parameters (the new arguments are then products of their expressions). Only plain steps
    /// are rewritten (no material, name or annotation of their own, so a `let` keeps its nodes;
    /// turns about a constant axis unless the scale is uniform), and only where
    /// every argument made stays within [`catalog::GPU_RANGE`] and the nodes fit under
    /// [`MAX_NODES`]. `None`: the scale stays.
    ///
    /// The surface is the same; the field off it is the distance instead of a bound, which is
    /// what operators that read it there (`round`, `onion`, the smooth blends, `mix`, `blob`)
    /// then see, whether the factors are constants or parameters.
    pub(super) fn absorb_scale(
        &mut self,
        v: &[Field; 3],
        child: NodeId,
        span: Span,
    ) -> Option<NodeId> {
        let (steps, id) = self.scale_steps(v, child)?;
        let NodeKind::Primitive { prim, ctx } = &self.nodes[id].kind else {
            return None;
        };
        let args = to_args(catalog::absorb::scaled(prim, ctx, v)?);
        // Each new node is built at the end and moved into the slot of the node it
        // replaces (no one else refers to an unnamed plain node), so the scene
        // does not grow: one node more only for that moment.
        if !fits(&args.0) || self.nodes.len() + 1 > MAX_NODES {
            return None;
        }
        let prim = *prim;
        self.rebuild_scaled(prim, args, id, steps, span)
    }

    /// The steps from the scale down to a primitive, each as (operator, arguments once scaled,
    /// its node), and the primitive's node; `None` where a step is not plain or does not
    /// commute with the scale `v`.
    fn scale_steps(&self, v: &[Field; 3], child: NodeId) -> Option<(Vec<Step>, NodeId)> {
        // (A uniform scale is exact already; taken in all the same, it leaves one node fewer
        // and lets an outer non-uniform scale reach the box.)
        let uniform = v[0] == v[1] && v[1] == v[2];
        // (An annotation that keeps λ still takes exactness away: `exact` tells.)
        let plain = |n: &Node| {
            n.material.is_none() && n.name.is_none() && n.lambda == n.inferred_lambda && n.exact
        };
        let mut steps: Vec<Step> = Vec::new();
        let mut id = child;
        loop {
            let node = &self.nodes[id];
            if !plain(node) {
                return None;
            }
            match &node.kind {
                NodeKind::Operator { op, ctx, children } => {
                    let args = match op.traits.motion {
                        // A uniform scale commutes with every turn.
                        Motion::Turn if uniform => (ctx.args.clone(), ctx.sym.clone()),
                        Motion::Turn if ctx.sym(0).is_none() => {
                            let axis = ctx.vec(0);
                            let on: Vec<usize> = (0..3).filter(|&k| axis[k] != 0.0).collect();
                            let &[k] = on.as_slice() else {
                                return None;
                            };
                            if v[(k + 1) % 3] != v[(k + 2) % 3] {
                                return None;
                            }
                            (ctx.args.clone(), ctx.sym.clone())
                        }
                        Motion::Move => to_args(vec![times3(&comps(ctx, 0), v)]),
                        _ => return None,
                    };
                    if !fits(&args.0) {
                        return None;
                    }
                    steps.push((op.name, args, id));
                    id = children[0];
                }
                NodeKind::Primitive { .. } => return Some((steps, id)),
                _ => return None,
            }
        }
    }

    /// The primitive at `id` rebuilt with the scaled `args`, then each of `steps` (outermost
    /// first) rebuilt over it, each new node moved into the slot of the node it replaces;
    /// `None`, with the replaced nodes put back, if a step cannot be built after all.
    fn rebuild_scaled(
        &mut self,
        prim: &'static catalog::Primitive,
        args: Args,
        id: NodeId,
        steps: Vec<Step>,
        span: Span,
    ) -> Option<NodeId> {
        // Each node keeps its span; the outermost takes the scale's (it stands for
        // the whole expression now).
        let span_of = |c: &Self, n: NodeId, outermost: bool| {
            if outermost { span } else { c.nodes[n].span }
        };
        let before = self.diags.len();
        // The nodes replaced, put back if a step cannot be built after all.
        let mut saved = Vec::new();
        let at = span_of(self, id, steps.is_empty());
        let mut built = self.primitive_node(prim, args, at);
        let mut top = id;
        let mut rest = steps.into_iter().enumerate().rev();
        while let Some(new) = built {
            saved.push((top, self.nodes[top].clone()));
            self.move_node(new, top);
            let Some((i, (name, args, old))) = rest.next() else {
                // With constant arguments that fit and room for a node, building
                // them reports nothing (each step's were given where written).
                debug_assert_eq!(self.diags.len(), before, "{:?}", &self.diags[before..]);
                return Some(top);
            };
            let at = span_of(self, old, i == 0);
            built = self.operator_node(name, args, vec![top], at);
            top = old;
        }
        for (slot, node) in saved {
            self.nodes[slot] = node;
        }
        None
    }

    /// Moves the node just built (`new`, the last) into the slot `old`.
    fn move_node(&mut self, new: NodeId, old: NodeId) {
        debug_assert_eq!(new + 1, self.nodes.len(), "the node just built is the last");
        let node = self.nodes.pop().expect("the node just built");
        self.nodes[old] = node;
        // (A chain's nodes are built just before and no union holds them yet, so none has a
        // lattice form; were one numbered, its number would now be stale.)
        self.forms.forget(old);
    }
}

/// Whether every argument made stays within [`catalog::GPU_RANGE`].
fn fits(args: &[Val]) -> bool {
    args.iter().all(|a| a.fits_gpu())
}

/// Arguments from expressions: values where the scene is checked, and expressions where any
/// reads a parameter.
fn to_args(comps: Vec<Vec<Field>>) -> Args {
    let (vals, syms): Args = comps.iter().map(|c| to_arg(c)).unzip();
    (vals, catalog::arg_syms(syms))
}
