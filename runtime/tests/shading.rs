//! Shading on the GPU against the f64 CPU reference shader (`sdfc_compiler::reference::shading`), one
//! scene per feature: the same rays, the same formulas, compared per pixel in 8-bit sRGB.

use crate::common::{EXTREMES_BASE, compile, every_feature_scene, gpu, off_by, render, srgb8};
use sdfc_compiler::color::to_srgb;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::reference::pixel;
use sdfc_compiler::view::View;

const W: u32 = 96;
const H: u32 = 64;

/// Most 8-bit levels a channel may differ by (f32 against f64: normals, shadow ray steps).
const LEVELS: i32 = 2;
/// Least share of pixels within [`LEVELS`] on every channel: what is left are pixels where a
/// ray grazes a surface and f32 and f64 decide a hit (of the camera or a shadow ray)
/// differently.
const SHARE: f64 = 0.995;

/// A box on a floor with a ball beside it, lit from above and the side; `extra` adds the
/// feature under test.
fn scene(extra: &str) -> String {
    format!(
        "camera {{ eye (2, 1.8, -3)  target (0.3, 0.4, 0) }}\n\
         material red {{ color #c04030  specular 0.5 }}\n\
         material floor {{ color #a0a8b0 }}\n\
         {extra}\n\
         union {{\n\
           box((1, 1, 1)) at (0, 0.5, 0) : red\n\
           sphere(0.5) at (1.1, 0.5, -0.3)\n\
           plane(y, 0) : floor\n\
         }}\n"
    )
}

#[test]
fn every_shading_feature_matches_the_cpu_reference() {
    let gpu = gpu();
    let light = "light { direction (-0.6, 1, 0.5) ";
    let cases = [
        ("lambert and specular", format!("{light} }}")),
        ("hard shadow", format!("{light} shadow hard }}")),
        ("soft shadow", format!("{light} shadow soft  softness 6 }}")),
        (
            "point light, shadow",
            "light point { position (2, 3, -2)  intensity 1.5  shadow hard }".to_string(),
        ),
        (
            "occlusion",
            format!("{light} }}\nocclusion {{ samples 5  distance 0.6  strength 1.5 }}"),
        ),
        (
            "fog",
            format!("{light} }}\nfog {{ density 0.12  color #8090a0 }}"),
        ),
        (
            "mirror",
            format!(
                "{light} }}\nmaterial chrome {{ color #ccc  reflect 0.8 }}\nsphere(0.45) at (-0.6, 0.45, -0.9) : chrome"
            ),
        ),
        (
            "glass",
            format!(
                "{light} }}\nmaterial glass {{ color #eef4ff  transparent 0.9  ior 1.5 }}\nsphere(0.45) at (-0.6, 0.45, -0.9) : glass"
            ),
        ),
        (
            "diamond (total internal reflection)",
            format!(
                "{light} }}\nmaterial gem {{ color #fff  transparent 0.95  ior 2.42 }}\noctahedron(0.6) at (-0.6, 0.6, -0.9) : gem"
            ),
        ),
        (
            "everything",
            format!(
                "{light} shadow soft }}\nocclusion {{ }}\nfog {{ density 0.05 }}\n\
                 trace basic {{ antialias cone }}"
            ),
        ),
    ];
    let mut report = String::new();
    let mut plain: Option<Vec<u32>> = None;
    for (name, extra) in &cases {
        let scene = compile(&scene(extra));
        let view = View::new(&scene.camera, W, H);
        let frame = render(&gpu, &scene, &view);
        // The feature shows: pixels it changes from the plain scene (and the plain scene has
        // surfaces, not only background).
        let changed = match &plain {
            None => frame.depth.iter().filter(|&&d| d >= 0.0).count(),
            Some(p) => p
                .iter()
                .zip(&frame.color)
                .filter(|(a, b)| {
                    let (a, b) = (a.to_le_bytes(), b.to_le_bytes());
                    (0..3).any(|k| a[k].abs_diff(b[k]) as i32 > LEVELS)
                })
                .count(),
        };
        assert!(changed > 200, "{name}: only {changed} pixels show it");
        plain.get_or_insert_with(|| frame.color.clone());
        let (mut within, mut worst, mut sum) = (0usize, 0i32, 0.0f64);
        for y in 0..H {
            for x in 0..W {
                let i = (y * W + x) as usize;
                let c = pixel::pixel(&scene, &scene.trace, &view, x as f64 + 0.5, y as f64 + 0.5);
                let diff = off_by(frame.color[i], srgb8(c));
                worst = worst.max(diff);
                sum += diff as f64;
                if diff <= LEVELS {
                    within += 1;
                }
            }
        }
        let n = (W * H) as f64;
        let share = within as f64 / n;
        report += &format!(
            "{name}: {changed} pixels differ from the plain scene; {:.2}% within {LEVELS} levels of the CPU, mean {:.4}, worst {worst}\n",
            share * 100.0,
            sum / n
        );
        assert!(
            share >= SHARE,
            "{name}: only {:.2}% of pixels within {LEVELS} levels of the CPU reference\n{report}",
            share * 100.0
        );
    }
    println!("{report}");
}

/// Anti-aliasing at the output's size (`--samples N`): N frames, each with its rays moved to
/// one point of an s×s grid in every pixel, averaged in linear light — the mean of the CPU
/// reference's colours at those points; and the edges change from one sample per pixel.
#[test]
fn anti_aliasing_samples_average_the_cpu_reference_at_their_points() {
    use sdfc::images::{Accumulator, Channel, rgba, sample_points};
    let gpu = gpu();
    let scene = compile(&scene("light { direction (-0.6, 1, 0.5)  shadow soft }"));
    let (w, h) = (48, 32);
    let view = View::new(&scene.camera, w, h);
    let (module, _) = emit::module(&scene, Entry::Compute, &Options::from_scene(&scene)).unwrap();
    let n = (w * h) as usize;
    let render = |points: &[[f64; 2]]| {
        let mut sum = Accumulator::new(n, true);
        gpu.render_samples(
            &module,
            &view,
            None,
            points,
            |_, _| {},
            |f| {
                sum.add(&rgba(&f, Channel::Color, scene.trace.steps));
                Ok(())
            },
        )
        .unwrap();
        sum.finish()
    };
    let points = sample_points(9);
    assert_eq!(points.len(), 9);
    let (one, nine) = (render(&sample_points(1)), render(&points));
    let (mut within, mut edges) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let mean = points
                .iter()
                .map(|[px, py]| {
                    pixel::pixel(&scene, &scene.trace, &view, x as f64 + px, y as f64 + py)
                        .clamp(glam::DVec3::ZERO, glam::DVec3::ONE)
                })
                .sum::<glam::DVec3>()
                / points.len() as f64;
            let want = [mean.x, mean.y, mean.z].map(|v| (to_srgb(v) * 255.0).round() as i32);
            if (0..3).all(|k| (nine[4 * i + k] as i32 - want[k]).abs() <= LEVELS) {
                within += 1;
            }
            if (0..3).any(|k| one[4 * i + k].abs_diff(nine[4 * i + k]) > 8) {
                edges += 1;
            }
        }
    }
    let share = within as f64 / n as f64;
    assert!(share >= SHARE, "only {:.2}% of pixels match", share * 100.0);
    assert!(edges > 40, "anti-aliasing changed only {edges} pixels");
    println!(
        "9 samples: {:.2}% within {LEVELS} levels of the CPU; {edges} pixels changed",
        share * 100.0
    );
    // One point off the centre and off every symmetry of the grid, on an image two tiles wide
    // (256-pixel tiles): every pixel's ray passes through (x + 0.1, y + 0.8).
    let (w, h) = (300, 24);
    let view = View::new(&scene.camera, w, h);
    let mut got = Vec::new();
    gpu.render_samples(
        &module,
        &view,
        None,
        &[[0.1, 0.8]],
        |_, _| {},
        |f| {
            got = f.color;
            Ok(())
        },
    )
    .unwrap();
    let within = (0..w * h)
        .filter(|&i| {
            let (x, y) = ((i % w) as f64 + 0.1, (i / w) as f64 + 0.8);
            let c = pixel::pixel(&scene, &scene.trace, &view, x, y);
            off_by(got[i as usize], srgb8(c)) <= LEVELS
        })
        .count();
    let share = within as f64 / (w * h) as f64;
    assert!(
        share >= SHARE,
        "jitter (0.1, 0.8): only {:.2}% match",
        share * 100.0
    );
}

/// Refraction (Keinert §3.3): a glass ball and a diamond-like octahedron in front of a checker
/// floor, against the CPU reference pixel by pixel; their rays really pass through (the
/// picture differs from the same solids opaque), total internal reflection happens inside the
/// octahedron (counted by the reference), and the reference's colours are finite (the GPU's
/// raw colours: `runtime/tests/nan.rs`).
#[test]
fn refraction_through_glass_and_a_gem_matches_the_cpu_reference() {
    let gpu = gpu();
    let source = |glass: &str, gem: &str| {
        format!(
            "camera {{ eye (0, 1.4, -3.2)  target (0, 0.5, 0) }}\n\
             light {{ direction (-0.4, 1, -0.6) }}\n\
             material glass {{ color #f0f6ff  {glass} }}\n\
             material gem {{ color #ffffff  {gem} }}\n\
             material pale {{ color #e8e0d0 }}\n\
             material dark {{ color #202838 }}\n\
             sphere(0.55) at (-0.6, 0.55, 0) : glass\n\
             octahedron(0.7) at (0.7, 0.72, 0.2) : gem\n\
             plane(y, 0) : pale\n\
             repeat((1, 0, 1)) {{ union {{\n\
               box((0.5, 0.02, 0.5)) at (-0.25, 0, -0.25)\n\
               box((0.5, 0.02, 0.5)) at (0.25, 0, 0.25)\n\
             }} }} : dark\n"
        )
    };
    let clear = compile(&source(
        "transparent 0.9  ior 1.5",
        "transparent 0.95  ior 2.42",
    ));
    let opaque = compile(&source("", ""));
    let (w, h) = (96, 64);
    let view = View::new(&clear.camera, w, h);
    let (got, solid) = (render(&gpu, &clear, &view), render(&gpu, &opaque, &view));
    let (mut within, mut differ, mut internal, mut worst) = (0, 0, 0, 0);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let (c, bounces) =
                pixel::pixel_counted(&clear, &clear.trace, &view, x as f64 + 0.5, y as f64 + 0.5);
            assert!(c.is_finite(), "({x}, {y}): {c}");
            internal += (bounces.total_internal > 0) as u32;
            let d = off_by(got.color[i], srgb8(c));
            let px = got.color[i].to_le_bytes();
            worst = worst.max(d);
            within += (d <= LEVELS) as u32;
            let o = solid.color[i].to_le_bytes();
            differ += (0..3).any(|k| o[k].abs_diff(px[k]) > 8) as u32;
        }
    }
    let share = within as f64 / (w * h) as f64;
    println!(
        "refraction: {:.2}% of pixels within {LEVELS} levels of the CPU (worst {worst}); {differ} differ from opaque solids; {internal} pixels with total internal reflection",
        share * 100.0
    );
    assert!(share >= SHARE, "only {:.2}% match", share * 100.0);
    assert!(differ > 300, "only {differ} pixels see through the solids");
    assert!(
        internal > 50,
        "only {internal} pixels reflect totally inside the gem"
    );
}

/// Every shading feature at once (soft shadows, occlusion, fog, a mirror, a glass ball) on the
/// extremes suite's scene scaled from 1e-4 to 1e4: the CPU reference's colours are finite and
/// the GPU's agree with them on 97% of the pixels at least (the rest are left to f32 against
/// f64; the GPU's raw colours are checked finite in `runtime/tests/nan.rs`).
#[test]
fn every_feature_stays_finite_at_every_scale() {
    let gpu = gpu();
    let mut report = String::new();
    for s in [1e-4, 1e-2, 1.0, 1e2, 1e4] {
        let source = every_feature_scene(s, "", EXTREMES_BASE);
        let scene = compile(&source);
        let (w, h) = (64, 40);
        let view = View::new(&scene.camera, w, h);
        let frame = render(&gpu, &scene, &view);
        let mut within = 0;
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                let c = pixel::pixel(&scene, &scene.trace, &view, x as f64 + 0.5, y as f64 + 0.5);
                assert!(c.is_finite(), "× {s:e}, ({x}, {y}): {c}");
                within += (off_by(frame.color[i], srgb8(c)) <= LEVELS) as u32;
            }
        }
        let share = within as f64 / (w * h) as f64;
        report += &format!("× {s:e}: {:.2}% within {LEVELS} levels\n", share * 100.0);
        assert!(
            share >= 0.97,
            "× {s:e}: only {:.2}% agree\n{report}",
            share * 100.0
        );
    }
    println!("{report}");
}

/// The compute entry counts shading's evaluations of the field (`Frame::shading`, what `sdfc
/// bench` reports as "+shading"): without shadows, occlusion or secondary rays, exactly the
/// normal's four and the material's one at every hit and none at a miss; occlusion adds its
/// samples at every hit; a shadowing light and a mirror add more.
#[test]
fn shading_counts_its_evaluations() {
    let gpu = gpu();
    let (w, h) = (48, 32);
    let run = |extra: &str| {
        let scene = compile(&scene(extra));
        render(&gpu, &scene, &View::new(&scene.camera, w, h))
    };
    let light = "light { direction (-0.6, 1, 0.5) }";
    let plain = run(light);
    for (d, &e) in plain.depth.iter().zip(&plain.shading) {
        assert_eq!(e, if *d >= 0.0 { 5 } else { 0 });
    }
    let occluded = run(&format!("{light}\nocclusion {{ samples 6 }}"));
    for (d, &e) in occluded.depth.iter().zip(&occluded.shading) {
        assert_eq!(e, if *d >= 0.0 { 11 } else { 0 });
    }
    let mean = |f: &sdfc::gpu::Frame| f.shading.iter().sum::<u32>() as f64 / (w * h) as f64;
    let shadowed = run("light { direction (-0.6, 1, 0.5)  shadow hard }");
    let mirrored = run(&format!(
        "{light}\nmaterial chrome {{ reflect 0.8 }}\nsphere(0.45) at (-0.6, 0.45, -0.9) : chrome"
    ));
    assert!(
        mean(&shadowed) > mean(&plain) + 5.0,
        "{} {}",
        mean(&shadowed),
        mean(&plain)
    );
    // Every mirror pixel: the normal and material (5), the lift off the surface (1), at least
    // one step of the reflected ray (1), and where that ray hits, its normal and material (5).
    let chrome = 3; // after red and floor
    let mirror: Vec<u32> = (0..mirrored.shading.len())
        .filter(|&i| mirrored.material[i] == chrome)
        .map(|i| mirrored.shading[i])
        .collect();
    assert!(mirror.len() > 50, "{} mirror pixels", mirror.len());
    assert!(mirror.iter().all(|&e| e >= 7), "{mirror:?}");
    assert!(
        mirror.iter().filter(|&&e| e >= 12).count() > mirror.len() / 2,
        "{mirror:?}"
    );
}
