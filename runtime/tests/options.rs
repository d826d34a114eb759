//! The tracer options on the CPU reference and the GPU: convex bounds (Keinert §3.5) and
//! multi-resolution passes (Bálint §4).

use crate::common::{Safety, Tally, camera_rays, compile, examples, gpu, gpu_trace, with_method};
use glam::DVec3;
use sdfc_compiler::check::tracer::TRACE_METHODS;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::passes;
use sdfc_compiler::reference::trace;
use sdfc_compiler::scene::Scene;
use sdfc_compiler::view::View;

/// A unit sphere in a convex bound: rays from outside the bound, from inside the bound but
/// outside the sphere, from inside the sphere, and rays missing the bound; (origin, direction,
/// the hit distance expected, `None` for a miss).
fn bound_cases() -> Vec<(DVec3, DVec3, Option<f64>)> {
    let z = DVec3::Z;
    let diag = DVec3::new(1.0, 1.0, 0.0).normalize();
    let inside = DVec3::new(0.3, 0.2, 0.1);
    // |inside + t·diag| = 1 for t > 0.
    let b = inside.dot(diag);
    let exit = -b + (b * b - (inside.length_squared() - 1.0)).sqrt();
    vec![
        (DVec3::new(0.0, 0.0, -5.0), z, Some(4.0)),
        (
            DVec3::new(0.2, -0.1, -1.2),
            z,
            Some(1.2 - (1.0f64 - 0.05).sqrt()),
        ),
        (DVec3::ZERO, z, Some(1.0)),
        (inside, diag, Some(exit)),
        (DVec3::new(0.0, 3.0, -5.0), z, None),
        (DVec3::new(0.0, 0.0, 5.0), z, None),
    ]
}

#[test]
fn convex_bounds_cull_start_at_entry_and_trace_backwards_from_inside() {
    let gpu = gpu();
    let mut report = String::new();
    for shape in [
        "sphere { radius 1.5 convex yes }",
        "box { size (3, 2.5, 3.2) convex yes }",
    ] {
        let base = compile(&format!(
            "trace basic {{ epsilon 0.0001 steps 400 }}\nbound {shape}\nsphere(1)"
        ));
        for &(name, method, _) in TRACE_METHODS {
            let mut scene = base.clone();
            scene.trace = with_method(&base, method);
            let cases = bound_cases();
            let rays: Vec<_> = cases
                .iter()
                .map(|(o, d, _)| {
                    (
                        o.to_array().map(|v| v as f32),
                        d.to_array().map(|v| v as f32),
                        0.0,
                    )
                })
                .collect();
            let on_gpu = gpu_trace(&gpu, &scene, &rays);
            for (i, (o, d, want)) in cases.iter().enumerate() {
                let c = trace::ray(&scene, &scene.trace, *o, *d, 0.0);
                let g = on_gpu[i];
                let line = format!(
                    "{shape} {name}: ray {i}: CPU {:?} GPU t {} steps {} flags {}",
                    c, g.0, g.1, g.2
                );
                report += &line;
                report.push('\n');
                match want {
                    Some(t) => {
                        assert!(c.hit && (c.t - t).abs() < 2e-3, "{line}: want t = {t}");
                        assert!((g.0 as f64 - t).abs() < 2e-3, "{line}: want t = {t}");
                    }
                    None => {
                        assert!(!c.hit, "{line}: want a miss");
                        assert_eq!(c.steps, 0, "{line}: a culled ray spends nothing");
                    }
                }
                assert_eq!(c.hit, g.2 & 1 == 1, "{line}");
                assert!(c.steps.abs_diff(g.1) <= 1, "{line}");
            }
        }
    }
    println!("{report}");
}

#[test]
fn a_bound_saves_steps_and_misses_nothing() {
    // The gem example declares a bound; without it every ray starts at the camera.
    let path = examples()
        .into_iter()
        .find(|p| p.ends_with("gem.sdf"))
        .unwrap();
    let bounded = compile(&std::fs::read_to_string(path).unwrap());
    let mut free = bounded.clone();
    free.bound = None;
    let view = View::new(&bounded.camera, 64, 48);
    let (mut with, mut without) = (0u64, 0u64);
    let (mut culled, mut missed, mut grazed, mut deeper) = (0, 0, 0, 0);
    for y in 0..view.height {
        for x in 0..view.width {
            let rd = view.ray(x as f64 + 0.5, y as f64 + 0.5);
            let a = trace::ray(&bounded, &bounded.trace, view.eye, rd, view.pixel);
            let b = trace::ray(&free, &free.trace, view.eye, rd, view.pixel);
            with += a.steps as u64;
            without += b.steps as u64;
            culled += (a.steps == 0) as u32;
            if b.hit && !a.hit {
                // A real miss, or a ray passing within ε of the silhouette without touching it?
                let f = trace::ray_exact(&free, &free.trace, 1e-7, view.eye, rd);
                if f.hit {
                    missed += 1;
                } else {
                    grazed += 1;
                }
            }
            // Both hits must lie within 2ε(t) of the surface, judged by the field's first-order
            // distance |f|/|∇f| at the hit point (depth along the ray is ε/sin θ off at
            // grazing incidence θ, so the two may differ by more than 2ε along the ray).
            for r in [a, b].iter().filter(|r| r.hit) {
                let p = view.eye + rd * r.t;
                let f = sdfc_compiler::reference::eval::distance(&free, p);
                let g = trace::tetra_gradient(
                    |q| sdfc_compiler::reference::eval::distance(&free, q),
                    p,
                    1e-6,
                );
                if f.abs() > 2.0 * view.pixel * r.t * g {
                    deeper += 1;
                }
            }
        }
    }
    let n = (view.width * view.height) as f64;
    println!(
        "gem 64×48 relaxed: {:.2} evaluations per pixel with the bound, {:.2} without; {culled} rays culled; missed {missed}, grazed {grazed}, hits farther than 2ε from the surface {deeper}",
        with as f64 / n,
        without as f64 / n
    );
    assert_eq!(missed + deeper, 0);
    assert!(culled > 0 && with < without);
}

fn passes_module(scene: &Scene) -> naga::Module {
    let mut options = Options::from_scene(scene);
    options.passes = true;
    emit::module(scene, Entry::Compute, &options)
        .unwrap_or_else(|e| panic!("{}", e.0))
        .0
}

#[test]
fn gpu_passes_agree_with_the_cpu_reference() {
    let gpu = gpu();
    let mut report = String::new();
    for path in examples() {
        let scene = compile(&std::fs::read_to_string(&path).unwrap());
        let module = passes_module(&scene);
        gpu.set_scene(&scene);
        for count in [2, 4] {
            let (w, h) = (64, 40);
            let plan = passes::plan(&scene, w, h, scene.trace.steps, count).unwrap();
            let (cpu, _) = passes::trace_image(&scene, &plan);
            let view = View::new(&scene.camera, w, h);
            let frame = gpu.render(&module, &view, Some(&plan), |_, _| {}).unwrap();
            let (mut hit_differs, mut steps_differ) = (0, 0);
            let (mut cpu_steps, mut gpu_steps) = (0u64, 0u64);
            let mut worst = 0;
            for (i, c) in cpu.iter().enumerate() {
                let g_hit = frame.depth[i] >= 0.0;
                hit_differs += (g_hit != c.hit) as u32;
                steps_differ += (c.steps.abs_diff(frame.steps[i]) > count as u32) as u32;
                worst = worst.max(c.steps.abs_diff(frame.steps[i]));
                cpu_steps += c.steps as u64;
                gpu_steps += frame.steps[i] as u64;
            }
            let n = cpu.len() as f64;
            report += &format!(
                "{:>14} {count} passes: hit/miss differs on {hit_differs}, steps by more than ±{count} on {steps_differ} of {}; mean steps CPU {:.1} GPU {:.1}, worst difference {worst}\n",
                path.file_stem().unwrap().to_string_lossy(),
                cpu.len(),
                cpu_steps as f64 / n,
                gpu_steps as f64 / n
            );
            assert!(hit_differs as f64 <= 0.01 * n, "{report}");
            // Over loose parts (implicit's gyroid, blobs, non-uniform scales) a hit is confirmed
            // by walking the zone of f < ε in quarter-ε steps (trace::careful), where f32 and
            // f64 can enter and leave a zone a step apart: 4% (2% before that walk), and the
            // worst difference is printed.
            assert!(steps_differ as f64 <= 0.04 * n, "{report}");
        }
    }
    println!("{report}");
}

#[test]
fn passes_miss_nothing_the_ground_truth_hits() {
    let mut report = String::new();
    for path in examples() {
        let base = compile(&std::fs::read_to_string(&path).unwrap());
        let safety = Safety::new(&base);
        let (w, h) = (48, 30);
        let view = View::new(&base.camera, w, h);
        let rays: Vec<_> = (0..w * h)
            .map(|i| view.ray((i % w) as f64 + 0.5, (i / w) as f64 + 0.5))
            .collect();
        let truth: Vec<_> = rays.iter().map(|&rd| safety.truth(&view, rd)).collect();
        for &(name, method, _) in TRACE_METHODS {
            let mut scene = base.clone();
            scene.trace = with_method(&base, method);
            let mut row = format!(
                "{:>14} {name:>8}:",
                path.file_stem().unwrap().to_string_lossy()
            );
            for count in [1, 2, 4] {
                let plan = passes::plan(&scene, w, h, scene.trace.steps, count).unwrap();
                let (got, work) = passes::trace_image(&scene, &plan);
                let mut tally = Tally::default();
                for (i, r) in got.iter().enumerate() {
                    // The first pass's pixels are the widest.
                    let footprint = plan[0].view.pixel;
                    safety.judge(
                        &mut tally,
                        (&view, rays[i], &scene.trace, footprint),
                        r,
                        &truth[i],
                    );
                }
                let Tally {
                    missed,
                    grazed,
                    exhausted,
                    slivers,
                } = tally;
                row += &format!(
                    "  {count}× {:.1} evals/px (missed {missed}, grazed {grazed}, budget out {exhausted}, slivers {slivers})",
                    work as f64 / got.len() as f64
                );
                assert_eq!(missed, 0, "{row}");
                assert!(slivers <= 4, "{row}");
            }
            report += &row;
            report.push('\n');
        }
    }
    println!("{report}");
}

#[test]
fn coverage_is_the_disc_area_beyond_the_chord() {
    // Independent check of Hart's formula: integrate the chord lengths 2·√(1 − x²) over x ∈ [q, 1]
    // of the unit disc, divided by its area π.
    for i in 0..=20 {
        let q = i as f64 / 20.0;
        let n = 20_000;
        let h = (1.0 - q) / n as f64;
        let area: f64 = (0..n)
            .map(|k| {
                let x = q + (k as f64 + 0.5) * h;
                2.0 * (1.0 - x * x).max(0.0).sqrt() * h
            })
            .sum();
        let want = area / std::f64::consts::PI;
        let got = trace::coverage(q);
        assert!(
            (got - want).abs() < 1e-5,
            "q = {q}: formula {got}, integral {want}"
        );
    }
}

#[test]
fn cone_antialiasing_agrees_on_cpu_and_gpu() {
    let scene = compile(
        "camera { eye (0, 1.2, -4)  target (0, 0.3, 0)  fov 40deg }\n\
         trace basic { antialias cone  steps 200 }\n\
         sphere(0.6) at (-0.5, 0.6, 0)\n\
         box((0.7, 0.7, 0.7)) |> rotate(y, 30deg) at (0.7, 0.35, 0.8)\n\
         plane(y, 0)",
    );
    let gpu = gpu();
    let view = View::new(&scene.camera, 96, 60);
    let pts: Vec<(f64, f64)> = (0..view.height)
        .flat_map(|y| (0..view.width).map(move |x| (x as f64 + 0.5, y as f64 + 0.5)))
        .collect();
    let rays = camera_rays(&view, &pts);
    let (module, _) = emit::module(&scene, Entry::Rays, &Options::from_scene(&scene)).unwrap();
    gpu.set_scene(&scene);
    let on_gpu = gpu.trace_rays_full(&module, &rays).unwrap();
    let (mut covered, mut differ, mut worst) = (0, 0, 0.0f64);
    for (i, &(x, y)) in pts.iter().enumerate() {
        let c = trace::ray(&scene, &scene.trace, view.eye, view.ray(x, y), view.pixel);
        let g = on_gpu[i];
        assert!(c.cover >= 0.0 && c.cover <= 0.5 && g[3].is_finite());
        covered += (c.cover > 0.0) as u32;
        let same = c.hit == (g[2] as u32 & 1 == 1) && c.steps.abs_diff(g[1] as u32) <= 1;
        if !same || (c.cover > 0.0) != (g[3] > 0.0) {
            differ += 1;
        } else {
            worst = worst.max((c.cover - g[3] as f64).abs());
        }
    }
    println!(
        "cone anti-aliasing, 96×60: {covered} rays with a near miss; {differ} differ between CPU and GPU; largest coverage difference elsewhere {worst:.2e}"
    );
    assert!(covered > 50, "near misses must be found on silhouettes");
    assert!(differ as f64 <= 0.01 * pts.len() as f64);
    assert!(worst < 0.02);
}
