//! Baked parts on the GPU (`bake`, Liktor §3): a shape with no Lipschitz bound traced through
//! its map against its f64 surface, and every primitive baked against itself analytic.

use crate::common::{compile, gpu, render, report};
use glam::DVec3;
use sdfc_compiler::view::View;

/// The first root of `f` along `ro + t·rd` for t in (0, far): marched in steps of `dt`, the
/// sign change bisected to 1e-9.
fn first_root(f: impl Fn(DVec3) -> f64, ro: DVec3, rd: DVec3, far: f64, dt: f64) -> Option<f64> {
    let mut t0 = 0.0;
    let mut f0 = f(ro);
    while t0 < far {
        let t1 = t0 + dt;
        let f1 = f(ro + rd * t1);
        if (f0 >= 0.0) != (f1 >= 0.0) {
            let (mut lo, mut hi) = (t0, t1);
            while hi - lo > 1e-9 {
                let mid = 0.5 * (lo + hi);
                if (f(ro + rd * mid) >= 0.0) == (f0 >= 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
        (t0, f0) = (t1, f1);
    }
    None
}

/// Hit masks and depths of two renders: (pixels where one hits and the other not, pixels both
/// hit, their |Δt| sorted).
fn compare(a: &[Option<f64>], b: &[f32]) -> (usize, Vec<f64>) {
    let mut mask = 0;
    let mut dt = Vec::new();
    for (x, &y) in a.iter().zip(b) {
        match (x, y >= 0.0) {
            (Some(x), true) => dt.push((x - f64::from(y)).abs()),
            (None, false) => {}
            _ => mask += 1,
        }
    }
    dt.sort_by(f64::total_cmp);
    (mask, dt)
}

/// The winding ramp of `examples/baked.sdf` (its height jumps where `atan2` crosses its cut:
/// no Lipschitz bound, refused without `bake`) traced on the GPU through its map at 64 points,
/// against its surface found in f64 along each ray (marched in steps of 1e-3, bisected): the
/// hit masks differ on at most 1% of the pixels (the silhouette), and on 99% of the pixels
/// both hit the depth is within one cell of the map.
#[test]
fn a_shape_without_a_bound_renders_baked_within_a_cell_of_its_surface() {
    let shape = "intersect { implicit { y - 0.5 - 0.12 * atan2(z, x) }  cylinder(radius = 0.9, height = 1.6) }";
    let camera = "camera { eye (1.6, 2.2, -2.6)  target (0, 0.1, 0)  fov 45deg }\n";
    let refused = sdfc_compiler::check::compile(&format!("{camera}{shape}"));
    assert!(refused.scene.is_none(), "the ramp compiled without a bound");
    let scene = compile(&format!("{camera}bake(res = 64) {{ {shape} }}"));
    let cell = scene.volumes()[0].grid.h;
    let exact = |p: DVec3| {
        let ramp = p.y - 0.5 - 0.12 * p.z.atan2(p.x);
        let q = DVec3::new(
            DVec3::new(p.x, 0.0, p.z).length() - 0.9,
            p.y.abs() - 0.8,
            0.0,
        );
        ramp.max(q.x.max(q.y).min(0.0) + q.max(DVec3::ZERO).length())
    };
    let (w, h) = (96u32, 72u32);
    let view = View::new(&scene.camera, w, h);
    let pixels: Vec<u32> = (0..w * h).collect();
    let truth = sdfc_compiler::parallel::par_map(&pixels, |&i| {
        let rd = view.ray(f64::from(i % w) + 0.5, f64::from(i / w) + 0.5);
        first_root(exact, view.eye, rd, 8.0, 1e-3)
    });
    let frame = render(&gpu(), &scene, &view);
    let (mask, dt) = compare(&truth, &frame.depth);
    let at = |q: f64| dt[((dt.len() - 1) as f64 * q) as usize] / cell;
    report(&format!(
        "bake: the unbounded ramp at 64 points (cell {cell:.4}) on the GPU against its f64 surface: \
         {mask} of {} pixels differ in hit, depth error in cells median {:.3}, 99% {:.3}, max {:.3}",
        w * h,
        at(0.5),
        at(0.99),
        at(1.0)
    ));
    assert!(
        dt.len() > (w * h / 4) as usize,
        "too few hits: {}",
        dt.len()
    );
    assert!(
        mask * 100 <= (w * h) as usize,
        "{mask} pixels differ in hit"
    );
    assert!(at(0.99) <= 1.0, "99% of depths within {} cells", at(0.99));
}

/// Every solid primitive whose arguments all have defaults, baked at 64 points and analytic,
/// rendered on the GPU from the same camera (hit threshold 1e-4): hit masks differ only on the
/// silhouette (a pixel whose hit differs has a neighbour whose analytic hit differs from its
/// own), and every baked hit point lies within one cell of the analytic surface by the
/// analytic field there (|f|/λ: the distance for exact primitives, a lower bound otherwise).
#[test]
fn every_primitive_baked_renders_as_itself_within_a_cell() {
    let camera = "camera { eye (2.2, 1.7, -3.2)  target (0, 0, 0)  fov 42deg }\ntrace basic { steps 512  epsilon 0.0001 }\n";
    let (w, h) = (64u32, 48u32);
    let gpu = gpu();
    let mut lines = Vec::new();
    for p in sdfc_compiler::catalog::PRIMITIVES {
        if p.planar || p.params.iter().any(|a| a.default.is_none()) {
            continue;
        }
        let plain = compile(&format!("{camera}{}()", p.name));
        if !plain.root_node().bound.is_finite() {
            continue;
        }
        let baked = compile(&format!("{camera}bake(res = 64) {{ {}() }}", p.name));
        let cell = baked.volumes()[0].grid.h;
        let view = View::new(&plain.camera, w, h);
        let a = render(&gpu, &plain, &view);
        let b = render(&gpu, &baked, &view);
        // A pixel whose hit differs must be on the analytic silhouette.
        let hit = |x: i64, y: i64| {
            let (x, y) = (x.clamp(0, w as i64 - 1), y.clamp(0, h as i64 - 1));
            a.depth[(y * w as i64 + x) as usize] >= 0.0
        };
        let differ: Vec<usize> = (0..a.depth.len())
            .filter(|&i| (a.depth[i] >= 0.0) != (b.depth[i] >= 0.0))
            .collect();
        let inner = differ
            .iter()
            .filter(|&&i| {
                let (x, y) = ((i as u32 % w) as i64, (i as u32 / w) as i64);
                let own = hit(x, y);
                (-1..=1).all(|dy| (-1..=1).all(|dx| hit(x + dx, y + dy) == own))
            })
            .count();
        let mut off: Vec<f64> = (0..b.depth.len())
            .filter(|&i| b.depth[i] >= 0.0)
            .map(|i| {
                let rd = view.ray(f64::from(i as u32 % w) + 0.5, f64::from(i as u32 / w) + 0.5);
                let q = view.eye + rd * f64::from(b.depth[i]);
                sdfc_compiler::reference::eval::distance(&plain, q).abs() / cell
            })
            .collect();
        off.sort_by(f64::total_cmp);
        let worst = off.last().copied().unwrap_or(0.0);
        let p99 = off
            .get((off.len().max(1) - 1) * 99 / 100)
            .copied()
            .unwrap_or(0.0);
        lines.push(format!(
            "{} {} pixels differ ({inner} off the silhouette), hits off the surface by 99% {p99:.3} max {worst:.3} cells",
            p.name,
            differ.len()
        ));
        // A fractal's detail finer than a cell is lost by any grid: reported, not judged.
        if p.name == "mandelbulb" {
            continue;
        }
        assert_eq!(
            inner, 0,
            "{}: {inner} pixels off the silhouette differ in hit",
            p.name
        );
        assert!(
            worst <= 1.0,
            "{}: a hit {worst:.3} cells off the surface",
            p.name
        );
    }
    report(&format!(
        "bake: every primitive baked at 64 points against itself — {}",
        lines.join("; ")
    ));
    assert!(
        lines.len() >= 10,
        "only {} primitives compared",
        lines.len()
    );
}

/// `sdfc emit --bake-res N` bakes at N whatever the scene's `res` says: the manifest's size
/// and the volume file's length agree with N; a volume file that cannot be written (a folder
/// in its place) is refused before anything is written.
#[test]
fn emit_writes_the_volume_at_bake_res_and_refuses_an_unwritable_one() {
    let dir = crate::common::scratch("bake-res");
    let scene = crate::common::write(&dir, "ball.sdf", "bake(res = 16) { sphere(1) }\n");
    let out = dir.join("ball.wgsl");
    let manifest = dir.join("ball.json");
    let (o, m) = (out.to_str().unwrap(), manifest.to_str().unwrap());
    let run = crate::common::sdfc(&["emit", &scene, "-o", o, "--manifest", m, "--bake-res", "9"]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&manifest).unwrap()).unwrap();
    let volume = &json["volumes"][0];
    assert_eq!(volume["size"], serde_json::json!([9, 9, 9]), "{volume}");
    let file = dir.join(volume["file"].as_str().unwrap());
    assert_eq!(std::fs::metadata(&file).unwrap().len(), 9 * 9 * 9 * 4);
    // Out of range: refused by the command line, nothing written.
    let other = dir.join("other.wgsl");
    let o2 = other.to_str().unwrap();
    crate::common::refused(
        &["emit", &scene, "-o", o2, "--bake-res", "513"],
        "513",
        &other,
    );
    // A folder where the volume goes.
    std::fs::create_dir_all(dir.join("other.volume0.r32f")).unwrap();
    crate::common::refused(&["emit", &scene, "-o", o2], "other.volume0.r32f", &other);
}

/// The GPU sampler (the part's `Entry::Field` module on lavapipe, a slab of points per
/// dispatch) gives the CPU's samples to f32's precision, and the volume baked from them is
/// the CPU's within a thousandth of a cell: a blob of 40 balls on a grid of 48 points.
#[test]
fn the_gpu_sampler_bakes_the_cpus_volume() {
    use sdfc::bake_gpu::GpuSampler;
    use sdfc_compiler::bake::{Grid, Volume};
    use sdfc_compiler::check::sampler::Sampler;
    let mut balls = String::new();
    let mut r = sdfc_tests_rng(7);
    for _ in 0..40 {
        let (x, y, z) = (r() * 2.0 - 1.0, r() * 0.6 - 0.3, r() * 2.0 - 1.0);
        balls += &format!(
            "sphere({:.3}) at ({x:.3}, {y:.3}, {z:.3})\n",
            0.08 + 0.1 * r()
        );
    }
    let scene = compile(&format!("blob(radius = 0.3) {{\n{balls}}}"));
    let b = scene.root_node().bound;
    let grid = Grid::around(b.lo, b.hi, 48);
    let gpu = GpuSampler::new()
        .sample(&scene, &grid)
        .expect("lavapipe samples");
    let cpu = grid.sample(&|p| sdfc_compiler::reference::eval::distance(&scene, p));
    let scale = cpu.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = gpu
        .iter()
        .zip(&cpu)
        .map(|(g, c)| (g - c).abs())
        .fold(0.0, f64::max);
    println!("GPU samples within {worst:.2e} of the CPU's (largest |value| {scale:.2e})");
    assert!(worst <= 1e-5 * scale.max(1.0), "{worst}");
    let field = |p: glam::DVec3| sdfc_compiler::reference::eval::distance(&scene, p);
    let a = Volume::from_samples(grid, &gpu, &field);
    let c = Volume::from_samples(grid, &cpu, &field);
    let off = a
        .values
        .iter()
        .zip(&c.values)
        .map(|(x, y)| f64::from((x - y).abs()))
        .fold(0.0, f64::max);
    println!("volumes within {:.2e} cells", off / grid.h);
    assert!(off <= 1e-3 * grid.h, "{} cells", off / grid.h);
}

/// A small deterministic generator of numbers in [0, 1).
fn sdfc_tests_rng(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A map baked by one run is read back from the cache folder by the next (`bench` says which
/// it did), and not with `SDFC_CACHE_DIR=off`.
#[test]
fn the_next_run_reads_the_map_from_the_cache_folder() {
    let dir = crate::common::scratch("bake-store");
    let scene = crate::common::write(
        &dir,
        "ball.sdf",
        "bake(res = 20) { torus(0.8, 0.3) at (0.37, -0.61, 0.2) }\n",
    );
    let bench = |cache: &str| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_sdfc"))
            .args([
                "bench",
                &scene,
                "--tracers",
                "basic",
                "--steps",
                "8",
                "--repeat",
                "1",
            ])
            .args(["--size", "16x9"])
            .env("SDFC_CACHE_DIR", cache)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).to_string()
    };
    let store = dir.join("cache");
    let store = store.to_str().unwrap();
    assert!(bench(store).contains("baked in"));
    assert!(bench(store).contains("read from the cache"));
    assert!(bench("off").contains("baked in"));
}
