//! The manifest's `data` section: the data form's buffers, where each is bound, its file, and
//! which parameters they were made at.

use crate::scene::Scene;
use crate::tape::data::{BUFFERS, Data};
use serde_json::{Value, json};

/// What `emit --form data` wrote for a host: the buffers and the files that hold them (as the
/// manifest names them: beside it), in [`BUFFERS`]' order.
pub struct DataFiles<'a> {
    /// The buffers, made at the parameters' defaults.
    pub data: &'a Data,
    /// Their files.
    pub files: &'a [String],
}

/// The manifest's `data` section (null when `module` is the inline form): per buffer its
/// global and binding in `module`, element type, bytes and file; the grid its ranges' header
/// holds; and the parameters the buffers follow. A host uploads each file as a read-only
/// storage buffer at its binding; changing a parameter of `follows` moves parts, which needs
/// buffers made again at the new value.
pub(super) fn section(scene: &Scene, module: &naga::Module, given: Option<&DataFiles>) -> Value {
    let globals: Vec<&naga::GlobalVariable> = crate::layout::TAPE_BINDINGS
        .iter()
        .filter_map(|&binding| {
            module.global_variables.iter().map(|(_, g)| g).find(|g| {
                g.binding
                    .is_some_and(|b| b.group == crate::layout::GROUP && b.binding == binding)
                    && matches!(g.space, naga::AddressSpace::Storage { .. })
            })
        })
        .collect();
    if globals.len() != BUFFERS.len() {
        return Value::Null;
    }
    let bytes = given.map(|g| g.data.buffers().map(|b| b.len()));
    let buffers: Vec<Value> = BUFFERS
        .iter()
        .zip(&globals)
        .enumerate()
        .map(|(i, ((name, element), g))| {
            json!({
                "name": name,
                "global": g.name,
                "binding": g.binding.map(|b| json!({"group": b.group, "binding": b.binding})),
                "element": element,
                "bytes": bytes.map(|b| b[i]),
                "file": given.and_then(|g| g.files.get(i)),
            })
        })
        .collect();
    let follows: Vec<&str> = crate::tape::data::follows(scene)
        .into_iter()
        .map(|i| scene.params[i].name.as_str())
        .collect();
    let grid = given.map(|g| {
        let (lo, cell, cells) = g.data.grid();
        json!({"lo": lo, "cell": cell, "cells": cells})
    });
    json!({
        "doc": "docs/data-form.md",
        "buffers": buffers,
        "layout": "little-endian u32 words; each file is uploaded whole as a read-only storage buffer at its binding",
        "grid": grid,
        "made_at": "the parameters' defaults",
        "follows": follows,
    })
}
