//! Reading a prepared module's outputs back: a full frame's channels, found by name in
//! `sdfc_compiler::layout::PIXEL_OUTPUTS`, or a trace-only frame's rays.

use super::{Error, Layout, Prepared};
use sdfc_compiler::layout::{self, HAND_OVER, PIXEL_OUTPUTS, TRACE_OUTPUT};

/// The per-pixel outputs of a render, row-major, y down.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA8, packed little-endian (r in the low byte).
    pub color: Vec<u32>,
    /// Distance t to the hit, −1 for a miss.
    pub depth: Vec<f32>,
    /// Unit normal (xyz) at the hit, 0 for a miss.
    pub normal: Vec<[f32; 4]>,
    /// Material id (0 default, i + 1 the i-th declared).
    pub material: Vec<u32>,
    /// Evaluations of the field by the camera ray's trace.
    pub steps: Vec<u32>,
    /// Evaluations of the field by shading: the normal, the material, shadow rays, occlusion,
    /// reflected and refracted rays.
    pub shading: Vec<u32>,
    /// Wall time of the dispatches: from the first tile's submission to the last one's
    /// completion (pipeline creation, buffer set-up and read-back excluded).
    pub seconds: f64,
    /// With passes: the t where each pixel's ray stopped in the last pass, hit or not (the
    /// hand-over buffer); empty otherwise.
    pub reached: Vec<f32>,
}

/// One ray of a trace-only frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray stopped, hit or not.
    pub t: f32,
    /// Evaluations of the field.
    pub steps: u32,
    /// Whether it hit.
    pub hit: bool,
}

impl Prepared {
    /// Reads a trace-only frame back.
    pub fn rays(&self) -> Result<Vec<Ray>, Error> {
        assert!(
            matches!(self.layout, Layout::TraceOnly { .. }),
            "a trace-only module"
        );
        let bytes = self.read_output(TRACE_OUTPUT.name)?;
        Ok(bytes
            .chunks_exact(TRACE_OUTPUT.stride as usize)
            .map(|c| {
                let t = f32::from_le_bytes(c[..4].try_into().unwrap());
                let s = u32::from_le_bytes(c[4..].try_into().unwrap());
                Ray {
                    t,
                    steps: s & 0x7fff_ffff,
                    hit: s >> 31 == 1,
                }
            })
            .collect())
    }

    /// Reads a full frame back; `seconds` is recorded in it.
    pub fn frame(&self, seconds: f64) -> Result<Frame, Error> {
        assert!(matches!(self.layout, Layout::Full { .. }), "a full module");
        let reached = self.reached()?;
        let [color, depth, normal, material, steps, shading] = PIXEL_OUTPUTS.map(|b| b.name);
        let words = |name| -> Result<Vec<u32>, Error> {
            Ok(self
                .read_output(name)?
                .chunks_exact(4)
                .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
                .collect())
        };
        let floats = |name| -> Result<Vec<f32>, Error> {
            Ok(self
                .read_output(name)?
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
                .collect())
        };
        Ok(Frame {
            width: self.width,
            height: self.height,
            color: words(color)?,
            depth: floats(depth)?,
            normal: floats(normal)?
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect(),
            material: words(material)?,
            steps: words(steps)?,
            shading: words(shading)?,
            seconds,
            reached,
        })
    }

    /// With passes: the t where each pixel's ray stopped in the last pass (the hand-over
    /// buffer it wrote); empty without.
    fn reached(&self) -> Result<Vec<f32>, Error> {
        if self.hand_over.is_empty() {
            return Ok(Vec::new());
        }
        // The last pass wrote `pass_out` of its bind group: buffer 1 − (its index % 2).
        let last = (self.passes.len() - 1) % 2;
        let stride = HAND_OVER[1].stride;
        let b = self
            .gpu
            .read(&self.hand_over[1 - last], self.pixels * stride)?;
        Ok(b.chunks_exact(stride as usize)
            .map(|c| f32::from_le_bytes(c[..4].try_into().unwrap()))
            .collect())
    }

    /// The bytes of the output buffer whose global is `name` (`layout::Buffer::name`).
    fn read_output(&self, name: &str) -> Result<Vec<u8>, Error> {
        let out = self
            .outputs
            .iter()
            .find(|o| o.spec.name == name)
            .unwrap_or_else(|| panic!("the layout has an output `{name}`"));
        self.gpu.read(&out.buffer, out.size)
    }
}

/// One output buffer of a prepared module: what the layout says of it, and its size.
pub(super) struct Output {
    pub(super) buffer: wgpu::Buffer,
    pub(super) size: u64,
    pub(super) spec: layout::Buffer,
}
