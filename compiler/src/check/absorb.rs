//! A non-uniform `scale` taken into the primitive it scales (`catalog::absorb`), through the
//! turns and moves between them: an exact field where the scale alone gives a bound.

use super::Checker;
use crate::catalog::{self, Val};
use crate::diag::Span;
use crate::scene::{Node, NodeId, NodeKind};
use glam::DVec3;

impl Checker<'_> {
    /// `scale(v)` of `child` rewritten as the primitive with scaled arguments under the same
    /// turns and moves, where every step between allows it: a turn about a coordinate axis k
    /// commutes with a scale whose other two factors are equal, and a move by t becomes a move
    /// by t·v. Only plain steps are rewritten (constant arguments; no material, name or
    /// annotation of their own, so a `let` keeps its nodes). `None`: the scale stays.
    pub(super) fn absorb_scale(&mut self, v: DVec3, child: NodeId, span: Span) -> Option<NodeId> {
        if v.min_element() == v.max_element() {
            return None; // a uniform scale is exact already
        }
        let plain =
            |n: &Node| n.material.is_none() && n.name.is_none() && n.lambda == n.inferred_lambda;
        let constant = |c: &catalog::Ctx| c.sym.iter().all(Option::is_none);
        // The steps from the scale down, each as (operator, arguments once scaled, span).
        let mut steps: Vec<(&'static str, Vec<Val>, Span)> = Vec::new();
        let mut id = child;
        loop {
            let node = &self.nodes[id];
            if !plain(node) {
                return None;
            }
            match &node.kind {
                NodeKind::Operator { op, ctx, children } if constant(ctx) => {
                    let args = match op.name {
                        "rotate" => {
                            let axis = ctx.vec(0);
                            let on: Vec<usize> = (0..3).filter(|&k| axis[k] != 0.0).collect();
                            let &[k] = on.as_slice() else {
                                return None;
                            };
                            if v[(k + 1) % 3] != v[(k + 2) % 3] {
                                return None;
                            }
                            ctx.args.clone()
                        }
                        "translate" => vec![Val::Vec3(ctx.vec(0) * v)],
                        _ => return None,
                    };
                    steps.push((op.name, args, node.span));
                    id = children[0];
                }
                NodeKind::Primitive { prim, ctx } if constant(ctx) => {
                    let args = catalog::absorb::scaled(prim, ctx, v)?;
                    let (prim, at) = (*prim, node.span);
                    // Where the rewrite is the whole expression, it takes the scale's span.
                    let at = if steps.is_empty() { span } else { at };
                    let before = self.diags.len();
                    let mut top = self.primitive_node(prim, (args, Vec::new()), at);
                    let outermost = steps.len();
                    for (i, (name, args, at)) in steps.into_iter().enumerate().rev() {
                        let at = if i == 0 && outermost > 0 { span } else { at };
                        top = top.and_then(|c| {
                            self.operator_node(name, (args, Vec::new()), vec![c], at)
                        });
                    }
                    // Each step's diagnostics were given where it was written.
                    self.diags.truncate(before);
                    return top;
                }
                _ => return None,
            }
        }
    }
}
