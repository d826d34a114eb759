//! Turning a frame into pictures: colour, depth, normals, a step-count heat map, material ids;
//! depth also as raw 32-bit floats (`.npy`).

use crate::gpu::Frame;

/// Why a picture could not be encoded.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The pixels are not width × height × 4 bytes (a bug in sdfc).
    #[error("internal error: image size mismatch")]
    SizeMismatch,
    /// The PNG encoder failed.
    #[error("cannot encode PNG: {0}")]
    Png(image::ImageError),
}

/// What `--output` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Channel {
    /// Shaded colour.
    Color,
    /// Distance along the ray, near bright, misses black (or raw floats to `.npy`).
    Depth,
    /// Normals mapped from [−1, 1] to [0, 255].
    Normal,
    /// Evaluations per pixel as a heat map from 0 (dark blue) to the step budget (yellow).
    Steps,
    /// Material ids in distinct colours (the default material grey, misses black).
    Material,
}

/// RGBA8 pixels of one channel.
pub fn rgba(frame: &Frame, channel: Channel, budget: u32) -> Vec<u8> {
    let n = (frame.width * frame.height) as usize;
    let mut out = Vec::with_capacity(n * 4);
    let far = frame.depth.iter().copied().fold(0.0f32, f32::max).max(1e-6);
    for i in 0..n {
        let px: [u8; 4] = match channel {
            Channel::Color => frame.color[i].to_le_bytes(),
            Channel::Depth => match frame.depth[i] {
                d if d < 0.0 => [0, 0, 0, 255],
                d => {
                    let v = (255.0 * (1.0 - 0.85 * d / far)).round() as u8;
                    [v, v, v, 255]
                }
            },
            Channel::Normal => {
                let n = frame.normal[i];
                let c = |x: f32| ((x * 0.5 + 0.5) * 255.0).round().clamp(0.0, 255.0) as u8;
                if n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0 {
                    [0, 0, 0, 255]
                } else {
                    [c(n[0]), c(n[1]), c(n[2]), 255]
                }
            }
            Channel::Steps => heat(frame.steps[i] as f32 / budget.max(1) as f32),
            // A miss is black, apart from the default material's grey (issue 30).
            Channel::Material if frame.depth[i] < 0.0 => [0, 0, 0, 255],
            Channel::Material => palette(frame.material[i]),
        };
        out.extend_from_slice(&px);
    }
    out
}

/// A blue → magenta → orange → yellow ramp for 0..1.
fn heat(x: f32) -> [u8; 4] {
    let stops = [
        [13.0, 8.0, 135.0],
        [156.0, 23.0, 158.0],
        [237.0, 121.0, 83.0],
        [240.0, 249.0, 33.0],
    ];
    let x = x.clamp(0.0, 1.0) * 3.0;
    let i = (x.floor() as usize).min(2);
    let f = x - i as f32;
    let c = |k: usize| (stops[i][k] + (stops[i + 1][k] - stops[i][k]) * f).round() as u8;
    [c(0), c(1), c(2), 255]
}

fn palette(id: u32) -> [u8; 4] {
    if id == 0 {
        return [128, 128, 128, 255];
    }
    // Golden-ratio hues, full saturation.
    let h = (id as f32 * 0.618_034).fract() * 6.0;
    let x = 1.0 - (h % 2.0 - 1.0).abs();
    let (r, g, b) = match h as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    [(r * 255.0) as u8, (g * 255.0) as u8, (b * 255.0) as u8, 255]
}

/// Anti-aliasing samples accumulated at the output's size (memory independent of their
/// number): the sum of several frames' RGBA8 pixels, colour in linear light (decoded from sRGB,
/// averaged, encoded again), other channels as they are.
pub struct Accumulator {
    sum: Vec<f32>,
    frames: u32,
    srgb: bool,
}

impl Accumulator {
    /// An empty sum over `pixels` pixels; `srgb`: the frames are sRGB-encoded colour.
    pub fn new(pixels: usize, srgb: bool) -> Accumulator {
        Accumulator {
            sum: vec![0.0; pixels * 4],
            frames: 0,
            srgb,
        }
    }

    /// Adds one frame's RGBA8 pixels.
    pub fn add(&mut self, rgba: &[u8]) {
        // Each byte's value, decoded from sRGB (colour) or not: the same f64 arithmetic as
        // before, computed once per byte value instead of once per pixel.
        static TABLES: std::sync::OnceLock<[[f32; 256]; 2]> = std::sync::OnceLock::new();
        let tables = TABLES.get_or_init(|| {
            let plain = std::array::from_fn(|v| (v as f64 / 255.0) as f32);
            let decoded =
                std::array::from_fn(|v| sdfc_compiler::color::to_linear(v as f64 / 255.0) as f32);
            [plain, decoded]
        });
        for (i, (s, &v)) in self.sum.iter_mut().zip(rgba).enumerate() {
            let decode = usize::from(self.srgb && i % 4 < 3);
            *s += tables[decode][v as usize];
        }
        self.frames += 1;
    }

    /// The mean of the frames added, as RGBA8.
    pub fn finish(self) -> Vec<u8> {
        self.mean()
    }

    /// How many frames were added.
    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// The mean of the frames added so far, as RGBA8 (more may be added).
    pub fn mean(&self) -> Vec<u8> {
        use sdfc_compiler::color::to_srgb;
        let n = self.frames.max(1) as f64;
        self.sum
            .iter()
            .enumerate()
            .map(|(i, &s)| {
                let mean = s as f64 / n;
                let v = if self.srgb && i % 4 < 3 {
                    to_srgb(mean)
                } else {
                    mean
                };
                (v.clamp(0.0, 1.0) * 255.0).round() as u8
            })
            .collect()
    }
}

/// The points in a pixel where `n` anti-aliasing samples pass (`n` a square, s²): the centres
/// of an s×s grid of sub-pixels, row by row.
pub fn sample_points(n: u32) -> Vec<[f64; 2]> {
    let s = (n as f64).sqrt().round().max(1.0) as u32;
    (0..s * s)
        .map(|k| {
            let (i, j) = (k % s, k / s);
            [(i as f64 + 0.5) / s as f64, (j as f64 + 0.5) / s as f64]
        })
        .collect()
}

/// Encodes RGBA8 pixels as PNG bytes.
pub fn png(pixels: Vec<u8>, width: u32, height: u32) -> Result<Vec<u8>, Error> {
    let img = image::RgbaImage::from_raw(width, height, pixels).ok_or(Error::SizeMismatch)?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(Error::Png)?;
    Ok(out.into_inner())
}

/// Depth as a NumPy `.npy` array of little-endian f32, shape (height, width); −1 for a miss.
pub fn npy(depth: &[f32], width: u32, height: u32) -> Vec<u8> {
    let mut header =
        format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({height}, {width}), }}");
    // Magic (6) + version (2) + length (2) + header + newline, padded to a multiple of 64.
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat(total.next_multiple_of(64) - total));
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    for d in depth {
        out.extend_from_slice(&d.to_le_bytes());
    }
    out
}
