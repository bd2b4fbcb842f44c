//! One pass: subsample k of every (active) pixel, traced in parallel by bands of rows.

use super::accumulator::Accumulator;
use super::region::PixelRect;
use super::settings::RenderSettings;
use crate::accel::{CameraView, Reach};
use crate::camera::CameraRays;
use crate::integrator::{Emitters, Integrator, RayCounts};
use crate::sampler::{SampleStream, Sampler};
use crate::scene::PreparedScene;
use rayon::prelude::*;

/// Rows per unit of parallel work: small enough to balance two cores and to notice a
/// cancel request quickly, large enough to amortise the scheduling.
pub const BAND_ROWS: usize = 4;

/// What one pass did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassStats {
    /// Rays traced, by kind.
    pub rays: RayCounts,
    /// Pixels that received a subsample.
    pub pixels_traced: u64,
    /// Wall-clock time of the pass.
    pub seconds: f64,
}

/// Adds subsample `pass` to every pixel of `window` (the frame's pixels that `acc` holds)
/// whose `active` flag is set (all of them when `active` is None); subsample 0 replaces
/// whatever the sum held, so pass 0 needs no cleared accumulator. Each pixel depends only
/// on its own position and the pass index, so the result is the same whatever the number
/// of threads. Returns None if `cancelled()` turned true
/// part-way, leaving the accumulator holding a partial pass.
#[allow(clippy::too_many_arguments)]
pub fn render_pass(
    scene: &PreparedScene,
    rays: &CameraRays,
    view: &CameraView,
    window: PixelRect,
    sampler: &Sampler,
    pass: u32,
    settings: &RenderSettings,
    acc: &mut Accumulator,
    active: Option<&[bool]>,
    emitters: Option<&Emitters>,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Option<PassStats> {
    let start = std::time::Instant::now();
    debug_assert_eq!((acc.width, acc.height), (window.width(), window.height()));
    let width = acc.width as usize;
    let band = width * BAND_ROWS;
    let results: Vec<Option<(RayCounts, u64)>> = acc
        .pixels
        .par_chunks_mut(band)
        .enumerate()
        .map(|(band_index, pixels)| {
            if cancelled() {
                return None;
            }
            let mut integrator = Integrator::new(scene, settings.min_weight)
                .with_self_intersection(settings.self_intersection)
                .with_kind(settings.integrator)
                .with_emitters(emitters);
            let mut traced = 0u64;
            for (row, row_pixels) in pixels.chunks_mut(width).enumerate() {
                let local_y = band_index * BAND_ROWS + row;
                let row_active = active.map(|a| &a[local_y * width..(local_y + 1) * width]);
                let y = window.y0 + local_y as u32;
                let subsamples = sampler.row(y, pass);
                // What the row's primary rays can hit first, looked up once per run of
                // pixels that share it (`run_end` is the first column past the run).
                let (mut reach, mut run_end) = (Reach::After(0.0), 0);
                for (local_x, sum) in row_pixels.iter_mut().enumerate() {
                    if row_active.is_some_and(|a| !a[local_x]) {
                        continue;
                    }
                    let x = window.x0 + local_x as u32;
                    let mut stream = SampleStream::new(x, y, pass);
                    let sample = if rays.has_lens() {
                        // Lens rays do not start at the eye: the camera view (which lists
                        // what rays from the eye can hit first) does not apply to them.
                        let u = stream.next_2d();
                        let (dx, dy) = subsamples.offset(x);
                        let ray = rays.ray_through_lens(x as f32 + dx, y as f32 + dy, u);
                        integrator.trace_primary(Reach::After(0.0), || ray, stream)
                    } else {
                        let ray = || {
                            let (dx, dy) = subsamples.offset(x);
                            rays.ray(x as f32 + dx, y as f32 + dy)
                        };
                        if x >= run_end {
                            (reach, run_end) = view.reach_run(x, y);
                        }
                        integrator.trace_primary(reach, ray, stream)
                    };
                    let color = if settings.high_dynamic_range {
                        sample.color
                    } else {
                        sample.color.clamp(glam::Vec3::ZERO, glam::Vec3::ONE)
                    };
                    if pass == 0 {
                        // The first subsample of a pixel starts its sum: a restarted
                        // render's old sums are replaced here, never cleared apart.
                        *sum = super::accumulator::PixelSum::default();
                    }
                    sum.add(color, sample.signature);
                    traced += 1;
                }
            }
            Some((integrator.counts, traced))
        })
        .collect();
    let mut stats = PassStats::default();
    for r in results {
        let (counts, traced) = r?;
        stats.rays += counts;
        stats.pixels_traced += traced;
    }
    stats.seconds = start.elapsed().as_secs_f64();
    Some(stats)
}
