//! Emitted code: snapshots of every example's WGSL and GLSL, every example × target × entry
//! validated by naga and by the external validators, "only what the scene requires", and the
//! library output used from a host shader.

use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::scene::Scene;
use sdfc_tests::{have, run_tool, tempdir};

const TARGETS: [Target; 5] = [
    Target::Wgsl,
    Target::Spirv,
    Target::Glsl,
    Target::Msl,
    Target::Hlsl,
];
const ENTRIES: [Entry; 3] = [Entry::Compute, Entry::Fragment, Entry::Library];

fn emit(scene: &Scene, target: Target, entry: Entry) -> Output {
    emit_passes(scene, target, entry, false)
}

/// Emits with the multi-resolution passes compiled in, or not.
fn emit_passes(scene: &Scene, target: Target, entry: Entry, passes: bool) -> Output {
    let mut options = Options::from_scene(scene);
    options.passes = passes;
    let (m, info) = emit::module(scene, entry, &options).unwrap_or_else(|e| panic!("{}", e.0));
    emit::write(&m, &info, target, entry).unwrap_or_else(|e| panic!("{}", e.0))
}

fn text(scene: &Scene, target: Target, entry: Entry) -> String {
    match emit(scene, target, entry) {
        Output::Text(s) => s,
        Output::Binary(_) => unreachable!("text target"),
    }
}

#[test]
fn example_snapshots() {
    insta::glob!("..", "examples/*.sdf", |path| {
        let scene = sdfc_tests::example(path);
        insta::assert_snapshot!("wgsl", text(&scene, Target::Wgsl, Entry::Compute));
        insta::assert_snapshot!("glsl", text(&scene, Target::Glsl, Entry::Compute));
    });
}

/// The compute entry with multi-resolution passes (Bálint §4): the `handoff` field of the
/// view, the two hand-over buffers, the trace continuing from the previous pass's t with the
/// pass's budget and cone.
#[test]
fn passes_snapshot() {
    let scene = sdfc_tests::example(
        &sdfc_tests::examples()
            .into_iter()
            .find(|p| p.ends_with("village.sdf"))
            .unwrap(),
    );
    match emit_passes(&scene, Target::Wgsl, Entry::Compute, true) {
        Output::Text(s) => insta::assert_snapshot!("village_passes_wgsl", s),
        Output::Binary(_) => unreachable!(),
    }
}

#[test]
fn every_example_target_and_entry_validates() {
    let dir = tempdir();
    let (spirv_val, glslang) = (have("spirv-val"), have("glslangValidator"));
    let mut checked = 0;
    let mut tally = [0; 4];
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let combinations = ENTRIES
            .iter()
            .map(|&e| (e, false))
            .chain([(Entry::Compute, true)]);
        for (entry, passes) in combinations {
            for target in TARGETS {
                let what = format!("{stem} {target:?} {entry:?} passes {passes}");
                let out = emit_passes(&scene, target, entry, passes);
                checked += 1;
                let stage = if entry == Entry::Fragment {
                    "frag"
                } else {
                    "comp"
                };
                match (target, out) {
                    (Target::Spirv, Output::Binary(words)) if spirv_val => {
                        let f = dir.join(format!("{stem}-{entry:?}-{passes}.spv"));
                        sdfc_tests::write_spirv(&f, &words);
                        run_tool("spirv-val", &["--target-env", "vulkan1.1"], &f, &what);
                        tally[0] += 1;
                    }
                    (Target::Glsl, Output::Text(s)) if glslang => {
                        let f = dir.join(format!("{stem}-{entry:?}-{passes}.{stage}"));
                        std::fs::write(&f, s).unwrap();
                        run_tool("glslangValidator", &["-V", "-o", "/dev/null"], &f, &what);
                        tally[1] += 1;
                    }
                    (Target::Hlsl, Output::Text(s)) if glslang && entry != Entry::Library => {
                        let f = dir.join(format!("{stem}-{entry:?}-{passes}.hlsl"));
                        std::fs::write(&f, s).unwrap();
                        run_tool(
                            "glslangValidator",
                            &["-D", "-e", "main", "-S", stage, "-V", "-o", "/dev/null"],
                            &f,
                            &what,
                        );
                        tally[2] += 1;
                    }
                    // No MSL validator runs on Linux; at least every resource has a real slot
                    // (naga's `fake_missing_bindings` writes invalid MSL).
                    (Target::Msl, Output::Text(s)) => {
                        assert!(
                            !s.contains("fake") && !s.contains("[[user("),
                            "{what}: a fake binding"
                        );
                        if entry != Entry::Library {
                            assert!(s.contains("[[buffer(0)]]"), "{what}: no view at buffer 0");
                        }
                        tally[3] += 1;
                    }
                    _ => {}
                }
            }
        }
    }
    let tools = [
        "spirv-val (vulkan1.1), SPIR-V",
        "glslangValidator, GLSL 4.50",
        "glslangValidator's HLSL front end, HLSL",
        "slots only (no Metal compiler here), MSL",
    ];
    for (tool, n) in tools.iter().zip(tally) {
        sdfc_tests::report(&format!(
            "{tool}: {n} modules of every example x entry, 0 refused"
        ));
    }
    assert!(checked >= 150, "only {checked} combinations");
}

fn functions(wgsl: &str) -> Vec<String> {
    wgsl.lines()
        .filter_map(|l| l.strip_prefix("fn "))
        .map(|l| l.split('(').next().unwrap().to_string())
        .collect()
}

#[test]
fn only_what_the_scene_requires() {
    let one = sdfc_tests::scene("sphere", "sphere(1)");
    let wgsl = text(&one, Target::Wgsl, Entry::Compute);
    // The specular highlight is `pow(…, 32f)` (the shininess); the compute entry's sRGB
    // encoding has its own `pow` and is always there.
    for absent in ["sd_box", "map_material", "op_", "32f)", "shadow"] {
        assert!(
            !wgsl.contains(absent),
            "a sphere-only scene emits `{absent}`:\n{wgsl}"
        );
    }
    let two = sdfc_tests::scene("sphere and box", "union { sphere(1) box(1) }");
    let wgsl2 = text(&two, Target::Wgsl, Entry::Compute);
    let (f1, f2) = (functions(&wgsl), functions(&wgsl2));
    let added: Vec<&String> = f2.iter().filter(|f| !f1.contains(f)).collect();
    assert_eq!(added, ["sd_box"], "adding a box added {added:?}");
    assert!(f1.iter().all(|f| f2.contains(f)));
    // A material adds `map_material`; a specular one adds the highlight.
    let mat = sdfc_tests::scene("m", "material red { color #f00 }\nsphere(1) : red");
    let wgsl = text(&mat, Target::Wgsl, Entry::Compute);
    assert!(wgsl.contains("fn map_material") && !wgsl.contains("32f)"));
    let spec = sdfc_tests::scene(
        "s",
        "material red { color #f00 specular 0.5 }\nsphere(1) : red",
    );
    assert!(text(&spec, Target::Wgsl, Entry::Compute).contains("32f)"));
    // Constants are folded: the step budget appears as a literal, not a uniform.
    let steps = sdfc_tests::scene("t", "trace basic { steps 77 }\nsphere(1)");
    assert!(text(&steps, Target::Wgsl, Entry::Compute).contains(">= 77u"));
}

/// Shadows, occlusion, fog, mirrors and transparent solids, patterns and a material blend each
/// add their own
/// functions and nothing else (no function of the plain scene goes); a scene without them has none of them (issue 17: each feature
/// emitted only when used).
#[test]
fn each_shading_feature_adds_only_its_function() {
    let base = "material m { color #fff }\nlight { direction (0, 1, 0) }\n\
                union { sphere(1) : m  plane(y, -1) }";
    let plain = text(
        &sdfc_tests::scene("plain", base),
        Target::Wgsl,
        Entry::Compute,
    );
    for absent in [
        "shadow",
        "occlusion",
        "fog",
        "march",
        "path",
        "refract",
        "reflect",
        "texture",
        "noise",
    ] {
        assert!(!plain.contains(absent), "the plain scene emits `{absent}`");
    }
    let light = "light { direction (0, 1, 0) }";
    let material = "material m { color #fff }";
    let cases: [(&str, &str, &[&str]); 9] = [
        (
            light,
            "light { direction (0, 1, 0)  shadow hard }",
            &["shadow"],
        ),
        (
            light,
            "light { direction (0, 1, 0)  shadow soft }",
            &["shadow"],
        ),
        (
            light,
            "occlusion { samples 4 }\nlight { direction (0, 1, 0) }",
            &["occlusion"],
        ),
        (
            light,
            "fog { density 0.1 }\nlight { direction (0, 1, 0) }",
            &["fog"],
        ),
        (
            material,
            "material m { color #fff  reflect 0.5 }",
            &["march", "path"],
        ),
        (
            material,
            "material m { color #fff  transparent 0.5  ior 1.3 }",
            &["march", "path"],
        ),
        (
            material,
            "material m { color checker(#fff, #000) }",
            &["map_texture"],
        ),
        (
            material,
            "material m { color marble(#fff, #000) }",
            &["map_texture", "lattice_hash", "value_noise"],
        ),
        // (A smooth union also brings its blend function and, its field not being a distance
        // everywhere, the tracer's `map_loose`.)
        (
            "union {",
            "smooth_union(0.2) {",
            &["op_smooth_union", "map_loose", "map_blend"],
        ),
    ];
    for (from, to, expected) in cases {
        let source = base.replacen(from, to, 1);
        let wgsl = text(
            &sdfc_tests::scene(to, &source),
            Target::Wgsl,
            Entry::Compute,
        );
        let (f1, f2) = (functions(&plain), functions(&wgsl));
        let added: Vec<&String> = f2.iter().filter(|f| !f1.contains(f)).collect();
        assert_eq!(added, expected, "`{to}` added {added:?}");
        assert!(
            f1.iter().all(|f| f2.contains(f)),
            "`{to}` removed a function"
        );
    }
}

/// The library's documented interface (docs/interface.md), the same signatures whatever the
/// scene's settings: a host shader calling every function parses and validates, for every
/// example.
#[test]
fn library_output_is_usable_from_a_host_shader() {
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        let lib = text(&scene, Target::Wgsl, Entry::Library);
        let host = format!(
            "{lib}\n@group(0) @binding(0) var<storage, read_write> result: array<vec4<f32>>;\n\
             @compute @workgroup_size(1)\nfn host_main(@builtin(global_invocation_id) id: vec3<u32>) {{\n\
             let ro = vec3<f32>(0.0, 1.0, -5.0);\n  let rd = normalize(vec3<f32>(0.0, -0.1, 1.0));\n\
             let r: TraceResult = trace(ro, rd, 0.001);\n  let p = ro + rd * r.t;\n\
             let n: vec3<f32> = normal(p, 0.001);\n  let m: u32 = map_material(p);\n\
             let s: vec3<f32> = shade(p, n, rd, m, 0.001);\n  let c: vec4<f32> = color(ro, rd, 0.001);\n\
             let hit = (r.flags & 1u) != 0u;\n\
             result[id.x] = vec4<f32>(s + c.rgb, map(ro) + f32(r.steps) + select(0.0, 1.0, hit));\n}}\n"
        );
        let module = naga::front::wgsl::parse_str(&host).unwrap_or_else(|e| {
            panic!(
                "{}: host shader does not parse:\n{}",
                path.display(),
                e.emit_to_string(&host)
            )
        });
        emit::validate(&module).unwrap_or_else(|e| panic!("{}: {}", path.display(), e.0));
    }
}

/// User names never reach a target as they are: `let` shapes become `let_<name>`, so names that
/// are reserved words of a target (`sampler2D` in HLSL, `float4`, `kernel` in MSL, `main`) cannot
/// leak into its output.
#[test]
fn let_names_cannot_collide_with_reserved_words() {
    use sdfc_compiler::emit::{self, Output, Target};
    use sdfc_compiler::lower::{Entry, tracer::Options};
    let source = "let sampler2D = sphere(1)\nlet kernel = box(0.5)\nlet main = torus(1, 0.2)\nunion { sampler2D  kernel at (2, 0, 0)  main at (-2, 0, 0) }\n";
    let scene = sdfc_tests::scene("reserved", source);
    let (module, info) =
        emit::module(&scene, Entry::Library, &Options::from_scene(&scene)).unwrap();
    for target in [Target::Hlsl, Target::Msl, Target::Glsl, Target::Wgsl] {
        let Ok(Output::Text(text)) = emit::write(&module, &info, target, Entry::Library) else {
            continue;
        };
        for name in ["sampler2D", "kernel"] {
            assert!(
                !text.contains(&format!(" {name}(")),
                "{target:?} output declares or calls `{name}` bare"
            );
        }
        // (GLSL's own `main` is the back end's; the scene's is `let_main`.)
        assert!(text.contains("let_main"), "{target:?}: no `let_main`");
    }
}

/// `--spirv-version`: every example, every entry, SPIR-V 1.0 (Vulkan 1.0; storage buffers by
/// SPV_KHR_storage_buffer_storage_class), 1.3 (Vulkan 1.1), 1.5 (Vulkan 1.2) and 1.6 (Vulkan
/// 1.3), each through
/// `spirv-val` for the matching environment.
#[test]
fn every_spirv_version_validates_for_its_vulkan() {
    if !have("spirv-val") {
        eprintln!("spirv-val is not installed: skipped (CI installs it)");
        return;
    }
    let dir = tempdir();
    let mut checked = 0;
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        for entry in ENTRIES {
            let (module, info) = emit::module(&scene, entry, &Options::from_scene(&scene)).unwrap();
            for (version, env) in [
                ((1, 0), "vulkan1.0"),
                ((1, 3), "vulkan1.1"),
                ((1, 5), "vulkan1.2"),
                ((1, 6), "vulkan1.3"),
            ] {
                let settings = emit::Settings {
                    spirv_version: version,
                    ..Default::default()
                };
                let Ok(Output::Binary(words)) =
                    emit::write_with(&module, &info, Target::Spirv, entry, &settings)
                else {
                    panic!("{stem} {entry:?}: no SPIR-V {version:?}");
                };
                assert_eq!(
                    words[1] >> 8 & 0xffff,
                    (version.0 as u32) << 8 | version.1 as u32
                );
                let f = dir.join(format!("{stem}-{entry:?}-{}{}.spv", version.0, version.1));
                sdfc_tests::write_spirv(&f, &words);
                run_tool(
                    "spirv-val",
                    &["--target-env", env],
                    &f,
                    &format!("{stem} {entry:?} {version:?}"),
                );
                checked += 1;
            }
        }
    }
    sdfc_tests::report(&format!(
        "spirv-val, SPIR-V 1.0/1.3/1.5/1.6 for vulkan1.0/1.1/1.2/1.3: {checked} modules, 0 refused"
    ));
    assert!(checked >= 100, "only {checked}");
}

/// `map` with bounding volumes (`--bvh`) and the trace-only entry `sdfc bench` times, on the
/// composition: each group of parts behind `if (|max(|p − c| − h, 0)|² <= max(d, 0)²)`, the
/// ground plane first; the entry writes `vec2<u32>(bitcast(t), steps | hit << 31)`.
#[test]
fn bounding_volumes_and_trace_only_snapshot() {
    let scene = sdfc_tests::example(
        &sdfc_tests::examples()
            .into_iter()
            .find(|p| p.ends_with("composition.sdf"))
            .unwrap(),
    );
    let mut options = Options::from_scene(&scene);
    options.bounding_volumes = sdfc_compiler::lower::tracer::BoundingVolumes::All;
    let (m, info) =
        emit::module(&scene, Entry::Trace, &options).unwrap_or_else(|e| panic!("{}", e.0));
    match emit::write(&m, &info, Target::Wgsl, Entry::Trace).unwrap_or_else(|e| panic!("{}", e.0)) {
        Output::Text(s) => insta::assert_snapshot!("composition_bvh_trace_wgsl", s),
        Output::Binary(_) => unreachable!(),
    }
}

/// `--glsl-version`: every example's fragment and library entries as GLSL ES 3.00 (WebGL 2)
/// and its compute, fragment and library entries as GLSL ES 3.10 pass `glslangValidator` in
/// the matching stage and profile (its `#version` line).
#[test]
fn every_example_validates_as_glsl_es() {
    if !have("glslangValidator") {
        eprintln!("glslangValidator is not installed: skipped (CI installs it)");
        return;
    }
    let dir = tempdir();
    let mut checked = 0;
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let versions = [
            (emit::GlslVersion::Es310, "310es", &ENTRIES[..]),
            (
                emit::GlslVersion::Es300,
                "300es",
                &[Entry::Fragment, Entry::Library][..],
            ),
        ];
        for (version, name, entries) in versions {
            for &entry in entries {
                let (m, info) = emit::module(&scene, entry, &Options::from_scene(&scene))
                    .unwrap_or_else(|e| panic!("{}", e.0));
                let settings = emit::Settings {
                    glsl_version: version,
                    ..Default::default()
                };
                let Output::Text(s) = emit::write_with(&m, &info, Target::Glsl, entry, &settings)
                    .unwrap_or_else(|e| panic!("{stem} {name} {entry:?}: {}", e.0))
                else {
                    unreachable!()
                };
                assert!(s.starts_with(&format!("#version {} es", &name[..3])));
                let fragment = entry == Entry::Fragment || version == emit::GlslVersion::Es300;
                let ext = if fragment { "frag" } else { "comp" };
                let f = dir.join(format!("{stem}-{name}-{entry:?}.{ext}"));
                std::fs::write(&f, s).unwrap();
                run_tool(
                    "glslangValidator",
                    &[],
                    &f,
                    &format!("{stem} {name} {entry:?}"),
                );
                checked += 1;
            }
        }
    }
    sdfc_tests::report(&format!(
        "glslangValidator, GLSL ES 3.00 and 3.10: {checked} modules, 0 refused"
    ));
    assert!(checked >= 60, "only {checked}");
}
