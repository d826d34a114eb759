//! Shading on the GPU against the f64 CPU reference shader (`sdfc_compiler::shading`), one
//! scene per feature: the same rays, the same formulas, compared per pixel in 8-bit sRGB.

mod common;

use common::{compile, gpu};
use sdfc_compiler::color::to_srgb;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::shading;
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
        let (module, _) = emit::module(&scene, Entry::Compute, &Options::from_scene(&scene))
            .unwrap_or_else(|e| panic!("{name}: {}", e.0));
        let frame = gpu.render(&module, &view, None, |_, _| {}).unwrap();
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
                let c = shading::pixel(&scene, &scene.trace, &view, x as f64 + 0.5, y as f64 + 0.5);
                let want =
                    [c.x, c.y, c.z].map(|v| (to_srgb(v.clamp(0.0, 1.0)) * 255.0).round() as i32);
                let got = frame.color[i].to_le_bytes();
                let diff = (0..3)
                    .map(|k| (got[k] as i32 - want[k]).abs())
                    .max()
                    .unwrap();
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
                    shading::pixel(&scene, &scene.trace, &view, x as f64 + px, y as f64 + py)
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
}
