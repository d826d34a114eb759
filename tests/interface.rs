//! What hosts rely on (docs/interface.md): the manifest describes the module it came with
//! (bindings, uniform layouts, parameters, functions), `--prefix` keeps two scenes' libraries
//! apart in one shader, and the manifest's format is snapshotted.

use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::manifest::{self, Origin};
use sdfc_compiler::scene::Scene;

fn compiled(scene: &Scene, entry: Entry, prefix: Option<&str>) -> (naga::Module, String) {
    compiled_with(scene, entry, prefix, &Options::from_scene(scene))
}

fn compiled_with(
    scene: &Scene,
    entry: Entry,
    prefix: Option<&str>,
    options: &Options,
) -> (naga::Module, String) {
    let (mut m, _) = emit::module(scene, entry, options).unwrap();
    if let Some(p) = prefix {
        manifest::prefix(&mut m, p);
    }
    let info = emit::validate(&m).unwrap_or_else(|e| panic!("{}", e.0));
    let Output::Text(text) = emit::write(&m, &info, Target::Wgsl, entry).unwrap() else {
        unreachable!()
    };
    (m, text)
}

fn describe(
    scene: &Scene,
    m: &naga::Module,
    entry: Entry,
    prefix: Option<&str>,
) -> serde_json::Value {
    let info = emit::validate(m).unwrap_or_else(|e| panic!("{}", e.0));
    let settings = emit::Settings::default();
    let (code, reflection) =
        emit::write_reflected(m, &info, Target::Wgsl, entry, &settings).unwrap();
    let origin = Origin {
        volume_files: &[],
        data: None,
        scene: "scene.sdf",
        target: "wgsl",
        entry,
        prefix,
        written: Some((&code, &reflection)),
    };
    manifest::manifest(scene, m, &origin)
}

/// For every example and entry: each binding the manifest lists is declared in the WGSL with
/// that group, binding, address space and type, and the WGSL declares no other; each struct's
/// members and offsets are the module's; the parameters' offsets are the `Params` struct's.
#[test]
fn the_manifest_describes_the_module() {
    let mut checked = 0;
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        for entry in [Entry::Compute, Entry::Fragment, Entry::Library] {
            let (m, wgsl) = compiled(&scene, entry, None);
            let d = describe(&scene, &m, entry, None);
            let name = format!("{} ({entry:?})", path.display());
            let bindings = d["bindings"].as_array().unwrap();
            for b in bindings {
                // A handle (a baked volume's texture) is declared without an address space.
                let space = match b["space"].as_str().unwrap() {
                    "handle" => String::new(),
                    s => format!(
                        "<{s}{}>",
                        b.get("access")
                            .map_or(String::new(), |a| format!(", {}", a.as_str().unwrap()))
                    ),
                };
                let decl = format!(
                    "@group({}) @binding({}) \nvar{space} {}: {};",
                    b["group"],
                    b["binding"],
                    b["name"].as_str().unwrap(),
                    b["type"].as_str().unwrap()
                );
                assert!(wgsl.contains(&decl), "{name}: `{decl}` not in the WGSL");
            }
            assert_eq!(
                wgsl.matches("@binding(").count(),
                bindings.len(),
                "{name}: the WGSL has bindings the manifest does not list"
            );
            for s in d["structs"].as_array().unwrap() {
                let (_, t) = m
                    .types
                    .iter()
                    .find(|(_, t)| t.name.as_deref() == s["name"].as_str())
                    .unwrap();
                let naga::TypeInner::Struct { members, span } = &t.inner else {
                    panic!("{name}: not a struct")
                };
                assert_eq!(s["size"], *span, "{name}");
                for (a, b) in members.iter().zip(s["members"].as_array().unwrap()) {
                    assert_eq!(b["name"].as_str(), a.name.as_deref(), "{name}");
                    assert_eq!(b["offset"], a.offset, "{name}");
                }
                assert!(wgsl.contains(&format!("struct {} {{", s["name"].as_str().unwrap())));
            }
            let fields = d["params"]["fields"].as_array().unwrap();
            assert_eq!(fields.len(), scene.params.len(), "{name}");
            if !fields.is_empty() {
                let s = d["structs"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .find(|s| s["name"] == "Params")
                    .unwrap_or_else(|| panic!("{name}: no Params struct"));
                for (f, member) in fields.iter().zip(s["members"].as_array().unwrap()) {
                    assert_eq!(f["member"], member["name"], "{name}");
                    assert_eq!(f["offset"], member["offset"], "{name}");
                    assert_eq!(f["type"], member["type"], "{name}");
                }
                assert_eq!(d["params"]["size"], s["size"], "{name}");
            }
            if entry == Entry::Library {
                let functions = d["functions"].as_array().unwrap();
                assert_eq!(
                    functions.len(),
                    manifest::LIBRARY_FUNCTIONS.len(),
                    "{name}: every documented function is there"
                );
                let described = &d["materials"].as_array().unwrap()[1..];
                for (mat, m) in scene.materials.iter().zip(described) {
                    let c = format!(
                        "const {}: u32 = {}u;",
                        m["constant"].as_str().unwrap(),
                        m["id"]
                    );
                    assert!(wgsl.contains(&c), "{name}: no `{c}` for `{}`", mat.name);
                }
            }
            checked += 1;
        }
    }
    assert!(checked >= 30, "{checked}");
}

/// Two scenes' libraries, each with its own `--prefix` and the second's parameters at another
/// binding (`--params-binding 10`), in one host shader: they parse and validate together
/// (nothing collides), and no name of either is left unprefixed.
#[test]
fn prefixed_libraries_live_side_by_side() {
    let root = sdfc_tests::root();
    let a = sdfc_tests::example(&root.join("examples/lamp.sdf"));
    let b = sdfc_compiler::check::compile(
        "param tint = #c04030\nparam size = 1 in 0.5..2\nmaterial red { color tint }\nsphere(size) : red\n",
    )
    .scene
    .unwrap();
    let mut options = Options::from_scene(&b);
    options.params_binding = 10;
    let (_, la) = compiled(&a, Entry::Library, Some("lamp"));
    let (mb, lb) = compiled_with(&b, Entry::Library, Some("ball"), &options);
    let described = describe(&b, &mb, Entry::Library, Some("ball"));
    assert_eq!(described["params"]["binding"]["binding"], 10);
    for (lib, p) in [(&la, "lamp"), (&lb, "ball")] {
        for line in lib.lines() {
            for head in ["fn ", "struct ", "const ", "var<"] {
                if let Some(rest) = line.strip_prefix(head) {
                    let rest = match head {
                        "var<" => rest.split_once("> ").map_or(rest, |(_, r)| r),
                        _ => rest,
                    };
                    assert!(rest.starts_with(&format!("{p}_")), "unprefixed: `{line}`");
                }
            }
        }
    }
    let host = format!(
        "{la}\n{lb}\n@group(1) @binding(0) var<storage, read_write> out: array<vec4<f32>>;\n\
         @compute @workgroup_size(1)\nfn main() {{\n\
         let ro = vec3<f32>(0.0, 1.0, -5.0);\n  let rd = vec3<f32>(0.0, 0.0, 1.0);\n\
         out[0] = lamp_color(ro, rd, 0.001) + ball_color(ro, rd, 0.001);\n\
         out[1] = vec4<f32>(f32(lamp_MATERIAL_brass + ball_MATERIAL_red), lamp_params.height, ball_params.size, 0.0);\n}}\n"
    );
    let module = naga::front::wgsl::parse_str(&host)
        .unwrap_or_else(|e| panic!("does not parse:\n{}", e.emit_to_string(&host)));
    emit::validate(&module).unwrap_or_else(|e| panic!("{}", e.0));
}

/// The parametric example's manifest (library, prefixed) and its WGSL, read and kept.
#[test]
fn parametric_example_snapshots() {
    let scene = sdfc_tests::example(&sdfc_tests::root().join("examples/lamp.sdf"));
    let (m, wgsl) = compiled(&scene, Entry::Library, Some("lamp"));
    let d = describe(&scene, &m, Entry::Library, Some("lamp"));
    insta::assert_snapshot!("lamp_manifest", serde_json::to_string_pretty(&d).unwrap());
    insta::assert_snapshot!("lamp_library_wgsl", wgsl);
}

/// Every back end's library has every documented function, for every example: naga's GLSL
/// back end writes only what an entry point uses, so the placeholder `main` must use the
/// `Params` uniform, or the library of a scene with parameters loses its functions.
#[test]
fn every_target_library_has_every_function() {
    use sdfc_compiler::emit::{GlslVersion, Settings};
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        let (m, info) = emit::module(&scene, Entry::Library, &Options::from_scene(&scene)).unwrap();
        let targets = [
            (Target::Wgsl, GlslVersion::Core450),
            (Target::Glsl, GlslVersion::Core450),
            (Target::Glsl, GlslVersion::Es300),
            (Target::Msl, GlslVersion::Core450),
            (Target::Hlsl, GlslVersion::Core450),
        ];
        for (target, glsl_version) in targets {
            let settings = Settings {
                glsl_version,
                ..Settings::default()
            };
            let Output::Text(text) =
                emit::write_with(&m, &info, target, Entry::Library, &settings).unwrap()
            else {
                unreachable!()
            };
            for f in manifest::LIBRARY_FUNCTIONS {
                let defined = text.lines().any(|l| {
                    !l.starts_with(' ') && l.contains(&format!(" {f}("))
                        || l.starts_with(&format!("fn {f}("))
                });
                assert!(
                    defined,
                    "{} {target:?} {glsl_version:?}: no `{f}`",
                    path.display()
                );
            }
        }
    }
}

/// `--entry shadertoy` for every example: no `#version`, precision, `main` or uniform of its own
/// (Shadertoy supplies those), one `mainImage`, and it compiles as GLSL ES 3.00 inside
/// Shadertoy's prelude (`iResolution`, `iTime`, `iMouse`) and `main`.
#[test]
fn every_example_pastes_into_shadertoy() {
    let glslang = sdfc_tests::have("glslangValidator");
    let dir = sdfc_tests::tempdir();
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        // A baked part is a 3D texture Shadertoy has no input for (`sdfc emit` refuses it:
        // runtime's `cli::emit_refuses_what_a_host_cannot_bind`).
        if !scene.volumes().is_empty() {
            continue;
        }
        let toy = sdfc_compiler::shadertoy::shader(&scene, &Options::from_scene(&scene)).unwrap();
        let name = path.display();
        for banned in ["#version", "precision ", "void main(", "uniform "] {
            assert!(
                !toy.contains(banned),
                "{name}: `{banned}` in the Shadertoy shader"
            );
        }
        assert_eq!(toy.matches("void mainImage(").count(), 1, "{name}");
        assert!(toy.contains("vec4 color("), "{name}: no `color`");
        if scene.params.iter().any(|p| p.name == "time") {
            assert!(toy.contains("iTime"), "{name}: `time` is not `iTime`");
        }
        if glslang {
            let stem = path.file_stem().unwrap().to_string_lossy();
            let f = dir.join(format!("{stem}-shadertoy.frag"));
            let harness = format!(
                "#version 300 es\nprecision highp float;\nprecision highp int;\n\
                 uniform vec3 iResolution;\nuniform float iTime;\nuniform vec4 iMouse;\n\
                 out vec4 shadertoy_color;\n{toy}\n\
                 void main() {{ mainImage(shadertoy_color, gl_FragCoord.xy); }}\n"
            );
            std::fs::write(&f, harness).unwrap();
            sdfc_tests::run_tool("glslangValidator", &[], &f, &format!("{name} (Shadertoy)"));
        }
    }
}

/// The Shadertoy shader kept in `examples/hosts/shadertoy/lamp.glsl` is what `sdfc emit
/// examples/lamp.sdf --entry shadertoy` writes today (regenerate it with that command).
#[test]
fn the_kept_shadertoy_shader_is_current() {
    let root = sdfc_tests::root();
    let scene = sdfc_tests::example(&root.join("examples/lamp.sdf"));
    let now = sdfc_compiler::shadertoy::shader(&scene, &Options::from_scene(&scene)).unwrap();
    let kept = std::fs::read_to_string(root.join("examples/hosts/shadertoy/lamp.glsl")).unwrap();
    assert!(
        kept == now,
        "examples/hosts/shadertoy/lamp.glsl is stale: sdfc emit examples/lamp.sdf --entry shadertoy -o examples/hosts/shadertoy/lamp.glsl"
    );
}
