//! No NaN or Inf reaches a colour: the library entry's `trace`, `normal`, `map_material`,
//! `shade`, `path` and `fog` called from a host compute shader that writes whether each pixel's
//! raw f32 colour is finite (the compute entry writes bytes, where a NaN would only show as a
//! wrong value), run on the GPU for every shading feature at scene scales 1e-4 to 1e4.

use crate::common::{compile, every_feature_scene, gpu};
use sdfc::gpu::{Layout, Source, TILE};
use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::scene::Scene;
use sdfc_compiler::view::View;

/// The host: the camera ray of each pixel (as the compute entry's `camera_ray`), traced and
/// shaded with the library's functions; binding 1 gets `vec2(bitcast(1.0 if not finite), hit)`,
/// the test on the bits (an exponent of all ones: NaN or Inf), which a compiler assuming no
/// NaN cannot fold away as it folds `c != c`.
/// `poison` multiplies the colour by a NaN the compiler cannot see (its bits depend on the
/// uniform), to show that the check sees one.
fn host(scene: &Scene, poison: bool) -> String {
    let (m, info) = emit::module(scene, Entry::Library, &Options::from_scene(scene)).unwrap();
    let Output::Text(lib) = emit::write(&m, &info, Target::Wgsl, Entry::Library).unwrap() else {
        unreachable!()
    };
    let has = |f: &str| lib.contains(&format!("fn {f}("));
    let path = if has("path") {
        "c = path(p, n, rd, m, h, c);"
    } else {
        ""
    };
    let fog = if has("fog") { "c = fog(c, r.t);" } else { "" };
    let poison = if poison {
        "c = c * bitcast<f32>(0x7fc00000u | (view.offset.z & 1u));"
    } else {
        ""
    };
    format!(
        "{lib}\n\
         struct HostView {{ eye: vec4<f32>, right: vec4<f32>, up: vec4<f32>, forward: vec4<f32>, size: vec4<f32>, offset: vec4<u32> }}\n\
         @group(0) @binding(0) var<uniform> view: HostView;\n\
         @group(0) @binding(1) var<storage, read_write> out: array<vec2<u32>>;\n\
         @compute @workgroup_size(8, 8)\n\
         fn main(@builtin(global_invocation_id) gid: vec3<u32>) {{\n\
           let px = gid.xy + view.offset.xy;\n\
           if (px.x >= view.offset.z || px.y >= view.offset.w) {{ return; }}\n\
           let uv = vec2<f32>(px) + vec2<f32>(view.right.w, view.up.w);\n\
           let u = 2.0 * uv.x / view.size.x - 1.0;\n\
           let v = 1.0 - 2.0 * uv.y / view.size.y;\n\
           let rd = normalize(view.forward.xyz + view.right.xyz * u + view.up.xyz * v);\n\
           let ro = view.eye.xyz;\n\
           let r = trace(ro, rd, view.size.z);\n\
           var c = vec3<f32>(0.0);\n\
           var hit = 0u;\n\
           if ((r.flags & 1u) != 0u) {{\n\
             hit = 1u;\n\
             let p = ro + rd * r.t;\n\
             let h = max(view.size.z * r.t, 1e-6);\n\
             let n = normal(p, h);\n\
             let m = map_material(p);\n\
             c = shade(p, n, rd, m, h);\n\
             {path}\n\
             {fog}\n\
             {poison}\n\
           }}\n\
           let bits = bitcast<vec3<u32>>(c) & vec3<u32>(0x7f800000u);\n\
           let bad = any(bits == vec3<u32>(0x7f800000u));\n\
           out[px.y * view.offset.z + px.x] = vec2<u32>(bitcast<u32>(select(0.0, 1.0, bad)), hit << 31u);\n\
         }}\n"
    )
}

/// (pixels whose colour is not finite, hit pixels) of `scene` through the host shader.
fn run(gpu: &sdfc::gpu::Gpu, scene: &Scene, poison: bool) -> (usize, usize) {
    let text = host(scene, poison);
    // This scene has all of them: none may be skipped for want of its function.
    for f in [
        "map_material",
        "path",
        "fog",
        "map_blend",
        "map_texture",
        "shadow",
        "occlusion",
    ] {
        assert!(
            text.contains(&format!("fn {f}(")),
            "the library has no `{f}`"
        );
    }
    let view = View::new(&scene.camera, 64, 40);
    let prepared = gpu
        .prepare(
            Source::Wgsl(&text, "host.wgsl"),
            Layout::TraceOnly { passes: false },
            &view,
            None,
            TILE,
        )
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    prepared.run_tiles(|_, _| {}).unwrap();
    let rays = prepared.rays().unwrap();
    (
        rays.iter().filter(|r| r.t != 0.0).count(),
        rays.iter().filter(|r| r.hit).count(),
    )
}

#[test]
fn no_colour_is_nan_or_infinite_at_any_scale() {
    let gpu = gpu();
    let mut report = String::new();
    for s in [1e-4, 1e-2, 1.0, 1e2, 1e4] {
        let materials = format!(
            "material stone {{ color marble(#fff, #345, {}) }}\nmaterial red {{ color #d03020 }}",
            0.5 * s
        );
        let shapes = "smooth_union(0.4) { sphere(1) at (0, 1, 0) : stone  box(0.8) at (0.9, 0.4, 0) : red }\n\
                      torus(0.8, 0.2) at (-2, 0.2, 0.5)\n\
                      plane(y, 0)";
        let scene = compile(&every_feature_scene(s, &materials, shapes));
        let (bad, hits) = run(&gpu, &scene, false);
        report += &format!("× {s:e}: {bad} non-finite colours of {hits} hits\n");
        assert!(hits > 500, "× {s:e}: only {hits} hits\n{report}");
        assert_eq!(bad, 0, "× {s:e}\n{report}");
        // The check sees a NaN when there is one.
        let (poisoned, _) = run(&gpu, &scene, true);
        assert!(
            poisoned >= hits / 2,
            "× {s:e}: the poisoned shader shows only {poisoned}"
        );
    }
    println!("{report}");
}
