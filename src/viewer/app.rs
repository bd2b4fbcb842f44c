//! The window's state (`App`: the panel, the document, the history, the render thread's
//! channel, the window's drawing) and its frame: the newest image and the panel drawn, the
//! panel's changes taken, the render thread's status reported.

use super::camera_input::CameraInput;
use super::document::{Document, LoadMessage};
use super::gfx::Gfx;
use super::history::History;
use super::panel::{self, PANEL_WIDTH, PanelState};
use super::render_thread::{RenderThread, Request, Status};
use super::timing;
use anyhow::{Context, Result};
use prism::render::{AdaptiveSettings, RenderSettings};
use std::path::PathBuf;
use std::sync::mpsc::Receiver;
use std::time::{Duration, Instant};
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event_loop::{ActiveEventLoop, EventLoopProxy};

/// While nothing changes, repaints the window system asks for (X11 exposures; under Xvfb
/// every present causes one) are served at most this often.
pub(super) const IDLE_REPAINT: Duration = Duration::from_millis(200);

/// Which input egui (the panel) takes this event.
pub(super) struct EguiClaims {
    pub(super) keys: bool,
    pub(super) pointer: bool,
    pub(super) wheel: bool,
}

/// Sent by the render thread when it has published a new image.
#[derive(Debug, Clone, Copy)]
pub(super) struct Wake;

pub(super) struct App {
    pub(super) proxy: EventLoopProxy<Wake>,
    pub(super) screenshot_dir: PathBuf,
    pub(super) panel: PanelState,
    pub(super) input: CameraInput,
    pub(super) document: Document,
    /// Finished loads of the scene file (the watcher's, Open's, F5's).
    pub(super) loads: Receiver<LoadMessage>,
    pub(super) history: History,
    /// Recently opened scene files, newest first.
    pub(super) recent: Vec<PathBuf>,
    /// How many picks the render thread had answered when last looked at.
    pub(super) seen_picks: u64,
    pub(super) timing: Option<timing::Timing>,
    pub(super) initial_image: (u32, u32),
    pub(super) gfx: Option<Gfx>,
    pub(super) error: Option<anyhow::Error>,
    pub(super) last_frame: Instant,
    pub(super) shown_serial: u64,
    pub(super) cursor: Option<PhysicalPosition<f64>>,
    /// Something (input, a new image, a resize, egui) changed since the last frame.
    pub(super) dirty: bool,
    pub(super) last_present: Instant,
    /// An idle repaint was deferred; the event loop wakes for it at IDLE_REPAINT.
    pub(super) refresh_pending: bool,
    /// A frame was held for a change's image (`RenderThread::image_due`); the image's
    /// wake, or the event loop at the deadline, draws it.
    pub(super) holding: bool,
    pub(super) modifiers: winit::keyboard::ModifiersState,
    pub(super) status: Status,
    /// The last failure of the render thread, reported again when the window closes.
    pub(super) render_error: Option<String>,
    /// Where a left press on the image began, and how far the cursor has moved since: a
    /// press released where it began is a click (which focuses the lens).
    pub(super) press: Option<(PhysicalPosition<f64>, f64)>,
    /// A focus click was sent; the panel takes the distance from the next status.
    pub(super) awaiting_focus: bool,
}

impl App {
    pub(super) fn settings(&self, width: u32, height: u32) -> RenderSettings {
        let mut s = RenderSettings::new(width, height, self.panel.aa);
        s.samples = self.panel.samples;
        s.integrator = self.panel.integrator;
        if self.panel.adaptive {
            s.adaptive = Some(AdaptiveSettings {
                tolerance: self.panel.tolerance,
                ..AdaptiveSettings::default()
            });
        }
        s
    }

    pub(super) fn create_gfx(&mut self, event_loop: &ActiveEventLoop) -> Result<Gfx> {
        let proxy = self.proxy.clone();
        let (scene, camera) = (&self.panel.scene, self.panel.camera);
        let settings = |(w, h)| self.settings(w, h);
        let denoise = self.panel.denoise;
        Gfx::open(event_loop, self.initial_image, |image| {
            let thread = RenderThread::spawn(scene, camera, settings(image), move || {
                let _ = proxy.send_event(Wake);
            });
            if denoise {
                thread.send(Request::Denoise(true));
            }
            thread
        })
    }

    /// One frame: fly the camera, show the newest image, run the panel, draw, and send the
    /// panel's changes to the render thread.
    pub(super) fn redraw(&mut self) -> Result<()> {
        let now = Instant::now();
        let dt = (now - self.last_frame).as_secs_f32().min(0.1);
        self.last_frame = now;
        if self.input.flying() && self.input.fly(&mut self.panel.camera, dt) {
            self.send_camera(true);
        }
        let Some(g) = &mut self.gfx else {
            return Ok(());
        };
        let (status, serial, uploaded) = g.take_published(self.shown_serial);
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
            t.frame(self.status.generation, self.status.preview, now, uploaded);
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

    /// Draws a frame, unless the image of a change just sent is due (`image_due`), or
    /// nothing changed and one was drawn within `IDLE_REPAINT` (a deferred repaint then
    /// follows).
    pub(super) fn on_redraw_requested(&mut self, event_loop: &ActiveEventLoop) {
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

    /// Takes the render thread's status, saying on stderr when the image converges or the
    /// render fails (for whoever launched the viewer, and for the window test).
    pub(super) fn report(&mut self, status: Status) {
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

    /// Shows `text` in the panel and on stderr (for whoever launched the viewer, and for
    /// the window test).
    pub(super) fn say(&mut self, text: String, error: bool) {
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

    pub(super) fn resize(&mut self, size: PhysicalSize<u32>) -> Result<()> {
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
        g.clear_image();
        self.shown_serial = 0;
        let (iw, ih) = g.image_size();
        let s = self.settings(iw, ih);
        if let Some(g) = &self.gfx {
            g.render.send(Request::Settings(s));
        }
        Ok(())
    }

    /// Closes the window; dropping the graphics joins the render thread.
    pub(super) fn close(&mut self, event_loop: &ActiveEventLoop) {
        self.gfx = None;
        event_loop.exit();
    }

    pub(super) fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error = Some(error);
        self.gfx = None;
        event_loop.exit();
    }
}
