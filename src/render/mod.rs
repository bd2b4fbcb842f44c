//! Turning a prepared scene into pixels: one subsample of every pixel per pass, summed in
//! an accumulator. The command line, the viewer and the bench all run these same passes,
//! so a one-shot render equals a finished progressive one by construction.

mod accumulator;
mod compare;
mod heat_map;
mod output;
mod pass;
mod progressive;
mod settings;

pub use accumulator::{Accumulator, PixelSum, luminance, to_8bit};
pub use compare::fraction_differing;
pub use heat_map::{ERROR_SCALE, Legend, View, mean_error, scale_color, write_view_rgba8};
pub use output::{
    ImageFormat, OutputError, PendingFile, remove_pending_files, write_bytes, write_png,
};
pub use pass::{BAND_ROWS, PassStats, render_pass};
pub use progressive::{PassOutcome, ProgressiveRender};
pub use settings::{AdaptiveSettings, DEFAULT_MIN_WEIGHT, RenderSettings, SettingsError};

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
    mut on_pass: impl FnMut(&ProgressiveRender, &PassStats),
) -> ProgressiveRender {
    let mut job = ProgressiveRender::new(scene, camera, settings);
    let never = || false;
    while let PassOutcome::Finished(stats) = job.step(&never) {
        on_pass(&job, &stats);
    }
    job
}
