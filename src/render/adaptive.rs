//! Adaptive sampling: after each power-of-two pass count, which pixels go on refining.
//!
//! A pixel's error is estimated from its subsamples' halves (`PixelSum::error_estimate`:
//! the full mean against the first half's, Dammertz et al. 2010). In a render without
//! random numbers beyond the pixel positions that estimate is sharp, and a pixel stops as
//! soon as it is within tolerance. In a noisy (stochastic) render one pixel's estimate is a
//! single draw of its noise, and a quarter of the time it is under a third of the true
//! error: such pixels would stop early and leave speckles. There the estimate is pooled, as
//! Dammertz et al. do over blocks: each pixel's noise per subsample (σ̂² = e²·n) is averaged
//! over its last two checks and over its 3×3 neighbourhood, and the larger of its own and
//! its neighbourhood's is taken. And where stopping at a fixed error would spend subsamples
//! in proportion to σ², the noisiest pixels taking nearly all, a noisy pixel stops once one
//! more subsample would take less off its squared error (σ̂²/n²) than the tolerance² /16
//! (it would at 16 subsamples and the tolerance): subsamples then go in proportion to σ,
//! which minimises the image's mean squared error for their number.
//! Beside an edge a pixel goes on to a minimum count either way (`beside_edge`).

use super::accumulator::PixelSum;
use super::settings::AdaptiveSettings;
use rayon::prelude::*;

/// The subsample count at which a noisy pixel stops at exactly the tolerance: one that
/// took n subsamples stops at tolerance × √(n / this).
const NOISE_REFERENCE_COUNT: f32 = 16.0;

/// What a noisy render keeps of each pixel's noise between checks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PixelNoise {
    /// The variance of one subsample, σ̂² = e²·n, from the latest check (NaN before one).
    latest: f32,
    /// The pixel's own estimate of it: the mean of its last two checks'. Kept once the
    /// pixel stops, for its neighbours.
    own: f32,
}

impl Default for PixelNoise {
    fn default() -> Self {
        PixelNoise {
            latest: f32::NAN,
            own: 0.0,
        }
    }
}

/// The pixels of a `w`-wide image after `n` passes (a power of two, at least the minimum,
/// checked by the caller): clears `active` for those that stop, and returns how many go on.
/// A stopped pixel never restarts. `stochastic` chooses the pooled estimate (above).
pub(super) fn update_active(
    pixels: &[PixelSum],
    active: &mut [bool],
    noise: &mut [PixelNoise],
    w: usize,
    n: u32,
    adaptive: AdaptiveSettings,
    stochastic: bool,
) -> usize {
    let h = pixels.len() / w.max(1);
    if stochastic {
        active
            .par_chunks(w)
            .zip(noise.par_chunks_mut(w))
            .enumerate()
            .for_each(|(y, (row, noise))| {
                for (x, (&active, noise)) in row.iter().zip(noise).enumerate() {
                    if active {
                        let e = pixels[y * w + x].error_estimate();
                        let now = e * e * n as f32;
                        noise.own = if noise.latest.is_nan() {
                            now
                        } else {
                            0.5 * (now + noise.latest)
                        };
                        noise.latest = now;
                    }
                }
            });
    }
    let noise = &*noise;
    let near_edges_decided = n >= adaptive.edge_samples;
    let tolerance2 = adaptive.tolerance * adaptive.tolerance;
    active
        .par_chunks_mut(w)
        .enumerate()
        .map(|(y, row)| {
            let mut count = 0;
            for (x, active) in row.iter_mut().enumerate() {
                if !*active {
                    continue;
                }
                let p = &pixels[y * w + x];
                let settled = if stochastic {
                    // σ̂²/n is the squared error of the mean, and σ̂²/n² what one more
                    // subsample would take off it.
                    let variance = noise[y * w + x]
                        .own
                        .max(neighbourhood_noise(noise, w, h, x, y));
                    variance / (n as f32 * n as f32) <= tolerance2 / NOISE_REFERENCE_COUNT
                } else {
                    p.error_estimate() <= adaptive.tolerance
                };
                let beside_edge = settled
                    && !near_edges_decided
                    && beside_edge(pixels, w, h, x, y, adaptive.edge_contrast);
                *active = !settled || beside_edge;
                count += *active as usize;
            }
            count
        })
        .sum()
}

/// The mean of the pixels' own noise estimates over the 3×3 neighbourhood of (x, y)
/// (clipped at the image's border).
fn neighbourhood_noise(noise: &[PixelNoise], w: usize, h: usize, x: usize, y: usize) -> f32 {
    let (mut sum, mut count) = (0.0f32, 0u32);
    for ny in y.saturating_sub(1)..(y + 2).min(h) {
        for q in &noise[ny * w + x.saturating_sub(1)..ny * w + (x + 2).min(w)] {
            sum += q.own;
            count += 1;
        }
    }
    sum / count as f32
}

/// Whether pixel (x, y) and one of its eight neighbours lie on either side of an edge: a
/// pixel beside an edge goes on to at least `edge_samples`, since its first few subsamples
/// may have missed the edge. The edge is one between it and a neighbour when either of them
/// is mixed (its own subsamples disagree) or their signatures differ, and when their means
/// differ by more than `contrast`.
pub(super) fn beside_edge(
    pixels: &[PixelSum],
    w: usize,
    h: usize,
    x: usize,
    y: usize,
    contrast: f32,
) -> bool {
    let p = &pixels[y * w + x];
    let mut mean = None;
    for ny in y.saturating_sub(1)..(y + 2).min(h) {
        for nx in x.saturating_sub(1)..(x + 2).min(w) {
            let q = &pixels[ny * w + nx];
            let edge = p.mixed || q.mixed || q.signature != p.signature;
            if edge && (nx, ny) != (x, y) {
                let mean = *mean.get_or_insert_with(|| p.mean());
                if (q.mean() - mean).abs().max_element() > contrast {
                    return true;
                }
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A 3×3 block of pixels, each with four subsamples of one colour and signature, the
    /// centre one possibly mixed.
    fn block(colors: [f32; 9], signatures: [u32; 9], centre_mixed: bool) -> Vec<PixelSum> {
        let mut pixels: Vec<PixelSum> = colors
            .iter()
            .zip(signatures)
            .map(|(&c, s)| {
                let mut p = PixelSum::default();
                for _ in 0..4 {
                    p.add(Vec3::splat(c), s);
                }
                p
            })
            .collect();
        pixels[4].mixed = centre_mixed;
        pixels
    }

    #[test]
    fn an_edge_needs_a_signature_change_and_contrast() {
        let edge = |pixels: &[PixelSum], contrast| beside_edge(pixels, 3, 3, 1, 1, contrast);
        // A neighbour on another surface, 0.5 brighter: an edge.
        let strong = block(
            [0.2, 0.2, 0.7, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2],
            [1, 1, 2, 1, 1, 1, 1, 1, 1],
            false,
        );
        assert!(edge(&strong, 0.04));
        assert!(!edge(&strong, 0.6), "fainter than asked for");
        // Another surface of almost the same colour: nothing worth finding.
        let faint = block(
            [0.2, 0.2, 0.21, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2],
            [1, 1, 2, 1, 1, 1, 1, 1, 1],
            false,
        );
        assert!(!edge(&faint, 0.04));
        assert!(edge(&faint, 0.0), "zero contrast searches every edge");
        // A texture gradient on one surface: contrast but no edge.
        let gradient = block([0.1, 0.2, 0.3, 0.1, 0.2, 0.3, 0.1, 0.2, 0.3], [1; 9], false);
        assert!(!edge(&gradient, 0.04));
        // The centre pixel straddles an edge its neighbours show on one side.
        assert!(edge(
            &block([0.2, 0.2, 0.2, 0.2, 0.5, 0.2, 0.2, 0.2, 0.2], [1; 9], true),
            0.04
        ));
        // A contrasting pixel two steps away is not a neighbour: corner (0, 0) of a 3×3
        // image sees only its own 2×2 corner.
        let far = block(
            [0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.2, 0.9],
            [1, 1, 1, 1, 1, 1, 1, 1, 2],
            false,
        );
        assert!(!beside_edge(&far, 3, 3, 0, 0, 0.04));
        assert!(beside_edge(&far, 3, 3, 1, 1, 0.04));
    }

    /// A pixel after 16 subsamples whose mean grey is `mean` and whose first half's is off
    /// by `error`: `error_estimate` gives `error`.
    fn pixel(mean: f32, error: f32) -> PixelSum {
        PixelSum {
            color: Vec3::splat(16.0 * mean),
            half: Vec3::splat(8.0 * (mean - error)),
            count: 16,
            signature: 1,
            mixed: false,
        }
    }

    /// Which pixels of a 5×5 image go on after the check at 16 subsamples, with errors
    /// `errors` (row-major), in a render that is or is not noisy.
    fn going_on(errors: [f32; 25], stochastic: bool) -> Vec<bool> {
        let pixels: Vec<PixelSum> = errors.iter().map(|&e| pixel(0.5, e)).collect();
        let mut active = vec![true; 25];
        let mut noise = vec![PixelNoise::default(); 25];
        let adaptive = AdaptiveSettings {
            tolerance: 0.01,
            ..AdaptiveSettings::default()
        };
        let count = update_active(
            &pixels,
            &mut active,
            &mut noise,
            5,
            16,
            adaptive,
            stochastic,
        );
        assert_eq!(count, active.iter().filter(|&&a| a).count());
        active
    }

    #[test]
    fn a_noisy_pixel_whose_halves_agree_by_chance_goes_on() {
        // Every pixel noisy (error 0.03, three times the tolerance) but the centre, whose
        // halves happen to agree.
        let mut errors = [0.03f32; 25];
        errors[12] = 0.001;
        assert!(!going_on(errors, false)[12], "alone, its estimate stops it");
        assert!(
            going_on(errors, true)[12],
            "its neighbours' noise keeps it going"
        );
        // A quiet image stops everywhere; a noisy pixel in it goes on, with the neighbours
        // its noise spills into (noise comes in patches), and the rest stop.
        let mut quiet = [0.002f32; 25];
        assert!(going_on(quiet, true).iter().all(|&a| !a));
        quiet[6] = 0.05;
        let active = going_on(quiet, true);
        for (i, &a) in active.iter().enumerate() {
            let (x, y) = (i % 5, i / 5);
            assert_eq!(a, x <= 2 && y <= 2, "pixel {x}, {y}");
        }
    }

    /// A pixel's own noise is the mean of its last two checks', so one lucky check after
    /// a noisy one does not stop it; and a stopped pixel keeps its estimate for its
    /// neighbours.
    #[test]
    fn the_estimate_remembers_the_check_before() {
        let adaptive = AdaptiveSettings {
            tolerance: 0.01,
            ..AdaptiveSettings::default()
        };
        let mut active = vec![true];
        let mut noise = vec![PixelNoise::default()];
        // At 8 subsamples, error 0.05: noisy; at 16 the halves agree.
        let p = PixelSum {
            color: Vec3::splat(8.0 * 0.5),
            half: Vec3::splat(4.0 * 0.45),
            count: 8,
            ..pixel(0.5, 0.0)
        };
        let e8 = p.error_estimate();
        assert!((e8 - 0.05).abs() < 1e-5, "{e8}");
        update_active(&[p], &mut active, &mut noise, 1, 8, adaptive, true);
        // A check at 16 subsamples whose halves agree.
        let check_quiet = |active: &mut [bool], noise: &mut [PixelNoise]| {
            update_active(&[pixel(0.5, 0.0)], active, noise, 1, 16, adaptive, true)
        };
        assert!(active[0]);
        check_quiet(&mut active, &mut noise);
        assert!(active[0], "the check before still speaks");
        assert!((noise[0].own - 0.5 * e8 * e8 * 8.0).abs() < 1e-6);
        check_quiet(&mut active, &mut noise);
        assert!(!active[0], "two quiet checks stop it");
        assert_eq!(noise[0].own, 0.0);
    }
}
