//! Input on the image: keys (movement, undo, save, screenshot), the cursor and its drags
//! (look around, or orbit the selection), clicks (pick, focus the lens), the wheel (zoom).

use super::app::App;
use super::camera_input::CameraInput;
use super::render_thread::Request;
use super::screenshot;
use std::time::Instant;
use winit::dpi::PhysicalPosition;
use winit::event::{ElementState, KeyEvent, MouseScrollDelta};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::{KeyCode, PhysicalKey};

impl App {
    pub(super) fn send_camera(&self, moving: bool) {
        if let Some(g) = &self.gfx {
            g.render.send(Request::Camera {
                camera: self.panel.camera,
                moving,
            });
        }
    }

    pub(super) fn screenshot(&mut self) {
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

    /// Ctrl+Q quits, movement keys fly, F12 and P save a screenshot. A press the panel
    /// takes (`to_egui`) moves nothing; releases always count, so a key never sticks.
    pub(super) fn on_key(&mut self, event_loop: &ActiveEventLoop, event: &KeyEvent, to_egui: bool) {
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
    pub(super) fn on_cursor_moved(&mut self, position: PhysicalPosition<f64>) {
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
    pub(super) fn orbit_target(&self) -> Option<glam::Vec3> {
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
    pub(super) fn on_left_button(&mut self, state: ElementState, on_image: bool) {
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
    pub(super) fn on_wheel(&mut self, delta: MouseScrollDelta) {
        let lines = match delta {
            MouseScrollDelta::LineDelta(_, y) => y,
            MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
        };
        CameraInput::scroll(&mut self.panel.camera, lines);
        self.send_camera(false);
    }
}
