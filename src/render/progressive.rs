//! The progressive render: a state machine that adds one pass at a time, can be cancelled
//! and restarted at any moment, and knows when it has converged.

use super::accumulator::Accumulator;
use super::adaptive::{self, PixelNoise};
use super::pass::{PassStats, render_pass};
use super::region::PixelRect;
use super::settings::RenderSettings;
use crate::accel::CameraView;
use crate::appearance::Appearance;
use crate::camera::{Camera, CameraRays};
use crate::integrator::{Emitters, IntegratorKind, RayCounts};
use crate::sampler::Sampler;
use crate::scene::PreparedScene;
use std::sync::Arc;

/// What one step of a progressive render did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PassOutcome {
    /// One more subsample was added to every active pixel.
    Finished(PassStats),
    /// The pass stopped part-way; the next step starts over from an empty image.
    Cancelled,
    /// Nothing left to do.
    Converged,
}

/// A render refined one subsample per pixel per step, which can be restarted with a new scene, camera or settings at any moment.
pub struct ProgressiveRender {
    scene: Arc<PreparedScene>,
    camera: Camera,
    settings: RenderSettings,
    sampler: Sampler,
    rays: CameraRays,
    /// The pixels rendered: the whole frame, or a region of it with its margin
    /// (`region::adaptive_margin`). The accumulator and the flags below cover just these.
    window: PixelRect,
    /// What primary rays can hit first, by pixel: built at the first pass after the camera
    /// or the geometry changes.
    view: Option<CameraView>,
    /// The glowing objects a path tracer samples as lights: built at the first path-traced
    /// pass after the scene changes.
    emitters: Option<Emitters>,
    accumulator: Accumulator,
    /// Pixels still refining (all of them unless adaptive sampling has stopped some).
    active: Vec<bool>,
    /// What adaptive sampling keeps of each pixel's noise between checks.
    noise: Vec<PixelNoise>,
    active_count: usize,
    passes_done: u32,
    /// The accumulator holds a partial pass: the next step restarts at pass 0.
    dirty: bool,
    rays_traced: RayCounts,
    seconds: f64,
}

impl ProgressiveRender {
    /// `settings` should have passed `RenderSettings::validate`; the one exception is the
    /// bench's reference image, which uses more than 8×8 subsamples.
    pub fn new(scene: Arc<PreparedScene>, camera: Camera, settings: RenderSettings) -> Self {
        let window = PixelRect::full(settings.width, settings.height);
        Self::in_window(scene, camera, settings, window)
    }

    /// A render of just the pixels in `window` of the frame `settings` describes, each
    /// traced exactly as in the whole frame. `window` must lie inside the frame.
    pub fn in_window(
        scene: Arc<PreparedScene>,
        camera: Camera,
        settings: RenderSettings,
        window: PixelRect,
    ) -> Self {
        assert!(settings.width > 0 && settings.height > 0 && settings.aa > 0);
        assert!(window.check_within(settings.width, settings.height).is_ok());
        let pixels = window.area() as usize;
        Self {
            sampler: Sampler::new(settings.aa, settings.layout),
            rays: camera.rays(settings.width, settings.height),
            window,
            view: None,
            emitters: None,
            accumulator: Accumulator::new(window.width(), window.height()),
            active: vec![true; pixels],
            noise: vec![PixelNoise::default(); pixels],
            active_count: pixels,
            scene,
            camera,
            settings,
            passes_done: 0,
            dirty: false,
            rays_traced: RayCounts::default(),
            seconds: 0.0,
        }
    }

    /// Throws away all samples; the next step starts at pass 0. The sums are not cleared
    /// here (for a large image that alone is tens of milliseconds of an edit's latency):
    /// pass 0 writes every pixel's sum afresh, so until the next pass `accumulator()` still
    /// holds the old ones.
    pub fn restart(&mut self) {
        self.active.fill(true);
        self.noise.fill(PixelNoise::default());
        self.active_count = self.active.len();
        self.passes_done = 0;
        self.dirty = false;
        self.rays_traced = RayCounts::default();
        self.seconds = 0.0;
    }

    /// A new scene; the camera view is kept when the geometry is the same.
    pub fn set_scene(&mut self, scene: Arc<PreparedScene>) {
        if !Arc::ptr_eq(&scene.geometry, &self.scene.geometry) {
            self.view = None;
        }
        self.scene = scene;
        self.emitters = None;
        self.restart();
    }

    /// Changes the scene's appearance in place (a material, a light's colour): no
    /// geometry is rebuilt, and the accumulation restarts.
    pub fn edit_appearance(&mut self, edit: impl FnOnce(&mut Appearance)) {
        edit(&mut Arc::make_mut(&mut self.scene).appearance);
        self.emitters = None;
        self.restart();
    }

    /// A new camera; the accumulation restarts.
    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = camera;
        self.rays = camera.rays(self.settings.width, self.settings.height);
        self.view = None;
        self.restart();
    }

    /// New settings (size, anti-aliasing, adaptivity); `settings` must be valid. The render
    /// covers the whole of the new frame.
    pub fn set_settings(&mut self, settings: RenderSettings) {
        *self = Self::new(self.scene.clone(), self.camera, settings);
    }

    /// Traces the next pass unless converged; checks `cancelled` between bands of rows.
    pub fn step(&mut self, cancelled: &(dyn Fn() -> bool + Sync)) -> PassOutcome {
        if self.dirty {
            self.restart();
        }
        if self.is_converged() {
            return PassOutcome::Converged;
        }
        // The view's build time counts as part of the pass that needs it.
        let build_start = std::time::Instant::now();
        let (w, h) = (self.settings.width, self.settings.height);
        let (scene, rays) = (&self.scene, &self.rays);
        let view = self
            .view
            .get_or_insert_with(|| scene.geometry.accel().camera_view(rays, w, h));
        let emitters = match self.settings.integrator {
            IntegratorKind::Path => {
                Some(&*self.emitters.get_or_insert_with(|| Emitters::new(scene)))
            }
            IntegratorKind::Whitted => None,
        };
        let build_seconds = build_start.elapsed().as_secs_f64();
        let active = self.settings.adaptive.map(|_| self.active.as_slice());
        let Some(mut stats) = render_pass(
            &self.scene,
            &self.rays,
            view,
            self.window,
            &self.sampler,
            self.passes_done,
            &self.settings,
            &mut self.accumulator,
            active,
            emitters,
            cancelled,
        ) else {
            self.dirty = true;
            return PassOutcome::Cancelled;
        };
        stats.seconds += build_seconds;
        self.passes_done += 1;
        self.rays_traced += stats.rays;
        self.seconds += stats.seconds;
        self.update_active();
        PassOutcome::Finished(stats)
    }

    /// Adaptive sampling (adaptive.rs): after a power-of-two pass count at or past the
    /// minimum, stops the pixels whose estimated error is within tolerance.
    fn update_active(&mut self) {
        let Some(adaptive) = self.settings.adaptive else {
            return;
        };
        // Only a power-of-two count has an error estimate, so only then can a pixel stop.
        let n = self.passes_done;
        if n < adaptive.min_samples || n < 2 || !n.is_power_of_two() {
            return;
        }
        let stochastic = self.is_stochastic();
        self.active_count = adaptive::update_active(
            &self.accumulator.pixels,
            &mut self.active,
            &mut self.noise,
            self.window.width() as usize,
            n,
            adaptive,
            stochastic,
        );
    }

    /// Whether the render draws random numbers beyond the pixel positions, so that its
    /// pixels are noisy (`is_stochastic`).
    pub fn is_stochastic(&self) -> bool {
        is_stochastic(&self.scene, &self.camera, &self.settings)
    }

    /// Whether every pixel has all its subsamples, or adaptive sampling has stopped them all.
    pub fn is_converged(&self) -> bool {
        self.passes_done >= self.settings.total_passes() || self.active_count == 0
    }

    /// Passes finished since the last restart.
    pub fn passes_done(&self) -> u32 {
        self.passes_done
    }

    /// Passes to convergence.
    pub fn total_passes(&self) -> u32 {
        self.settings.total_passes()
    }

    /// The pixels rendered (the whole frame unless made `in_window`).
    pub fn window(&self) -> PixelRect {
        self.window
    }

    /// The sums so far of the pixels of `region`, which lies inside the window.
    pub fn sums_of(&self, region: PixelRect) -> std::borrow::Cow<'_, Accumulator> {
        assert!(self.window.contains(&region));
        if region == self.window {
            return std::borrow::Cow::Borrowed(&self.accumulator);
        }
        std::borrow::Cow::Owned(self.accumulator.crop(region.relative_to(self.window)))
    }

    /// The sums so far, of the window's pixels (after a restart, those before it until the
    /// next pass replaces them).
    pub fn accumulator(&self) -> &Accumulator {
        &self.accumulator
    }

    /// Pixels that will receive the next pass.
    pub fn active_pixels(&self) -> usize {
        self.active_count
    }

    /// Rays traced since the last restart.
    pub fn rays_traced(&self) -> RayCounts {
        self.rays_traced
    }

    /// Time spent tracing finished passes since the last restart.
    pub fn seconds(&self) -> f64 {
        self.seconds
    }

    /// The settings in force.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// The camera in force.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The scene being rendered.
    pub fn scene(&self) -> &Arc<PreparedScene> {
        &self.scene
    }

    /// Samples per pixel of the image as it stands (the mean over all pixels).
    pub fn samples_per_pixel(&self) -> f64 {
        self.accumulator.sample_count() as f64 / self.active.len().max(1) as f64
    }
}

/// Whether a render draws random numbers beyond the pixel positions (a lens, an area light,
/// a glossy material, paths), so that its pixels are noisy.
pub fn is_stochastic(scene: &PreparedScene, camera: &Camera, settings: &RenderSettings) -> bool {
    camera.aperture > 0.0
        || scene.appearance.is_stochastic()
        || settings.integrator == IntegratorKind::Path
}
