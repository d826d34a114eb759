//! Turning a frame into pictures: colour, depth, normals, a step-count heat map, material ids;
//! depth also as raw 32-bit floats (`.npy`).

use crate::gpu::Frame;

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
    /// Material ids in distinct colours (the default material grey).
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

/// Averages `s`×`s` blocks of an RGBA8 image (supersampling's resolve); with `srgb`, in linear
/// light (each sample decoded, the mean encoded again), as colour must be averaged.
pub fn downsample(pixels: &[u8], width: u32, height: u32, s: u32, srgb: bool) -> Vec<u8> {
    use sdfc_compiler::color::{to_linear, to_srgb};
    if s == 1 {
        return pixels.to_vec();
    }
    let (w, h) = (width / s, height / s);
    let mut out = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            for c in 0..4 {
                let decode = srgb && c < 3;
                let mut sum = 0.0;
                for dy in 0..s {
                    for dx in 0..s {
                        let v = pixels[(((y * s + dy) * width + x * s + dx) * 4 + c) as usize];
                        let v = v as f64 / 255.0;
                        sum += if decode { to_linear(v) } else { v };
                    }
                }
                let mean = sum / (s * s) as f64;
                let mean = if decode { to_srgb(mean) } else { mean };
                out.push((mean * 255.0).round() as u8);
            }
        }
    }
    out
}

/// Encodes RGBA8 pixels as PNG bytes.
pub fn png(pixels: Vec<u8>, width: u32, height: u32) -> Result<Vec<u8>, String> {
    let img = image::RgbaImage::from_raw(width, height, pixels)
        .ok_or("internal error: image size mismatch")?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| format!("cannot encode PNG: {e}"))?;
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
