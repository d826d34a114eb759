//! The data form (`--form data`, issue 33) draws what the inline form (without box trees)
//! draws: hit masks, depths (within a hundredth) and materials equal on all but a few pixels
//! in a thousand, colours within 2 levels on all but a few in a hundred —
//! for many smoothly blended balls on a plane, a hard union with materials, materials blended through nested smooth unions, and cuts.

use crate::common::{compile, gpu, report};
use sdfc_compiler::emit;
use sdfc_compiler::lower::Entry;
use sdfc_compiler::lower::tracer::{Form, Options};
use sdfc_compiler::view::View;

/// `n` balls in the unit box (a fixed sequence), as lines of a union.
pub(crate) fn balls(n: usize, materials: bool) -> String {
    balls_from(0x9e37_79b9, n, materials)
}

/// [`balls`] from another seed (another sequence).
fn balls_from(seed: u64, n: usize, materials: bool) -> String {
    let mut x: u64 = seed;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x % 10_000) as f64 / 5_000.0 - 1.0
    };
    (0..n)
        .map(|i| {
            let (a, b, c, r) = (next(), next(), next(), 0.04 + 0.02 * next());
            let tag = if materials {
                [" : red", " : blue", ""][i % 3]
            } else {
                ""
            };
            format!("sphere({r:.3}) at ({a:.3}, {b:.3}, {c:.3}){tag}")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_data_form_draws_what_the_inline_form_draws() {
    let scenes = [
        ("300 smooth balls on a plane", format!("camera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nsmooth_union(0.03) {{\n{}\n}}\nplane(y, -1.2)", balls(300, false))),
        ("200 balls with materials", format!("material red {{ color #d04038 }}\nmaterial blue {{ color #3050d0 }}\ncamera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nunion {{\n{}\n}}", balls(200, true))),
        // Materials blended through nested smooth unions (the evaluator's stack, a group's own
        // material for its untagged balls, the ground's): `map_blend` from the data.
        ("nested blends of materials", format!("material red {{ color #d04038 }}\nmaterial blue {{ color #3050d0 }}\nmaterial gold {{ color #d0a038 }}\ncamera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nsmooth_union(0.2) {{\nsmooth_union(0.15) {{\n{}\n}}\nsmooth_union(0.15) {{\n{}\n}} : gold\nplane(y, -1.1) : blue\n}}", balls_from(1, 60, true), balls_from(0x0123_4567, 60, true))),
        ("cuts", "material red { color #d04038 }\ncamera { eye (2, 2, -4)  target (0, 0, 0) }\nsubtract {\n  box((1.6, 1.2, 1.4)) : red\n  sphere(0.8) at (0.5, 0.4, 0)\n  smooth_intersect(0.1) { sphere(0.7) at (-0.6, 0, 0)  box((0.8, 0.8, 3)) |> rotate(y, 30deg) }\n}\nplane(y, -0.6)".to_string()),
    ];
    let gpu = gpu();
    let mut said = Vec::new();
    for (name, source) in &scenes {
        let scene = compile(source);
        let view = View::new(&scene.camera, 160, 90);
        let draw = |form: Form| {
            // (Inline without the unions' box trees: those return a box's distance far from
            // the parts, a different bound there than the whole field the data form gives.)
            let options = Options {
                form,
                bounding_volumes: sdfc_compiler::lower::tracer::BoundingVolumes::Off,
                ..Options::from_scene(&scene)
            };
            let (module, _) = emit::module(&scene, Entry::Compute, &options)
                .unwrap_or_else(|e| panic!("{name}: {}", e.0));
            gpu.set_scene(&scene);
            let data = (form == Form::Data).then(|| {
                let (tree, layout) =
                    sdfc_compiler::tape::data::layout(&scene, None).expect("a data form");
                sdfc_compiler::tape::data::data(&scene, &tree, &layout).expect("its buffers")
            });
            gpu.set_tape(data.as_ref()).unwrap();
            (gpu.render(&module, &view, None, |_, _| {}).unwrap(), data)
        };
        let (inline, _) = draw(Form::Inline);
        let (data, buffers) = draw(Form::Data);
        gpu.set_tape(None).unwrap();
        let pixels = inline.color.len();
        let mut masks = 0;
        let mut deep = 0;
        let mut colours = 0;
        let mut materials = 0;
        for i in 0..pixels {
            let (a, b) = (inline.depth[i], data.depth[i]);
            if (a < 0.0) != (b < 0.0) {
                masks += 1;
            } else if a >= 0.0 && (a - b).abs() > 0.01 * a.max(1.0) {
                deep += 1;
            }
            let (ca, cb) = (inline.color[i].to_le_bytes(), data.color[i].to_le_bytes());
            if (0..3).any(|k| ca[k].abs_diff(cb[k]) > 2) {
                colours += 1;
            }
            materials += usize::from(inline.material[i] != data.material[i]);
        }
        // Outside its grid the data form steps by the distance to the grid's box, and in a cell
        // far from every surface by the cell's clearance (bounds, not the field), so a ray
        // arrives by other steps and stops where its field first drops below ε: within ε of
        // the inline hit. Where that moves the hit across a small ball's rim or a crease, the
        // normal and so the colour differ (about 1.5% of the pixels of 200 small balls); hit
        // masks, depths and materials agree but for a few pixels in a thousand (the cuts'
        // creases: 29 materials of 14 400, as measured).
        let most = pixels / 400;
        assert!(
            masks <= most && deep <= most && colours <= pixels / 40 && materials <= most,
            "{name}: of {pixels} pixels {masks} hit masks, {deep} depths, {colours} colours, {materials} materials differ"
        );
        let b = buffers.expect("buffers");
        said.push(format!("{name} ({masks}/{deep}/{colours}/{materials} of {pixels} differ; {:.1} leaves a cell, {} KiB)", b.mean_leaves, b.bytes() / 1024));
    }
    report(&format!(
        "data form against inline (hit mask/depth/colour/material): {}",
        said.join("; ")
    ));
}

/// `--form auto` (the default) draws a union of 150 spheres as data and one of 20 inline; a
/// scene the data form cannot hold (a `repeat`) inline whatever its size; `--form data` on
/// that one is an error naming the node.
#[test]
fn the_form_by_default_follows_the_parts() {
    use crate::common::{scratch, sdfc, write};
    let dir = scratch("auto-form");
    let form = |name: &str, text: String, extra: &[&str]| {
        let file = write(&dir, name, &text);
        let mut args = vec![
            "bench",
            &file,
            "--size",
            "16x9",
            "--tracers",
            "basic",
            "--steps",
            "16",
            "--repeat",
            "1",
            "--no-truth",
            "--json",
        ];
        args.extend_from_slice(extra);
        let o = sdfc(&args);
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        match o.status.code() {
            Some(0) => {
                serde_json::from_slice::<serde_json::Value>(&o.stdout).expect("JSON")["form"]
                    .as_str()
                    .unwrap()
                    .to_string()
            }
            _ => err,
        }
    };
    let union = |n: usize| {
        format!(
            "camera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nunion {{\n{}\n}}",
            balls(n, false)
        )
    };
    assert_eq!(form("many.sdf", union(150), &[]), "data");
    assert_eq!(form("few.sdf", union(20), &[]), "inline");
    assert_eq!(
        form("many.sdf", union(150), &["--form", "inline"]),
        "inline"
    );
    let repeated = format!("{}\nsphere(0.1) |> repeat((0.5, 0.5, 0.5))", union(150));
    assert_eq!(form("repeat.sdf", repeated.clone(), &[]), "inline");
    let err = form("repeat.sdf", repeated, &["--form", "data"]);
    assert!(
        err.contains("`--form data` cannot hold this scene") && err.contains("repeat"),
        "{err}"
    );
}

/// Parameters and `time` in shapes' arguments drive the data form without a new shader:
/// `render --param … --time T` makes the buffers at the values for the shader compiled at the
/// defaults, and draws what the inline form draws there — here a sphere among 150 that grows
/// and moves, and a bar turning with `time`.
#[test]
fn parameters_move_the_parts_of_the_data_form() {
    use crate::common::{scratch, succeeded, write};
    let dir = scratch("data-params");
    let text = format!(
        "param r = 0.3 in 0.05..0.8\nparam pos = (0, 0, -1.2)\ncamera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nunion {{\n{}\nsphere(r) at pos\nbox((0.7, 0.15, 0.15)) |> rotate(z, time * 45deg) at (-0.6, -0.5, -1.4)\n}}",
        balls(150, false)
    );
    let file = write(&dir, "moved.sdf", &text);
    let draw = |form: &str, values: &[&str]| {
        let out = dir.join(format!("{form}-{}.png", values.len()));
        let out = out.to_str().unwrap().to_string();
        let mut args = vec![
            "render",
            &file,
            "--size",
            "160x90",
            "--samples",
            "1",
            "--form",
            form,
            "-o",
            &out,
            "-q",
        ];
        args.extend_from_slice(values);
        succeeded(&args);
        image::open(&out).unwrap().to_rgba8()
    };
    let moved = [
        "--param",
        "r=0.6",
        "--param",
        "pos=0.5,0.9,-1.3",
        "--time",
        "2",
    ];
    let (data, inline) = (draw("data", &moved), draw("inline", &moved));
    let differ = |a: &image::RgbaImage, b: &image::RgbaImage| {
        a.pixels()
            .zip(b.pixels())
            .filter(|(p, q)| (0..3).any(|k| p[k].abs_diff(q[k]) > 2))
            .count()
    };
    let pixels = (160 * 90) as usize;
    // (Measured: 169 pixels differ, on the small balls' rims: the data form's rays cross far
    // cells by their clearance and stop elsewhere within ε; 0 before far-field culling. The
    // bar's turn alone moves about 3% of them.)
    assert!(
        differ(&data, &inline) <= pixels / 50,
        "{} of {pixels} pixels differ",
        differ(&data, &inline)
    );
    assert!(
        differ(&data, &draw("data", &[])) > pixels / 20,
        "the parameters moved nothing"
    );
    let at_zero = draw("data", &moved[..4]);
    assert!(
        differ(&data, &at_zero) > pixels / 100,
        "`time` moved nothing: {} pixels",
        differ(&data, &at_zero)
    );
}

/// `sdfc emit --form data` hands a host everything it needs: the shader reads the three buffers
/// at the bindings the manifest names, each written beside the shader with the bytes the
/// manifest says and the runtime itself uploads; the parameters they follow are listed. By
/// default `emit` writes the inline form (no files beside it); targets without storage buffers
/// (GLSL ES 3.00, a Shadertoy tab) and a shader with no file to write the buffers beside are
/// refused, leaving nothing behind. (Chrome's WebGPU page drawing an emitted data form:
/// `browser::the_webgpu_page_draws_what_render_draws`.)
#[test]
fn emit_writes_the_data_form_for_a_host() {
    use crate::common::{refused, scratch, succeeded, write};
    let dir = scratch("data-emit");
    let text = format!(
        "param lift = -1.2 in -1.5..0\ncamera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nunion {{\n{}\nplane(y, lift)\n}}",
        balls(150, false)
    );
    let file = write(&dir, "host.sdf", &text);
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (wgsl, json) = (path("host.wgsl"), path("host.json"));
    succeeded(&[
        "emit",
        &file,
        "--form",
        "data",
        "-o",
        &wgsl,
        "--manifest",
        &json,
        "-q",
    ]);
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let data = &manifest["data"];
    assert_eq!(data["follows"], serde_json::json!(["lift"]), "{data}");
    let scene = compile(&text);
    let (tree, layout) = sdfc_compiler::tape::data::layout(&scene, None).unwrap();
    let made = sdfc_compiler::tape::data::data(&scene, &tree, &layout).unwrap();
    let shader = std::fs::read_to_string(&wgsl).unwrap();
    for (i, bytes) in made.buffers().iter().enumerate() {
        let b = &data["buffers"][i];
        let written = std::fs::read(path(b["file"].as_str().unwrap())).unwrap();
        assert_eq!(&written, bytes, "{b}");
        assert_eq!(b["bytes"], written.len(), "{b}");
        let binding = b["binding"]["binding"].as_u64().unwrap();
        let declared = format!(
            "@group(0) @binding({binding}) \nvar<storage> {}",
            b["global"].as_str().unwrap()
        );
        assert!(shader.contains(&declared), "{declared}");
    }
    assert_eq!(data["grid"]["cells"], serde_json::json!(layout.n), "{data}");
    // By default, inline: nothing beside the shader.
    let (inline, inline_json) = (path("inline.wgsl"), path("inline.json"));
    succeeded(&[
        "emit",
        &file,
        "-o",
        &inline,
        "--manifest",
        &inline_json,
        "-q",
    ]);
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&inline_json).unwrap()).unwrap();
    assert!(manifest["data"].is_null(), "{}", manifest["data"]);
    assert!(!dir.join("inline.nodes.u32").exists());
    let out = dir.join("no.nodes.u32");
    let no = path("no.frag");
    let gles = [
        "emit",
        &file,
        "--form",
        "data",
        "--target",
        "glsl",
        "--glsl-version",
        "300es",
        "--entry",
        "fragment",
        "-o",
        &no,
    ];
    refused(&gles, "GLSL ES 3.00 (WebGL2) does not have", &out);
    let toy = [
        "emit",
        &file,
        "--form",
        "data",
        "--entry",
        "shadertoy",
        "-o",
        &no,
    ];
    refused(&toy, "a Shadertoy tab has none", &out);
    refused(
        &["emit", &file, "--form", "data"],
        "give the shader a file with `-o FILE`",
        &out,
    );
    let lost = dir.join("missing/no.wgsl");
    let lost = lost.to_str().unwrap();
    refused(
        &["emit", &file, "--form", "data", "-o", lost],
        "",
        &dir.join("missing/no.nodes.u32"),
    );
    report(&format!(
        "emit --form data: 3 buffers ({} bytes) beside the shader, equal to the runtime's, bindings as the manifest says; GLSL ES 3.00, Shadertoy and no file refused",
        made.buffers().iter().map(Vec::len).sum::<usize>()
    ));
}

/// Buffers larger than the device binds (lavapipe: 128 MiB a buffer) are a clear error before
/// anything is drawn, not the device's: 1000 balls blended over 0.6 — wide enough that every
/// cell keeps hundreds of them — make a program buffer of about 300 MB.
#[test]
fn buffers_beyond_the_device_are_refused() {
    use crate::common::{refused, scratch, write};
    let dir = scratch("data-large");
    let text = format!(
        "camera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nsmooth_union(0.6) {{\n{}\n}}",
        balls(1000, false)
    );
    let file = write(&dir, "wide.sdf", &text);
    let out = dir.join("wide.png");
    let args = [
        "render",
        &file,
        "--size",
        "64x36",
        "-o",
        out.to_str().unwrap(),
    ];
    refused(&args, "this device binds at most", &out);
}

/// `--cells N` sets the data form's grid (the grid is data: the same shader draws any): 150
/// balls drawn on 8 cells a side are the picture drawn on the parts' own grid (a pruned program
/// is the whole field inside its cell, whatever the cell); a count out of range, or for a
/// scene drawn inline, is refused.
#[test]
fn the_grid_s_cells_change_the_work_not_the_picture() {
    use crate::common::{refused, scratch, succeeded, write};
    let dir = scratch("data-cells");
    let text = format!(
        "material red {{ color #d04038 }}\nmaterial blue {{ color #3050d0 }}\ncamera {{ eye (0, 1, -4)  target (0, 0, 0) }}\nsmooth_union(0.05) {{\n{}\n}}\nplane(y, -1.2)",
        balls(150, true)
    );
    let file = write(&dir, "cells.sdf", &text);
    let draw = |cells: &[&str], name: &str| {
        let out = dir.join(name);
        let mut args = vec![
            "render",
            &file,
            "--size",
            "96x54",
            "--samples",
            "1",
            "--form",
            "data",
            "-q",
            "-o",
        ];
        args.push(out.to_str().unwrap());
        args.extend_from_slice(cells);
        succeeded(&args);
        image::open(&out).unwrap().to_rgba8()
    };
    let (coarse, own) = (draw(&["--cells", "8"], "8.png"), draw(&[], "own.png"));
    let differ = coarse
        .pixels()
        .zip(own.pixels())
        .filter(|(p, q)| (0..3).any(|k| p[k].abs_diff(q[k]) > 2))
        .count();
    assert!(differ <= 96 * 54 / 1000, "{differ} pixels differ");
    let out = dir.join("no.png");
    let no = out.to_str().unwrap();
    refused(
        &["render", &file, "--cells", "0", "-o", no],
        "1 to 128 cells",
        &out,
    );
    refused(
        &["render", &file, "--cells", "129", "-o", no],
        "1 to 128 cells",
        &out,
    );
    let inline = [
        "render", &file, "--form", "inline", "--cells", "8", "-o", no,
    ];
    refused(&inline, "is for the data form", &out);
}
