//! A volume's bytes: its values as the GPU reads them (`r32float`, little-endian, x fastest,
//! then y, then z — what `emit` writes beside the shader), and the cache's file, the same
//! values after a header that says which grid they are on.

use super::{Grid, Volume};
use glam::DVec3;

/// The cache file's first bytes.
const MAGIC: &[u8; 8] = b"SDFCVOL2";

/// The header's length: magic, three u32 counts, seven f64 (lo, hi and h).
const HEADER: usize = 8 + 12 + 56;

/// The name of `emit`'s file for the scene's volume `index`, beside a shader named `stem`.
pub fn raw_name(stem: &str, index: usize) -> String {
    format!("{stem}.volume{index}.r32f")
}

/// The values as raw little-endian `f32`s, x fastest: `emit`'s volume file.
pub fn raw(volume: &Volume) -> Vec<u8> {
    volume.values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// The cache's file: a header (magic `SDFCVOL2`, points per axis as u32, the first and last
/// points and the spacing as f64, all little-endian) and [`raw`] values.
pub fn with_header(volume: &Volume) -> Vec<u8> {
    let g = &volume.grid;
    let mut out = Vec::with_capacity(HEADER + 4 * volume.values.len());
    out.extend_from_slice(MAGIC);
    for n in g.n {
        out.extend_from_slice(&(n as u32).to_le_bytes());
    }
    for x in [g.lo.x, g.lo.y, g.lo.z, g.hi.x, g.hi.y, g.hi.z, g.h] {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out.extend_from_slice(&raw(volume));
    out
}

/// The volume a cache file holds, if it is one (and whole): λ proven again from its values.
pub fn from_header(bytes: &[u8]) -> Option<Volume> {
    if bytes.len() < HEADER || &bytes[..8] != MAGIC {
        return None;
    }
    let u = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes")) as usize;
    let f = |at: usize| f64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes"));
    let n = [u(8), u(12), u(16)];
    if n.iter().any(|&k| !(2..=super::MAX_RES).contains(&k)) {
        return None;
    }
    let (lo, hi, h) = (
        DVec3::new(f(20), f(28), f(36)),
        DVec3::new(f(44), f(52), f(60)),
        f(68),
    );
    let len = n[0] * n[1] * n[2];
    if bytes.len() != HEADER + 4 * len || !(h > 0.0 && h.is_finite() && lo.is_finite()) {
        return None;
    }
    // (The last point is stored as the grid had it, not recomputed: lo + extent can differ
    // from it in the last bit, and a grid that differs is not the one asked for.)
    let extent = DVec3::new((n[0] - 1) as f64, (n[1] - 1) as f64, (n[2] - 1) as f64) * h;
    if !hi.is_finite()
        || (lo + extent - hi).abs().max_element() > 1e-9 * (1.0 + hi.abs().max_element())
    {
        return None;
    }
    let values: Vec<f32> = bytes[HEADER..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")))
        .collect();
    if values.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let grid = Grid { lo, hi, h, n };
    Some(Volume::from_values(grid, values))
}

/// How a volume file's bytes are laid out, as the manifest says it.
pub const LAYOUT: &str = "r32float texels, little-endian, x fastest, then y, then z; no header";
