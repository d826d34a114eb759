//! The manifest's `volumes` section: where each baked volume is bound and how its file is laid out.

use crate::scene::Scene;
use serde_json::{Value, json};

/// The manifest's `volumes` section: per baked volume of `scene` (`Scene::volumes`' order) its
/// texture's global and binding in `module`, format, size, box, spacing, λ and file (from
/// `files`, if written). A host uploads the file as a 3D texture of that size and binds it
/// there; the shader reads texels with `textureLoad` (no sampler).
pub(super) fn section(scene: &Scene, module: &naga::Module, files: &[String]) -> Vec<Value> {
    let globals: Vec<&naga::GlobalVariable> = module
        .global_variables
        .iter()
        .map(|(_, g)| g)
        .filter(|g| matches!(module.types[g.ty].inner, naga::TypeInner::Image { .. }))
        .collect();
    scene
        .volumes()
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let binding = crate::layout::VOLUME_BINDING + i as u32;
            let global = globals
                .iter()
                .find(|g| g.binding.is_some_and(|b| b.binding == binding));
            let g = &v.grid;
            json!({
                "global": global.and_then(|g| g.name.clone()),
                "binding": global.and_then(|g| g.binding).map(|b| json!({"group": b.group, "binding": b.binding})),
                "format": "r32float",
                "size": g.n,
                "box": {"lo": g.lo.to_array(), "hi": g.hi.to_array()},
                "spacing": g.h,
                "lambda": v.lambda,
                "bytes": v.bytes(),
                "layout": crate::bake::file::LAYOUT,
                "file": files.get(i),
            })
        })
        .collect()
}
