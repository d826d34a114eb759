//! Materials through smooth operators (`sdfc_compiler::reference::blend`): the GPU's blended colours
//! against the f64 reference pixel by pixel, and the colour continuous across a seam.

use crate::common::{compile, gpu, off_by, render, srgb8};
use sdfc_compiler::reference::pixel;
use sdfc_compiler::view::View;

/// A smooth union of two spheres and a box (three materials), a smooth intersection and a
/// smooth subtraction of two tagged shapes, a `mix` of a tagged ball and box, and a part of a
/// blend with no material of its own under an outer tag.
const SCENE: &str = "camera { eye (0, 2.2, -6)  target (0, 0.6, 0) }\n\
     light { direction (-0.4, 1, -0.5) }\n\
     material red   { color #d03020  specular 0.6 }\n\
     material blue  { color #2050d0 }\n\
     material gold  { color #d0a030 }\n\
     material green { color #30a050  specular 0.3 }\n\
     smooth_union(0.6) {\n\
       sphere(0.6) at (-0.5, 0.6, 0) : red\n\
       sphere(0.6) at (0.5, 0.6, 0) : blue\n\
       box(0.4) at (0, 1.3, 0) : gold\n\
     }\n\
     smooth_intersect(0.3) { sphere(0.7) at (2.2, 0.6, 0) : green  box(1) at (2.2, 0.6, 0) : red }\n\
     smooth_subtract(0.3) { box(1) at (-2.2, 0.5, 0) : gold  sphere(0.5) at (-2.2, 0.9, -0.4) : blue }\n\
     mix(0.35) { sphere(0.35) at (-1, 0.35, -1.6) : red  box(0.6) at (-1, 0.35, -1.6) : green }\n\
     smooth_union(0.4) { sphere(0.3) at (1, 0.3, -1.6) : blue  box(0.4) at (1.5, 0.2, -1.6) } : gold\n\
     plane(y, 0)\n";

#[test]
fn blended_materials_match_the_cpu_reference() {
    let gpu = gpu();
    let scene = compile(SCENE);
    let view = View::new(&scene.camera, 128, 72);
    let frame = render(&gpu, &scene, &view);
    let (mut within, mut worst, mut blended) = (0, 0, 0);
    for i in 0..frame.color.len() {
        let (x, y) = (
            (i as u32 % view.width) as f64 + 0.5,
            (i as u32 / view.width) as f64 + 0.5,
        );
        let c = pixel::pixel(&scene, &scene.trace, &view, x, y);
        let d = off_by(frame.color[i], srgb8(c));
        worst = worst.max(d);
        within += (d <= 2) as u32;
        if frame.depth[i] >= 0.0 {
            let p = view.eye + view.ray(x, y) * frame.depth[i] as f64;
            let bl = sdfc_compiler::reference::eval::blend(&scene, p);
            blended += (bl.t > 0.05 && bl.t < 0.95 && bl.a != bl.b) as u32;
        }
    }
    let share = within as f64 / frame.color.len() as f64;
    println!(
        "blends: {:.2}% within 2 levels of the CPU (worst {worst}); {blended} pixels blend two materials",
        share * 100.0
    );
    assert!(share >= 0.999, "only {:.2}% match", share * 100.0);
    assert!(blended > 200, "only {blended} pixels blend");
}

/// Across the seam of a smooth union of a red and a blue ball the colour changes by small
/// steps from pixel to pixel — no hard edge — while it goes from red to blue in all.
#[test]
fn a_seam_changes_colour_gradually() {
    let scene = compile(
        "camera { eye (0, 0.6, -4)  target (0, 0.6, 0) }\n\
         light { direction (0, 0, -1) }\n\
         material red  { color #ff0000 }\n\
         material blue { color #0000ff }\n\
         smooth_union(0.8) { sphere(0.6) at (-0.55, 0.6, 0) : red  sphere(0.6) at (0.55, 0.6, 0) : blue }\n",
    );
    let view = View::new(&scene.camera, 400, 400);
    // Along the middle row: red and blue components of the shaded colour, hits only.
    let row: Vec<glam::DVec3> = (0..view.width)
        .map(|x| pixel::pixel(&scene, &scene.trace, &view, x as f64 + 0.5, 200.5))
        .collect();
    let hits: Vec<glam::DVec3> = row.into_iter().filter(|c| c.x + c.z > 0.05).collect();
    // The share of red in the colour (the hue, whatever the lighting).
    let red: Vec<f64> = hits.iter().map(|c| c.x / (c.x + c.z)).collect();
    // (+x is to the left of the picture: blue first.)
    let (first, last) = (red[0], red[red.len() - 1]);
    assert!(first < 0.05 && last > 0.95, "{first} … {last}");
    let biggest = red
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f64::max);
    assert!(
        biggest < 0.05,
        "a step of {biggest} between neighbouring pixels: {red:.3?}"
    );
    assert!(red.len() > 100, "{} pixels", red.len());
    println!(
        "largest step of the red share between neighbours: {biggest:.4} over {} pixels",
        red.len()
    );
}
