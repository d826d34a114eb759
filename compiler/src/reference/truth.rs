//! The ground truth the benchmarks measure against (Bálint & Valasek §5): basic sphere tracing
//! in f64 with 10 000 steps and a hit threshold far below any tracer's, refined by bisection
//! across the surface.

use crate::reference::eval;
use crate::reference::trace;
use crate::scene::{Method, Scene};
use crate::view::View;
use glam::DVec3;

/// Steps of the ground truth's basic tracing.
pub const STEPS: u32 = 10_000;

/// Its hit threshold, relative to the camera's distance from its target.
pub const EPSILON: f64 = 1e-7;

/// Bisection iterations at the hit.
pub const BISECTIONS: u32 = 60;

/// The distance along `ro + t·rd` to the first surface, or `None` if the ray escapes (or the
/// 10 000 steps run out first). The truth traces every ray from the camera, whatever `bound`
/// the scene declares, with no f32 floor on ε.
pub fn depth(scene: &Scene, ro: DVec3, rd: DVec3) -> Option<f64> {
    let scale = (scene.camera.eye - scene.camera.target).length();
    let mut t = scene.trace;
    t.method = Method::Basic;
    t.steps = STEPS;
    t.discontinuity = 0;
    t.antialias = false;
    let r = trace::ray_exact(scene, &t, EPSILON * scale, ro, rd);
    if !r.hit {
        return None;
    }
    let f = |t: f64| eval::distance(scene, ro + rd * t);
    // Basic tracing stops outside, within ε of the surface: look for a point inside just
    // beyond, then bisect between the two.
    let mut lo = r.t;
    if f(lo) <= 0.0 {
        return Some(lo);
    }
    let mut step = EPSILON * scale;
    let mut hi = lo + step;
    let mut tries = 0;
    while f(hi) > 0.0 {
        tries += 1;
        if tries > 20 {
            // The ray passed within ε without crossing (a silhouette): keep the traced point.
            return Some(r.t);
        }
        lo = hi;
        step *= 2.0;
        hi = lo + step;
    }
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The ground-truth depth of every pixel of `view` (row by row), on all cores.
pub fn depth_map(scene: &Scene, view: &View) -> Vec<Option<f64>> {
    let w = view.width as usize;
    let pixels: Vec<usize> = (0..w * view.height as usize).collect();
    crate::parallel::par_map(&pixels, |&i| {
        let rd = view.ray((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
        depth(scene, view.eye, rd)
    })
}
