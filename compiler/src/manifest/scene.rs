//! The manifest's sections about the scene itself: its parameters, materials and lights, and
//! which parameters each setting reads.

use super::{Origin, prefixed};
use crate::lower::Entry;
use crate::scene::{LightKind, Scene, Shadow};
use serde_json::{Value, json};

/// The names of the parameters each of a material's or light's settings reads (`syms`
/// indexed as the settings are in `names`); null when none reads one.
fn reads(scene: &Scene, syms: &crate::catalog::ArgSyms, names: &[&str]) -> Value {
    let mut out = serde_json::Map::new();
    for (name, sym) in names.iter().zip(syms) {
        let mut read: Vec<String> = Vec::new();
        for field in sym.iter().flatten() {
            field.params(&mut |r| {
                let n = &scene.params[r.index].name;
                if !read.contains(n) {
                    read.push(n.clone());
                }
            });
        }
        if !read.is_empty() {
            out.insert(name.to_string(), json!(read));
        }
    }
    if out.is_empty() {
        Value::Null
    } else {
        Value::Object(out)
    }
}

/// The scene's parameters, each at its offset in the `Params` struct.
pub(super) fn params(scene: &Scene, offsets: &[u32]) -> Vec<Value> {
    scene
        .params
        .iter()
        .zip(offsets)
        .map(|(p, &offset)| {
            let n = p.kind.components();
            let comps = |v: glam::DVec3| v.to_array()[..n].to_vec();
            let mut v = json!({
                "name": p.name,
                "member": crate::lower::interface::shader_name(&p.name),
                "kind": p.kind.name(),
                "type": crate::lower::params::wgsl_type(p.kind),
                "offset": offset,
                "default": comps(p.default),
                "builtin": p.name == crate::check::TIME && p.span.start == p.span.end,
            });
            if let Some((lo, hi)) = p.range {
                v["min"] = json!(comps(lo));
                v["max"] = json!(comps(hi));
            }
            if p.kind == crate::scene::ParamKind::Angle {
                v["unit"] = json!("radians");
            }
            v
        })
        .collect()
}

/// The default material (id 0) and the scene's, by id.
pub(super) fn materials(scene: &Scene, origin: &Origin) -> Vec<Value> {
    let mut materials = vec![json!({
        "id": 0,
        "name": "default",
        "color": crate::reference::shading::DEFAULT_COLOR.to_array(),
    })];
    for (i, m) in scene.materials.iter().enumerate() {
        let mut v = json!({
            "id": i + 1,
            "name": m.name,
            "color": m.color.to_array(),
            "specular": m.specular,
            "reflect": m.reflect,
            "transparent": m.transparent,
            "ior": m.ior,
            "params": reads(scene, &m.sym, &["color", "specular"]),
        });
        if let Some(pt) = &m.pattern {
            let kind = crate::reference::texture::PATTERNS
                .iter()
                .find(|p| p.1 == pt.kind)
                .map_or("?", |p| p.0);
            v["pattern"] = json!({
                "kind": kind,
                "second": pt.other.to_array(),
                "scale": pt.scale,
                "octaves": pt.octaves,
            });
        }
        if origin.entry == Entry::Library {
            v["constant"] = json!(prefixed(
                origin.prefix,
                &crate::lower::interface::material_constant(&m.name)
            ));
        }
        materials.push(v);
    }
    materials
}

/// The scene's lights: kind, direction or position, colour, intensity, shadow.
pub(super) fn lights(scene: &Scene) -> Vec<Value> {
    scene
        .lights
        .iter()
        .map(|l| {
            let (kind, place, vector) = match l.kind {
                LightKind::Directional(d) => ("directional", "direction", d),
                LightKind::Point(p) => ("point", "position", p),
            };
            let params = reads(scene, &l.sym, &[place, "color", "intensity"]);
            let shadow = match l.shadow {
                Shadow::None => json!("none"),
                Shadow::Hard => json!("hard"),
                Shadow::Soft(k) => json!({"soft": k}),
            };
            json!({
                "kind": kind,
                place: vector.to_array(),
                "color": l.color.to_array(),
                "intensity": l.intensity,
                "shadow": shadow,
                "params": params,
            })
        })
        .collect()
}
