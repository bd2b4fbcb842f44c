//! False-colour pictures of where a progressive render spends its work and how far each
//! pixel may still be from converged: the viewer's sample-count and error views. Both map
//! a number per pixel through one colour scale (`scale_color`) whose ends the legend names.

use super::accumulator::Accumulator;
use glam::Vec3;

/// What an image of the render shows (a closed set).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// The image itself.
    #[default]
    Image,
    /// Each pixel's subsample count, from none (the scale's start) to the most any pixel
    /// has (its end).
    Samples,
    /// Each pixel's error estimate (`PixelSum::error_so_far`), on a log scale from
    /// `ERROR_SCALE`'s start to its end; grey where it is not known yet.
    Error,
}

/// The error view's scale: estimates at or below the start show its first colour, at or
/// above the end its last.
pub const ERROR_SCALE: (f32, f32) = (1e-4, 1e-1);

/// The colour of unknown values.
pub const UNKNOWN: [u8; 3] = [96, 96, 96];

/// What the ends of a view's colour scale stand for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Legend {
    /// The value shown in the scale's first colour.
    pub low: f32,
    /// The value shown in its last colour.
    pub high: f32,
    /// Whether the colours step evenly in the logarithm of the value.
    pub logarithmic: bool,
}

/// The colour at `t` in [0, 1] along the scale: dark blue through teal and green to yellow,
/// brightening steadily (viridis's endpoints and midpoints, interpolated), so that more
/// reads as brighter also in grey.
pub fn scale_color(t: f32) -> [u8; 3] {
    const STOPS: [Vec3; 5] = [
        Vec3::new(0.267, 0.005, 0.329),
        Vec3::new(0.231, 0.322, 0.545),
        Vec3::new(0.129, 0.569, 0.549),
        Vec3::new(0.369, 0.788, 0.384),
        Vec3::new(0.993, 0.906, 0.144),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (STOPS.len() - 1) as f32;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let c = STOPS[i].lerp(STOPS[i + 1], x - i as f32);
    super::accumulator::to_8bit(c)
}

/// Writes `view` of `acc` as 8-bit RGBA into `out`, and returns its legend (None for the
/// image itself).
pub fn write_view_rgba8(acc: &Accumulator, view: View, out: &mut [u8]) -> Option<Legend> {
    let pixels = acc.pixels.iter().zip(out.chunks_exact_mut(4));
    match view {
        View::Image => {
            acc.write_rgba8(out);
            None
        }
        View::Samples => {
            let most = acc.pixels.iter().map(|p| p.count).max().unwrap_or(0).max(1);
            for (p, px) in pixels {
                let [r, g, b] = scale_color(p.count as f32 / most as f32);
                px.copy_from_slice(&[r, g, b, 255]);
            }
            Some(Legend {
                low: 0.0,
                high: most as f32,
                logarithmic: false,
            })
        }
        View::Error => {
            let (lo, hi) = (ERROR_SCALE.0.ln(), ERROR_SCALE.1.ln());
            for (p, px) in pixels {
                let [r, g, b] = match p.error_so_far() {
                    Some(e) => scale_color((e.max(ERROR_SCALE.0).ln() - lo) / (hi - lo)),
                    None => UNKNOWN,
                };
                px.copy_from_slice(&[r, g, b, 255]);
            }
            Some(Legend {
                low: ERROR_SCALE.0,
                high: ERROR_SCALE.1,
                logarithmic: true,
            })
        }
    }
}

/// The mean error estimate over the pixels that have one (None while none has): the
/// viewer's convergence plot.
pub fn mean_error(acc: &Accumulator) -> Option<f64> {
    let (sum, n) = acc
        .pixels
        .iter()
        .filter_map(|p| p.error_so_far())
        .fold((0.0f64, 0usize), |(s, n), e| (s + e as f64, n + 1));
    (n > 0).then(|| sum / n as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_runs_from_dark_to_bright() {
        let lum = |c: [u8; 3]| 0.2126 * c[0] as f32 + 0.7152 * c[1] as f32 + 0.0722 * c[2] as f32;
        let mut last = -1.0;
        for i in 0..=20 {
            let l = lum(scale_color(i as f32 / 20.0));
            assert!(l > last, "brightness rises along the scale");
            last = l;
        }
        assert_eq!(scale_color(-1.0), scale_color(0.0));
        assert_eq!(scale_color(f32::NAN), scale_color(0.0));
        assert_eq!(scale_color(7.0), scale_color(1.0));
    }

    /// Two pixels, one sampled four times and one once: the sample view shows the first in
    /// the scale's last colour and the second a quarter along; the error view shows the
    /// converged pixel in the first colour and the unknown one grey.
    #[test]
    fn views_map_counts_and_errors_onto_the_scale() {
        let mut acc = Accumulator::new(2, 1);
        for _ in 0..4 {
            acc.pixels[0].add(Vec3::splat(0.5), 0);
        }
        acc.pixels[1].add(Vec3::splat(0.5), 0);
        let mut out = vec![0u8; 8];
        let legend = write_view_rgba8(&acc, View::Samples, &mut out).unwrap();
        assert_eq!((legend.low, legend.high), (0.0, 4.0));
        assert_eq!(out[0..3], scale_color(1.0));
        assert_eq!(out[4..7], scale_color(0.25));
        let legend = write_view_rgba8(&acc, View::Error, &mut out).unwrap();
        assert!(legend.logarithmic);
        assert_eq!(out[0..3], scale_color(0.0), "no error: the scale's start");
        assert_eq!(out[4..7], UNKNOWN);
        assert_eq!(mean_error(&acc), Some(0.0));
        assert!(write_view_rgba8(&acc, View::Image, &mut out).is_none());
        assert_eq!(out[0..4], [128, 128, 128, 255]);
    }
}
