//! 2D shapes in the checker: which nodes are 2D, and the errors for mixing them with solids —
//! a 2D shape becomes a solid only through `extrude` or `revolve`, moves and turns only in its
//! plane, and is never a shape of the scene by itself.

use super::Checker;
use crate::catalog::Operator;
use crate::catalog::planar::primitives_2d;
use crate::catalog::traits::{Plane, PlaneRule};
use crate::diag::{Diagnostic, Span};
use crate::scene::{NodeId, NodeKind};

impl Checker<'_> {
    /// Whether node `n` is a 2D shape.
    pub(super) fn is_planar(&self, n: NodeId) -> bool {
        self.planar.get(n).copied().unwrap_or(false)
    }

    /// Records whether the node just pushed is 2D.
    pub(super) fn note_planar(&mut self, kind: &NodeKind) {
        let planar = match kind {
            NodeKind::Primitive { prim, .. } => prim.planar,
            NodeKind::Operator { op, children, .. } => {
                matches!(op.traits.plane, Plane::Keeps | Plane::KeepsIf(_))
                    && children.iter().any(|&c| self.is_planar(c))
            }
            NodeKind::Implicit { .. } => false,
        };
        self.planar.push(planar);
    }

    /// The errors of an operator over its children: `extrude`/`revolve` of a solid, a solid
    /// and a 2D shape combined, a 2D shape turned out of its plane or given to an operator
    /// of solids. `axis`: the first argument, when the operator's plane rule reads it, and
    /// whether it is set at run time. `Err` when reported.
    pub(super) fn check_planar(
        &mut self,
        op: &Operator,
        axis: Option<(glam::DVec3, bool)>,
        children: &[NodeId],
        span: Span,
    ) -> Result<(), ()> {
        let name = op.name;
        let flat: Vec<bool> = children.iter().map(|&c| self.is_planar(c)).collect();
        if let Plane::Makes = op.traits.plane {
            return self.check_takes_planar(name, &flat, children, span);
        }
        if !flat.iter().any(|&f| f) {
            return Ok(());
        }
        let first = flat.iter().position(|&f| f).expect("one is 2D");
        let c = self.nodes[children[first]].span;
        let rule = match op.traits.plane {
            Plane::Keeps => None,
            Plane::KeepsIf(rule) => Some(rule),
            Plane::Solids | Plane::Makes => {
                self.diags.push(
                    Diagnostic::error(c, format!("`{name}` works on solids, and this is a 2D shape"))
                        .label("a 2D shape")
                        .also(span, format!("`{name}` here"))
                        .help(format!("make a solid of it first: `extrude(1) {{ … }}` or `revolve(0.5) {{ … }}`, then `{name}`")),
                );
                return Err(());
            }
        };
        if let Some(solid) = flat.iter().position(|f| !f) {
            let s = self.nodes[children[solid]].span;
            self.diags.push(
                Diagnostic::error(span, format!("`{name}` of a 2D shape and a solid"))
                    .label("2D shapes combine with 2D shapes, solids with solids")
                    .also(c, "a 2D shape")
                    .also(s, "a solid")
                    .help("extrude or revolve the 2D shape first: `extrude(1) { … }`"),
            );
            return Err(());
        }
        match (rule, axis) {
            (Some(rule), Some(axis)) => self.check_in_plane(name, rule, axis, (c, span)),
            _ => Ok(()),
        }
    }

    /// `extrude`/`revolve` (`name`) of children (`flat`: which are 2D): an error for a solid.
    fn check_takes_planar(
        &mut self,
        name: &str,
        flat: &[bool],
        children: &[NodeId],
        span: Span,
    ) -> Result<(), ()> {
        if let Some(i) = flat.iter().position(|f| !f) {
            let c = self.nodes[children[i]].span;
            let shapes_2d = primitives_2d()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ");
            self.diags.push(
                Diagnostic::error(c, format!("`{name}` makes a solid of a 2D shape"))
                    .label("this is already a solid")
                    .also(span, format!("`{name}` here"))
                    .note(format!(
                        "the 2D shapes are {shapes_2d}, and what operators make of them"
                    )),
            );
            return Err(());
        }
        Ok(())
    }

    /// A 2D shape (at `c`) turned, mirrored or repeated by `name` about or along `a` (and
    /// whether that is set at run time): an error unless `rule` keeps it in its plane.
    fn check_in_plane(
        &mut self,
        name: &str,
        rule: PlaneRule,
        (a, run_time): (glam::DVec3, bool),
        (c, span): (Span, Span),
    ) -> Result<(), ()> {
        // A 2D shape must stay the same at every z (extrude's λ = 1 rests on it): turns only
        // about z, mirrors only across planes that contain z or are across it, repeats only in
        // its plane — and none of these set at run time.
        if !(rule.keeps)(a) {
            self.diags.push(
                Diagnostic::error(span, rule.message)
                    .label("out of the xy plane")
                    .also(c, "a 2D shape, in the xy plane")
                    .help(rule.help),
            );
            return Err(());
        }
        if run_time {
            self.diags.push(
                Diagnostic::error(span, format!("the first argument of `{name}` of a 2D shape cannot be a parameter"))
                    .label("set at run time")
                    .also(c, "a 2D shape")
                    .note("a 2D shape must stay in its plane for every value, which a parameter's range does not promise; a turn's angle may be a parameter"),
            );
            return Err(());
        }
        Ok(())
    }

    /// A 2D shape as a shape of the scene: an error.
    pub(super) fn check_root_not_planar(&mut self, root: NodeId) {
        if self.is_planar(root) {
            let d = Diagnostic::error(self.nodes[root].span, "a 2D shape is not a solid")
                .label("a 2D shape, the same at every z")
                .help("make a solid of it: `extrude(1) { … }` along z or `revolve(0.5) { … }` about y");
            let d = self.with_call_site(d, root);
            self.diags.push(d);
        }
    }
}
