//! The pinhole camera (Munini §2.1) shared by the GPU's `View` uniform and the CPU reference
//! tracer, so both trace exactly the same rays.

use crate::layout::{FRAGMENT_SRGB, FRAGMENT_Y_UP, VIEW_BYTES, view_field};
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
    /// Where in its pixel the compute entry's ray passes, in pixels from the pixel's corner
    /// (x right, y down): (0.5, 0.5) the centre; other points for anti-aliasing samples.
    pub jitter: [f64; 2],
    /// The fragment entry's host conventions (`layout::FRAGMENT_Y_UP`, `layout::FRAGMENT_SRGB`):
    /// GL's origin (y up) and an sRGB-encoded output. Both off for every other host.
    pub fragment: Fragment,
}

// Both flags are `w` components, which `View::uniform` writes from its `vecs`.
const _: () = assert!(FRAGMENT_Y_UP.1 == 3 && FRAGMENT_SRGB.1 == 3);

/// How the fragment entry meets its host: where y starts and what it writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Fragment {
    /// Window y grows upwards (GL's `gl_FragCoord`), not downwards.
    pub y_up: bool,
    /// The colour is written sRGB-encoded (for a plain 8-bit target), not linear.
    pub srgb: bool,
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
            jitter: [0.5, 0.5],
            fragment: Fragment::default(),
        }
    }

    /// The same picture at another resolution: the same rays through the same rectangle of the
    /// image plane, with pixels that may be slightly non-square when the sizes do not divide
    /// evenly; the footprint is the larger half-extent of a pixel.
    pub fn resized(&self, width: u32, height: u32) -> View {
        View {
            width,
            height,
            pixel: self.half_pixel(width, height).max_element(),
            ..*self
        }
    }

    /// Half the width and height of a pixel of a `width`×`height` image of this view, per unit
    /// distance along the view direction.
    pub fn half_pixel(&self, width: u32, height: u32) -> glam::DVec2 {
        glam::DVec2::new(
            self.right.length() / width as f64,
            self.up.length() / height as f64,
        )
    }

    /// The unit direction through image point (x, y), in pixels with y down (pixel centres at
    /// +0.5), as the shader's `camera_ray` computes it.
    pub fn ray(&self, x: f64, y: f64) -> DVec3 {
        let u = 2.0 * x / self.width as f64 - 1.0;
        let v = 1.0 - 2.0 * y / self.height as f64;
        (self.forward + self.right * u + self.up * v).normalize()
    }

    /// The `View` uniform's bytes (`layout::VIEW_BYTES`): seven vec4s, the sixth (tile offset, image size) as
    /// u32, the seventh the multi-resolution `pass` field (cone slope, budget, previous pass's
    /// width and height; zeros outside passes, where the module's view is 96 bytes). `right.w`
    /// and `up.w` hold the jitter (x and y).
    pub fn uniform(&self, tile_x: u32, tile_y: u32, pass: [f32; 4]) -> [u8; VIEW_BYTES] {
        let mut out = [0u8; VIEW_BYTES];
        let mut vecs = [
            (self.eye, 0.0),
            (self.right, self.jitter[0]),
            (self.up, self.jitter[1]),
            (self.forward, 0.0),
            (
                DVec3::new(self.width as f64, self.height as f64, self.pixel),
                0.0,
            ),
        ];
        let flag = |on: bool| if on { 1.0 } else { 0.0 };
        for ((field, _), on) in [
            (FRAGMENT_Y_UP, self.fragment.y_up),
            (FRAGMENT_SRGB, self.fragment.srgb),
        ] {
            vecs[view_field(field)].1 = flag(on);
        }
        for (i, (v, w)) in vecs.iter().enumerate() {
            for (j, c) in [v.x, v.y, v.z, *w].iter().enumerate() {
                let at = 16 * i + 4 * j;
                out[at..at + 4].copy_from_slice(&(*c as f32).to_le_bytes());
            }
        }
        for (j, c) in [tile_x, tile_y, self.width, self.height].iter().enumerate() {
            let at = 16 * view_field("offset") + 4 * j;
            out[at..at + 4].copy_from_slice(&c.to_le_bytes());
        }
        for (j, c) in pass.iter().enumerate() {
            let at = 16 * view_field("handoff") + 4 * j;
            out[at..at + 4].copy_from_slice(&c.to_le_bytes());
        }
        out
    }
}
