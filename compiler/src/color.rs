//! sRGB and linear light: scene colours are written as sRGB (as editors show them), lighting
//! adds and scales linear values, and images are encoded to sRGB once, at the end.

/// An sRGB-encoded component (0…1) as linear light (the IEC 61966-2-1 curve).
pub fn to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// A linear component (0…1) encoded as sRGB.
pub fn to_srgb(c: f64) -> f64 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// [`to_linear`] of each component.
pub fn linear(c: glam::DVec3) -> glam::DVec3 {
    glam::DVec3::new(to_linear(c.x), to_linear(c.y), to_linear(c.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_byte_survives_the_round_trip() {
        for v in 0..=255u8 {
            let c = v as f64 / 255.0;
            let back = (to_srgb(to_linear(c)) * 255.0).round() as u8;
            assert_eq!(back, v);
        }
        // The curve's known points: mid-grey 0.5 is 21.4% light; 1 stays 1.
        assert!((to_linear(0.5) - 0.214_041).abs() < 1e-6);
        assert!((to_linear(1.0) - 1.0).abs() < 1e-12);
    }
}
