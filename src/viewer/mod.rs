//! The interactive viewer: a winit window whose `pixels` framebuffer shows the progressive
//! render beside an egui side panel. Rendering runs on its own thread (render_thread.rs);
//! this thread only handles input, copies finished passes into the framebuffer, and draws.

mod camera_input;
mod gfx;
mod panel;
mod render_thread;
mod screenshot;

use anyhow::{Context, Result, anyhow};
use camera_input::CameraInput;
use gfx::Gfx;
use panel::{PANEL_WIDTH, PanelState};
use prism::render::{AdaptiveSettings, RenderSettings};
use prism::scene::Scene;
use render_thread::{RenderThread, Request, Status};
use std::path::PathBuf;
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

/// What the viewer opens with, resolved and checked by the command line.
pub struct Launch {
    /// The scene to show.
    pub scene: Scene,
    /// The image size (beside the panel) and anti-aliasing level to start with.
    pub settings: RenderSettings,
    /// Where screenshots are saved.
    pub screenshot_dir: PathBuf,
}

/// Opens the window and runs until it closes.
pub fn run(launch: Launch) -> Result<()> {
    let Launch {
        scene,
        settings: mut probe,
        screenshot_dir,
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
    let event_loop = EventLoop::<Wake>::with_user_event().build().map_err(|e| {
        anyhow!(
            "cannot open a window ({e}); is there a display? \
             `prism render` renders without one"
        )
    })?;
    event_loop.set_control_flow(ControlFlow::Wait);
    // A tap moves 1/64 of the scene's size; a held key flies a quarter of it a second.
    let step = scene
        .bounds()
        .map_or(0.625, |b| ((b.max - b.min).length() / 64.0).max(1e-3));
    probe.width = probe.width.max(1);
    let mut app = App {
        proxy: event_loop.create_proxy(),
        screenshot_dir,
        panel: PanelState::new(scene, aa),
        input: CameraInput::new(step),
        initial_image: (probe.width, probe.height),
        gfx: None,
        error: None,
        last_frame: Instant::now(),
        shown_serial: 0,
        cursor: None,
        dirty: true,
        last_present: Instant::now(),
        refresh_pending: false,
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

struct App {
    proxy: EventLoopProxy<Wake>,
    screenshot_dir: PathBuf,
    panel: PanelState,
    input: CameraInput,
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

    /// Sends what the panel changed to the render thread.
    fn apply(&mut self, changes: panel::Changes) {
        let Some(g) = &self.gfx else { return };
        for &object in &changes.materials {
            let material = self.panel.scene.objects[object].material.clone();
            g.render.send(Request::Material { object, material });
        }
        for &index in &changes.lights {
            let light = self.panel.scene.lights[index];
            g.render.send(Request::Light { index, light });
        }
        if changes.fog {
            g.render.send(Request::Fog(self.panel.scene.fog));
        }
        if changes.camera {
            self.send_camera(false);
        }
        if changes.settings {
            let (iw, ih) = g.image_size();
            g.render.send(Request::Settings(self.settings(iw, ih)));
        }
        if changes.screenshot {
            self.screenshot();
        }
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

    /// Draws a frame, unless nothing changed and one was drawn within `IDLE_REPAINT` (a
    /// deferred repaint then follows).
    fn on_redraw_requested(&mut self, event_loop: &ActiveEventLoop) {
        let idle = !self.dirty && !self.input.moving() && self.status.converged;
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
        // Ctrl+Q quits wherever the keyboard focus is (the panel's too).
        if pressed && code == KeyCode::KeyQ && self.modifiers.control_key() {
            return self.close(event_loop);
        }
        if pressed && to_egui {
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
                CameraInput::drag(&mut self.panel.camera, dx as f32, dy as f32);
                self.send_camera(true);
            }
        }
        self.cursor = Some(position);
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
                if self.input.dragging {
                    self.input.dragging = false;
                    if !self.input.moving() {
                        self.send_camera(false);
                    }
                }
                // A click (no drag) with a lens focuses on what is under the cursor.
                if let (Some((at, moved)), Some(g)) = (self.press.take(), &self.gfx)
                    && moved < 3.0
                    && self.panel.camera.aperture > 0.0
                {
                    let x = (at.x - g.panel_px() as f64) as f32;
                    g.render.send(Request::FocusAt { x, y: at.y as f32 });
                    self.awaiting_focus = true;
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
            && self.refresh_pending
        {
            self.refresh_pending = false;
            self.dirty = true;
            if let Some(g) = &self.gfx {
                g.window.request_redraw();
            }
        }
    }

    fn user_event(&mut self, _: &ActiveEventLoop, _: Wake) {
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
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        // Keep drawing while anything changes; sleep once the image has converged.
        if let Some(g) = &self.gfx
            && (self.input.moving() || !self.status.converged)
        {
            self.dirty = true;
            g.window.request_redraw();
        }
        event_loop.set_control_flow(if self.refresh_pending {
            ControlFlow::WaitUntil(self.last_present + IDLE_REPAINT)
        } else {
            ControlFlow::Wait
        });
    }
}
