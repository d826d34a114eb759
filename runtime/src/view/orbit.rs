//! The viewer's orbit camera: turning around the target, panning, zooming — pure camera
//! math, tested apart from any window.

use glam::DVec3;
use sdfc_compiler::scene::Camera;

/// Degrees the camera turns per pixel dragged.
pub const DEGREES_PER_PIXEL: f64 = 0.5;
/// How much one wheel step brings the camera closer (a factor on its distance).
pub const ZOOM_PER_STEP: f64 = 0.9;
/// The highest elevation above (or below) the target, short of the pole where the view's up
/// would be lost.
const MAX_ELEVATION: f64 = 89.0;

/// A camera turning around its target: distance, azimuth and elevation about the scene's up.
#[derive(Clone, Debug, PartialEq)]
pub struct Orbit {
    home: Camera,
    target: DVec3,
    distance: f64,
    /// Radians about `up`, from the scene camera's side.
    azimuth: f64,
    /// Radians above the plane across `up`.
    elevation: f64,
    /// The scene's up and two horizontal directions, the first towards the scene camera.
    basis: [DVec3; 3],
}

impl Orbit {
    /// The orbit that starts at `camera`.
    pub fn new(camera: &Camera) -> Orbit {
        let up = camera.up.normalize();
        let offset = camera.eye - camera.target;
        let distance = offset.length().max(1e-9);
        let across = offset - up * offset.dot(up);
        let h0 = if across.length() > 1e-9 * distance {
            across.normalize()
        } else {
            up.any_orthonormal_vector()
        };
        let h1 = up.cross(h0);
        let elevation = (offset.dot(up) / distance).clamp(-1.0, 1.0).asin();
        Orbit {
            home: *camera,
            target: camera.target,
            distance,
            azimuth: 0.0,
            elevation,
            basis: [up, h0, h1],
        }
    }

    /// The camera now.
    pub fn camera(&self) -> Camera {
        let [up, h0, h1] = self.basis;
        let (se, ce) = self.elevation.sin_cos();
        let (sa, ca) = self.azimuth.sin_cos();
        let dir = (h0 * ca + h1 * sa) * ce + up * se;
        Camera {
            eye: self.target + dir * self.distance,
            target: self.target,
            up,
            fov: self.home.fov,
        }
    }

    /// A drag of (dx, dy) pixels (right, down): the scene turns with the pointer.
    pub fn turn(&mut self, dx: f64, dy: f64) {
        let k = DEGREES_PER_PIXEL.to_radians();
        self.azimuth -= dx * k;
        let limit = MAX_ELEVATION.to_radians();
        self.elevation = (self.elevation + dy * k).clamp(-limit, limit);
    }

    /// A pan of (dx, dy) pixels in a window `height` pixels high: the target moves in the
    /// view's plane so that the point under the pointer at the target's distance follows it.
    pub fn pan(&mut self, dx: f64, dy: f64, height: f64) {
        let c = self.camera();
        let forward = (c.target - c.eye).normalize();
        let right = forward.cross(c.up).normalize();
        let up = right.cross(forward);
        let per_pixel = 2.0 * self.distance * (self.home.fov / 2.0).tan() / height.max(1.0);
        self.target += (-right * dx + up * dy) * per_pixel;
    }

    /// `steps` wheel steps (positive: closer).
    pub fn zoom(&mut self, steps: f64) {
        self.distance = (self.distance * ZOOM_PER_STEP.powf(steps)).clamp(1e-6, 1e12);
    }

    /// Back to the scene's camera.
    pub fn reset(&mut self) {
        *self = Orbit::new(&self.home);
    }

    /// The scene's own camera changed (a reload): start from it if the user had not moved.
    pub fn rehome(&mut self, camera: &Camera) {
        let moved = *self != Orbit::new(&self.home);
        if moved {
            self.home = *camera;
        } else {
            *self = Orbit::new(camera);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            eye: DVec3::new(0.0, 1.0, -5.0),
            target: DVec3::new(0.0, 1.0, 0.0),
            up: DVec3::Y,
            fov: 45f64.to_radians(),
        }
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-9
    }

    #[test]
    fn starts_at_the_scene_camera_and_comes_back() {
        let mut o = Orbit::new(&camera());
        assert!(close(o.camera().eye, camera().eye));
        o.turn(37.0, -12.0);
        o.zoom(3.0);
        o.pan(5.0, 7.0, 400.0);
        assert!(!close(o.camera().eye, camera().eye));
        o.reset();
        assert!(close(o.camera().eye, camera().eye));
    }

    /// 180 pixels to the right turn the camera 90° about the target's vertical towards the
    /// image's left (world +x here: the image's right is −x), so that the scene follows the
    /// pointer; the distance stays.
    #[test]
    fn a_drag_turns_around_the_target() {
        let mut o = Orbit::new(&camera());
        o.turn(180.0, 0.0);
        assert!(
            close(o.camera().eye, DVec3::new(5.0, 1.0, 0.0)),
            "{}",
            o.camera().eye
        );
        let mut o = Orbit::new(&camera());
        o.turn(0.0, 60.0);
        let e = o.camera().eye;
        assert!(
            (e.y - 1.0 - 5.0 * 30f64.to_radians().sin()).abs() < 1e-9,
            "{e}"
        );
        assert!(((e - camera().target).length() - 5.0).abs() < 1e-9);
    }

    #[test]
    fn elevation_stops_short_of_the_pole() {
        let mut o = Orbit::new(&camera());
        o.turn(0.0, 10_000.0);
        let c = o.camera();
        let dir = (c.eye - c.target).normalize();
        assert!(dir.dot(DVec3::Y) < 89.5f64.to_radians().sin());
    }

    #[test]
    fn zoom_and_pan_move_as_documented() {
        let mut o = Orbit::new(&camera());
        o.zoom(2.0);
        assert!(((o.camera().eye - o.camera().target).length() - 5.0 * 0.81).abs() < 1e-9);
        let mut o = Orbit::new(&camera());
        // 100 pixels right in a window 400 high: the target moves left by 100 × (2 d tan(fov/2) / 400).
        o.pan(100.0, 0.0, 400.0);
        let shift = 100.0 * 2.0 * 5.0 * (22.5f64.to_radians()).tan() / 400.0;
        assert!(
            close(o.camera().target, DVec3::new(shift, 1.0, 0.0)),
            "{}",
            o.camera().target
        );
    }
}
