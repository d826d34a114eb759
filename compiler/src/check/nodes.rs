//! Building the scene graph's nodes: a node's λ, bound and properties from its catalog rules
//! (over its parameters' ranges), operator nodes over children, and the checks of the whole
//! graph (every reachable node bounded, `repeat`'s copies within the limit).

use super::{Checker, MAX_EVALUATIONS, MAX_NODES, MIN_LAMBDA, ranges};
use crate::catalog::traits::{Motion, Plane};
use crate::catalog::{Bound, Ctx, Operator};
use crate::diag::{Diagnostic, Span};
use crate::scene::{Node, NodeId, NodeKind};

impl Checker<'_> {
    /// Adds a node; `None` (with an error) past [`MAX_NODES`].
    pub(super) fn push_node(
        &mut self,
        kind: NodeKind,
        lambda: f64,
        bound: Bound,
        span: Span,
    ) -> Option<NodeId> {
        if self.nodes.len() >= MAX_NODES {
            if self.nodes.len() == MAX_NODES {
                self.diags.push(
                    Diagnostic::error(span, "the scene has too many nodes")
                        .note(format!("the limit is {MAX_NODES} nodes")),
                );
                // Push a placeholder so the message is given once.
                self.nodes.push(self.nodes[0].clone());
                self.planar.push(false);
                self.call_site.push(None);
            }
            return None;
        }
        // A zero slope (a constant field) would divide by zero; any larger λ is still a bound.
        let lambda = lambda.max(MIN_LAMBDA);
        let unit_gradient = match &kind {
            NodeKind::Primitive { prim, ctx } => (prim.unit_gradient)(ctx),
            NodeKind::Operator { op, ctx, children } => {
                (op.unit_gradient)(ctx) && children.iter().all(|&c| self.nodes[c].unit_gradient)
            }
            NodeKind::Implicit { .. } => false,
        };
        let exact = match &kind {
            NodeKind::Primitive { prim, .. } => prim.exact,
            NodeKind::Operator { op, ctx, children } => {
                (op.keeps_exact)(ctx) && children.iter().all(|&c| self.nodes[c].exact)
            }
            NodeKind::Implicit { .. } => false,
        };
        let (mirror, swap) = match &kind {
            NodeKind::Primitive { prim, ctx } => ((prim.mirror)(ctx), (prim.swap)(ctx)),
            NodeKind::Operator { op, ctx, .. } => ((op.mirror)(ctx), (op.swap)(ctx)),
            NodeKind::Implicit { .. } => ([false; 3], [false; 3]),
        };
        self.note_planar(&kind);
        let call_site = self.frames.first().map(|f| f.call_span);
        self.call_site.push(call_site);
        self.nodes.push(Node {
            call_site,
            mirror,
            swap,
            unit_gradient,
            exact,
            // (An operator's is set by `operator_node`.)
            evaluations: 1.0,
            kind,
            span,
            lambda,
            inferred_lambda: lambda,
            bound,
            material: None,
            name: None,
        });
        Some(self.nodes.len() - 1)
    }

    /// What a primitive or operator with these arguments knows of these checked children (none
    /// for a primitive; no bounding-volume tree yet).
    pub(super) fn ctx_over(
        &self,
        (args, sym): (Vec<crate::catalog::Val>, crate::catalog::ArgSyms),
        children: &[NodeId],
    ) -> Ctx {
        Ctx {
            args,
            sym,
            child_lambda: children.iter().map(|&c| self.nodes[c].lambda).collect(),
            child_bound: children.iter().map(|&c| self.nodes[c].bound).collect(),
            child_mirror: children.iter().map(|&c| self.nodes[c].mirror).collect(),
            child_swap: children.iter().map(|&c| self.nodes[c].swap).collect(),
            child_exact: children.iter().map(|&c| self.nodes[c].exact).collect(),
            prune: None,
            baked: None,
        }
    }

    /// Builds an operator node over checked children.
    pub(super) fn operator_node(
        &mut self,
        name: &str,
        (args, sym): (Vec<crate::catalog::Val>, crate::catalog::ArgSyms),
        children: Vec<NodeId>,
        span: Span,
    ) -> Option<NodeId> {
        let op = crate::catalog::operator(name).expect("operator in the catalog");
        if op.traits.motion == Motion::Scale
            && let ([arg], [child]) = (args.as_slice(), children.as_slice())
        {
            use crate::catalog::absorb::{comps_of, spread};
            let v = spread(&comps_of(sym.first().and_then(|s| s.as_deref()), *arg));
            if let Some(id) = self.absorb_scale(&v, *child, span) {
                return Some(id);
            }
        }
        // The first argument of the operators that may move a 2D shape out of its plane (a
        // turn's or mirror's axis, a repeat's spacing), and whether the host may change it.
        let axis = matches!(op.traits.plane, Plane::KeepsIf(_)).then(|| {
            let v = match args.first() {
                Some(crate::catalog::Val::Vec3(v)) => *v,
                _ => glam::DVec3::ZERO,
            };
            (v, sym.first().is_some_and(Option::is_some))
        });
        if self.check_planar(op, axis, &children, span).is_err() {
            return None;
        }
        let children = if op.traits.groups {
            self.lattices(children)
        } else {
            children
        };
        let mut ctx = self.ctx_over((args, sym), &children);
        if op.traits.groups {
            ctx.prune = crate::catalog::prune::Tree::build(&ctx).map(std::sync::Arc::new);
        }
        if op.traits.bakes {
            ctx.baked = Some(self.bake(&ctx, children[0], span)?);
        }
        let rules =
            self.rules_over_ranges(&ctx, span, name, &|c| ranges::Rules::operator(op, c))?;
        let (lambda, bound) = (rules.lambda, rules.bound);
        let copies = self.copies_of(op, &ctx, span);
        // A baked shape is read from its map, not evaluated.
        let each: f64 = match op.traits.bakes {
            true => 1.0,
            false => children.iter().map(|&c| self.nodes[c].evaluations).sum(),
        };
        let evaluations = each * copies;
        self.check_evaluations(&children, evaluations, span);
        let id = self.push_node(
            NodeKind::Operator { op, ctx, children },
            lambda,
            bound,
            span,
        )?;
        self.nodes[id].evaluations = evaluations;
        self.narrow_rules(id, &rules);
        Some(id)
    }

    /// How many copies of its child an operator evaluates at a point (1 but for the repeats,
    /// whose copies are checked against their limits).
    fn copies_of(&mut self, op: &Operator, ctx: &Ctx, span: Span) -> f64 {
        let Some(c) = op.traits.copies else {
            return 1.0;
        };
        let copies = (c.count)(ctx);
        self.diags.extend((c.diagnose)(ctx, copies, span));
        copies
    }

    /// An error when a node of `evaluations` primitive evaluations goes past
    /// [`MAX_EVALUATIONS`] (once: at the node whose children are all within it).
    fn check_evaluations(&mut self, children: &[NodeId], evaluations: f64, span: Span) {
        if evaluations > MAX_EVALUATIONS
            && children
                .iter()
                .all(|&c| self.nodes[c].evaluations <= MAX_EVALUATIONS)
        {
            self.diags.push(
                Diagnostic::error(span, "this shape costs too many evaluations")
                    .label(format!(
                        "one evaluation of it evaluates {evaluations:.0} primitives"
                    ))
                    .note(format!(
                        "counting every use of a shared `let` and every copy a `repeat` looks at; the limit is {MAX_EVALUATIONS:.0} per evaluation of the field"
                    ))
                    .help("use a shape fewer times, or fewer copies"),
            );
        }
    }

    /// A node's symmetries, exactness and gradient as every value of its parameters has them.
    pub(super) fn narrow_rules(&mut self, id: NodeId, rules: &ranges::Rules) {
        let n = &mut self.nodes[id];
        for i in 0..3 {
            n.mirror[i] &= rules.mirror[i];
            n.swap[i] &= rules.swap[i];
        }
        n.unit_gradient &= rules.unit;
        n.exact &= rules.exact;
    }

    /// Every reachable node needs a finite λ; report those that have none.
    pub(super) fn check_bounded(&mut self, root: NodeId) {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack = vec![root];
        while let Some(n) = stack.pop() {
            if std::mem::replace(&mut seen[n], true) {
                continue;
            }
            let node = &self.nodes[n];
            let children_bounded = node
                .children()
                .iter()
                .all(|&c| self.nodes[c].lambda.is_finite());
            if !node.lambda.is_finite() && children_bounded {
                let what = node.kind_name();
                let mut d = Diagnostic::error(
                    node.span,
                    format!("cannot bound the slope of this `{what}`"),
                )
                .label("no Lipschitz bound")
                .help("add `@lipschitz(L)` after it with a bound L on the gradient's length");
                if let NodeKind::Implicit { field } = &node.kind {
                    let mut free = Vec::new();
                    field.params(&mut |r| {
                        if !r.ranged() && !free.contains(&r.index) {
                            free.push(r.index);
                        }
                    });
                    if let Some(&i) = free.first() {
                        let name = &self.params[i].name;
                        d = d
                            .note(format!(
                                "`{name}` has no range, and the slope grows without bound with it"
                            ))
                            .help(format!(
                                "give `{name}` a range: `param {name} = … in low..high`"
                            ));
                    }
                }
                // (A baked shape reads no parameters: no such help for one that does.)
                let mut reads = false;
                if let NodeKind::Implicit { field } = &node.kind {
                    field.params(&mut |_| reads = true);
                }
                if let (NodeKind::Implicit { .. }, false) = (&node.kind, reads) {
                    d = d.help("or bake it into a distance map, which needs no bound: `bake(res = 64) { … }` around a bounded shape holding it (docs/bake.md)");
                }
                if let NodeKind::Implicit { field } = &node.kind
                    && crate::lipschitz::crosses_branch_cut(field)
                {
                    d = d.note("`atan2(a, b)` jumps by 2π where a crosses 0 while b < 0; only a field that is periodic in the angle (e.g. `sin(n * atan2(a, b))` with a whole n) stays continuous there, and then an annotation is right");
                }
                if let NodeKind::Operator { op, .. } = &node.kind
                    && let Some(note) = op.traits.unbounded
                {
                    d = d.note(note);
                }
                let d = self.with_call_site(d, n);
                self.diags.push(d);
            }
            // A baked shape needs no bound of its own: the map's is proven from its values.
            if let NodeKind::Operator { op, .. } = &self.nodes[n].kind
                && op.traits.bakes
            {
                continue;
            }
            stack.extend(self.nodes[n].children().iter().copied());
        }
    }
}
