//! `sdfc mesh` from the outside: every example meshed and read by tools that are not sdfc's —
//! trimesh and manifold3d (PyPI) and admesh (Debian) on the STL, Khronos's glTF-Validator
//! (npm) on the glTF — closed, 2-manifold, consistently oriented, its volume within 1% of a
//! stratified Monte-Carlo estimate from the field; and bad input refused before any work.
//!
//! The checkers come from `.ci/run` (`scripts/mesh_check.py`, `examples/hosts/test`); without
//! them the test says SKIPPED loudly, and fails instead when `SDFC_REQUIRE_MESH_TOOLS=1` (as
//! `.ci/run` sets).

use crate::common::{compile, examples, report, root, scratch, sdfc};
use glam::DVec3;
use sdfc_compiler::mesh::{self, field::Field};
use sdfc_compiler::scene::Scene;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The resolution every example is meshed at: moderate, as issue 35 asks.
const RESOLUTION: u32 = 48;

/// Whether the independent checkers are here (said loudly when not, a failure when
/// `SDFC_REQUIRE_MESH_TOOLS` is set).
fn tools() -> bool {
    let python = Command::new("python3")
        .args(["-c", "import trimesh, manifold3d"])
        .output()
        .is_ok_and(|o| o.status.success());
    let admesh = Command::new("admesh").arg("--version").output().is_ok();
    let validator = root()
        .join("examples/hosts/test/node_modules/gltf-validator")
        .exists();
    let ready = python && admesh && validator;
    if !ready {
        assert!(
            std::env::var("SDFC_REQUIRE_MESH_TOOLS").is_err(),
            "SDFC_REQUIRE_MESH_TOOLS is set but a checker is missing: trimesh/manifold3d {python}, \
             admesh {admesh}, gltf-validator {validator}"
        );
        eprintln!(
            "\n*** trimesh, manifold3d, admesh or gltf-validator is missing: the mesh checks are SKIPPED (`.ci/run` installs them) ***\n"
        );
    }
    ready
}

/// The box an example is meshed in: its own (grown as `sdfc mesh` grows it) or, for a scene
/// with a floor or other unbounded part, a box around what its camera looks at.
fn box_of(scene: &Scene) -> Option<(DVec3, DVec3)> {
    if mesh::scene_bounds(scene).is_some() {
        return None;
    }
    let c = &scene.camera;
    let reach = 0.5 * (c.eye - c.target).length();
    Some((c.target - reach, c.target + reach))
}

/// The box `sdfc mesh` meshes for `scene` with `bounds`.
fn meshed_box(scene: &Scene, bounds: Option<(DVec3, DVec3)>) -> (DVec3, DVec3) {
    bounds.unwrap_or_else(|| {
        let (lo, hi) = mesh::scene_bounds(scene).unwrap();
        let grow = 0.01 * (hi - lo).max_element();
        (lo - grow, hi + grow)
    })
}

/// The volume inside the clipped field, by stratified Monte Carlo: one jittered point in each
/// of n³ cells of the box.
fn field_volume(scene: &Scene, (lo, hi): (DVec3, DVec3), n: u32) -> f64 {
    let field = Field::new(scene, lo, hi);
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut random = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let cell = (hi - lo) / n as f64;
    let mut points = Vec::with_capacity((n * n * n) as usize);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let jitter = DVec3::new(random(), random(), random());
                points.push(lo + (DVec3::new(i as f64, j as f64, k as f64) + jitter) * cell);
            }
        }
    }
    let inside = sdfc_compiler::parallel::par_map(&points, |&p| field.at(p) < 0.0)
        .into_iter()
        .filter(|&b| b)
        .count();
    inside as f64 / points.len() as f64 * (hi - lo).element_product()
}

/// Runs `sdfc mesh` on `file` into `out`; fails the test on an error.
fn mesh_file(file: &Path, out: &Path, bounds: Option<(DVec3, DVec3)>) -> String {
    let mut args = vec![
        "mesh".to_string(),
        file.display().to_string(),
        "-o".into(),
        out.display().to_string(),
        "--resolution".into(),
        RESOLUTION.to_string(),
    ];
    if let Some((lo, hi)) = bounds {
        let v = [lo.x, lo.y, lo.z, hi.x, hi.y, hi.z].map(|x| x.to_string());
        args.push(format!("--bounds={}", v.join(",")));
    }
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let run = sdfc(&refs);
    let said = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "sdfc {}: {said}", args.join(" "));
    said
}

/// One JSON line per file from a checker.
fn json_lines(out: &std::process::Output, what: &str) -> Vec<serde_json::Value> {
    assert!(
        out.status.success(),
        "{what}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{what}: {e}: {l}")))
        .collect()
}

#[test]
fn every_example_is_closed_manifold_to_independent_checkers() {
    if !tools() {
        return;
    }
    let dir = scratch("mesh-examples");
    let mut stls: Vec<PathBuf> = Vec::new();
    let mut glbs: Vec<PathBuf> = Vec::new();
    let mut volumes = Vec::new();
    for path in examples() {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let scene = compile(&std::fs::read_to_string(&path).unwrap());
        let bounds = box_of(&scene);
        let stl = dir.join(format!("{name}.stl"));
        let glb = dir.join(format!("{name}.glb"));
        let said = mesh_file(&path, &stl, bounds);
        assert!(said.contains("closed, 2-manifold"), "{name}: {said}");
        mesh_file(&path, &glb, bounds);
        volumes.push((name, field_volume(&scene, meshed_box(&scene, bounds), 96)));
        stls.push(stl);
        glbs.push(glb);
    }
    let checked = Command::new("python3")
        .arg(root().join("scripts/mesh_check.py"))
        .args(&stls)
        .output()
        .expect("python3");
    let reports = json_lines(&checked, "mesh_check.py");
    assert_eq!(reports.len(), stls.len());
    for (r, (name, field)) in reports.iter().zip(&volumes) {
        let t = &r["trimesh"];
        let m = &r["manifold"];
        let a = &r["admesh"];
        assert_eq!(t["watertight"], true, "{name}: trimesh: {r}");
        assert_eq!(t["winding_consistent"], true, "{name}: trimesh: {r}");
        assert_eq!(m["status"], "NoError", "{name}: manifold3d: {r}");
        for key in [
            "degenerate_facets",
            "edges_fixed",
            "backwards_edges",
            "facets_removed",
        ] {
            assert_eq!(a[key], 0.0, "{name}: admesh {key}: {r}");
        }
        let volume = t["volume"].as_f64().unwrap();
        let off = volume / field - 1.0;
        report(&format!(
            "mesh {name}: trimesh watertight, manifold3d {}, admesh {} parts; volume {volume:.4} \
             against the field's {field:.4} ({:+.2}%)",
            m["status"],
            a["parts"],
            100.0 * off
        ));
        assert!(off.abs() < 0.01, "{name}: volume {volume} against {field}");
    }
    let validated = Command::new("node")
        .arg(root().join("examples/hosts/test/gltf-validate.mjs"))
        .args(&glbs)
        .output()
        .expect("node");
    for v in json_lines(&validated, "gltf-validate.mjs") {
        assert_eq!(v["errors"], 0, "glTF-Validator: {v}");
        assert_eq!(v["warnings"], 0, "glTF-Validator: {v}");
    }
    report(&format!(
        "mesh: {} glTF files, 0 errors and 0 warnings from glTF-Validator",
        glbs.len()
    ));
}

/// Bad input gets a clear error before any work and leaves no file: an unbounded scene (with a
/// caret under the part), a resolution past the memory (estimated from the octree's coarse
/// levels), a folder that does not exist, a format sdfc does not write, a bad `--bounds`.
#[test]
fn bad_input_is_refused_before_work_and_leaves_no_file() {
    let dir = scratch("mesh-bad");
    let floor = crate::common::write(&dir, "floor.sdf", "sphere(1)\nplane(y, -1)\n");
    let ball = crate::common::write(&dir, "ball.sdf", "sphere(1)\n");
    let out = dir.join("out.stl");
    let o = out.display().to_string();
    let cases: [(&[&str], &str); 8] = [
        (&["mesh", &ball, "-o", &o, "--triangles", "3"], "at least 4"),
        (
            &[
                "mesh",
                &ball,
                "-o",
                &o,
                "--triangles",
                "100",
                "--resolution",
                "9",
            ],
            "cannot be used with",
        ),
        (&["mesh", &floor, "-o", &o], "--bounds X0,Y0,Z0,X1,Y1,Z1"),
        (
            &["mesh", &ball, "-o", &o, "--resolution", "60000"],
            "would need about",
        ),
        (
            &["mesh", &ball, "-o", "/no/such/folder/x.stl"],
            "does not exist",
        ),
        (
            &[
                "mesh",
                &ball,
                "-o",
                &dir.join("x.txt").display().to_string(),
            ],
            "`.stl`, `.obj`, `.ply` or `.glb`",
        ),
        (
            &["mesh", &ball, "-o", &o, "--bounds", "1,1,1,0,0,0"],
            "six numbers",
        ),
        (
            &["mesh", &ball, "-o", &o, "--bounds=5,5,5,6,6,6"],
            "no surface crosses the box",
        ),
    ];
    for (args, says) in cases {
        crate::common::refused(args, says, &out);
    }
    // The unbounded part is shown with its line and a caret.
    let run = sdfc(&["mesh", &floor, "-o", &o]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("floor.sdf:2:1") && err.contains('^'), "{err}");
}

/// A glTF from `sdfc mesh` loads in three.js (GLTFLoader, in headless Chromium) with every
/// triangle and material, and draws: the picture is kept as `docs/mesh/primitives_three.png`
/// shows it.
#[test]
fn a_gltf_loads_and_draws_in_three_js() {
    let Some((chrome, driver)) = crate::browser::browser() else {
        return;
    };
    if !driver.join("node_modules/three").exists() {
        assert!(
            std::env::var("SDFC_REQUIRE_BROWSER").is_err(),
            "three.js is missing (npm ci in {})",
            driver.display()
        );
        eprintln!("\n*** three.js is missing: the three.js mesh test is SKIPPED ***\n");
        return;
    }
    let dir = scratch("mesh-three");
    let glb = dir.join("primitives.glb");
    let file = root().join("examples/primitives.sdf");
    let bounds = (DVec3::new(-4.5, -0.5, -1.5), DVec3::new(4.5, 2.5, 6.5));
    let said = mesh_file(&file, &glb, Some(bounds));
    let triangles: u64 = said
        .split(" triangles")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no triangle count in {said}"));
    let png = dir.join("three.png");
    let run = Command::new("node")
        .arg(driver.join("three-glb.mjs"))
        .arg(&glb)
        .arg(&png)
        .env("CHROME", &chrome)
        .output()
        .expect("node");
    let out = json_lines(&run, "three-glb.mjs").remove(0);
    assert_eq!(out["triangles"].as_u64(), Some(triangles), "{out}");
    // The twelve primitives' materials and the floor's.
    assert_eq!(out["materials"].as_array().map(Vec::len), Some(13), "{out}");
    let drawn = out["drawn"].as_f64().unwrap() / out["pixels"].as_f64().unwrap();
    assert!(
        drawn > 0.1,
        "three.js drew {:.1}% of the picture",
        100.0 * drawn
    );
    report(&format!(
        "mesh: three.js loaded the primitives' glTF ({triangles} triangles, 13 materials) and \
         drew {:.0}% of the picture",
        100.0 * drawn
    ));
}

/// `--triangles N` comes near N: a scene I did not write for it (the composition example, its
/// floor cut by a box) asked for 2 000, 20 000 and 200 000 triangles gets each within 20 %.
/// Whole resolutions could not (at 2 000, 6 and 7 cells make 1 246 and 2 402 since stop 50
/// followed creases on the GPU); the resolution chosen need not be whole (stop 51).
#[test]
fn a_triangle_count_is_met_within_a_fifth() {
    let dir = scratch("mesh-count");
    let scene = root().join("examples/composition.sdf");
    for target in [2_000u64, 20_000, 200_000] {
        let out = dir.join(format!("{target}.stl"));
        let run = sdfc(&[
            "mesh",
            scene.to_str().unwrap(),
            "--bounds",
            "-3,-0.5,-3,3,3,3",
            "--triangles",
            &target.to_string(),
            "-o",
            out.to_str().unwrap(),
        ]);
        let said = String::from_utf8_lossy(&run.stderr).into_owned();
        assert!(run.status.success(), "{said}");
        assert!(said.contains(&format!("{target} asked for")), "{said}");
        // A binary STL's triangle count: the little-endian u32 after its 80-byte header.
        let bytes = std::fs::read(&out).unwrap();
        let got = u32::from_le_bytes(bytes[80..84].try_into().unwrap());
        let chosen = said.split("resolution ").nth(1).unwrap_or("?");
        println!("{target} asked: {got} triangles (resolution {chosen}");
        let off = (f64::from(got) / target as f64 - 1.0).abs();
        assert!(off <= 0.2, "{target} asked, {got} made: {said}");
    }
}

/// The GPU field (f32, the scene's `map` as the pictures compile it) meshes as the CPU's f64
/// reference does: examples whose field is costly (the GPU's purpose), a hand-written blob of
/// 60 balls and a turned box (creases), each closed and 2-manifold, its triangle count and
/// volume near the reference's, and its distance to the surface — measured by the f64 field,
/// not by the GPU — within a fiftieth of a cell of the reference mesh's at the vertices and at
/// the faces' centroids. The GPU's gradients sample a hundredth of a cell apart, and a crossing
/// nearer a crease than that gets a blend of its two planes' normals: the crossings on faces
/// where normals turn by more than 20° take theirs again in f64 (`edges::sharpen`; the 200-ball
/// fluid at 96 cells: 183 of them, +0.01 % evaluations). Turned box at 48 cells, faces in
/// cells: 1.2e-3 on the GPU as in the reference (stop 50; before, the GPU 0.21 while the
/// reference had come to 1.2e-3 by following corners, and 0.21 and 0.12 before that).
#[test]
fn the_gpu_field_meshes_as_the_f64_reference_does() {
    use sdfc::mesh_gpu::GpuField;
    use sdfc_compiler::mesh::measure;
    let mut scenes: Vec<(String, String)> = ["blobs", "shapes", "temple", "tori_terrain"]
        .iter()
        .map(|n| {
            let path = root().join(format!("examples/{n}.sdf"));
            (n.to_string(), std::fs::read_to_string(path).unwrap())
        })
        .collect();
    let balls: Vec<String> = (0..60)
        .map(|i| {
            let a = i as f64 * 2.399_963;
            let (r, y) = (0.9 * (i as f64 / 60.0).sqrt(), 0.4 * (a * 1.7).sin());
            format!(
                "sphere({:.3}) at ({:.3}, {y:.3}, {:.3})",
                0.12 + 0.05 * (a * 0.7).cos().abs(),
                r * a.cos(),
                r * a.sin()
            )
        })
        .collect();
    scenes.push((
        "blob of 60 balls".into(),
        format!("blob(0.25) {{ {} }}", balls.join(" ")),
    ));
    scenes.push((
        "turned box".into(),
        "box((1, 1, 1)) |> rotate(y, 30deg) |> rotate(x, 20deg)".into(),
    ));
    for (name, source) in scenes {
        let scene = compile(&source);
        let bounds = meshed_box(&scene, box_of(&scene));
        let options = mesh::Options {
            resolution: f64::from(RESOLUTION),
            bounds,
            sharp: true,
            prune: true,
            max_bytes: 1 << 32,
        };
        let gpu = crate::common::gpu();
        let field = GpuField::on((*gpu).clone(), &scene, bounds).expect("the field compiles");
        let on_gpu = mesh::mesh_with(&scene, &options, Some(&field), &|_| {}).unwrap();
        let reference = mesh::mesh(&scene, &options, &|_| {}).unwrap();
        let f64_field = Field::new(&scene, bounds.0, bounds.1);
        let h = on_gpu.stats.cell;
        let (dg, dc) = (
            measure::deviation(&f64_field, &on_gpu, h),
            measure::deviation(&f64_field, &reference, h),
        );
        let (vg, vc) = (measure::volume(&on_gpu), measure::volume(&reference));
        let count = on_gpu.triangles.len() as f64 / reference.triangles.len() as f64 - 1.0;
        report(&format!(
            "mesh on the GPU, {name}: {} triangles ({:+.2}% of the f64 reference's), volume \
             {:+.3}%, vertices ≤ {:.1e} (reference {:.1e}), faces ≤ {:.1e} (reference {:.1e}) \
             of a cell, by the f64 field",
            on_gpu.triangles.len(),
            100.0 * count,
            100.0 * (vg / vc - 1.0),
            dg.vertex_max / h,
            dc.vertex_max / h,
            dg.face_max / h,
            dc.face_max / h
        ));
        assert!(
            measure::topology(&on_gpu).is_closed_manifold(),
            "{name}: the GPU's mesh is not closed"
        );
        assert!(count.abs() < 0.02, "{name}: {count}");
        assert!(
            (vg / vc - 1.0).abs() < 0.002,
            "{name}: volume {vg} against {vc}"
        );
        assert!(
            dg.vertex_max <= dc.vertex_max + 0.02 * h,
            "{name}: {dg:?} {dc:?}"
        );
        assert!(
            dg.face_max <= dc.face_max + 0.02 * h,
            "{name}: {dg:?} {dc:?}"
        );
    }
}
