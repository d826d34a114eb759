//! The manifest `sdfc emit --manifest` writes beside a shader: everything a host needs to
//! drive it (bindings, uniform layouts, parameters, entry points, functions, materials, the
//! scene's camera and lights), read from the validated module itself. Format: docs/interface.md.

mod data;
mod scene;
mod volumes;

pub use data::DataFiles;

use crate::emit::{Output, Reflection};
use crate::lower::Entry;
use crate::scene::Scene;
use naga::{AddressSpace, Module, ScalarKind, TypeInner, VectorSize};
use serde_json::{Value, json};

/// The format's name and version, the manifest's first field.
pub const FORMAT: &str = "sdfc-manifest 1";

/// The library's documented functions, in the order the manifest lists them.
pub const LIBRARY_FUNCTIONS: &[&str] =
    &["map", "map_material", "normal", "trace", "shade", "color"];

/// What the manifest says about the shader's origin.
pub struct Origin<'a> {
    /// The scene file's name.
    pub scene: &'a str,
    /// The target language's name (`wgsl`, `glsl`…).
    pub target: &'a str,
    /// The entry kind.
    pub entry: Entry,
    /// The `--prefix`, if any.
    pub prefix: Option<&'a str>,
    /// What the back end wrote, when the manifest describes written code: the functions'
    /// declarations and GLSL's block names are read from it.
    pub written: Option<(&'a Output, &'a Reflection)>,
    /// The files `emit` wrote each baked volume of `Scene::volumes` to (as the manifest names
    /// them: beside it), if it wrote them.
    pub volume_files: &'a [String],
    /// The data form's buffers and the files `emit` wrote them to, if it did.
    pub data: Option<DataFiles<'a>>,
}

/// The manifest of `module` (already prefixed, if it is) compiled from `scene`.
pub fn manifest(scene: &Scene, module: &Module, origin: &Origin) -> Value {
    let (offsets, size) = crate::lower::params::layout(&scene.params);
    let params = scene::params(scene, &offsets);
    let c = &scene.camera;
    json!({
        "format": FORMAT,
        "sdfc": env!("CARGO_PKG_VERSION"),
        "scene": origin.scene,
        "target": origin.target,
        "entry": entry_name(origin.entry),
        "prefix": origin.prefix,
        "entry_points": entry_points(module),
        "functions": functions(module, origin),
        "bindings": bindings(module, origin),
        "structs": structs(module),
        "view": view_section(module, origin.prefix),
        "params": params_section(module, origin.prefix, params, size),
        "volumes": volumes::section(scene, module, origin.volume_files),
        "data": data::section(scene, module, origin.data.as_ref()),
        "materials": scene::materials(scene, origin),
        "fragment": fragment(origin.entry),
        "compile": (origin.entry != Entry::Library).then(|| compile_cost(module)),
        "camera": {
            "eye": c.eye.to_array(),
            "target": c.target.to_array(),
            "up": c.up.to_array(),
            "fov_degrees": c.fov.to_degrees(),
        },
        "lights": scene::lights(scene),
        "background": scene.background.to_array(),
        "colors": "sRGB components in 0..1; shaders compute in linear light",
    })
}

/// What the driver's compile of the module is predicted to cost (`crate::cost`): the inlined
/// shader's counts and lavapipe's seconds with the upper end (not for the library, whose cost
/// is that of the host's shader around it).
fn compile_cost(module: &Module) -> Value {
    let i = crate::cost::inlined(module);
    let p = crate::cost::predict(&i);
    json!({
        "inlined_size": i.size,
        "calls": i.calls,
        "branches": i.branches,
        "transcendental": i.transcendental,
        "squares": i.squares,
        "chains": i.chains,
        "predicted_seconds": p.seconds,
        "at_most_seconds": p.at_most,
    })
}

/// The entry kind's name as `--entry` spells it.
fn entry_name(entry: Entry) -> &'static str {
    match entry {
        Entry::Compute => "compute",
        Entry::Fragment => "fragment",
        Entry::Library => "library",
        Entry::Trace => "trace",
        Entry::Rays => "rays",
        Entry::Field => "field",
    }
}

/// The module's entry points: name, stage and workgroup size.
fn entry_points(module: &Module) -> Vec<Value> {
    module
        .entry_points
        .iter()
        .map(|e| {
            json!({
                "name": e.name,
                "stage": format!("{:?}", e.stage).to_lowercase(),
                "workgroup_size": e.workgroup_size,
            })
        })
        .collect()
}

/// Every bound global, sorted by group and binding, with GLSL's name of its block.
fn bindings(module: &Module, origin: &Origin) -> Vec<Value> {
    let blocks = origin.written.map_or(&[][..], |(_, r)| &r.blocks[..]);
    let mut bindings: Vec<(u32, u32, Value)> = module
        .global_variables
        .iter()
        .filter_map(|(_, g)| {
            let b = g.binding.as_ref()?;
            let mut v = binding(module, g, b);
            if let Some((_, block)) = blocks.iter().find(|(n, _)| *n == b.binding) {
                v["glsl_block"] = json!(block);
            }
            Some((b.group, b.binding, v))
        })
        .collect();
    bindings.sort_by_key(|(g, b, _)| (*g, *b));
    bindings.into_iter().map(|(_, _, v)| v).collect()
}

/// One bound global: where, its address space and access, its type, and its struct's size or
/// its array's stride.
fn binding(module: &Module, g: &naga::GlobalVariable, b: &naga::ResourceBinding) -> Value {
    let (space, access) = match g.space {
        AddressSpace::Uniform => ("uniform", None),
        AddressSpace::Storage { access } => (
            "storage",
            Some(if access.contains(naga::StorageAccess::STORE) {
                "read_write"
            } else {
                "read"
            }),
        ),
        AddressSpace::Handle => ("handle", None),
        _ => ("other", None),
    };
    let mut v = json!({
        "group": b.group,
        "binding": b.binding,
        "name": g.name,
        "space": space,
        "type": type_name(module, g.ty),
    });
    if let Some(a) = access {
        v["access"] = json!(a);
    }
    if let TypeInner::Struct { span, .. } = module.types[g.ty].inner {
        v["size"] = json!(span);
    }
    if let TypeInner::Array { stride, .. } = module.types[g.ty].inner {
        v["stride"] = json!(stride);
    }
    v
}

/// Every struct type of the module with its size and members' offsets.
fn structs(module: &Module) -> Vec<Value> {
    module
        .types
        .iter()
        .filter_map(|(_, t)| {
            let TypeInner::Struct { members, span } = &t.inner else {
                return None;
            };
            let members: Vec<Value> = members
                .iter()
                .map(|m| json!({"name": m.name, "type": type_name(module, m.ty), "offset": m.offset}))
                .collect();
            Some(json!({"name": t.name, "size": span, "members": members}))
        })
        .collect()
}

/// The library's documented functions with their signatures (none for other entries).
fn functions(module: &Module, origin: &Origin) -> Vec<Value> {
    if origin.entry != Entry::Library {
        return Vec::new();
    }
    LIBRARY_FUNCTIONS
        .iter()
        .filter_map(|name| {
            let full = prefixed(origin.prefix, name);
            let (_, f) = module
                .functions
                .iter()
                .find(|(_, f)| f.name.as_deref() == Some(full.as_str()))?;
            let args: Vec<Value> = f
                .arguments
                .iter()
                .map(|a| json!({"name": a.name, "type": type_name(module, a.ty)}))
                .collect();
            let result = f.result.as_ref().map(|r| type_name(module, r.ty));
            let written = origin.written.and_then(|(out, _)| match out {
                Output::Text(code) => declaration(code, &full),
                Output::Binary(_) => None,
            });
            Some(json!({"name": full, "arguments": args, "result": result, "declaration": written}))
        })
        .collect()
}

/// The declaration of the function `name` as `code` spells it, up to its body, on one line:
/// `float map(metal::float3 p, constant Params& params)` in MSL, where naga passes the globals a
/// function reads as arguments. `None` when no line declares it.
pub fn declaration(code: &str, name: &str) -> Option<String> {
    let call = format!("{name}(");
    let start = code.lines().scan(0, |at, line| {
        let here = *at;
        *at += line.len() + 1;
        Some((here, line))
    });
    let (at, _) = start
        .filter(|(_, l)| !l.starts_with(char::is_whitespace) && !l.trim_end().ends_with(';'))
        .find(|(_, l)| {
            l.find(&call)
                .is_some_and(|i| i > 0 && l[..i].ends_with([' ', '&']))
        })?;
    let rest = &code[at..];
    let open = rest.find(&call)? + call.len() - 1;
    let mut depth = 0;
    let close = rest[open..].char_indices().find_map(|(i, c)| {
        depth += match c {
            '(' => 1,
            ')' => -1,
            _ => 0,
        };
        (depth == 0).then_some(open + i)
    })?;
    let end = close + rest[close..].find('{')?;
    let one_line = rest[..end].split_whitespace().collect::<Vec<_>>().join(" ");
    Some(one_line.replace("( ", "(").replace(" )", ")"))
}

/// The fragment entry's host conventions (`crate::layout::FRAGMENT_Y_UP`, `FRAGMENT_SRGB`):
/// which `View` component flips y for GL's origin and which encodes the output to sRGB.
fn fragment(entry: Entry) -> Value {
    if entry != Entry::Fragment {
        return Value::Null;
    }
    let flag = |(field, comp): (&str, usize)| json!({"field": field, "component": comp});
    json!({
        "output_location": 0,
        "y_up": flag(crate::layout::FRAGMENT_Y_UP),
        "srgb": flag(crate::layout::FRAGMENT_SRGB),
        "writes": "linear light, or sRGB-encoded (clamped to 0..1) when the srgb flag is 1",
    })
}

/// The `params` section from the module itself: its `Params` global's binding (null when it
/// is a private global, or when no function reads it, so a host binds nothing), its size and
/// fields; no fields when the module has none (an entry that uses no parameter leaves the
/// global out).
fn params_section(module: &Module, prefix: Option<&str>, fields: Vec<Value>, size: u32) -> Value {
    let name = prefixed(prefix, "Params");
    let global = module
        .global_variables
        .iter()
        .find(|(_, g)| module.types[g.ty].name.as_deref() == Some(name.as_str()));
    let Some((handle, g)) = global else {
        return json!({"struct": Value::Null, "binding": Value::Null, "size": 0, "fields": []});
    };
    let read = module
        .functions
        .iter()
        .map(|(_, f)| f)
        .chain(module.entry_points.iter().map(|e| &e.function))
        .any(|f| {
            f.expressions
                .iter()
                .any(|(_, e)| matches!(e, naga::Expression::GlobalVariable(h) if *h == handle))
        });
    let binding = match (&g.binding, read) {
        (Some(b), true) => json!({"group": b.group, "binding": b.binding}),
        _ => Value::Null,
    };
    json!({"struct": name, "binding": binding, "size": size, "fields": fields})
}

/// The `View` uniform (the camera entries'): its struct's name and binding; null when the
/// module has none (the library).
fn view_section(module: &Module, prefix: Option<&str>) -> Value {
    let name = prefixed(prefix, "View");
    module
        .global_variables
        .iter()
        .find(|(_, g)| module.types[g.ty].name.as_deref() == Some(name.as_str()))
        .and_then(|(_, g)| g.binding.as_ref())
        .map_or(
            Value::Null,
            |b| json!({"struct": name, "binding": {"group": b.group, "binding": b.binding}}),
        )
}

fn prefixed(prefix: Option<&str>, name: &str) -> String {
    match prefix {
        Some(p) => format!("{p}_{name}"),
        None => name.to_string(),
    }
}

/// A type as WGSL spells it (`vec3<f32>`, `array<u32>`, a struct's name).
fn type_name(module: &Module, ty: naga::Handle<naga::Type>) -> String {
    let t = &module.types[ty];
    let scalar = |s: naga::Scalar| match (s.kind, s.width) {
        (ScalarKind::Float, 4) => "f32",
        (ScalarKind::Uint, 4) => "u32",
        (ScalarKind::Sint, 4) => "i32",
        (ScalarKind::Bool, _) => "bool",
        _ => "?",
    };
    let size = |v: VectorSize| v as u8;
    match &t.inner {
        TypeInner::Scalar(s) => scalar(*s).into(),
        TypeInner::Vector { size: n, scalar: s } => format!("vec{}<{}>", size(*n), scalar(*s)),
        TypeInner::Matrix {
            columns,
            rows,
            scalar: s,
        } => format!("mat{}x{}<{}>", size(*columns), size(*rows), scalar(*s)),
        TypeInner::Array { base, size: n, .. } => match n {
            naga::ArraySize::Constant(k) => format!("array<{}, {k}>", type_name(module, *base)),
            _ => format!("array<{}>", type_name(module, *base)),
        },
        TypeInner::Struct { .. } => t.name.clone().unwrap_or_else(|| "struct".into()),
        TypeInner::Image {
            dim: naga::ImageDimension::D3,
            class: naga::ImageClass::Sampled { kind, .. },
            ..
        } => format!(
            "texture_3d<{}>",
            scalar(naga::Scalar {
                kind: *kind,
                width: 4
            })
        ),
        other => format!("{other:?}"),
    }
}

/// Prefixes the module's own names (functions, structs, globals, constants) with `prefix_`,
/// so that they cannot collide with a host's; entry points and struct members keep theirs.
pub fn prefix(module: &mut Module, prefix: &str) {
    let add = |name: &mut Option<String>| {
        if let Some(n) = name {
            *n = format!("{prefix}_{n}");
        }
    };
    for (_, f) in module.functions.iter_mut() {
        add(&mut f.name);
    }
    for (_, g) in module.global_variables.iter_mut() {
        add(&mut g.name);
    }
    for (_, c) in module.constants.iter_mut() {
        add(&mut c.name);
    }
    // Types are interned: rebuild the arena with the struct names changed.
    let mut types = naga::UniqueArena::new();
    for (_, t) in module.types.iter() {
        let mut t = t.clone();
        if matches!(t.inner, TypeInner::Struct { .. }) {
            add(&mut t.name);
        }
        types.insert(t, naga::Span::UNDEFINED);
    }
    module.types = types;
}

/// Whether `name` can be a `--prefix`: a letter, then letters, digits or `_`.
pub fn valid_prefix(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}
