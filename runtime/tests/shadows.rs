//! Shadow rays against an analytic shadow: no acne and no leaks with Keinert's dynamic offset
//! (§3.3), and how much acne a fixed offset gives.

use crate::common::{compile, gpu};
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::view::View;

/// Whether the ray `o + s·d` (s > 0) passes through the box `centre ± half` (slab test).
fn ray_meets_box(o: glam::DVec3, d: glam::DVec3, centre: glam::DVec3, half: glam::DVec3) -> bool {
    let (mut near, mut far) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        let (lo, hi) = (centre[k] - half[k], centre[k] + half[k]);
        if d[k].abs() < 1e-12 {
            if o[k] < lo || o[k] > hi {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo - o[k]) / d[k], (hi - o[k]) / d[k]);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    near <= far
}

/// Shadow acne and leaks (Keinert §3.3): a light grazing a floor (14°) and a wall 0.04 thick.
/// Against the analytic shadow of the box, every floor pixel clearly lit is lit and every one
/// clearly in the wall's shadow is dark with ε_dynamic = 2·max(h, |f(p)|); starting shadow rays
/// a fixed 2·ε_floor off the surface instead (`--fixed-offset`) darkens lit floor (acne) — the
/// count is printed.
#[test]
fn shadows_have_no_acne_and_no_leaks_with_the_dynamic_offset() {
    use glam::DVec3;
    let gpu = gpu();
    let (centre, half) = (DVec3::new(0.0, 0.4, 0.0), DVec3::new(0.02, 0.4, 1.5));
    let scene = |shadow: &str| {
        compile(&format!(
            "camera {{ eye (3, 2.2, -4)  target (0.8, 0, 0) }}\n\
             light {{ direction (-1, 0.25, 0.2)  {shadow} }}\n\
             union {{ plane(y, 0)  box((0.04, 0.8, 3)) at (0, 0.4, 0) }}\n"
        ))
    };
    let (w, h) = (128, 80);
    let (lit, shadowed) = (scene(""), scene("shadow hard"));
    let view = View::new(&lit.camera, w, h);
    let frame = |s: &sdfc_compiler::scene::Scene, fixed: bool| {
        let mut options = Options::from_scene(s);
        options.fixed_offset = fixed;
        let (module, _) = emit::module(s, Entry::Compute, &options).unwrap();
        gpu.render(&module, &view, None, |_, _| {}).unwrap()
    };
    let plain = frame(&lit, false);
    let luma = |c: u32| c.to_le_bytes()[..3].iter().map(|&v| v as i32).sum::<i32>();
    let l = DVec3::new(-1.0, 0.25, 0.2).normalize();
    let margin = DVec3::splat(0.05);
    let count = |fixed: bool| {
        let f = frame(&shadowed, fixed);
        let (mut acne, mut leaks, mut sure_lit, mut sure_dark) = (0, 0, 0, 0);
        for i in 0..(w * h) as usize {
            if plain.depth[i] < 0.0 {
                continue;
            }
            let (x, y) = ((i as u32 % w) as f64 + 0.5, (i as u32 / w) as f64 + 0.5);
            let p = view.eye + view.ray(x, y) * plain.depth[i] as f64;
            if p.y > 0.01 || (p.x.abs() < 0.1 && p.z.abs() < 1.6) {
                continue; // the wall, or the floor at its foot
            }
            let dark = luma(f.color[i]) < luma(plain.color[i]) - 30;
            if !ray_meets_box(p, l, centre, half + margin) {
                sure_lit += 1;
                acne += dark as u32;
            } else if ray_meets_box(p, l, centre, half - DVec3::new(0.0, 0.05, 0.05)) {
                sure_dark += 1;
                leaks += !dark as u32;
            }
        }
        (acne, leaks, sure_lit, sure_dark)
    };
    let (acne, leaks, sure_lit, sure_dark) = count(false);
    let (fixed_acne, fixed_leaks, _, _) = count(true);
    println!(
        "dynamic ε: {acne} acne and {leaks} leaking pixels (of {sure_lit} lit, {sure_dark} shadowed floor pixels); fixed 2·ε_floor: {fixed_acne} acne, {fixed_leaks} leaking"
    );
    assert!(sure_lit > 300 && sure_dark > 200, "{sure_lit} {sure_dark}");
    assert_eq!((acne, leaks), (0, 0));
    assert!(
        fixed_acne > 0,
        "the fixed offset shows no acne: the test cannot tell them apart"
    );
}
