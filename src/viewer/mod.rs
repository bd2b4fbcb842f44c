//! The interactive viewer: a winit window whose `pixels` framebuffer shows the progressive
//! render beside an egui side panel. Rendering runs on its own thread (render_thread.rs);
//! this thread only handles input, copies finished passes into the framebuffer, and draws.

mod camera_input;
mod panel;
mod render_thread;
mod screenshot;

use anyhow::{Context, Result, anyhow};
use camera_input::CameraInput;
use panel::{PANEL_WIDTH, PanelState};
use pixels::{Pixels, PixelsBuilder, SurfaceTexture, wgpu};
use prism::render::{AdaptiveSettings, RenderSettings};
use prism::scene::Scene;
use render_thread::{RenderThread, Request, Status};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::{LogicalSize, PhysicalPosition, PhysicalSize};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop, EventLoopProxy};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

/// While nothing changes, repaints the window system asks for (X11 exposures; under Xvfb
/// every present causes one) are served at most this often.
const IDLE_REPAINT: Duration = Duration::from_millis(200);

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
    let speed = scene
        .bounds()
        .map_or(10.0, |b| ((b.max - b.min).length() * 0.25).max(1e-3));
    probe.width = probe.width.max(1);
    let mut app = App {
        proxy: event_loop.create_proxy(),
        screenshot_dir,
        panel: PanelState::new(scene, aa),
        input: CameraInput::new(speed),
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
}

/// Everything that exists only while the window does.
struct Gfx {
    window: Arc<Window>,
    pixels: Pixels<'static>,
    egui_ctx: egui::Context,
    egui_state: egui_winit::State,
    renderer: egui_wgpu::Renderer,
    render: RenderThread,
    size: PhysicalSize<u32>,
}

impl Gfx {
    fn panel_px(&self) -> u32 {
        panel_px(&self.window)
    }

    fn image_size(&self) -> (u32, u32) {
        image_size(self.size, &self.window)
    }
}

/// Width of the panel in physical pixels.
fn panel_px(window: &Window) -> u32 {
    (PANEL_WIDTH * window.scale_factor() as f32).ceil() as u32
}

/// The render resolution: the window area beside the panel.
fn image_size(size: PhysicalSize<u32>, window: &Window) -> (u32, u32) {
    let w = size.width.saturating_sub(panel_px(window)).max(1);
    (w, size.height.max(1))
}

impl App {
    fn settings(&self, width: u32, height: u32) -> RenderSettings {
        let mut s = RenderSettings::new(width, height, self.panel.aa);
        if self.panel.adaptive {
            s.adaptive = Some(AdaptiveSettings {
                tolerance: self.panel.tolerance,
                ..AdaptiveSettings::default()
            });
        }
        s
    }

    fn create_gfx(&mut self, event_loop: &ActiveEventLoop) -> Result<Gfx> {
        let (w, h) = self.initial_image;
        let attrs = Window::default_attributes()
            .with_title("prism")
            .with_inner_size(LogicalSize::new(w as f64 + PANEL_WIDTH as f64, h as f64))
            .with_min_inner_size(LogicalSize::new(PANEL_WIDTH as f64 + 64.0, 200.0));
        let window = Arc::new(
            event_loop
                .create_window(attrs)
                .context("cannot create the window")?,
        );
        let size = window.inner_size();
        let surface = SurfaceTexture::new(size.width.max(1), size.height.max(1), window.clone());
        let pixels = PixelsBuilder::new(size.width.max(1), size.height.max(1), surface)
            .enable_vsync(true)
            .build()
            .map_err(|e| {
                anyhow!(
                    "no usable GPU adapter for the window ({e}); \
                     `prism render` renders without one"
                )
            })?;
        let egui_ctx = egui::Context::default();
        let max_texture = pixels.device().limits().max_texture_dimension_2d as usize;
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &*window,
            Some(window.scale_factor() as f32),
            None,
            Some(max_texture),
        );
        let renderer = egui_wgpu::Renderer::new(
            pixels.device(),
            pixels.surface_texture_format(),
            egui_wgpu::RendererOptions::default(),
        );
        let (iw, ih) = image_size(size, &window);
        let proxy = self.proxy.clone();
        let render = RenderThread::spawn(
            &self.panel.scene,
            self.panel.camera,
            self.settings(iw, ih),
            move || {
                let _ = proxy.send_event(Wake);
            },
        );
        let gfx = Gfx {
            window,
            pixels,
            egui_ctx,
            egui_state,
            renderer,
            render,
            size,
        };
        Ok(gfx)
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
        let panel_px = g.panel_px();
        {
            let p = g.render.published();
            if p.status.converged && !self.status.converged {
                // A line for whoever launched the viewer (and for the window test).
                eprintln!(
                    "prism: converged: {} passes, {:.2} samples per pixel, {:.2} s",
                    p.status.passes_done, p.status.samples_per_pixel, p.status.seconds
                );
            }
            if let Some(e) = &p.status.error
                && self.status.error.as_ref() != Some(e)
            {
                eprintln!("prism: error: the render failed: {e}");
                self.render_error = Some(e.clone());
            }
            self.status = p.status.clone();
            if p.serial != self.shown_serial {
                self.shown_serial = p.serial;
                copy_image(
                    g.pixels.frame_mut(),
                    g.size.width,
                    g.size.height,
                    panel_px,
                    &p,
                );
            }
        }
        let input = g.egui_state.take_egui_input(&g.window);
        let mut changes = panel::Changes::default();
        let panel = &mut self.panel;
        let status = &self.status;
        let output = g.egui_ctx.run_ui(input, |ui| {
            egui::Panel::left("controls")
                .exact_size(PANEL_WIDTH)
                .resizable(false)
                .show(ui, |ui| changes = panel.show(ui, status));
        });
        g.egui_state
            .handle_platform_output(&g.window, output.platform_output);
        let paint_jobs = g
            .egui_ctx
            .tessellate(output.shapes, output.pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [g.size.width, g.size.height],
            pixels_per_point: output.pixels_per_point,
        };
        let textures = output.textures_delta;
        let renderer = &mut g.renderer;
        g.pixels
            .render_with(|encoder, target, context| {
                context.scaling_renderer.render(encoder, target);
                for (id, delta) in &textures.set {
                    renderer.update_texture(&context.device, &context.queue, *id, delta);
                }
                let extra = renderer.update_buffers(
                    &context.device,
                    &context.queue,
                    encoder,
                    &paint_jobs,
                    &screen,
                );
                debug_assert!(extra.is_empty(), "no egui paint callbacks are used");
                let mut pass = encoder
                    .begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some("egui"),
                        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                            view: target,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations {
                                load: wgpu::LoadOp::Load,
                                store: wgpu::StoreOp::Store,
                            },
                        })],
                        depth_stencil_attachment: None,
                        timestamp_writes: None,
                        occlusion_query_set: None,
                        multiview_mask: None,
                    })
                    .forget_lifetime();
                renderer.render(&mut pass, &paint_jobs, &screen);
                drop(pass);
                for id in &textures.free {
                    renderer.free_texture(id);
                }
                Ok(())
            })
            .context("drawing the window failed")?;
        let (iw, ih) = g.image_size();
        for &object in &changes.materials {
            let material = self.panel.scene.objects[object].material.clone();
            g.render.send(Request::Material { object, material });
        }
        if changes.camera {
            self.send_camera(false);
        }
        if changes.settings {
            let s = self.settings(iw, ih);
            if let Some(g) = &self.gfx {
                g.render.send(Request::Settings(s));
            }
        }
        if changes.screenshot {
            self.screenshot();
        }
        if let Some(g) = &self.gfx
            && output
                .viewport_output
                .get(&egui::ViewportId::ROOT)
                .is_some_and(|v| v.repaint_delay.is_zero())
        {
            self.dirty = true;
            g.window.request_redraw();
        }
        Ok(())
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

    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error = Some(error);
        self.gfx = None;
        event_loop.exit();
    }
}

/// Copies the published image into the framebuffer to the right of the panel, clipping to
/// whichever is smaller while a resize is on its way to the render thread.
fn copy_image(frame: &mut [u8], fw: u32, fh: u32, x0: u32, p: &render_thread::Published) {
    let cols = p.width.min(fw.saturating_sub(x0)) as usize;
    let rows = p.height.min(fh) as usize;
    // A window narrower than the panel shows no image at all.
    if cols == 0 {
        return;
    }
    for y in 0..rows {
        let src = y * p.width as usize * 4;
        let dst = (y * fw as usize + x0 as usize) * 4;
        frame[dst..dst + cols * 4].copy_from_slice(&p.rgba[src..src + cols * 4]);
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
        let panel_px = g.panel_px() as f64;
        let egui_keys = g.egui_ctx.egui_wants_keyboard_input();
        let egui_pointer = g.egui_ctx.egui_wants_pointer_input();
        match event {
            WindowEvent::CloseRequested => {
                // Dropping the graphics joins the render thread.
                self.gfx = None;
                event_loop.exit();
            }
            WindowEvent::Resized(size) => {
                if let Err(e) = self.resize(size) {
                    self.fail(event_loop, e);
                }
            }
            WindowEvent::RedrawRequested => {
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
            WindowEvent::Focused(false) => {
                let was_moving = self.input.moving();
                self.input.release_all();
                if was_moving {
                    self.send_camera(false);
                }
            }
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(code) = event.physical_key else {
                    return;
                };
                let pressed = event.state == ElementState::Pressed;
                // Releases always count, so a key never sticks.
                // Ctrl+Q quits wherever the keyboard focus is (the panel's too).
                if pressed && code == KeyCode::KeyQ && self.modifiers.control_key() {
                    self.gfx = None;
                    event_loop.exit();
                    return;
                }
                if pressed && (egui_keys || response.consumed) {
                    return;
                }
                let was_flying = self.input.flying();
                if self.input.key(code, pressed) {
                    if was_flying && !self.input.moving() {
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
            WindowEvent::ModifiersChanged(m) => self.modifiers = m.state(),
            WindowEvent::CursorMoved { position, .. } => {
                if self.input.dragging
                    && let Some(last) = self.cursor
                {
                    let (dx, dy) = (position.x - last.x, position.y - last.y);
                    if dx != 0.0 || dy != 0.0 {
                        CameraInput::drag(&mut self.panel.camera, dx as f32, dy as f32);
                        self.send_camera(true);
                    }
                }
                self.cursor = Some(position);
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => match state {
                ElementState::Pressed => {
                    let over_image = self.cursor.is_some_and(|c| c.x >= panel_px);
                    if over_image && !egui_pointer && !response.consumed {
                        self.input.dragging = true;
                    }
                }
                ElementState::Released => {
                    if self.input.dragging {
                        self.input.dragging = false;
                        if !self.input.moving() {
                            self.send_camera(false);
                        }
                    }
                }
            },
            WindowEvent::MouseWheel { delta, .. } => {
                let over_image = self.cursor.is_some_and(|c| c.x >= panel_px);
                if over_image && !response.consumed {
                    let lines = match delta {
                        MouseScrollDelta::LineDelta(_, y) => y,
                        MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                    };
                    CameraInput::scroll(&mut self.panel.camera, lines);
                    self.send_camera(false);
                }
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
