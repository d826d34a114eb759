//! Multi-resolution rendering (Bálint §4): the pass schedules, each pass's size, budget and cone
//! slope, and the CPU reference of a whole multi-pass image, which the runtime's passes mirror.

use crate::reference::trace::{self, Segment, Traced};
use crate::scene::Scene;
use crate::view::View;

/// The schedules from Bálint §5: (resolution relative to the image, share of the step budget)
/// per pass. Two passes put 1/8 of the budget into a half-resolution pass; four use 1/4, 1/2,
/// 3/4 and full resolution with 1/8, 1/8, 1/8, 5/8. The paper's six-pass split lists five
/// shares (1/8 four times, 3/8) for six resolutions; we read it as 1/8 five times and 3/8.
pub const SCHEDULES: &[&[(f64, f64)]] = &[
    &[(1.0, 1.0)],
    &[(0.5, 0.125), (1.0, 0.875)],
    &[(0.25, 0.125), (0.5, 0.125), (0.75, 0.125), (1.0, 0.625)],
    &[
        (1.0 / 6.0, 0.125),
        (1.0 / 3.0, 0.125),
        (0.5, 0.125),
        (2.0 / 3.0, 0.125),
        (5.0 / 6.0, 0.125),
        (1.0, 0.375),
    ],
];

/// The numbers of passes there are schedules for.
pub fn counts() -> Vec<usize> {
    SCHEDULES.iter().map(|s| s.len()).collect()
}

/// One pass of a render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pass {
    /// The camera at this pass's resolution.
    pub view: View,
    /// Evaluations this pass may spend per pixel.
    pub budget: u32,
    /// The cone slope α: half the diagonal of one of this pass's pixels per unit distance along
    /// the view direction (rays off the axis are closer together), so each ray of the next
    /// pass, which goes through the footprint of its nearest pixel here, stays inside the
    /// cone; plus the next pass's own cone, so that its whole cone stays inside this one (with
    /// more than two passes a pixel's nearest coarse pixel two passes back may not contain it:
    /// Bálint §4 uses each pass's own pixel size, which the tests showed can skip a surface).
    /// 0 in the last pass. Every pass's view covers the same image rectangle.
    pub cone: f64,
}

/// The passes of a `width`×`height` render with `count` passes and a total budget of `steps`
/// per pixel, or `None` if there is no schedule with that many passes. Every pass gets at
/// least one step; the last gets what the others leave.
pub fn plan(scene: &Scene, width: u32, height: u32, steps: u32, count: usize) -> Option<Vec<Pass>> {
    let schedule = SCHEDULES.iter().find(|s| s.len() == count)?;
    let full = View::new(&scene.camera, width, height);
    let mut left = steps;
    let n = schedule.len();
    let mut passes: Vec<Pass> = schedule
        .iter()
        .enumerate()
        .map(|(i, &(scale, share))| {
            let last = i + 1 == n;
            let w = ((width as f64 * scale).ceil() as u32).clamp(1, width);
            let h = ((height as f64 * scale).ceil() as u32).clamp(1, height);
            let view = full.resized(w, h);
            let budget = if last {
                left.max(1)
            } else {
                ((steps as f64 * share).round() as u32).clamp(1, left.saturating_sub(1).max(1))
            };
            left = left.saturating_sub(budget);
            Pass {
                view,
                budget,
                cone: if last {
                    0.0
                } else {
                    full.half_pixel(w, h).length()
                },
            }
        })
        .collect();
    // Nest the cones: a pass's cone must hold the next pass's whole cone, not only its rays.
    for k in (0..n.saturating_sub(2)).rev() {
        passes[k].cone += passes[k + 1].cone;
    }
    Some(passes)
}

/// The nearest pixel of a `from_w`×`from_h` pass to the centre of pixel (x, y) of a
/// `to_w`×`to_h` one, as the shader finds it (floor of the scaled centre, clamped) for rays
/// through pixel centres (`View::jitter` (0.5, 0.5); an anti-aliasing sample's jittered point
/// lies in the same pixel, whose coarse pixel it also finds).
pub fn nearest(
    x: u32,
    y: u32,
    (to_w, to_h): (u32, u32),
    (from_w, from_h): (u32, u32),
) -> (u32, u32) {
    let q = |c: u32, to: u32, from: u32| {
        let v = ((c as f64 + 0.5) * from as f64 / to as f64).floor();
        (v.min(from as f64 - 1.0).max(0.0)) as u32
    };
    (q(x, to_w, from_w), q(y, to_h, from_h))
}

/// The CPU reference of a multi-pass render: each pass traces its pixels from the t the
/// previous pass reached at the nearest pixel, with its budget and cone; returns the last
/// pass's results (row by row) with the steps of every pass along the way added up, and the
/// evaluations all passes spent together (the work: a coarse pixel's steps count once).
pub fn trace_image(scene: &Scene, passes: &[Pass]) -> (Vec<Traced>, u64) {
    let mut previous: Option<(Vec<Traced>, u32, u32)> = None;
    let mut work = 0;
    for pass in passes {
        let v = pass.view;
        let mut here = Vec::with_capacity(v.width as usize * v.height as usize);
        for y in 0..v.height {
            for x in 0..v.width {
                let (start, before) = match &previous {
                    Some((prev, pw, ph)) => {
                        let (qx, qy) = nearest(x, y, (v.width, v.height), (*pw, *ph));
                        let p = prev[(qy * pw + qx) as usize];
                        (p.t, p.steps)
                    }
                    None => (0.0, 0),
                };
                let segment = Segment {
                    start,
                    end: scene.trace.max_distance,
                    budget: pass.budget,
                    cone: pass.cone,
                };
                let rd = v.ray(x as f64 + 0.5, y as f64 + 0.5);
                let mut r = trace::ray_segment(scene, &scene.trace, v.eye, rd, v.pixel, segment);
                work += r.steps as u64;
                r.steps += before;
                here.push(r);
            }
        }
        previous = Some((here, v.width, v.height));
    }
    (previous.map(|p| p.0).unwrap_or_default(), work)
}
