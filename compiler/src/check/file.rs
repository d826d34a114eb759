//! Checking one parsed file: its statements in order, the scene's root (the union of its
//! shapes), the checks of the whole scene, and the diagnostics sorted and deduplicated.

use super::Checker;
use crate::diag::{Diagnostic, Span};
use crate::scene::NodeId;
use crate::source::Sources;
use crate::syntax::{self, Item};
use std::collections::HashMap;

/// Checks a parsed file whose spans point into `sources`, with parameters at `values`.
pub(super) fn check_with_lines(
    file: &syntax::File,
    sources: &Sources,
    values: &HashMap<String, Vec<f64>>,
) -> super::Checked {
    let mut c = Checker::new(file);
    c.overrides = values.clone();
    c.line_starts = sources.line_starts();
    let roots = c.items(file);
    let root = c.scene_root(file, roots);
    c.unused_params();
    c.unused_fns(sources.files.first().map_or(usize::MAX, |f| f.text.len()));
    if let Some(root) = root {
        c.check_root_not_planar(root);
        c.check_bounded(root);
        c.check_bound(root);
        c.check_epsilon();
        c.check_f32_range(root);
        c.check_implicit_overflow(root);
    }
    c.diags.sort_by_key(|d| (d.span.start, d.span.end));
    // A body's mistake is found at every call: shown once, with the first call.
    let mut seen = std::collections::HashSet::new();
    c.diags
        .retain(|d| seen.insert((d.span, d.message.clone(), d.label.clone())));
    let ok = !c.diags.iter().any(Diagnostic::is_error);
    let diagnostics = std::mem::take(&mut c.diags);
    let scene = match (ok, root) {
        (true, Some(root)) => Some(c.finish(root)),
        _ => None,
    };
    super::Checked {
        scene,
        diagnostics,
        sources: Sources::default(),
    }
}

impl<'a> Checker<'a> {
    /// Checks each statement in order; the shapes of the scene.
    fn items(&mut self, file: &'a syntax::File) -> Vec<NodeId> {
        let mut roots = Vec::new();
        for (index, item) in file.items.iter().enumerate() {
            self.depth_reported = false;
            self.item = index;
            match item {
                Item::Fn(def) => self.fn_definition(def, index),
                // Spliced in by `syntax::load`; a file checked without loading has none to read.
                Item::Import { .. } => {}
                Item::Let { name, value } => self.let_binding(name, value),
                Item::Param {
                    name,
                    value,
                    range,
                    span,
                } => self.param_statement(name, value, range.as_deref(), *span),
                Item::Block {
                    keyword,
                    kind,
                    settings,
                    span,
                } => self.block(keyword, kind.as_ref(), settings, *span),
                Item::Value { keyword, value } => self.value_statement(keyword, value),
                Item::Scene(e) => {
                    if let Some(n) = self.shape(e) {
                        roots.push(n);
                    }
                }
            }
        }
        roots
    }

    /// The scene's root: its one shape, or the union of its shapes; an error for a file
    /// without any.
    fn scene_root(&mut self, file: &syntax::File, roots: Vec<NodeId>) -> Option<NodeId> {
        let had_scene = file.items.iter().any(|i| matches!(i, Item::Scene(_)));
        match roots.len() {
            0 => {
                if !had_scene {
                    let end = file_end(file);
                    self.diags.push(
                        Diagnostic::error(Span::new(end, end), "the file has no shape to render")
                            .help("add a shape after the settings, e.g. `sphere(1)`"),
                    );
                }
                None
            }
            1 => Some(roots[0]),
            _ => {
                let span = self.nodes[roots[0]]
                    .span
                    .to(self.nodes[*roots.last().unwrap()].span);
                self.operator_node("union", (Vec::new(), Vec::new()), roots, span)
            }
        }
    }
}

/// The offset just past the file's last statement.
fn file_end(file: &syntax::File) -> usize {
    file.items
        .iter()
        .map(|i| match i {
            Item::Let { value, .. } | Item::Value { value, .. } | Item::Scene(value) => {
                value.span.end
            }
            Item::Block { span, .. } | Item::Param { span, .. } | Item::Import { span, .. } => {
                span.end
            }
            Item::Fn(def) => def.span.end,
        })
        .max()
        .unwrap_or(0)
}
