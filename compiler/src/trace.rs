//! The CPU reference tracer in f64: the same rays, hit condition and step counting as the
//! shader's `trace_basic`, for checking the GPU and as ground truth.

use crate::eval;
use crate::lower::tracer::EPSILON_FLOOR;
use crate::scene::{Epsilon, Scene, Trace};
use glam::DVec3;

/// Where a ray went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Traced {
    /// Distance along the ray where it stopped.
    pub t: f64,
    /// Evaluations of the field.
    pub steps: u32,
    /// Whether f < ε was reached.
    pub hit: bool,
}

/// Basic sphere tracing (Hart; Bálint Alg. 1): t += f/λ until f < ε(t), t > t_max or the budget
/// runs out; every evaluation counts. `pixel` is the footprint per unit distance for ε `pixel`.
pub fn basic(scene: &Scene, trace: &Trace, ro: DVec3, rd: DVec3, pixel: f64) -> Traced {
    let floor = EPSILON_FLOOR * (scene.camera.eye - scene.camera.target).length();
    let mut t = 0.0;
    let mut steps = 0;
    while steps < trace.steps {
        let d = eval::distance(scene, ro + rd * t);
        steps += 1;
        let eps = match trace.epsilon {
            Epsilon::Pixel => (pixel * t).max(floor),
            Epsilon::Absolute(e) => e,
        };
        if d < eps {
            return Traced {
                t,
                steps,
                hit: true,
            };
        }
        t += d;
        if t > trace.max_distance {
            break;
        }
    }
    Traced {
        t,
        steps,
        hit: false,
    }
}
