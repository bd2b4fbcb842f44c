//! Moving the camera by hand: drag to look around, WASD/QE to fly, scroll to zoom.

use prism::camera::Camera;
use prism::limits::{MAX_PITCH, VFOV};
use winit::keyboard::KeyCode;

/// Degrees of turn per pixel dragged.
const DEGREES_PER_PIXEL: f32 = 0.2;

/// A held key flies this many steps per second.
pub const STEPS_PER_SECOND: f32 = 16.0;

/// The movement keys, in the order of `CameraInput::held`.
const KEYS: [KeyCode; 6] = [
    KeyCode::KeyW,
    KeyCode::KeyS,
    KeyCode::KeyA,
    KeyCode::KeyD,
    KeyCode::KeyE,
    KeyCode::KeyQ,
];

#[derive(Default)]
pub struct CameraInput {
    /// Which movement key is down (forward, back, left, right, up, down).
    held: [bool; 6],
    /// How far each key has flown since it went down.
    travelled: [f32; 6],
    /// Keys released before they flew one step: the rest of the step is still to go.
    tapped: [bool; 6],
    pub dragging: bool,
    /// How far a tap of a movement key moves, in scene units; a held key flies
    /// `STEPS_PER_SECOND` of them a second.
    pub step: f32,
}

impl CameraInput {
    pub fn new(step: f32) -> Self {
        Self {
            step,
            ..Self::default()
        }
    }

    /// Records a movement key; false if `code` is not one. A key released before it flew
    /// one step leaves the rest of the step to `finish_taps`.
    pub fn key(&mut self, code: KeyCode, pressed: bool) -> bool {
        let Some(k) = KEYS.iter().position(|&c| c == code) else {
            return false;
        };
        if pressed && !self.held[k] {
            self.travelled[k] = 0.0;
        }
        if !pressed && self.held[k] && self.travelled[k] < self.step {
            self.tapped[k] = true;
        }
        self.held[k] = pressed;
        true
    }

    pub fn release_all(&mut self) {
        *self = Self::new(self.step);
    }

    pub fn flying(&self) -> bool {
        self.held.iter().any(|&h| h)
    }

    pub fn moving(&self) -> bool {
        self.flying() || self.dragging
    }

    /// The unit direction key `k` moves the camera in.
    fn direction(camera: &Camera, k: usize) -> glam::Vec3 {
        match k {
            0 => camera.forward(),
            1 => -camera.forward(),
            2 => -camera.right(),
            3 => camera.right(),
            4 => camera.up,
            _ => -camera.up,
        }
    }

    /// Moves the eye for `dt` seconds of the keys held; true if it moved.
    pub fn fly(&mut self, camera: &mut Camera, dt: f32) -> bool {
        if !self.flying() {
            return false;
        }
        let distance = self.step * STEPS_PER_SECOND * dt;
        let mut moved = glam::Vec3::ZERO;
        for k in 0..KEYS.len() {
            if self.held[k] {
                moved += Self::direction(camera, k) * distance;
                self.travelled[k] += distance;
            }
        }
        camera.eye += moved;
        moved != glam::Vec3::ZERO
    }

    /// Moves the eye the rest of one step for each key tapped since the last call (released
    /// before it flew a step); true if it moved.
    pub fn finish_taps(&mut self, camera: &mut Camera) -> bool {
        let mut moved = false;
        for k in 0..KEYS.len() {
            if std::mem::take(&mut self.tapped[k]) {
                let rest = (self.step - self.travelled[k]).max(0.0);
                camera.eye += Self::direction(camera, k) * rest;
                moved |= rest > 0.0;
            }
        }
        moved
    }

    /// Turns the camera by a mouse drag of (dx, dy) pixels: right turns right, up looks up.
    pub fn drag(camera: &mut Camera, dx: f32, dy: f32) {
        camera.yaw = (camera.yaw + dx * DEGREES_PER_PIXEL + 180.0).rem_euclid(360.0) - 180.0;
        camera.pitch = (camera.pitch - dy * DEGREES_PER_PIXEL).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// A drag in orbit mode: the camera swings about `target` at the same distance (turned
    /// as `drag` turns it) and looks at it.
    pub fn orbit(camera: &mut Camera, target: glam::Vec3, dx: f32, dy: f32) {
        let distance = (camera.eye - target).length();
        if !(distance.is_finite() && distance > 0.0) {
            return Self::drag(camera, dx, dy);
        }
        // Face the target first, then turn.
        if let Some(facing) =
            Camera::looking_along_up(camera.eye, target - camera.eye, camera.up, camera.vfov)
        {
            camera.yaw = facing.yaw;
            camera.pitch = facing.pitch;
        }
        Self::drag(camera, dx, dy);
        camera.eye = target - camera.forward() * distance;
    }

    /// Zooms by `lines` scroll notches (positive: in, narrowing the field of view).
    pub fn scroll(camera: &mut Camera, lines: f32) {
        camera.vfov = (camera.vfov * 0.9f32.powf(lines)).clamp(*VFOV.start(), *VFOV.end());
    }
}

/// A tap moves 1/64 of the scene's size; a held key flies a quarter of it a second.
pub fn step_for(scene: &prism::scene::Scene) -> f32 {
    scene
        .bounds()
        .map_or(0.625, |b| ((b.max - b.min).length() / 64.0).max(1e-3))
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
            handedness: Default::default(),
        }
    }

    #[test]
    fn a_tap_moves_one_step_and_a_hold_flies_on() {
        let mut input = CameraInput::new(2.0);
        let mut c = cam();
        // Pressed and released between two frames: no time flown, one whole step.
        input.key(KeyCode::KeyD, true);
        input.key(KeyCode::KeyD, false);
        assert!(!input.flying());
        assert!(input.finish_taps(&mut c));
        assert!(
            (c.eye - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-5,
            "{}",
            c.eye
        );
        assert!(!input.finish_taps(&mut c), "a tap moves once");
        // A short press that flew part of a step still ends one step along.
        input.key(KeyCode::KeyW, true);
        input.fly(&mut c, 0.02); // 0.64 of the 2-unit step
        input.key(KeyCode::KeyW, false);
        input.finish_taps(&mut c);
        assert!(
            (c.eye - Vec3::new(2.0, 0.0, -2.0)).length() < 1e-5,
            "{}",
            c.eye
        );
        // A long hold flies on and adds nothing at its release.
        input.key(KeyCode::KeyS, true);
        input.fly(&mut c, 0.25); // 4 steps back
        input.key(KeyCode::KeyS, false);
        assert!(!input.finish_taps(&mut c));
        assert!(
            (c.eye - Vec3::new(2.0, 0.0, 6.0)).length() < 1e-4,
            "{}",
            c.eye
        );
    }

    #[test]
    fn w_flies_forward_and_d_right() {
        let mut input = CameraInput::new(10.0 / STEPS_PER_SECOND);
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

    /// Orbiting keeps the distance to the target and looks at it; a quarter turn of drag
    /// moves the camera a quarter of the way round.
    #[test]
    fn orbit_swings_about_the_target() {
        let mut c = cam();
        c.eye = Vec3::new(0.0, 0.0, 10.0);
        let target = Vec3::new(0.0, 0.0, 0.0);
        // 90° of yaw: DEGREES_PER_PIXEL is 0.2°.
        CameraInput::orbit(&mut c, target, 450.0, 0.0);
        assert!((c.eye - target).length() - 10.0 < 1e-4);
        assert!(
            (c.eye - Vec3::new(-10.0, 0.0, 0.0)).length() < 1e-3,
            "{}",
            c.eye
        );
        assert!((c.forward() - (target - c.eye).normalize()).length() < 1e-5);
        CameraInput::orbit(&mut c, target, 0.0, -100.0);
        assert!(((c.eye - target).length() - 10.0).abs() < 1e-4);
        assert!(c.eye.y < -1.0, "dragging up looks up from below: {}", c.eye);
        // A camera on the target turns in place.
        let mut on = cam();
        CameraInput::orbit(&mut on, Vec3::ZERO, 50.0, 0.0);
        assert_eq!((on.eye, on.yaw), (Vec3::ZERO, 10.0));
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
