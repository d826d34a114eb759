//! A mesh as files other tools read: binary STL, OBJ with its MTL, binary PLY with vertex
//! colours, and binary glTF (GLB) with a primitive and a PBR material per scene material.
//! Written by hand: each is a page of a published layout, and no crate writes all four.

use super::Mesh;
use crate::parallel::par_map;
use crate::reference::{eval, shading};
use crate::scene::Scene;
use glam::DVec3;
use serde_json::json;

/// The file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Binary STL: triangles only (printers).
    Stl,
    /// Wavefront OBJ and an MTL file beside it: a group per material.
    Obj,
    /// Binary PLY with a colour per vertex.
    Ply,
    /// Binary glTF 2.0: a primitive and a PBR material per scene material.
    Glb,
}

impl Format {
    /// The format a file name's extension names (`.stl`, `.obj`, `.ply`, `.glb`).
    pub fn from_extension(ext: &str) -> Option<Format> {
        match ext.to_ascii_lowercase().as_str() {
            "stl" => Some(Format::Stl),
            "obj" => Some(Format::Obj),
            "ply" => Some(Format::Ply),
            "glb" => Some(Format::Glb),
            _ => None,
        }
    }
}

/// A material's name in the files: the scene's, or `default`.
pub fn material_name(scene: &Scene, m: u32) -> String {
    shading::material_of(scene, m).map_or_else(|| "default".to_string(), |m| m.name.clone())
}

/// A material's base colour as written in the scene (sRGB, 0…1).
fn srgb(scene: &Scene, m: u32) -> DVec3 {
    shading::material_of(scene, m).map_or(shading::DEFAULT_COLOR, |m| m.color)
}

/// The face normal of a triangle (zero if it is degenerate).
fn face_normal(mesh: &Mesh, t: [u32; 3]) -> DVec3 {
    let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
    (b - a).cross(c - a).try_normalize().unwrap_or(DVec3::ZERO)
}

/// Binary STL: an 80-byte header, the count, then per triangle its normal and corners (f32).
pub fn stl(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * mesh.triangles.len());
    // (A binary STL's header must not start with `solid`, which marks the text form.)
    let mut header = [b' '; 80];
    header[..9].copy_from_slice(b"sdfc mesh");
    out.extend_from_slice(&header);
    out.extend_from_slice(&(mesh.triangles.len() as u32).to_le_bytes());
    for &t in &mesh.triangles {
        let mut v = vec![face_normal(mesh, t)];
        v.extend(t.map(|i| mesh.positions[i as usize]));
        for p in v {
            for x in p.to_array() {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// OBJ text naming `mtl_file` and the MTL text: vertices, then a `usemtl` group per material.
/// `Kd` is the material's colour as the scene writes it (sRGB, as editors show MTL colours).
pub fn obj(mesh: &Mesh, scene: &Scene, mtl_file: &str) -> (String, String) {
    use std::fmt::Write;
    let mut o = format!("# sdfc mesh\nmtllib {mtl_file}\n");
    for p in &mesh.positions {
        let _ = writeln!(o, "v {} {} {}", p.x as f32, p.y as f32, p.z as f32);
    }
    let mut mtl = String::from("# sdfc materials\n");
    for (m, triangles) in by_material(mesh) {
        let name = material_name(scene, m);
        let c = srgb(scene, m);
        let _ = writeln!(mtl, "newmtl {name}\nKd {} {} {}\n", c.x, c.y, c.z);
        let _ = writeln!(o, "usemtl {name}");
        for t in triangles {
            let _ = writeln!(o, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
        }
    }
    (o, mtl)
}

/// The triangles grouped by material, in material order.
fn by_material(mesh: &Mesh) -> Vec<(u32, Vec<[u32; 3]>)> {
    let mut groups: std::collections::BTreeMap<u32, Vec<[u32; 3]>> = Default::default();
    for (t, &m) in mesh.triangles.iter().zip(&mesh.materials) {
        groups.entry(m).or_default().push(*t);
    }
    groups.into_iter().collect()
}

/// Each vertex's colour (sRGB bytes): the albedo of the material at the vertex, its pattern
/// included (`shading::albedo`, with the normal from the field at step `h`).
pub fn vertex_colors(scene: &Scene, mesh: &Mesh, h: f64) -> Vec<[u8; 3]> {
    par_map(&mesh.positions, |&p| {
        let m = eval::surface(scene, p).0;
        let n = eval::normal(scene, p, h);
        let c = shading::albedo(scene, m, p, n);
        c.to_array()
            .map(|x| (crate::color::to_srgb(x.clamp(0.0, 1.0)) * 255.0).round() as u8)
    })
}

/// Binary little-endian PLY: positions (f32) and colours (u8) per vertex, triangles.
pub fn ply(mesh: &Mesh, colors: &[[u8; 3]]) -> Vec<u8> {
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment sdfc mesh\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    let mut out = header.into_bytes();
    for (p, c) in mesh.positions.iter().zip(colors) {
        for x in p.to_array() {
            out.extend_from_slice(&(x as f32).to_le_bytes());
        }
        out.extend_from_slice(c);
    }
    for t in &mesh.triangles {
        out.push(3);
        for v in t {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}

/// Binary glTF 2.0: one mesh of a primitive per material sharing the positions; each material
/// PBR with the scene colour as base colour (converted to linear, as glTF wants), metallic = the
/// material's `reflect`, roughness = 1 − ½·`specular`, and `transparent` as alpha blending.
/// No normals: viewers shade flat, which keeps creases.
pub fn glb(mesh: &Mesh, scene: &Scene) -> Vec<u8> {
    let mut bin: Vec<u8> = Vec::new();
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for p in &mesh.positions {
        let p32 = p.as_vec3();
        (lo, hi) = (lo.min(p32.as_dvec3()), hi.max(p32.as_dvec3()));
        for x in p32.to_array() {
            bin.extend_from_slice(&x.to_le_bytes());
        }
    }
    let positions_len = bin.len();
    let mut views =
        vec![json!({"buffer": 0, "byteOffset": 0, "byteLength": positions_len, "target": 34962})];
    let mut accessors = vec![json!({
        "bufferView": 0, "componentType": 5126, "count": mesh.positions.len(), "type": "VEC3",
        "min": lo.as_vec3().to_array(), "max": hi.as_vec3().to_array(),
    })];
    let mut primitives = Vec::new();
    let mut materials = Vec::new();
    for (m, triangles) in by_material(mesh) {
        let offset = bin.len();
        for v in triangles.iter().flatten() {
            bin.extend_from_slice(&v.to_le_bytes());
        }
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": bin.len() - offset, "target": 34963}));
        accessors.push(json!({"bufferView": views.len() - 1, "componentType": 5125, "count": triangles.len() * 3, "type": "SCALAR"}));
        primitives.push(json!({"attributes": {"POSITION": 0}, "indices": accessors.len() - 1, "material": materials.len()}));
        materials.push(material(scene, m));
    }
    let doc = json!({
        "asset": {"version": "2.0", "generator": concat!("sdfc ", env!("CARGO_PKG_VERSION"))},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": primitives}],
        "materials": materials,
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": views,
        "accessors": accessors,
    });
    pack_glb(doc.to_string().into_bytes(), bin)
}

/// A scene material as a glTF PBR material.
fn material(scene: &Scene, m: u32) -> serde_json::Value {
    let c = crate::color::linear(srgb(scene, m));
    let mat = shading::material_of(scene, m);
    let (specular, reflect, transparent) =
        mat.map_or((0.0, 0.0, 0.0), |m| (m.specular, m.reflect, m.transparent));
    let alpha = 1.0 - transparent.clamp(0.0, 1.0);
    let mut v = json!({
        "name": material_name(scene, m),
        "pbrMetallicRoughness": {
            "baseColorFactor": [c.x, c.y, c.z, alpha],
            "metallicFactor": reflect.clamp(0.0, 1.0),
            "roughnessFactor": (1.0 - 0.5 * specular).clamp(0.0, 1.0),
        },
    });
    if alpha < 1.0 {
        v["alphaMode"] = json!("BLEND");
    }
    v
}

/// The GLB container: a 12-byte header, the JSON chunk padded with spaces and the binary chunk
/// padded with zeros to four bytes.
fn pack_glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Vec<u8> {
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}
