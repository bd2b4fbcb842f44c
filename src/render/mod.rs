//! Turning a prepared scene into pixels: one subsample of every pixel per pass, summed in
//! an accumulator. The command line, the viewer and the bench all run these same passes,
//! so a one-shot render equals a finished progressive one by construction.

mod accumulator;
mod adaptive;
mod compare;
#[cfg(feature = "denoise")]
mod denoise;
mod guides;
mod heat_map;
mod image_file;
mod image_read;
mod memory;
mod output;
mod pass;
mod progressive;
mod region;
mod settings;
mod stitch;

pub use accumulator::{Accumulator, PixelSum, luminance, to_8bit};
pub use compare::fraction_differing;
#[cfg(feature = "denoise")]
pub use denoise::{DenoiseError, denoise};
pub use guides::{GuideImages, MAX_GUIDE_SUBSAMPLES, guide_images};
pub use heat_map::{ERROR_SCALE, Legend, View, mean_error, scale_color, write_view_rgba8};
pub use image_file::{
    BitDepth, ImageFormat, OutputOptions, PLACEMENT_KEY, Placement, encode, sidecar_path, write_png,
};
pub use image_read::{
    ImageInfo, PixelType, ReadError, ReadImage, read_image, read_image_info, read_pixels,
};
pub use memory::{MemorySource, RenderMemory, available_memory, gib};
pub use output::{OutputError, PendingFile, remove_pending_files, write_bytes};
pub use pass::{BAND_ROWS, PassStats, render_pass};
pub use progressive::{PassOutcome, ProgressiveRender, is_stochastic};
pub use region::{PixelRect, RegionError, adaptive_margin};
pub use settings::{AdaptiveSettings, DEFAULT_MIN_WEIGHT, RenderSettings, SettingsError};
pub use stitch::{StitchError, StitchPlan, plan_stitch, stitch};

/// What a build without the `denoise` feature says when asked to denoise.
pub const DENOISE_NOT_BUILT: &str = "this prism was built without denoising; build it with \
    `cargo build --release --features denoise` where Intel Open Image Denoise 2 is installed \
    (OIDN_DIR names the folder whose lib/ holds libOpenImageDenoise; docs/effects.md, \
    \"Denoising\")";

use crate::camera::Camera;
use crate::scene::PreparedScene;
use std::sync::Arc;

/// The worker threads a render runs on: `threads` of them (all cores when None), each with
/// a stack deep enough for the longest ray tree (`limits::RENDER_STACK_BYTES`). Run passes
/// inside its `install`; rayon's global pool has smaller stacks.
pub fn thread_pool(
    threads: Option<usize>,
) -> Result<rayon::ThreadPool, rayon::ThreadPoolBuildError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .stack_size(crate::limits::RENDER_STACK_BYTES)
        .thread_name(|i| format!("prism-worker-{i}"))
        .build()
}

/// Renders to convergence in one go; `on_pass` sees each finished pass. Call it inside
/// `thread_pool(..).install` (see there).
pub fn render(
    scene: Arc<PreparedScene>,
    camera: Camera,
    settings: RenderSettings,
    on_pass: impl FnMut(&ProgressiveRender, &PassStats),
) -> ProgressiveRender {
    let full = PixelRect::full(settings.width, settings.height);
    render_region(scene, camera, settings, full, &|| false, on_pass)
}

/// Renders the pixels of `region` (inside the frame) to convergence, or until `stop()`
/// turns true (checked between bands of rows). The pixels come out exactly as the
/// same pixels of the whole frame would: the render covers a margin around the region for
/// adaptive sampling (`adaptive_margin`); `ProgressiveRender::sums_of` gives the region's.
pub fn render_region(
    scene: Arc<PreparedScene>,
    camera: Camera,
    settings: RenderSettings,
    region: PixelRect,
    stop: &(dyn Fn() -> bool + Sync),
    mut on_pass: impl FnMut(&ProgressiveRender, &PassStats),
) -> ProgressiveRender {
    let stochastic = is_stochastic(&scene, &camera, &settings);
    let margin = adaptive_margin(&settings, stochastic);
    let window = region.grown(margin, settings.width, settings.height);
    let mut job = ProgressiveRender::in_window(scene, camera, settings, window);
    // A stop part-way through a pass leaves some pixels with one subsample more than
    // others: each pixel's mean is still its own estimate so far.
    while let PassOutcome::Finished(stats) = job.step(stop) {
        on_pass(&job, &stats);
    }
    job
}
