//! The winit event loop's handler: each window event handed to the input, the frame or the
//! document, and the loop's sleep chosen (until the next image, input or deadline).

use super::app::{App, EguiClaims, IDLE_REPAINT, Wake};
use winit::application::ApplicationHandler;
use winit::event::{MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::window::WindowId;

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
