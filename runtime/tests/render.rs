//! Rendering for real on the machine's (software) GPU: every example's hit mask and depth
//! against the f64 CPU reference tracer on the same rays, and Vulkan against GL.

use crate::common::{examples, gpu, own_gpu, render};
use sdfc::gpu::{BackendChoice, Frame};
use sdfc_compiler::reference::trace::{self, Traced};
use sdfc_compiler::scene::{Epsilon, Scene};
use sdfc_compiler::view::View;
use std::path::PathBuf;

const W: u32 = 96;
const H: u32 = 64;

fn scene(path: &PathBuf) -> Scene {
    let source = std::fs::read_to_string(path).unwrap();
    sdfc_compiler::check::compile(&source)
        .scene
        .expect("example compiles")
}

/// The CPU reference on the shader's rays (pixel centres).
fn reference(scene: &Scene, view: &View) -> Vec<Traced> {
    let mut out = Vec::with_capacity((view.width * view.height) as usize);
    for y in 0..view.height {
        for x in 0..view.width {
            let rd = view.ray(x as f64 + 0.5, y as f64 + 0.5);
            out.push(trace::ray(scene, &scene.trace, view.eye, rd, view.pixel));
        }
    }
    out
}

/// `#` both hit, `.` both miss, `G` only the GPU hit, `C` only the CPU hit.
fn ascii_diff(frame: &Frame, cpu: &[Traced]) -> String {
    let mut s = String::new();
    for y in 0..frame.height {
        for x in 0..frame.width {
            let i = (y * frame.width + x) as usize;
            s.push(match (frame.depth[i] >= 0.0, cpu[i].hit) {
                (true, true) => '#',
                (false, false) => '.',
                (true, false) => 'G',
                (false, true) => 'C',
            });
        }
        s.push('\n');
    }
    s
}

#[test]
fn every_example_matches_the_cpu_reference() {
    let gpu = gpu();
    let mut report = String::new();
    for path in examples() {
        let scene = scene(&path);
        let view = View::new(&scene.camera, W, H);
        let frame = render(&gpu, &scene, &view);
        let cpu = reference(&scene, &view);
        let n = cpu.len();
        let same = (0..n)
            .filter(|&i| (frame.depth[i] >= 0.0) == cpu[i].hit)
            .count();
        let share = same as f64 / n as f64;
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        assert!(
            share >= 0.995,
            "{name}: hit masks agree on {:.2}% of pixels\n{}",
            share * 100.0,
            ascii_diff(&frame, &cpu)
        );
        // Depth where both hit: within the hit threshold, allowing for the ray's angle to the
        // surface (a grazing ray stops further along for the same field value).
        let (mut both, mut close, mut worst) = (0, 0, 0.0f64);
        for (c, &g) in cpu.iter().zip(&frame.depth) {
            if g < 0.0 || !c.hit {
                continue;
            }
            both += 1;
            let t = c.t;
            let eps = match scene.trace.epsilon {
                Epsilon::Pixel => {
                    (view.pixel * t).max(1e-5 * (scene.camera.eye - scene.camera.target).length())
                }
                Epsilon::Absolute(e) => e,
            };
            let dt = (g as f64 - t).abs();
            worst = worst.max(dt / t.max(1e-9));
            if dt <= 4.0 * eps + 2e-6 * t {
                close += 1;
            }
        }
        let depth_share = close as f64 / both.max(1) as f64;
        report += &format!(
            "{name}: masks {:.2}%, depth within 4ε on {:.2}% of {both} hits, worst |Δt|/t {worst:.2e}\n",
            share * 100.0,
            depth_share * 100.0
        );
        assert!(
            depth_share >= 0.99,
            "{name}: depth within 4ε on only {:.2}% of pixels",
            depth_share * 100.0
        );
        assert!(
            frame.depth.iter().all(|d| d.is_finite())
                && frame.normal.iter().flatten().all(|c| c.is_finite()),
            "{name}: a depth or normal is not finite"
        );
    }
    println!("{report}");
}

#[test]
fn vulkan_and_gl_give_the_same_image() {
    let (vk, gl) = (gpu(), own_gpu(BackendChoice::Gl));
    for path in examples() {
        let scene = scene(&path);
        let view = View::new(&scene.camera, W, H);
        let (a, b) = (render(&vk, &scene, &view), render(&gl, &scene, &view));
        let close = a
            .color
            .iter()
            .zip(&b.color)
            .filter(|(x, y)| {
                x.to_le_bytes()
                    .iter()
                    .zip(y.to_le_bytes())
                    .all(|(p, q)| p.abs_diff(q) <= 1)
            })
            .count();
        let share = close as f64 / a.color.len() as f64;
        assert!(
            share >= 0.999,
            "{}: Vulkan and GL agree within 1/255 on {:.2}%",
            path.display(),
            share * 100.0
        );
    }
}

#[test]
fn a_render_splits_into_tiles_without_seams() {
    // 300×200 needs 2×1 tiles of 256: the tiled image equals the CPU reference mask too.
    let gpu = gpu();
    let scene = scene(
        &examples()
            .into_iter()
            .find(|p| p.ends_with("jewel.sdf"))
            .unwrap(),
    );
    let view = View::new(&scene.camera, 300, 200);
    let frame = render(&gpu, &scene, &view);
    let cpu = reference(&scene, &view);
    let same = (0..cpu.len())
        .filter(|&i| (frame.depth[i] >= 0.0) == cpu[i].hit)
        .count();
    assert!(same as f64 / cpu.len() as f64 >= 0.995);
}

/// Colour is sRGB in, linear in between, sRGB out: a pixel that shows the background has the
/// background's bytes as written (`#202030` → 32, 32, 48), and a face lit head-on by a white
/// light is its colour decoded, lit (ambient + 1) and encoded again — 135 for `#808080`, where
/// lighting the encoded value as if it were linear gave 143.
#[test]
fn the_background_comes_out_as_written() {
    let gpu = gpu();
    let scene = scene(
        &examples()
            .into_iter()
            .find(|p| p.ends_with("composition.sdf"))
            .unwrap(),
    );
    let view = View::new(&scene.camera, W, H);
    let frame = render(&gpu, &scene, &view);
    // The top row looks at the sky above the colonnade.
    let misses: Vec<[u8; 4]> = (0..W as usize)
        .filter(|&i| frame.depth[i] < 0.0)
        .map(|i| frame.color[i].to_le_bytes())
        .collect();
    assert!(!misses.is_empty());
    for px in misses {
        assert_eq!(px, [0x20, 0x20, 0x30, 255]);
    }
}

#[test]
fn a_lit_colour_is_lit_in_linear_light() {
    let gpu = gpu();
    let scene = sdfc_compiler::check::compile(
        "camera { eye (0, 0, -5)  target (0, 0, 0) }\n\
         light { direction (0, 0, -1)  color #fff }\n\
         material grey { color #808080 }\n\
         box(4) : grey\n",
    )
    .scene
    .unwrap();
    let view = View::new(&scene.camera, W, H);
    let frame = render(&gpu, &scene, &view);
    let centre = (H / 2 * W + W / 2) as usize;
    assert!(frame.depth[centre] > 0.0, "the face is hit");
    use sdfc_compiler::color::{to_linear, to_srgb};
    let lit = to_linear(128.0 / 255.0) * (sdfc_compiler::reference::shading::AMBIENT + 1.0);
    let want = (to_srgb(lit) * 255.0).round() as i32;
    assert_eq!(want, 135);
    let px = frame.color[centre].to_le_bytes();
    for c in &px[..3] {
        assert!((*c as i32 - want).abs() <= 1, "{px:?}, want {want}");
    }
}

/// Shadows (Munini §2.3; Keinert §3.3 for the ray's start): the floor in a sphere's shadow
/// is darker with `shadow hard` than without, the floor far from it and the sphere's own
/// lit side are the same (no self-shadowing: the ray starts 2·max(h, |f(p)|) off the surface),
/// and `shadow soft` lies in between under the sphere's rim.
#[test]
fn shadows_darken_what_is_hidden_and_nothing_else() {
    let gpu = gpu();
    let frame = |shadow: &str| {
        let scene = sdfc_compiler::check::compile(&format!(
            "camera {{ eye (0, 4, -6)  target (0, 0.5, 0) }}\n\
             light {{ direction (0.3, 1, 0.8)  {shadow} }}\n\
             union {{ sphere(0.8) at (0, 1.5, 0)  plane(y, 0) }}\n"
        ))
        .scene
        .unwrap();
        let view = View::new(&scene.camera, 96, 64);
        (render(&gpu, &scene, &view), view, scene)
    };
    let (none, view, scene) = frame("");
    let (hard, _, _) = frame("shadow hard");
    let (soft, _, _) = frame("shadow soft  softness 4");
    let luma = |f: &Frame, i: usize| {
        f.color[i].to_le_bytes()[..3]
            .iter()
            .map(|&c| c as u32)
            .sum::<u32>()
    };
    // Classify each hit pixel by where its point is: on the floor under the sphere, on the
    // floor far from it, or on the sphere's upper half.
    let (mut under, mut far, mut top) = (0, 0, 0);
    for y in 0..view.height {
        for x in 0..view.width {
            let i = (y * view.width + x) as usize;
            if none.depth[i] < 0.0 {
                continue;
            }
            let p = view.eye + view.ray(x as f64 + 0.5, y as f64 + 0.5) * none.depth[i] as f64;
            let on_floor = p.y < 0.3;
            // The shadow's centre: the sphere's centre moved down along the light to the floor.
            let r = ((p.x + 0.45).powi(2) + (p.z + 1.2).powi(2)).sqrt();
            if on_floor && r < 0.4 {
                under += 1;
                assert!(
                    luma(&hard, i) + 30 < luma(&none, i),
                    "({x}, {y}) under the sphere is lit"
                );
                assert!(luma(&soft, i) <= luma(&none, i));
            } else if on_floor && r > 2.0 {
                far += 1;
                assert!(
                    luma(&hard, i).abs_diff(luma(&none, i)) <= 3,
                    "({x}, {y}) far away"
                );
            } else if !on_floor && p.y > 1.6 {
                top += 1;
                assert!(
                    luma(&hard, i).abs_diff(luma(&none, i)) <= 3,
                    "({x}, {y}) shadows itself"
                );
            }
        }
    }
    assert!(under > 20 && far > 100 && top > 20, "{under} {far} {top}");
    let _ = scene;
}
