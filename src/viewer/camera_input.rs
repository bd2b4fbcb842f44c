//! Moving the camera by hand: drag to look around, WASD/QE to fly, scroll to zoom.

use prism::camera::Camera;
use prism::limits::{MAX_PITCH, VFOV};
use winit::keyboard::KeyCode;

/// Degrees of turn per pixel dragged.
const DEGREES_PER_PIXEL: f32 = 0.2;

#[derive(Default)]
pub struct CameraInput {
    forward: bool,
    back: bool,
    left: bool,
    right: bool,
    up: bool,
    down: bool,
    pub dragging: bool,
    /// Scene units per second.
    pub speed: f32,
}

impl CameraInput {
    pub fn new(speed: f32) -> Self {
        Self {
            speed,
            ..Self::default()
        }
    }

    /// Records a movement key; false if `code` is not one.
    pub fn key(&mut self, code: KeyCode, pressed: bool) -> bool {
        let flag = match code {
            KeyCode::KeyW => &mut self.forward,
            KeyCode::KeyS => &mut self.back,
            KeyCode::KeyA => &mut self.left,
            KeyCode::KeyD => &mut self.right,
            KeyCode::KeyE => &mut self.up,
            KeyCode::KeyQ => &mut self.down,
            _ => return false,
        };
        *flag = pressed;
        true
    }

    pub fn release_all(&mut self) {
        *self = Self::new(self.speed);
    }

    pub fn flying(&self) -> bool {
        self.forward || self.back || self.left || self.right || self.up || self.down
    }

    pub fn moving(&self) -> bool {
        self.flying() || self.dragging
    }

    /// Moves the eye for `dt` seconds of the keys held; true if it moved.
    pub fn fly(&self, camera: &mut Camera, dt: f32) -> bool {
        let axis = |pos: bool, neg: bool| pos as i32 as f32 - neg as i32 as f32;
        let f = axis(self.forward, self.back);
        let r = axis(self.right, self.left);
        let u = axis(self.up, self.down);
        if f == 0.0 && r == 0.0 && u == 0.0 {
            return false;
        }
        let step = self.speed * dt;
        camera.eye += (camera.forward() * f + camera.right() * r + camera.up * u) * step;
        true
    }

    /// Turns the camera by a mouse drag of (dx, dy) pixels: right turns right, up looks up.
    pub fn drag(camera: &mut Camera, dx: f32, dy: f32) {
        camera.yaw = (camera.yaw + dx * DEGREES_PER_PIXEL + 180.0).rem_euclid(360.0) - 180.0;
        camera.pitch = (camera.pitch - dy * DEGREES_PER_PIXEL).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Zooms by `lines` scroll notches (positive: in, narrowing the field of view).
    pub fn scroll(camera: &mut Camera, lines: f32) {
        camera.vfov = (camera.vfov * 0.9f32.powf(lines)).clamp(*VFOV.start(), *VFOV.end());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn cam() -> Camera {
        Camera {
            eye: Vec3::ZERO,
            yaw: 0.0,
            pitch: 0.0,
            vfov: 30.0,
            up: Vec3::Y,
            aperture: 0.0,
            focus_distance: 1.0,
        }
    }

    #[test]
    fn w_flies_forward_and_d_right() {
        let mut input = CameraInput::new(10.0);
        assert!(input.key(KeyCode::KeyW, true));
        let mut c = cam();
        assert!(input.fly(&mut c, 0.5));
        assert!((c.eye - Vec3::new(0.0, 0.0, -5.0)).length() < 1e-5);
        input.key(KeyCode::KeyW, false);
        input.key(KeyCode::KeyD, true);
        input.fly(&mut c, 0.1);
        assert!((c.eye - Vec3::new(1.0, 0.0, -5.0)).length() < 1e-5);
        input.release_all();
        assert!(!input.moving());
        assert!(!input.key(KeyCode::KeyZ, true));
    }

    #[test]
    fn drag_turns_and_pitch_is_limited() {
        let mut c = cam();
        CameraInput::drag(&mut c, 50.0, 0.0);
        assert_eq!(c.yaw, 10.0);
        CameraInput::drag(&mut c, 0.0, -10_000.0);
        assert_eq!(c.pitch, MAX_PITCH);
    }

    #[test]
    fn scroll_zooms_within_limits() {
        let mut c = cam();
        CameraInput::scroll(&mut c, 1.0);
        assert!((c.vfov - 27.0).abs() < 1e-4);
        CameraInput::scroll(&mut c, -100.0);
        assert_eq!(c.vfov, *VFOV.end());
    }
}
