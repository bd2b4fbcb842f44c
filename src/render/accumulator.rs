//! The film: per-pixel sums of subsamples, and their average as an 8-bit image.

use glam::Vec3;

/// Running sums for one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSum {
    pub color: Vec3,
    /// Sum of squared luminance, for the adaptive sampler's variance estimate.
    pub luma_sq: f32,
    pub count: u32,
}

impl PixelSum {
    #[inline]
    pub fn add(&mut self, c: Vec3) {
        self.color += c;
        let y = luminance(c);
        self.luma_sq += y * y;
        self.count += 1;
    }

    #[inline]
    pub fn mean(&self) -> Vec3 {
        if self.count == 0 {
            Vec3::ZERO
        } else {
            self.color / self.count as f32
        }
    }

    /// The standard error of the mean luminance: how far the pixel may still move.
    #[inline]
    pub fn standard_error(&self) -> f32 {
        if self.count < 2 {
            return f32::INFINITY;
        }
        let n = self.count as f32;
        let mean = luminance(self.color) / n;
        let variance = ((self.luma_sq / n - mean * mean) * n / (n - 1.0)).max(0.0);
        (variance / n).sqrt()
    }
}

#[inline]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

#[derive(Clone, Debug, PartialEq)]
pub struct Accumulator {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<PixelSum>,
}

impl Accumulator {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![PixelSum::default(); width as usize * height as usize],
        }
    }

    pub fn clear(&mut self) {
        self.pixels.fill(PixelSum::default());
    }

    /// Total subsamples held.
    pub fn sample_count(&self) -> u64 {
        self.pixels.iter().map(|p| p.count as u64).sum()
    }

    /// The mean colour of pixel (x, y), unclamped.
    pub fn mean(&self, x: u32, y: u32) -> Vec3 {
        self.pixels[(y * self.width + x) as usize].mean()
    }

    /// The average of each pixel as 8-bit RGBA (alpha opaque), row-major from the top.
    pub fn write_rgba8(&self, out: &mut [u8]) {
        for (p, px) in self.pixels.iter().zip(out.chunks_exact_mut(4)) {
            let [r, g, b] = to_8bit(p.mean());
            px.copy_from_slice(&[r, g, b, 255]);
        }
    }

    pub fn to_rgb8(&self) -> image::RgbImage {
        let mut raw = Vec::with_capacity(self.pixels.len() * 3);
        for p in &self.pixels {
            raw.extend_from_slice(&to_8bit(p.mean()));
        }
        image::RgbImage::from_raw(self.width, self.height, raw).expect("size matches")
    }
}

/// Colours are display values in [0, 1], as in the seed; anything brighter clips.
#[inline]
pub fn to_8bit(c: Vec3) -> [u8; 3] {
    let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    [q(c.x), q(c.y), q(c.z)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_quantisation() {
        let mut p = PixelSum::default();
        p.add(Vec3::new(1.0, 0.0, 0.5));
        p.add(Vec3::new(0.0, 0.0, 0.5));
        assert_eq!(p.mean(), Vec3::new(0.5, 0.0, 0.5));
        assert_eq!(to_8bit(p.mean()), [128, 0, 128]);
        assert_eq!(to_8bit(Vec3::new(2.0, -1.0, f32::NAN)), [255, 0, 0]);
    }

    #[test]
    fn standard_error_of_constant_and_varying_samples() {
        let mut flat = PixelSum::default();
        for _ in 0..4 {
            flat.add(Vec3::splat(0.3));
        }
        assert!(flat.standard_error() < 1e-3);
        let mut edge = PixelSum::default();
        for i in 0..4 {
            edge.add(Vec3::splat((i % 2) as f32));
        }
        // Luminance 0,1,0,1: sample variance 1/3, standard error √(1/12) ≈ 0.289.
        assert!((edge.standard_error() - (1.0f32 / 12.0).sqrt()).abs() < 1e-3);
    }
}
