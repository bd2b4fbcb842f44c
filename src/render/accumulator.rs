//! The film: per-pixel sums of subsamples, and their average as an 8-bit image.

use glam::Vec3;

/// Running sums for one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSum {
    /// Sum of the subsamples' colours.
    pub color: Vec3,
    /// Sum of the first `count / 2` subsamples when `count` is a power of two (taken when
    /// `count` reached half of it): the half-size estimate that `error_estimate` compares to.
    pub half: Vec3,
    /// Subsamples summed.
    pub count: u32,
    /// The signature of the first subsample (integrator.rs).
    pub signature: u32,
    /// Whether a later subsample's signature differed: an edge crosses the pixel.
    pub mixed: bool,
}

impl PixelSum {
    /// Adds one subsample of colour `c` and signature `signature`.
    #[inline]
    pub fn add(&mut self, c: Vec3, signature: u32) {
        if self.count == 0 {
            self.signature = signature;
        } else {
            self.mixed |= signature != self.signature;
        }
        if self.count.is_power_of_two() {
            self.half = self.color;
        }
        self.color += c;
        self.count += 1;
    }

    /// The mean colour so far (black before any subsample).
    #[inline]
    pub fn mean(&self) -> Vec3 {
        if self.count == 0 {
            Vec3::ZERO
        } else {
            self.color / self.count as f32
        }
    }

    /// How far the mean luminance may still be from the converged pixel: its distance from
    /// the mean of the first half of the subsamples (Dammertz et al. 2010, "A hierarchical
    /// automatic stopping condition"). Known at power-of-two counts, when both halves of the
    /// sampler's order are stratified (sampler.rs); unknown (infinite) otherwise. Unlike the
    /// standard error, it follows the faster convergence of stratified subsamples at edges.
    #[inline]
    pub fn error_estimate(&self) -> f32 {
        if self.count < 2 || !self.count.is_power_of_two() {
            return f32::INFINITY;
        }
        let n = self.count as f32;
        (luminance(self.color) / n - luminance(self.half) / (0.5 * n)).abs()
    }
}

impl PixelSum {
    /// The error estimate of `error_estimate` at any count: the mean luminance's distance
    /// from the mean of the first power-of-two share of the subsamples (those `half` holds).
    /// What the viewer's error heat map and convergence plot show between the powers of two;
    /// None before two subsamples.
    pub fn error_so_far(&self) -> Option<f32> {
        if self.count < 2 {
            return None;
        }
        // `half` was taken when the count reached the largest power of two below it.
        let first = 1u32 << (31 - (self.count - 1).leading_zeros());
        let n = self.count as f32;
        Some((luminance(self.color) / n - luminance(self.half) / first as f32).abs())
    }
}

/// Rec. 709 luminance of a linear colour.
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// The running sums of every pixel of an image, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Accumulator {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// One sum per pixel.
    pub pixels: Vec<PixelSum>,
}

impl Accumulator {
    /// Empty sums for a `width` × `height` image.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![PixelSum::default(); width as usize * height as usize],
        }
    }

    /// The sums of the pixels in `rect` (in this image's coordinates, inside it).
    pub fn crop(&self, rect: super::region::PixelRect) -> Accumulator {
        assert!(rect.check_within(self.width, self.height).is_ok());
        let w = self.width as usize;
        let pixels = (rect.y0..rect.y1)
            .flat_map(|y| {
                let row = y as usize * w;
                self.pixels[row + rect.x0 as usize..row + rect.x1 as usize]
                    .iter()
                    .copied()
            })
            .collect();
        Accumulator {
            width: rect.width(),
            height: rect.height(),
            pixels,
        }
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

    /// The image as 8-bit RGB (linear values, rounded).
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

    /// At powers of two the estimate is `error_estimate`'s; between them it compares with
    /// the first power-of-two share.
    #[test]
    fn the_error_so_far_matches_the_stopping_rule_at_powers_of_two() {
        let mut p = PixelSum::default();
        assert_eq!(p.error_so_far(), None);
        let samples = [0.2, 0.6, 0.4, 0.8, 0.1, 0.9, 0.5];
        for (i, &v) in samples.iter().enumerate() {
            p.add(Vec3::splat(v), 0);
            let n = i + 1;
            if n >= 2 && n.is_power_of_two() {
                assert_eq!(p.error_so_far(), Some(p.error_estimate()));
            }
        }
        // Seven subsamples: compared with the first four.
        let mean = |s: &[f32]| s.iter().sum::<f32>() / s.len() as f32;
        let expected = (mean(&samples) - mean(&samples[..4])).abs();
        assert!((p.error_so_far().unwrap() - expected).abs() < 1e-6);
    }

    #[test]
    fn mean_and_quantisation() {
        let mut p = PixelSum::default();
        p.add(Vec3::new(1.0, 0.0, 0.5), 7);
        p.add(Vec3::new(0.0, 0.0, 0.5), 7);
        assert_eq!(p.mean(), Vec3::new(0.5, 0.0, 0.5));
        assert_eq!(to_8bit(p.mean()), [128, 0, 128]);
        assert_eq!(to_8bit(Vec3::new(2.0, -1.0, f32::NAN)), [255, 0, 0]);
    }

    #[test]
    fn a_differing_signature_marks_the_pixel_mixed() {
        let mut p = PixelSum::default();
        p.add(Vec3::ONE, 7);
        p.add(Vec3::ONE, 7);
        assert!(!p.mixed);
        p.add(Vec3::ONE, 8);
        p.add(Vec3::ONE, 7);
        assert!(p.mixed);
        assert_eq!(p.signature, 7, "the first subsample's signature stays");
    }

    #[test]
    fn error_estimate_compares_with_the_first_half_at_powers_of_two() {
        let mut p = PixelSum::default();
        for v in [1.0, 1.0, 0.0] {
            p.add(Vec3::splat(v), 0);
        }
        assert_eq!(p.error_estimate(), f32::INFINITY, "3 is not a power of two");
        p.add(Vec3::ZERO, 0);
        // Mean of all four 0.5, of the first two 1.
        assert!((p.error_estimate() - 0.5).abs() < 1e-6);
        let mut q = PixelSum::default();
        for v in [1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0] {
            q.add(Vec3::splat(v), 0);
        }
        assert!(
            q.error_estimate().abs() < 1e-6,
            "halves agree: {}",
            q.error_estimate()
        );
    }
}
