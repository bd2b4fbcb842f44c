//! Drawing directions toward a latitude-longitude background in proportion to its light:
//! a piecewise-constant density over its texels, weighted by brightness and by the solid
//! angle each texel covers (sin θ), so that a path tracer finds a small bright sun with
//! few samples.

use super::texture::ImageTexture;
use glam::Vec3A;
use std::f32::consts::{PI, TAU};

/// The density of directions over a background image.
#[derive(Debug, PartialEq)]
pub struct EnvironmentDistribution {
    width: usize,
    height: usize,
    /// Per row, the cumulative weights of its texels (the last is the row's total).
    rows: Vec<f32>,
    /// The cumulative totals of the rows.
    columns: Vec<f32>,
    /// The sum of every weight.
    total: f32,
}

impl EnvironmentDistribution {
    /// The distribution of `image`'s light. Each texel's weight is its mean brightness plus
    /// a hundredth of the image's, times sin θ at its row: no direction that the bilinear
    /// lookup can light is left with no density.
    pub fn new(image: &ImageTexture) -> Self {
        let (width, height) = (image.width as usize, image.height as usize);
        let brightness = |x: usize, y: usize| {
            let c = image.sample(
                (x as f32 + 0.5) / width as f32,
                (y as f32 + 0.5) / height as f32,
            );
            (c.x + c.y + c.z) / 3.0
        };
        let mean = {
            let m = image.mean();
            (m.x + m.y + m.z) / 3.0
        };
        let floor = (0.01 * mean).max(1e-6);
        let mut rows = Vec::with_capacity(width * height);
        let mut columns = Vec::with_capacity(height);
        let mut total = 0.0f64;
        for y in 0..height {
            let sin = (PI * (y as f32 + 0.5) / height as f32).sin();
            let mut sum = 0.0f64;
            for x in 0..width {
                sum += ((brightness(x, y) + floor) * sin) as f64;
                rows.push(sum as f32);
            }
            total += sum;
            columns.push(total as f32);
        }
        Self {
            width,
            height,
            rows,
            columns,
            total: total as f32,
        }
    }

    /// The weight of texel (x, y).
    #[inline]
    fn weight(&self, x: usize, y: usize) -> f32 {
        let row = &self.rows[y * self.width..(y + 1) * self.width];
        row[x] - if x > 0 { row[x - 1] } else { 0.0 }
    }

    /// A direction drawn with `u` (in [0, 1)²), and its density per steradian.
    pub fn sample(&self, u: (f32, f32)) -> (Vec3A, f32) {
        let y = pick(&self.columns, u.1 * self.total);
        let row = &self.rows[y * self.width..(y + 1) * self.width];
        let row_start = if y > 0 { self.columns[y - 1] } else { 0.0 };
        let row_total = self.columns[y] - row_start;
        let x = pick(row, u.0 * row[self.width - 1]);
        // Where in the texel: the leftover of each number, stretched back over [0, 1).
        let before_x = if x > 0 { row[x - 1] } else { 0.0 };
        let fx = ((u.0 * row[self.width - 1] - before_x) / self.weight(x, y)).clamp(0.0, 1.0);
        let fy = ((u.1 * self.total - row_start) / row_total).clamp(0.0, 1.0);
        let tu = (x as f32 + fx) / self.width as f32;
        let tv = (y as f32 + fy) / self.height as f32;
        let dir = direction(tu, tv);
        (dir, self.pdf_of_texel(x, y, tv))
    }

    /// The density per steradian with which `sample` draws unit direction `dir`.
    pub fn pdf(&self, dir: Vec3A) -> f32 {
        let (u, v) = super::background::lat_long(dir);
        let x = ((u * self.width as f32) as usize).min(self.width - 1);
        let y = ((v * self.height as f32) as usize).min(self.height - 1);
        self.pdf_of_texel(x, y, v)
    }

    /// The density per steradian in texel (x, y) at image height `v`: the texel's share of
    /// the weight over its share of the (u, v) square, over the 2π² sin θ steradians per
    /// unit of (u, v).
    #[inline]
    fn pdf_of_texel(&self, x: usize, y: usize, v: f32) -> f32 {
        let sin = (PI * v).sin();
        if sin <= 0.0 {
            return 0.0;
        }
        let uv_density = self.weight(x, y) / self.total * (self.width * self.height) as f32;
        uv_density / (TAU * PI * sin)
    }
}

/// The index of the first of the cumulative sums `cdf` beyond `target` (the last if none).
#[inline]
fn pick(cdf: &[f32], target: f32) -> usize {
    cdf.partition_point(|&c| c <= target).min(cdf.len() - 1)
}

/// The unit direction at (u, v) of a latitude-longitude image (the inverse of
/// `background::lat_long`).
pub fn direction(u: f32, v: f32) -> Vec3A {
    let theta = PI * v;
    let phi = TAU * (u - 0.5);
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    Vec3A::new(st * sp, ct, -st * cp)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 16×8 image, dark but for one bright texel.
    fn sun() -> ImageTexture {
        let mut raw = vec![1u8; 16 * 8 * 3];
        let at = (2 * 16 + 11) * 3;
        raw[at..at + 3].copy_from_slice(&[255, 250, 240]);
        ImageTexture::from_rgb8(16, 8, raw)
    }

    #[test]
    fn directions_round_trip_through_the_image() {
        for (u, v) in [(0.5, 0.5), (0.75, 0.3), (0.1, 0.9), (0.99, 0.01)] {
            let (bu, bv) = crate::appearance::background::lat_long(direction(u, v));
            assert!(
                (bu - u).abs() < 1e-5 && (bv - v).abs() < 1e-5,
                "{u} {v}: {bu} {bv}"
            );
        }
    }

    /// The density integrates to one over the sphere, `sample` reports the density `pdf`
    /// gives, and the bright texel gets most of the samples.
    #[test]
    fn density_is_normalised_and_follows_the_light() {
        let d = EnvironmentDistribution::new(&sun());
        let n = 400;
        let mut integral = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let (u, v) = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                // dω = 2π² sin θ du dv
                integral += d.pdf(direction(u, v)) as f64 * (TAU * PI * (PI * v).sin()) as f64
                    / (n * n) as f64;
            }
        }
        assert!((integral - 1.0).abs() < 0.01, "{integral}");
        let mut in_sun = 0;
        for i in 0..64 {
            for j in 0..64 {
                let (dir, pdf) = d.sample(((i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0));
                assert!((dir.length() - 1.0).abs() < 1e-5);
                assert!(
                    (pdf - d.pdf(dir)).abs() <= 1e-3 * pdf,
                    "{pdf} {}",
                    d.pdf(dir)
                );
                let (u, v) = crate::appearance::background::lat_long(dir);
                in_sun += ((u * 16.0) as usize == 11 && (v * 8.0) as usize == 2) as u32;
            }
        }
        assert!(
            in_sun > 4096 / 2,
            "{in_sun} of 4096 samples in the sun's texel"
        );
    }
}
