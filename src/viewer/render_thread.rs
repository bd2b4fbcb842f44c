//! The render thread: owns the progressive render, takes requests by message, and publishes
//! each finished pass for the UI thread to show. A generation counter, bumped with every
//! request, cancels the pass in flight at the next band of rows. Scenes are prepared here,
//! never on the UI thread, and an appearance edit changes a table in place.

use super::denoised::Denoised;
use prism::camera::Camera;
use prism::render::{Legend, PassOutcome, ProgressiveRender, RenderSettings, View};
use prism::scene::{PreparedScene, Scene};
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// While the camera moves, and before an edit's first full pass, one ray per block of at
/// least this many pixels on a side.
pub const PREVIEW_BLOCK: u32 = 4;

/// A coarse preview traces at most about this many rays: on an image larger than 1024×768
/// its blocks grow past `PREVIEW_BLOCK`, so that its cost (and an edit's wait for its
/// first image) stays that of a 1024×768 one.
pub const PREVIEW_RAYS: u32 = 1024 * 768 / (PREVIEW_BLOCK * PREVIEW_BLOCK);

/// How long the UI holds its next frame for the image of a change it sent. A frame
/// begun just after the change would show the old image and delay the new one by a whole
/// frame; the coarse preview of a change usually comes well within this.
pub const IMAGE_WAIT: Duration = Duration::from_millis(50);

/// The side of a preview's blocks, in pixels, for a `width` × `height` image.
pub fn preview_block(width: u32, height: u32) -> u32 {
    let pixels = width as f64 * height as f64;
    PREVIEW_BLOCK.max((pixels / PREVIEW_RAYS as f64).sqrt().ceil() as u32)
}

pub enum Request {
    /// The scene changed (an edit, already validated, an undo, a reload): geometry is
    /// rebuilt only if the edit changed it.
    Scene(Box<Scene>),
    /// `moving`: the camera is still being dragged or flown, so show a fast coarse preview
    /// and wait for the next position instead of refining.
    Camera {
        camera: Camera,
        moving: bool,
    },
    Settings(RenderSettings),
    /// Focus the lens on what lies under image point (x, y), in pixels.
    FocusAt {
        x: f32,
        y: f32,
    },
    /// Select the object under image point (x, y) (none there: no selection); the answer
    /// comes in `Status::picked`.
    Pick {
        x: f32,
        y: f32,
    },
    /// Select this object (from the panel's list), or none.
    Select(Option<usize>),
    /// Show the image, or a heat map of the samples or the error estimates.
    View(View),
    /// Show the image denoised (or raw).
    Denoise(bool),
}

/// What the render thread reports alongside each image.
#[derive(Clone, Debug, Default)]
pub struct Status {
    pub passes_done: u32,
    pub total_passes: u32,
    pub samples_per_pixel: f64,
    pub ms_per_pass: f64,
    pub rays_per_second: f64,
    /// Wall-clock seconds since the last restart; frozen once converged.
    pub seconds: f64,
    pub converged: bool,
    pub active_pixels: usize,
    pub total_pixels: usize,
    pub preview: bool,
    /// The lens's focus distance in the render (the render thread sets it on a focus
    /// click); 0 in a preview's status.
    pub focus_distance: f32,
    /// Why the last pass failed (a panic in the tracer): shown in the panel, and the
    /// viewer's exit code reports it.
    pub error: Option<String>,
    /// The object the last pick found (None: the background), and a count of the picks
    /// answered, so that the UI sees each answer once.
    pub picked: Option<usize>,
    pub picks: u64,
    /// The generation of the requests this image reflects (see `RenderThread::send`).
    pub generation: u64,
    /// What the heat map shown stands for (None: the image is shown).
    pub legend: Option<Legend>,
    /// The mean error estimate over the pixels that have one: the convergence plot's.
    pub mean_error: Option<f64>,
    /// Whether the image shown is denoised, and why denoising failed.
    pub denoised: bool,
    pub denoise_error: Option<String>,
}

/// The latest published image, as RGBA8 rows.
#[derive(Default)]
pub struct Published {
    pub rgba: Vec<u8>,
    pub width: u32,
    pub height: u32,
    /// Bumped with every publication, so the UI copies only what is new.
    pub serial: u64,
    pub status: Status,
    /// The pixels around the selected object (an outline two pixels wide), or None with no
    /// selection or while the camera moves. Shown on screen only, never in a screenshot.
    pub outline: Option<Arc<Vec<bool>>>,
}

pub struct RenderThread {
    requests: Option<Sender<Request>>,
    generation: Arc<AtomicU64>,
    published: Arc<Mutex<Published>>,
    handle: Option<JoinHandle<()>>,
    /// The generation of the last change sent whose image the UI waits for, and until when.
    awaited: Cell<Option<(u64, Instant)>>,
}

impl RenderThread {
    /// Prepares `scene` and starts rendering it on a thread of its own; `wake` is called
    /// after each publication (to redraw).
    pub fn spawn(
        scene: &Scene,
        camera: Camera,
        settings: RenderSettings,
        wake: impl Fn() + Send + 'static,
    ) -> Self {
        let (tx, rx) = channel();
        let generation = Arc::new(AtomicU64::new(0));
        let published = Arc::new(Mutex::new(Published::default()));
        let scene = scene.clone();
        let (generation_, published_) = (generation.clone(), published.clone());
        let handle = std::thread::Builder::new()
            .name("prism-render".into())
            .spawn(move || {
                let job =
                    ProgressiveRender::new(Arc::new(PreparedScene::new(&scene)), camera, settings);
                Worker {
                    job,
                    scene,
                    selection: None,
                    outline: None,
                    picked: None,
                    picks: 0,
                    last_pass_seconds: 0.0,
                    pass_generation: 0,
                    preview_first: false,
                    last_seconds: 0.0,
                    view: View::Image,
                    denoised: Denoised::default(),
                    requests: rx,
                    generation: generation_,
                    published: published_,
                    wake: Box::new(wake),
                    moving: false,
                    restarted: Instant::now(),
                }
                .run()
            })
            .expect("the render thread starts");
        Self {
            requests: Some(tx),
            generation,
            published,
            handle: Some(handle),
            awaited: Cell::new(None),
        }
    }

    /// Sends a change; the pass in flight is abandoned. Returns the change's generation:
    /// an image published with `Status::generation` at or past it shows the change.
    /// The UI waits (`image_due`) for the image of any change but a moving camera's, whose
    /// next position follows at once.
    pub fn send(&self, request: Request) -> u64 {
        let generation = self.generation.fetch_add(1, Ordering::SeqCst) + 1;
        if !matches!(request, Request::Camera { moving: true, .. }) {
            self.awaited
                .set(Some((generation, Instant::now() + IMAGE_WAIT)));
        }
        if let Some(tx) = &self.requests {
            // The worker only stops when we drop the sender, so this cannot fail first.
            let _ = tx.send(request);
        }
        generation
    }

    /// While the image of the last change sent is not published yet, and at most
    /// `IMAGE_WAIT` after it was sent: when to stop waiting for it.
    pub fn image_due(&self) -> Option<Instant> {
        let (generation, deadline) = self.awaited.get()?;
        if Instant::now() >= deadline || self.published().status.generation >= generation {
            self.awaited.set(None);
            return None;
        }
        Some(deadline)
    }

    pub fn published(&self) -> MutexGuard<'_, Published> {
        self.published.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl Drop for RenderThread {
    /// Closing the channel ends the worker after at most one band of rows.
    fn drop(&mut self) {
        self.generation.fetch_add(1, Ordering::SeqCst);
        self.requests.take();
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

struct Worker {
    job: ProgressiveRender,
    /// The scene as described, to tell what an edit changed.
    scene: Scene,
    selection: Option<usize>,
    /// The selection's outline for the current view; None when it must be found again.
    outline: Option<Arc<Vec<bool>>>,
    picked: Option<usize>,
    picks: u64,
    last_pass_seconds: f64,
    /// The generation the pass being traced started at.
    pass_generation: u64,
    /// A change was applied: show a coarse preview before the first full pass, so that the
    /// change is seen at once however large the image.
    preview_first: bool,
    /// Seconds from the restart to the end of the last pass.
    last_seconds: f64,
    view: View,
    denoised: Denoised,
    requests: Receiver<Request>,
    generation: Arc<AtomicU64>,
    published: Arc<Mutex<Published>>,
    wake: Box<dyn Fn() + Send>,
    moving: bool,
    restarted: Instant,
}

impl Worker {
    fn run(mut self) {
        lower_priority();
        let pool = rayon::ThreadPoolBuilder::new()
            .stack_size(prism::limits::RENDER_STACK_BYTES)
            .thread_name(|i| format!("prism-worker-{i}"))
            .start_handler(|_| lower_priority())
            .build();
        let pool = match pool {
            Ok(pool) => pool,
            Err(e) => return self.fail(format!("cannot start the worker threads: {e}")),
        };
        let mut waiting = false;
        loop {
            // Idle (converged, or a preview shown): sleep until a request comes.
            let first = if waiting {
                match self.requests.recv() {
                    Ok(r) => Some(r),
                    Err(_) => return,
                }
            } else {
                None
            };
            if let Some(r) = first {
                self.apply(r);
            }
            loop {
                match self.requests.try_recv() {
                    Ok(r) => self.apply(r),
                    Err(TryRecvError::Empty) => break,
                    Err(TryRecvError::Disconnected) => return,
                }
            }
            let generation = self.generation.load(Ordering::SeqCst);
            self.pass_generation = generation;
            // A scene no render can finish is shown as a failure until it changes.
            if self.job.passes_done() == 0
                && let Err(e) = self.job.scene().check_coincident(&self.scene)
            {
                self.fail(e.to_string());
                waiting = true;
                continue;
            }
            let counter = self.generation.clone();
            let cancelled = move || counter.load(Ordering::SeqCst) != generation;
            // A panic in the tracer is a bug: report it and wait for a change, rather
            // than die silently or fail again and again on the same pass.
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                pool.install(|| {
                    crate::fault_injection::injected_panic();
                    if self.moving {
                        self.preview(&cancelled);
                        return true;
                    }
                    if std::mem::take(&mut self.preview_first) && self.job.passes_done() == 0 {
                        self.preview(&cancelled);
                        return false;
                    }
                    match self.job.step(&cancelled) {
                        PassOutcome::Finished(stats) => {
                            self.publish(Some(stats.seconds));
                            false
                        }
                        PassOutcome::Cancelled => false,
                        // The last finished pass already published the converged image.
                        PassOutcome::Converged => true,
                    }
                })
            }));
            waiting = match outcome {
                Ok(waiting) => waiting,
                Err(payload) => {
                    self.fail(panic_message(payload.as_ref()));
                    true
                }
            };
        }
    }

    fn apply(&mut self, request: Request) {
        // Whatever changes, the outline is found again for the new image.
        self.outline = None;
        // A selection changes no pixel: the image so far is shown again with its outline.
        let republish = |w: &mut Self| {
            w.pass_generation = w.generation.load(Ordering::SeqCst);
            if w.job.passes_done() > 0 {
                w.publish(None);
            }
        };
        match request {
            Request::Pick { x, y } => {
                let s = self.job.settings();
                let rays = self.job.camera().rays(s.width, s.height);
                self.selection = self.job.scene().object_at(&rays, x, y);
                self.picked = self.selection;
                self.picks += 1;
                return republish(self);
            }
            Request::Select(selection) => {
                self.selection = selection;
                return republish(self);
            }
            Request::View(view) => {
                self.view = view;
                return republish(self);
            }
            Request::Denoise(on) => {
                self.denoised.on = on;
                return republish(self);
            }
            _ => {}
        }
        self.restarted = Instant::now();
        self.preview_first = true;
        self.denoised.restart();
        match request {
            Request::Pick { .. } | Request::Select(_) | Request::View(_) | Request::Denoise(_) => {}
            Request::Scene(scene) => {
                let prepared = self.job.scene().updated(&self.scene, &scene);
                self.job.set_scene(Arc::new(prepared));
                self.scene = *scene;
                if self
                    .selection
                    .is_some_and(|s| s >= self.scene.objects.len())
                {
                    self.selection = None;
                }
            }
            Request::Camera { camera, moving } => {
                self.moving = moving;
                self.job.set_camera(camera);
            }
            Request::Settings(settings) => self.job.set_settings(settings),
            Request::FocusAt { x, y } => {
                let mut camera = *self.job.camera();
                let s = self.job.settings();
                let rays = camera.rays(s.width, s.height);
                if let Some(depth) = self.job.scene().depth_at(&rays, x, y) {
                    camera.focus_distance = depth;
                    if camera.check().is_ok() {
                        self.job.set_camera(camera);
                    }
                }
            }
        }
    }

    /// One ray per block of pixels (`preview_block`), upscaled by repetition.
    fn preview(&mut self, cancelled: &(dyn Fn() -> bool + Sync)) {
        let full = *self.job.settings();
        let block = preview_block(full.width, full.height);
        let mut settings = full;
        settings.width = full.width.div_ceil(block);
        settings.height = full.height.div_ceil(block);
        settings.aa = 1;
        settings.adaptive = None;
        let mut coarse =
            ProgressiveRender::new(self.job.scene().clone(), *self.job.camera(), settings);
        let PassOutcome::Finished(stats) = coarse.step(cancelled) else {
            return;
        };
        let mut small = vec![0u8; (settings.width * settings.height * 4) as usize];
        coarse.accumulator().write_rgba8(&mut small);
        // Each coarse row is widened once, then repeated down its block.
        let (w, sw) = (full.width as usize * 4, settings.width as usize * 4);
        let mut rgba = vec![0u8; w * full.height as usize];
        for (sy, rows) in rgba.chunks_mut(w * block as usize).enumerate() {
            let coarse = &small[sy * sw..(sy + 1) * sw];
            let (first, rest) = rows.split_at_mut(w);
            for (x, px) in first.chunks_exact_mut(4).enumerate() {
                let s = x / block as usize * 4;
                px.copy_from_slice(&coarse[s..s + 4]);
            }
            for row in rest.chunks_mut(w) {
                row.copy_from_slice(first);
            }
        }
        let status = Status {
            passes_done: 0,
            total_passes: full.total_passes(),
            ms_per_pass: stats.seconds * 1e3,
            rays_per_second: stats.rays.total() as f64 / stats.seconds.max(1e-9),
            total_pixels: (full.width * full.height) as usize,
            preview: true,
            picked: self.picked,
            picks: self.picks,
            generation: self.pass_generation,
            ..Status::default()
        };
        self.store(rgba, full.width, full.height, status, None);
    }

    /// Publishes the image so far: after a pass that took `pass_seconds`, or again (None)
    /// in another view or with another selection, with the times of the last pass.
    fn publish(&mut self, pass_seconds: Option<f64>) {
        if let Some(s) = pass_seconds {
            self.last_pass_seconds = s;
            self.last_seconds = self.restarted.elapsed().as_secs_f64();
        }
        let pass_seconds = self.last_pass_seconds;
        let s = self.job.settings();
        let (width, height) = (s.width, s.height);
        let mut rgba = vec![0u8; (width * height * 4) as usize];
        let denoised = match self.view {
            View::Image => self.denoised.film(&self.job),
            View::Samples | View::Error => None,
        };
        let is_denoised = denoised.is_some();
        let film = denoised.unwrap_or(self.job.accumulator());
        let legend = prism::render::write_view_rgba8(film, self.view, &mut rgba);
        let rays = self.job.rays_traced();
        let converged = self.job.is_converged();
        let status = Status {
            passes_done: self.job.passes_done(),
            total_passes: self.job.total_passes(),
            samples_per_pixel: self.job.samples_per_pixel(),
            ms_per_pass: pass_seconds * 1e3,
            rays_per_second: rays.total() as f64 / self.job.seconds().max(1e-9),
            seconds: self.last_seconds,
            converged,
            active_pixels: if converged {
                0
            } else {
                self.job.active_pixels()
            },
            total_pixels: (width * height) as usize,
            preview: false,
            focus_distance: self.job.camera().focus_distance,
            error: None,
            picked: self.picked,
            picks: self.picks,
            generation: self.pass_generation,
            legend,
            mean_error: prism::render::mean_error(self.job.accumulator()),
            denoised: is_denoised,
            denoise_error: self.denoised.error.clone(),
        };
        if self.outline.is_none()
            && let Some(object) = self.selection
        {
            let rays = self.job.camera().rays(width, height);
            let covered = self.job.scene().coverage(&rays, width, height, object);
            self.outline = Some(Arc::new(outline(&covered, width, height)));
        }
        let outline = self.selection.and(self.outline.clone());
        self.store(rgba, width, height, status, outline);
    }

    /// Publishes the failure with the last image.
    fn fail(&self, message: String) {
        {
            let mut p = self.published.lock().unwrap_or_else(|e| e.into_inner());
            p.serial += 1;
            p.status.error = Some(message);
            p.status.converged = true;
        }
        (self.wake)();
    }

    fn store(
        &self,
        rgba: Vec<u8>,
        width: u32,
        height: u32,
        status: Status,
        outline: Option<Arc<Vec<bool>>>,
    ) {
        {
            let mut p = self.published.lock().unwrap_or_else(|e| e.into_inner());
            p.outline = outline;
            p.rgba = rgba;
            p.width = width;
            p.height = height;
            p.serial += 1;
            p.status = status;
        }
        (self.wake)();
    }
}

/// The pixels outside a covered region and within two pixels of it (by rows and columns).
fn outline(covered: &[bool], width: u32, height: u32) -> Vec<bool> {
    let (w, h) = (width as i64, height as i64);
    let at = |x: i64, y: i64| x >= 0 && y >= 0 && x < w && y < h && covered[(y * w + x) as usize];
    let mut out = vec![false; covered.len()];
    for y in 0..h {
        for x in 0..w {
            if at(x, y) {
                continue;
            }
            let near =
                (-2..=2i64).any(|d| at(x + d, y) || at(x, y + d) || at(x + d.signum(), y + d));
            out[(y * w + x) as usize] = near;
        }
    }
    out
}

/// Makes the calling thread yield to the window's: tracing takes every core, and the UI
/// thread, drawing the panel and the newest image, must still get its turn at once (the
/// responsiveness targets of benches/responsiveness.sh). Nice 10 on Linux; elsewhere a
/// no-op.
fn lower_priority() {
    #[cfg(target_os = "linux")]
    // SAFETY: setpriority only reads its arguments; gettid names the calling thread.
    unsafe {
        let tid = libc::syscall(libc::SYS_gettid) as libc::id_t;
        libc::setpriority(libc::PRIO_PROCESS, tid, 10);
    }
}

/// The text a panic was raised with.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic with no message".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Up to 1024×768 a preview's blocks are PREVIEW_BLOCK pixels wide; past it they grow
    /// so that the preview's rays stay about as many.
    #[test]
    fn preview_blocks_grow_with_the_image() {
        for (w, h) in [(1, 1), (320, 240), (800, 600), (1024, 768)] {
            assert_eq!(preview_block(w, h), PREVIEW_BLOCK, "{w}×{h}");
        }
        for (w, h) in [(1600, 1000), (3840, 2160), (16384, 16384)] {
            let block = preview_block(w, h);
            let rays = w.div_ceil(block) as u64 * h.div_ceil(block) as u64;
            assert!(block > PREVIEW_BLOCK, "{w}×{h}");
            assert!(
                rays <= PREVIEW_RAYS as u64 * 11 / 10,
                "{w}×{h}: {rays} rays"
            );
        }
    }

    /// The UI waits for the image of a change it sent until that image is published or
    /// IMAGE_WAIT has passed, and never for a moving camera's.
    #[test]
    fn a_change_is_awaited_until_its_image_is_published() {
        let scene = prism::seed::scene().unwrap();
        let settings = RenderSettings::new(32, 24, 1);
        let (woken, wakes) = channel();
        let thread = RenderThread::spawn(&scene, scene.camera, settings, move || {
            let _ = woken.send(());
        });
        let sent = Instant::now();
        let generation = thread.send(Request::Settings(RenderSettings::new(40, 30, 1)));
        let due = thread.image_due();
        // Unless the image is already out, the wait ends IMAGE_WAIT after sending at most.
        if let Some(deadline) = due {
            assert!(deadline >= sent && deadline <= Instant::now() + IMAGE_WAIT);
        }
        // Once an image of the change is published, nothing is awaited.
        loop {
            wakes.recv_timeout(Duration::from_secs(30)).unwrap();
            if thread.published().status.generation >= generation {
                break;
            }
        }
        assert_eq!(thread.image_due(), None);
        // A moving camera's image is not waited for.
        let mut camera = scene.camera;
        camera.eye.x += 0.1;
        thread.send(Request::Camera {
            camera,
            moving: true,
        });
        assert_eq!(thread.image_due(), None);
        // A change whose image never comes (no thread renders) is awaited no longer than
        // IMAGE_WAIT.
        let stopped = RenderThread {
            requests: None,
            generation: Arc::new(AtomicU64::new(0)),
            published: Arc::new(Mutex::new(Published::default())),
            handle: None,
            awaited: Cell::new(None),
        };
        let first = stopped.send(Request::Select(None));
        assert!(stopped.image_due().is_some());
        // Its publication ends the wait at once.
        stopped.published().status.generation = first;
        assert_eq!(stopped.image_due(), None);
        stopped.send(Request::Select(None));
        assert!(stopped.image_due().is_some());
        std::thread::sleep(IMAGE_WAIT);
        assert_eq!(stopped.image_due(), None);
    }
}
