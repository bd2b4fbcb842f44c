//! The interactive viewer: a winit window whose `pixels` framebuffer shows the progressive
//! render beside an egui side panel. Rendering runs on its own thread (render_thread.rs);
//! this thread only handles input, copies finished passes into the framebuffer, and draws.

mod camera_input;
mod document;
mod gfx;
mod history;
mod panel;
mod recent;
mod render_thread;
mod screenshot;
mod timing;
mod watch;

use anyhow::{Context, Result, anyhow};
use camera_input::CameraInput;
use document::{Document, LoadMessage};
use gfx::Gfx;
use history::{EditKey, History};
use panel::{PANEL_WIDTH, PanelState};
use prism::render::{AdaptiveSettings, RenderSettings};
use prism::scene::Scene;
use prism::scene_file::SceneLoad;
use render_thread::{RenderThread, Request, Status};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{ElementState, KeyEvent, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, EventLoopProxy};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::WindowId;

/// While nothing changes, repaints the window system asks for (X11 exposures; under Xvfb
/// every present causes one) are served at most this often.
const IDLE_REPAINT: Duration = Duration::from_millis(200);

/// Which input egui (the panel) takes this event.
struct EguiClaims {
    keys: bool,
    pointer: bool,
    wheel: bool,
}

/// Sent by the render thread when it has published a new image.
#[derive(Debug, Clone, Copy)]
struct Wake;

/// The scene the viewer opens with.
pub enum Start {
    /// The built-in seed scene.
    Seed(Scene),
    /// A scene file, as loaded (or refused: the window then opens with the error shown).
    File {
        /// The file.
        path: PathBuf,
        /// Its load.
        load: SceneLoad,
    },
}

/// What the viewer opens with, resolved and checked by the command line.
pub struct Launch {
    /// The scene to show.
    pub start: Start,
    /// The image size (beside the panel) and anti-aliasing level to start with.
    pub settings: RenderSettings,
    /// Where screenshots are saved.
    pub screenshot_dir: PathBuf,
    /// Log frame times and change latencies (`timing.rs`).
    pub log_timing: bool,
}

/// Opens the window and runs until it closes.
pub fn run(launch: Launch) -> Result<()> {
    let Launch {
        start,
        settings: mut probe,
        screenshot_dir,
        log_timing,
    } = launch;
    let aa = probe.aa;
    let window_width = probe.width as u64 + PANEL_WIDTH.ceil() as u64;
    let largest = prism::limits::MAX_WINDOW_SIDE;
    if window_width > largest as u64 || probe.height > largest {
        return Err(prism::render::SettingsError::Window {
            width: probe.width,
            height: probe.height,
            panel: PANEL_WIDTH.ceil() as u32,
        }
        .into());
    }
    let dir_problem = match std::fs::metadata(&screenshot_dir) {
        Ok(meta) if meta.is_dir() => None,
        Ok(_) => Some("it is not a directory".to_string()),
        Err(e) => Some(prism::messages::io_message(&e)),
    };
    if let Some(reason) = dir_problem {
        return Err(prism::render::OutputError::Create {
            path: screenshot_dir,
            reason: format!("screenshots cannot be saved here: {reason}"),
        }
        .into());
    }
    let event_loop = match EventLoop::<Wake>::with_user_event().build() {
        Ok(event_loop) => event_loop,
        // Without a window, a scene that failed to load is the error to report.
        Err(e) => {
            if let Start::File { load, .. } = start
                && let Err(scene_error) = load.result
            {
                return Err(scene_error.into());
            }
            return Err(anyhow!(
                "cannot open a window ({e}); is there a display? \
                 `prism render` renders without one"
            ));
        }
    };
    event_loop.set_control_flow(ControlFlow::Wait);
    let (sender, loads) = channel();
    let proxy = Mutex::new(event_loop.create_proxy());
    let mut document = Document::new(sender, move || {
        let _ = proxy
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .send_event(Wake);
    });
    let scene = match start {
        Start::Seed(scene) => {
            document.loaded = prism::seed::loaded().ok();
            document.saved = Some(scene.clone());
            scene
        }
        Start::File { path, load } => {
            document.path = Some(path.clone());
            document.watch(&path, load.files);
            match load.result {
                Ok(loaded) => {
                    let scene = loaded.scene.clone();
                    document.saved = Some(scene.clone());
                    document.loaded = Some(loaded);
                    scene
                }
                Err(e) => {
                    eprintln!("prism: error: the scene did not load: {e}");
                    document.error = Some(e.to_string());
                    empty_scene()
                }
            }
        }
    };
    let mut recent = recent::list_path()
        .as_deref()
        .map(recent::read)
        .unwrap_or_default();
    if let Some(path) = &document.path {
        recent = recent::remember(&recent, path);
    }
    let step = step_for(&scene);
    probe.width = probe.width.max(1);
    let mut app = App {
        proxy: event_loop.create_proxy(),
        screenshot_dir,
        panel: PanelState::new(scene, aa),
        input: CameraInput::new(step),
        document,
        loads,
        history: History::new(),
        recent,
        seen_picks: 0,
        timing: log_timing.then(timing::Timing::new),
        initial_image: (probe.width, probe.height),
        gfx: None,
        error: None,
        last_frame: Instant::now(),
        shown_serial: 0,
        cursor: None,
        dirty: true,
        last_present: Instant::now(),
        refresh_pending: false,
        holding: false,
        modifiers: Default::default(),
        status: Status::default(),
        render_error: None,
        press: None,
        awaiting_focus: false,
    };
    event_loop
        .run_app(&mut app)
        .context("the window's event loop failed")?;
    match (app.error, app.render_error) {
        (Some(e), _) => Err(e),
        (None, Some(e)) => Err(anyhow!("the render failed while the viewer ran: {e}")),
        (None, None) => Ok(()),
    }
}

/// A tap moves 1/64 of the scene's size; a held key flies a quarter of it a second.
fn step_for(scene: &Scene) -> f32 {
    scene
        .bounds()
        .map_or(0.625, |b| ((b.max - b.min).length() / 64.0).max(1e-3))
}

/// What the window shows while no scene has loaded: nothing, under the default camera.
fn empty_scene() -> Scene {
    prism::scene_file::parse_scene(
        "[camera]\neye = [0, 0, 0]\nfov = 40\n",
        Path::new("(no scene)"),
        Path::new("."),
    )
    .expect("the empty scene is valid")
}

struct App {
    proxy: EventLoopProxy<Wake>,
    screenshot_dir: PathBuf,
    panel: PanelState,
    input: CameraInput,
    document: Document,
    /// Finished loads of the scene file (the watcher's, Open's, F5's).
    loads: Receiver<LoadMessage>,
    history: History,
    /// Recently opened scene files, newest first.
    recent: Vec<PathBuf>,
    /// How many picks the render thread had answered when last looked at.
    seen_picks: u64,
    timing: Option<timing::Timing>,
    initial_image: (u32, u32),
    gfx: Option<Gfx>,
    error: Option<anyhow::Error>,
    last_frame: Instant,
    shown_serial: u64,
    cursor: Option<PhysicalPosition<f64>>,
    /// Something (input, a new image, a resize, egui) changed since the last frame.
    dirty: bool,
    last_present: Instant,
    /// An idle repaint was deferred; the event loop wakes for it at IDLE_REPAINT.
    refresh_pending: bool,
    /// A frame was held for a change's image (`RenderThread::image_due`); the image's
    /// wake, or the event loop at the deadline, draws it.
    holding: bool,
    modifiers: winit::keyboard::ModifiersState,
    status: Status,
    /// The last failure of the render thread, reported again when the window closes.
    render_error: Option<String>,
    /// Where a left press on the image began, and how far the cursor has moved since: a
    /// press released where it began is a click (which focuses the lens).
    press: Option<(PhysicalPosition<f64>, f64)>,
    /// A focus click was sent; the panel takes the distance from the next status.
    awaiting_focus: bool,
}

impl App {
    fn settings(&self, width: u32, height: u32) -> RenderSettings {
        let mut s = RenderSettings::new(width, height, self.panel.aa);
        s.samples = self.panel.samples;
        if self.panel.adaptive {
            s.adaptive = Some(AdaptiveSettings {
                tolerance: self.panel.tolerance,
                ..AdaptiveSettings::default()
            });
        }
        s
    }

    fn create_gfx(&mut self, event_loop: &ActiveEventLoop) -> Result<Gfx> {
        let proxy = self.proxy.clone();
        let (scene, camera) = (&self.panel.scene, self.panel.camera);
        let settings = |(w, h)| self.settings(w, h);
        Gfx::open(event_loop, self.initial_image, |image| {
            RenderThread::spawn(scene, camera, settings(image), move || {
                let _ = proxy.send_event(Wake);
            })
        })
    }

    fn send_camera(&self, moving: bool) {
        if let Some(g) = &self.gfx {
            g.render.send(Request::Camera {
                camera: self.panel.camera,
                moving,
            });
        }
    }

    fn screenshot(&mut self) {
        let Some(g) = &self.gfx else { return };
        let result = {
            let p = g.render.published();
            screenshot::save(
                &self.screenshot_dir,
                &p.rgba,
                p.width,
                p.height,
                p.status.samples_per_pixel,
            )
        };
        let message = match result {
            Ok(path) => (format!("saved {}", path.display()), false),
            Err(e) => (format!("screenshot failed: {e:#}"), true),
        };
        eprintln!("prism: {}", message.0);
        self.panel.message = Some(message);
        if let Some(g) = &self.gfx {
            g.window.request_redraw();
        }
    }

    /// One frame: fly the camera, show the newest image, run the panel, draw, and send the
    /// panel's changes to the render thread.
    fn redraw(&mut self) -> Result<()> {
        let now = Instant::now();
        let dt = (now - self.last_frame).as_secs_f32().min(0.1);
        self.last_frame = now;
        if self.input.flying() && self.input.fly(&mut self.panel.camera, dt) {
            self.send_camera(true);
        }
        let Some(g) = &mut self.gfx else {
            return Ok(());
        };
        let (status, serial) = g.take_published(self.shown_serial);
        self.shown_serial = serial;
        self.report(status);
        let Some(g) = &mut self.gfx else {
            return Ok(());
        };
        let input = g.egui_state.take_egui_input(&g.window);
        let mut changes = panel::Changes::default();
        self.panel.step = self.input.step;
        self.panel.file = panel::FileStatus {
            path: self.document.path.clone(),
            error: self.document.error.clone(),
            unsaved: self.document.unsaved(&self.panel.scene),
            loaded: self.document.loaded.is_some(),
            can_undo: self.history.can_undo(),
            can_redo: self.history.can_redo(),
            recent: self.recent.clone(),
            animation: (self.document.loaded.as_ref())
                .and_then(|l| l.animation.as_ref())
                .map(|a| (a.frames, a.fps)),
            frame: self.document.frame(),
        };
        let panel = &mut self.panel;
        let status = &self.status;
        let output = g.egui_ctx.run_ui(input, |ui| {
            egui::Panel::left("controls")
                .exact_size(PANEL_WIDTH)
                .resizable(false)
                .show(ui, |ui| changes = panel.show(ui, status));
        });
        self.input.step = self.panel.step;
        g.egui_state
            .handle_platform_output(&g.window, output.platform_output);
        g.draw(
            output.shapes,
            output.pixels_per_point,
            output.textures_delta,
        )?;
        if let Some(t) = &mut self.timing {
            t.frame(self.status.generation, self.status.preview, now);
        }
        let repaint_now = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .is_some_and(|v| v.repaint_delay.is_zero());
        self.apply(changes);
        if repaint_now && let Some(g) = &self.gfx {
            self.dirty = true;
            g.window.request_redraw();
        }
        Ok(())
    }

    /// Takes the render thread's status, saying on stderr when the image converges or the
    /// render fails (for whoever launched the viewer, and for the window test).
    fn report(&mut self, status: Status) {
        if status.converged && !self.status.converged {
            eprintln!(
                "prism: converged: {} passes, {:.2} samples per pixel, {:.2} s",
                status.passes_done, status.samples_per_pixel, status.seconds
            );
        }
        if let Some(e) = &status.error
            && self.status.error.as_ref() != Some(e)
        {
            eprintln!("prism: error: the render failed: {e}");
            self.render_error = Some(e.clone());
        }
        // The convergence plot follows the accumulation, and starts again with it.
        if !status.preview && status.passes_done > 0 {
            let restarted = self
                .panel
                .convergence
                .last()
                .is_some_and(|p| status.seconds < p[0] || status.samples_per_pixel < p[1]);
            if restarted {
                self.panel.convergence.clear();
            }
            let point = [
                status.seconds,
                status.samples_per_pixel,
                status.mean_error.unwrap_or(0.0),
            ];
            if self.panel.convergence.last() != Some(&point) {
                self.panel.convergence.push(point);
            }
        } else if status.preview {
            self.panel.convergence.clear();
        }
        // A pick's answer: the selection, named in the panel.
        if status.picks != self.seen_picks {
            self.seen_picks = status.picks;
            self.panel.selected = status.picked;
            match status.picked.and_then(|i| self.panel.scene.objects.get(i)) {
                Some(o) => eprintln!("prism: selected {}", o.name),
                None => eprintln!("prism: selected nothing"),
            }
        }
        // A focus click's distance, once the render thread has found it.
        if self.awaiting_focus
            && !status.preview
            && status.focus_distance > 0.0
            && status.focus_distance != self.panel.camera.focus_distance
        {
            self.panel.camera.focus_distance = status.focus_distance;
            self.awaiting_focus = false;
            eprintln!("prism: focused at {}", status.focus_distance);
        }
        self.status = status;
    }

    /// Sends what the panel changed to the render thread, and does what it asked.
    fn apply(&mut self, changes: panel::Changes) {
        let now = Instant::now();
        let mut edits = changes.edits;
        if let Some((object, placement, field)) = changes.place
            && let Some(loaded) = &self.document.loaded
        {
            // The entry is validated again with these values, as a load of the file would be.
            let before = self.panel.scene.clone();
            match loaded.place_object(&mut self.panel.scene, object, placement) {
                Ok(()) if self.panel.scene != before => {
                    edits.push((EditKey(format!("object {object} {field}")), before))
                }
                Ok(()) => {}
                Err(e) => self.panel.message = Some((e.to_string(), true)),
            }
        }
        let edited = !edits.is_empty();
        for (key, before) in edits {
            self.history.record(&before, key, now);
        }
        if edited {
            self.send_scene();
        }
        let Some(g) = &self.gfx else { return };
        if let Some(selection) = changes.select {
            g.render.send(Request::Select(selection));
        }
        if let Some(view) = changes.view {
            g.render.send(Request::View(view));
        }
        if changes.camera {
            self.send_camera(false);
        }
        if changes.settings {
            let (iw, ih) = g.image_size();
            let generation = g.render.send(Request::Settings(self.settings(iw, ih)));
            if let Some(t) = &mut self.timing {
                t.sent(generation, "settings");
            }
        }
        if changes.screenshot {
            self.screenshot();
        }
        if changes.save {
            self.save();
        }
        if let Some(path) = changes.save_as {
            self.save_as(path);
        }
        if let Some(path) = changes.open {
            self.open(path);
        }
        if changes.reload {
            self.reload();
        }
        if let Some(frame) = changes.frame {
            // The file is loaded again at the frame: unsaved edits are one undo away, as
            // for any reload.
            self.document.set_frame(frame);
            self.reload();
        }
        if changes.undo {
            self.undo();
        }
        if changes.redo {
            self.redo();
        }
    }

    /// The panel's scene to the render thread (which rebuilds only what changed).
    fn send_scene(&mut self) {
        if let Some(g) = &self.gfx {
            let generation = g
                .render
                .send(Request::Scene(Box::new(self.panel.scene.clone())));
            if let Some(t) = &mut self.timing {
                t.sent(generation, "edit");
            }
        }
    }

    /// Shows `text` in the panel and on stderr (for whoever launched the viewer, and for
    /// the window test).
    fn say(&mut self, text: String, error: bool) {
        if error {
            eprintln!("prism: error: {text}");
        } else {
            eprintln!("prism: {text}");
        }
        self.panel.message = Some((text, error));
        if let Some(g) = &self.gfx {
            g.window.request_redraw();
        }
    }

    fn undo(&mut self) {
        match self.history.undo(&self.panel.scene) {
            Some(scene) => {
                self.panel.set_scene(scene);
                self.send_scene();
                self.say("undid the last edit".into(), false);
            }
            None => self.say("nothing to undo".into(), false),
        }
    }

    fn redo(&mut self) {
        match self.history.redo(&self.panel.scene) {
            Some(scene) => {
                self.panel.set_scene(scene);
                self.send_scene();
                self.say("redid the edit".into(), false);
            }
            None => self.say("nothing to redo".into(), false),
        }
    }

    /// Ctrl+S: the edits and the camera written into the scene file, atomically.
    fn save(&mut self) {
        match self.document.path.clone() {
            Some(path) => {
                self.write_scene(&path);
            }
            None => self.say(
                "the built-in seed scene has no file: type a path in File and press Save as".into(),
                true,
            ),
        }
    }

    /// Writes the scene to `path` (another file), then shows that file.
    fn save_as(&mut self, path: PathBuf) {
        if path.extension().is_none_or(|e| e != "toml") {
            return self.say(
                format!("{}: a scene file's name ends in .toml", path.display()),
                true,
            );
        }
        if self.write_scene(&path) {
            if self.document.path.as_deref() != Some(path.as_path()) {
                self.say(
                    format!(
                        "saved {}; textures and meshes are named relative to the file, so                          copy them beside it if it is in another folder",
                        path.display()
                    ),
                    false,
                );
            }
            self.document.path = Some(path.clone());
            self.recent = recent::remember(&self.recent, &path);
            self.document.load_in_background(path);
        }
    }

    /// The scene and camera written into the last good load's text, at `path`; true when
    /// written.
    fn write_scene(&mut self, path: &Path) -> bool {
        if let Some(e) = &self.document.error {
            let text = format!("not saved: the file has an error to fix first ({e})");
            self.say(text, true);
            return false;
        }
        let Some(loaded) = &self.document.loaded else {
            self.say("not saved: no scene file has loaded".into(), true);
            return false;
        };
        let saved =
            match prism::scene_file::saved_text(loaded, &self.panel.scene, &self.panel.camera) {
                Ok(saved) => saved,
                Err(e) => {
                    self.say(format!("not saved: {e}"), true);
                    return false;
                }
            };
        match prism::render::write_bytes(path, saved.text.as_bytes()) {
            Ok(_) => {
                self.document.saved = Some(self.panel.scene.clone());
                let mut text = format!("saved {}", path.display());
                for s in &saved.skipped {
                    text.push_str(&format!("; not saved: {s}"));
                }
                self.say(text, !saved.skipped.is_empty());
                true
            }
            Err(e) => {
                self.say(format!("not saved: {e}"), true);
                false
            }
        }
    }

    /// Opens another scene file (loaded on a thread; the window shows it when it is ready).
    fn open(&mut self, path: PathBuf) {
        self.say(format!("opening {}", path.display()), false);
        if self.document.path.as_deref() != Some(path.as_path()) {
            self.document.set_frame(0);
        }
        self.document.load_in_background(path);
    }

    /// F5: loads the scene file again now.
    fn reload(&mut self) {
        if let Some(path) = self.document.path.clone() {
            self.document.load_in_background(path);
        }
    }

    /// Takes the finished loads: a good one replaces the scene, a bad one is shown and the
    /// last good scene stays.
    fn take_loads(&mut self) {
        while let Ok(message) = self.loads.try_recv() {
            self.on_load(message);
        }
    }

    fn on_load(&mut self, LoadMessage { path, load, asked }: LoadMessage) {
        let same_file = self.document.path.as_deref() == Some(path.as_path());
        if asked || !same_file {
            // A load asked for (Open, F5, Save as) watches what it read from now on.
            self.document.watch(&path, load.files);
        }
        if !same_file {
            self.document.path = Some(path.clone());
            self.recent = recent::remember(&self.recent, &path);
        }
        let loaded = match load.result {
            Ok(loaded) => loaded,
            Err(e) => {
                let text = e.to_string();
                self.document.error = Some(text.clone());
                return self.say(format!("the scene did not load: {text}"), true);
            }
        };
        // Frames asked for one after another load in parallel: only the last one asked
        // for is shown.
        if let Some(animation) = &loaded.animation
            && loaded.frame != self.document.frame().min(animation.frames - 1)
        {
            return;
        }
        let scene = loaded.scene.clone();
        let camera = match (&self.document.loaded, same_file) {
            (Some(before), true) => {
                document::camera_after_reload(&before.scene, &scene, self.panel.camera)
            }
            _ => scene.camera,
        };
        if same_file {
            // Unsaved edits are one undo away rather than lost.
            if self.document.unsaved(&self.panel.scene) {
                self.history
                    .record(&self.panel.scene, EditKey("reload".into()), Instant::now());
            }
            self.history.break_run();
        } else {
            self.history = History::new();
            self.panel.initial_camera = scene.camera;
            self.input.step = step_for(&scene);
            self.panel.samples = scene.render.samples;
        }
        let what = match (&loaded.animation, same_file) {
            (Some(_), true) => format!("frame {} of", loaded.frame),
            (_, true) => "reloaded".into(),
            _ => "opened".into(),
        };
        self.document.error = None;
        self.document.saved = Some(scene.clone());
        self.document.loaded = Some(loaded);
        self.panel.set_scene(scene);
        self.panel.camera = camera;
        self.send_scene();
        self.send_camera(false);
        self.say(format!("{what} {}", path.display()), false);
    }

    fn resize(&mut self, size: PhysicalSize<u32>) -> Result<()> {
        let Some(g) = &mut self.gfx else {
            return Ok(());
        };
        if size.width == 0 || size.height == 0 || size == g.size {
            return Ok(());
        }
        g.size = size;
        g.pixels
            .resize_surface(size.width, size.height)
            .context("resizing the window surface")?;
        g.pixels
            .resize_buffer(size.width, size.height)
            .context("resizing the framebuffer")?;
        g.pixels.frame_mut().fill(0);
        self.shown_serial = 0;
        let (iw, ih) = g.image_size();
        let s = self.settings(iw, ih);
        if let Some(g) = &self.gfx {
            g.render.send(Request::Settings(s));
        }
        Ok(())
    }

    /// Closes the window; dropping the graphics joins the render thread.
    fn close(&mut self, event_loop: &ActiveEventLoop) {
        self.gfx = None;
        event_loop.exit();
    }

    /// Draws a frame, unless the image of a change just sent is due (`image_due`), or
    /// nothing changed and one was drawn within `IDLE_REPAINT` (a deferred repaint then
    /// follows).
    fn on_redraw_requested(&mut self, event_loop: &ActiveEventLoop) {
        if self
            .gfx
            .as_ref()
            .is_some_and(|g| g.render.image_due().is_some())
        {
            // The image of a change is due: the frame waits for it (or its deadline).
            self.holding = true;
            return;
        }
        // Nothing new since the last frame: a pass's image and input set `dirty`.
        let idle = !self.dirty && !self.input.moving();
        if idle && self.last_present.elapsed() < IDLE_REPAINT {
            self.refresh_pending = true;
            return;
        }
        self.dirty = false;
        if let Err(e) = self.redraw() {
            self.fail(event_loop, e);
        }
        self.last_present = Instant::now();
    }

    /// Ctrl+Q quits, movement keys fly, F12 and P save a screenshot. A press the panel
    /// takes (`to_egui`) moves nothing; releases always count, so a key never sticks.
    fn on_key(&mut self, event_loop: &ActiveEventLoop, event: &KeyEvent, to_egui: bool) {
        let PhysicalKey::Code(code) = event.physical_key else {
            return;
        };
        let pressed = event.state == ElementState::Pressed;
        let ctrl = self.modifiers.control_key();
        // Ctrl+Q quits and Ctrl+S saves wherever the keyboard focus is (the panel's too).
        if pressed && ctrl && code == KeyCode::KeyQ {
            return self.close(event_loop);
        }
        if pressed && ctrl && code == KeyCode::KeyS && !event.repeat {
            return self.save();
        }
        if pressed && to_egui {
            return;
        }
        if pressed && ctrl && matches!(code, KeyCode::KeyZ | KeyCode::KeyY) {
            if code == KeyCode::KeyY || self.modifiers.shift_key() {
                self.redo();
            } else {
                self.undo();
            }
            return;
        }
        if pressed && !event.repeat && code == KeyCode::F5 {
            return self.reload();
        }
        if pressed && code == KeyCode::Escape && self.panel.selected.is_some() {
            self.panel.selected = None;
            if let Some(g) = &self.gfx {
                g.render.send(Request::Select(None));
            }
            return;
        }
        // Ctrl with a movement key is a command, not a move.
        if pressed && ctrl {
            return;
        }
        let was_flying = self.input.flying();
        if self.input.key(code, pressed) {
            // A tap shorter than a frame still moves one step.
            let tapped = self.input.finish_taps(&mut self.panel.camera);
            if (was_flying || tapped) && !self.input.moving() {
                self.send_camera(false);
            }
            self.last_frame = Instant::now();
            if let Some(g) = &self.gfx {
                g.window.request_redraw();
            }
        } else if pressed && !event.repeat && matches!(code, KeyCode::F12 | KeyCode::KeyP) {
            self.screenshot();
        }
    }

    /// A drag over the image turns the camera.
    fn on_cursor_moved(&mut self, position: PhysicalPosition<f64>) {
        if self.input.dragging
            && let Some(last) = self.cursor
        {
            let (dx, dy) = (position.x - last.x, position.y - last.y);
            if let Some((_, moved)) = &mut self.press {
                *moved += dx.abs() + dy.abs();
            }
            if dx != 0.0 || dy != 0.0 {
                let (dx, dy) = (dx as f32, dy as f32);
                match self.orbit_target() {
                    Some(target) => CameraInput::orbit(&mut self.panel.camera, target, dx, dy),
                    None => CameraInput::drag(&mut self.panel.camera, dx, dy),
                }
                self.send_camera(true);
            }
        }
        self.cursor = Some(position);
    }

    /// What a drag orbits: the selected object's centre, in orbit mode.
    fn orbit_target(&self) -> Option<glam::Vec3> {
        let object = self.panel.scene.objects.get(self.panel.selected?)?;
        if !self.panel.orbit {
            return None;
        }
        let b = object.shape.bounds();
        let center = (b.min + b.max) * 0.5;
        Some(if center.is_finite() {
            center
        } else {
            object.shape.origin()
        })
    }

    /// A press on the image (`on_image`, and not taken by the panel) starts a drag; the
    /// release ends it and refines the view.
    fn on_left_button(&mut self, state: ElementState, on_image: bool) {
        match state {
            ElementState::Pressed => {
                if on_image {
                    self.input.dragging = true;
                    self.press = self.cursor.map(|c| (c, 0.0));
                }
            }
            ElementState::Released => {
                let dragged = self.press.is_none_or(|(_, moved)| moved > 0.0);
                if self.input.dragging {
                    self.input.dragging = false;
                    // A drag showed coarse previews: refine where it ended.
                    if dragged && !self.input.moving() {
                        self.send_camera(false);
                    }
                }
                // A click (no drag) selects what is under the cursor, and with a lens
                // focuses on it.
                if let (Some((at, moved)), Some(g)) = (self.press.take(), &self.gfx)
                    && moved < 3.0
                {
                    let (x, y) = ((at.x - g.panel_px() as f64) as f32, at.y as f32);
                    g.render.send(Request::Pick { x, y });
                    if self.panel.camera.aperture > 0.0 {
                        g.render.send(Request::FocusAt { x, y });
                        self.awaiting_focus = true;
                    }
                }
            }
        }
    }

    /// Scrolling over the image zooms.
    fn on_wheel(&mut self, delta: MouseScrollDelta) {
        let lines = match delta {
            MouseScrollDelta::LineDelta(_, y) => y,
            MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
        };
        CameraInput::scroll(&mut self.panel.camera, lines);
        self.send_camera(false);
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error = Some(error);
        self.gfx = None;
        event_loop.exit();
    }
}

impl ApplicationHandler<Wake> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gfx.is_some() {
            return;
        }
        match self.create_gfx(event_loop) {
            Ok(g) => {
                g.window.request_redraw();
                self.gfx = Some(g);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn new_events(&mut self, _: &ActiveEventLoop, cause: winit::event::StartCause) {
        if let winit::event::StartCause::ResumeTimeReached { .. } = cause
            && (self.refresh_pending || self.holding)
        {
            self.refresh_pending = false;
            self.holding = false;
            self.dirty = true;
            if let Some(g) = &self.gfx {
                g.window.request_redraw();
            }
        }
    }

    fn user_event(&mut self, _: &ActiveEventLoop, _: Wake) {
        self.take_loads();
        self.dirty = true;
        if let Some(g) = &self.gfx {
            g.window.request_redraw();
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(g) = &mut self.gfx else { return };
        if !matches!(event, WindowEvent::RedrawRequested) {
            self.dirty = true;
        }
        let response = g.egui_state.on_window_event(&g.window, &event);
        if response.repaint {
            g.window.request_redraw();
        }
        // What egui takes: then the image's camera does not.
        let egui = EguiClaims {
            keys: g.egui_ctx.egui_wants_keyboard_input() || response.consumed,
            pointer: g.egui_ctx.egui_wants_pointer_input() || response.consumed,
            wheel: response.consumed,
        };
        let over_image = self.cursor.is_some_and(|c| c.x >= g.panel_px() as f64);
        match event {
            WindowEvent::CloseRequested => self.close(event_loop),
            WindowEvent::Resized(size) => {
                if let Err(e) = self.resize(size) {
                    self.fail(event_loop, e);
                }
            }
            WindowEvent::RedrawRequested => self.on_redraw_requested(event_loop),
            WindowEvent::Focused(false) => {
                let was_moving = self.input.moving();
                self.input.release_all();
                if was_moving {
                    self.send_camera(false);
                }
            }
            WindowEvent::KeyboardInput { event, .. } => self.on_key(event_loop, &event, egui.keys),
            WindowEvent::ModifiersChanged(m) => self.modifiers = m.state(),
            WindowEvent::CursorMoved { position, .. } => self.on_cursor_moved(position),
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => self.on_left_button(state, over_image && !egui.pointer),
            WindowEvent::MouseWheel { delta, .. } if over_image && !egui.wheel => {
                self.on_wheel(delta)
            }
            WindowEvent::DroppedFile(path) => self.open(path),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let due = self.gfx.as_ref().and_then(|g| g.render.image_due());
        // Keep drawing while the camera moves (but for a change's image, due soon). A new
        // pass's image wakes the loop itself (the render thread's Wake), and input redraws
        // as it comes: between them nothing on screen changes, and a frame drawn then would
        // only take the cores the tracer runs on.
        if let Some(g) = &self.gfx
            && due.is_none()
            && self.input.moving()
        {
            self.dirty = true;
            g.window.request_redraw();
        }
        let refresh = self
            .refresh_pending
            .then(|| self.last_present + IDLE_REPAINT);
        let hold = due.filter(|_| self.holding);
        event_loop.set_control_flow(match (refresh, hold) {
            (Some(a), Some(b)) => ControlFlow::WaitUntil(a.min(b)),
            (Some(t), None) | (None, Some(t)) => ControlFlow::WaitUntil(t),
            (None, None) => ControlFlow::Wait,
        });
    }
}
