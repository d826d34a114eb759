//! Procedural textures on the GPU against the f64 reference (`sdfc_compiler::reference::texture`,
//! `sdfc_compiler::reference::shading::albedo`), pixel by pixel in 8-bit sRGB.

use crate::common::{compile, gpu, off_by, render, srgb8};
use sdfc_compiler::reference::pixel;
use sdfc_compiler::view::View;

/// Most 8-bit levels a channel may differ by (f32 against f64).
const LEVELS: i32 = 2;

/// Procedural textures (Liktor §4): every pattern — a solid checker, triplanar tiles on a
/// turned box touching an untagged one, noise, turbulence, marble and wood on turned and moved
/// shapes (each material given to the shape before it is transformed, so that its pattern is
/// evaluated in the shape's own coordinates) — against the CPU reference pixel by pixel; and
/// each pattern shows (the picture differs from the same scene with plain colours).
#[test]
fn procedural_textures_match_the_cpu_reference() {
    let gpu = gpu();
    let source = |patterns: bool| {
        let color = |pattern: &str, plain: &str| {
            if patterns {
                pattern.to_string()
            } else {
                plain.to_string()
            }
        };
        format!(
            "camera {{ eye (0, 3, -7)  target (0, 0.5, 0) }}\n\
             light {{ direction (-0.4, 1, -0.5) }}\n\
             material chk {{ color {} }}\n\
             material tile {{ color {} }}\n\
             material nz {{ color {} }}\n\
             material tb {{ color {} }}\n\
             material mb {{ color {} }}\n\
             material wd {{ color {} }}\n\
             union {{\n\
               (box((1.2, 1.2, 1.2)) : tile) |> rotate(y, 30deg) at (-2.2, 0.6, 0)\n\
               box((0.5, 0.5, 0.5)) at (-1.5, 0.25, -0.9)\n\
               (sphere(0.7) : mb) |> rotate(z, 35deg) at (0, 0.7, 0)\n\
               (cylinder(0.6, 1.4) : wd) |> rotate(z, 20deg) at (2.2, 0.7, 0)\n\
               sphere(0.5) at (-1.1, 0.5, -1.8) : nz\n\
               sphere(0.5) at (1.1, 0.5, -1.8) : tb\n\
               plane(y, 0) : chk\n\
             }}\n",
            color("checker(#f0f0f0, #303848, 0.5)", "#f0f0f0"),
            color("tiles(#e0d0b0, #804020, 0.25)", "#e0d0b0"),
            color("noise(#203040, #c0d0e0, 0.3, 5)", "#203040"),
            color("turbulence(#ffffff, #402010, 0.5, 5)", "#ffffff"),
            color("marble(#f4f0ea, #405060, 0.8, 5)", "#f4f0ea"),
            color("wood(#c08040, #603010, 0.15, 3)", "#c08040"),
        )
    };
    let (textured, plain) = (compile(&source(true)), compile(&source(false)));
    let view = View::new(&textured.camera, 128, 80);
    let (got, flat) = (render(&gpu, &textured, &view), render(&gpu, &plain, &view));
    let mut shows = [0u32; 7];
    let (mut within, mut worst) = (0, 0);
    for i in 0..got.color.len() {
        let (x, y) = (
            (i as u32 % view.width) as f64 + 0.5,
            (i as u32 / view.width) as f64 + 0.5,
        );
        let c = pixel::pixel(&textured, &textured.trace, &view, x, y);
        let d = off_by(got.color[i], srgb8(c));
        worst = worst.max(d);
        within += (d <= LEVELS) as u32;
        let (a, b) = (got.color[i].to_le_bytes(), flat.color[i].to_le_bytes());
        if (0..3).any(|k| a[k].abs_diff(b[k]) > 8) {
            shows[got.material[i] as usize] += 1;
        }
    }
    let share = within as f64 / got.color.len() as f64;
    println!(
        "textures: {:.2}% within {LEVELS} levels of the CPU (worst {worst}); pixels changed per material {shows:?}",
        share * 100.0
    );
    assert!(share >= 0.999, "only {:.2}% match", share * 100.0);
    for (m, &n) in shows.iter().enumerate().skip(1) {
        assert!(n > 20, "material {m}'s pattern changes only {n} pixels");
    }
}
