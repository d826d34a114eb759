//! The pinhole camera (Munini §2.1) shared by the GPU's `View` uniform and the CPU reference
//! tracer, so both trace exactly the same rays.

use crate::scene::Camera;
use glam::DVec3;

/// Camera basis and image size for one render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Eye position.
    pub eye: DVec3,
    /// Right vector scaled by tan(fov/2)·aspect.
    pub right: DVec3,
    /// Up vector scaled by tan(fov/2).
    pub up: DVec3,
    /// Unit view direction.
    pub forward: DVec3,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// tan of half a pixel's angle at the centre: the pixel footprint per unit of distance.
    pub pixel: f64,
}

impl View {
    /// The view of `camera` for a `width`×`height` image.
    pub fn new(camera: &Camera, width: u32, height: u32) -> View {
        let forward = (camera.target - camera.eye).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let t = (camera.fov / 2.0).tan();
        let aspect = width as f64 / height as f64;
        View {
            eye: camera.eye,
            right: right * t * aspect,
            up: up * t,
            forward,
            width,
            height,
            pixel: t / height as f64,
        }
    }

    /// The unit direction through image point (x, y), in pixels with y down (pixel centres at
    /// +0.5), as the shader's `camera_ray` computes it.
    pub fn ray(&self, x: f64, y: f64) -> DVec3 {
        let u = 2.0 * x / self.width as f64 - 1.0;
        let v = 1.0 - 2.0 * y / self.height as f64;
        (self.forward + self.right * u + self.up * v).normalize()
    }

    /// The `View` uniform's 96 bytes: six vec4s, the last (tile offset, image size) as u32.
    pub fn uniform(&self, tile_x: u32, tile_y: u32) -> [u8; 96] {
        let mut out = [0u8; 96];
        let vecs = [
            self.eye,
            self.right,
            self.up,
            self.forward,
            DVec3::new(self.width as f64, self.height as f64, self.pixel),
        ];
        for (i, v) in vecs.iter().enumerate() {
            for (j, c) in [v.x, v.y, v.z, 0.0].iter().enumerate() {
                let at = 16 * i + 4 * j;
                out[at..at + 4].copy_from_slice(&(*c as f32).to_le_bytes());
            }
        }
        for (j, c) in [tile_x, tile_y, self.width, self.height].iter().enumerate() {
            let at = 80 + 4 * j;
            out[at..at + 4].copy_from_slice(&c.to_le_bytes());
        }
        out
    }
}
