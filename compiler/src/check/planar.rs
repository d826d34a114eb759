//! 2D shapes in the checker: which nodes are 2D, and the errors for mixing them with solids —
//! a 2D shape becomes a solid only through `extrude` or `revolve`, moves and turns only in its
//! plane, and is never a shape of the scene by itself.

use super::Checker;
use crate::catalog::planar::{PRIMITIVES_2D, is_planar_primitive, keeps_planar, takes_planar};
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
            NodeKind::Primitive { prim, .. } => is_planar_primitive(prim.name),
            NodeKind::Operator { op, children, .. } => {
                keeps_planar(op.name) && children.iter().any(|&c| self.is_planar(c))
            }
            NodeKind::Implicit { .. } => false,
        };
        self.planar.push(planar);
    }

    /// The errors of an operator over its children: `extrude`/`revolve` of a solid, a solid
    /// and a 2D shape combined, a 2D shape turned out of its plane or given to an operator
    /// of solids. `Err` when reported.
    pub(super) fn check_planar(
        &mut self,
        name: &str,
        axis: Option<(glam::DVec3, bool)>,
        children: &[NodeId],
        span: Span,
    ) -> Result<(), ()> {
        let flat: Vec<bool> = children.iter().map(|&c| self.is_planar(c)).collect();
        if takes_planar(name) {
            return self.check_takes_planar(name, &flat, children, span);
        }
        if !flat.iter().any(|&f| f) {
            return Ok(());
        }
        let first = flat.iter().position(|&f| f).expect("one is 2D");
        let c = self.nodes[children[first]].span;
        if !keeps_planar(name) {
            self.diags.push(
                Diagnostic::error(c, format!("`{name}` works on solids, and this is a 2D shape"))
                    .label("a 2D shape")
                    .also(span, format!("`{name}` here"))
                    .help(format!("make a solid of it first: `extrude(1) {{ … }}` or `revolve(0.5) {{ … }}`, then `{name}`")),
            );
            return Err(());
        }
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
        self.check_in_plane(name, axis, c, span)
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
            let shapes_2d = PRIMITIVES_2D
                .iter()
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

    /// A 2D shape (at `c`) turned, mirrored or repeated by `name` about or along `axis` (and
    /// whether that is set at run time): an error unless it stays in its plane.
    fn check_in_plane(
        &mut self,
        name: &str,
        axis: Option<(glam::DVec3, bool)>,
        c: Span,
        span: Span,
    ) -> Result<(), ()> {
        // A 2D shape must stay the same at every z (extrude's λ = 1 rests on it): turns only
        // about z, mirrors only across planes that contain z or are across it, repeats only in
        // its plane — and none of these set at run time.
        let Some((a, run_time)) = axis else {
            return Ok(());
        };
        let (ok, what, help) = match name {
            "rotate" => (
                (a.z.abs() - 1.0).abs() <= 1e-12,
                "a 2D shape turns only in its plane",
                "turn it about `z`, or turn the solid after `extrude` or `revolve`",
            ),
            "mirror" => (
                a.z == 0.0 || (a.z.abs() - 1.0).abs() <= 1e-12,
                "a 2D shape mirrors only within its plane",
                "mirror it across a plane through the z axis (a normal `(x, y, 0)`), or mirror the solid",
            ),
            _ => (
                a.z == 0.0,
                "a 2D shape repeats only in its plane",
                "give the spacing 0 along z: `repeat((sx, sy, 0)) { … }`",
            ),
        };
        if !ok {
            self.diags.push(
                Diagnostic::error(span, what)
                    .label("out of the xy plane")
                    .also(c, "a 2D shape, in the xy plane")
                    .help(help),
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
