//! The pinhole camera: where it stands, where it looks, and how wide it sees.

use crate::geometry::Ray;
use glam::Vec3;

/// A pinhole camera in the seed's convention: +y is up and yaw = pitch = 0 looks down −z.
/// Angles are in degrees: positive yaw turns right (towards +x), positive pitch looks up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub yaw: f32,
    pub pitch: f32,
    /// Vertical field of view.
    pub vfov: f32,
}

/// Pitch stays short of straight up or down, where yaw would lose its meaning.
pub const MAX_PITCH: f32 = 89.0;
pub const MIN_VFOV: f32 = 0.01;
pub const MAX_VFOV: f32 = 179.0;

impl Camera {
    /// A camera at `eye` looking along `direction`; None when `direction` has no length.
    pub fn looking_along(eye: Vec3, direction: Vec3, vfov: f32) -> Option<Camera> {
        let d = crate::numerics::try_normalize(direction)?;
        let pitch = d.y.clamp(-1.0, 1.0).asin().to_degrees();
        let yaw = d.x.atan2(-d.z).to_degrees();
        Some(Camera {
            eye,
            yaw,
            pitch: pitch.clamp(-MAX_PITCH, MAX_PITCH),
            vfov,
        })
    }

    pub fn forward(&self) -> Vec3 {
        let (sy, cy) = self.yaw.to_radians().sin_cos();
        let (sp, cp) = self.pitch.to_radians().sin_cos();
        Vec3::new(sy * cp, sp, -cy * cp)
    }

    pub fn right(&self) -> Vec3 {
        let (sy, cy) = self.yaw.to_radians().sin_cos();
        Vec3::new(cy, 0.0, sy)
    }

    /// The precomputed frame for an image of `width` × `height` pixels.
    pub fn rays(&self, width: u32, height: u32) -> CameraRays {
        let forward = self.forward();
        let right = self.right();
        let up = right.cross(forward);
        let tan_half = (self.vfov.to_radians() * 0.5).tan();
        let aspect = width as f32 / height as f32;
        CameraRays {
            origin: self.eye,
            forward,
            right: right * (tan_half * aspect),
            up: up * tan_half,
            inv_width: 1.0 / width as f32,
            inv_height: 1.0 / height as f32,
        }
    }
}

/// Turns image positions into primary rays.
#[derive(Clone, Copy, Debug)]
pub struct CameraRays {
    origin: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    inv_width: f32,
    inv_height: f32,
}

impl CameraRays {
    /// The ray through image position (x, y), in pixels from the top-left corner.
    #[inline]
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let sx = 2.0 * x * self.inv_width - 1.0;
        let sy = 1.0 - 2.0 * y * self.inv_height;
        let dir = self.forward + self.right * sx + self.up * sy;
        Ray::new(self.origin, dir.normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_orientation_looks_down_negative_z() {
        let cam = Camera {
            eye: Vec3::ZERO,
            yaw: 0.0,
            pitch: 0.0,
            vfov: 90.0,
        };
        let rays = cam.rays(200, 100);
        let centre = rays.ray(100.0, 50.0);
        assert!((centre.dir - -Vec3::Z).length() < 1e-6);
        // Top edge at 45° up (vfov 90°), right edge wider by the aspect ratio.
        let top = rays.ray(100.0, 0.0).dir;
        assert!((top - Vec3::new(0.0, 1.0, -1.0).normalize()).length() < 1e-6);
        let right = rays.ray(200.0, 50.0).dir;
        assert!((right - Vec3::new(2.0, 0.0, -1.0).normalize()).length() < 1e-6);
    }

    #[test]
    fn seed_field_of_view_spans_ten_in_forty() {
        let cam = Camera {
            eye: Vec3::ZERO,
            yaw: 0.0,
            pitch: 0.0,
            vfov: 2.0 * (10.0f32 / 40.0).atan().to_degrees(),
        };
        let top = cam.rays(100, 100).ray(50.0, 0.0).dir;
        assert!((top.y / -top.z - 0.25).abs() < 1e-6);
    }

    #[test]
    fn looking_along_round_trips_direction() {
        for d in [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.3, 0.4, -0.5),
            Vec3::new(-2.0, -1.0, 3.0),
        ] {
            let cam = Camera::looking_along(Vec3::ZERO, d, 40.0).unwrap();
            assert!((cam.forward() - d.normalize()).length() < 1e-5, "{d}");
        }
        assert!(Camera::looking_along(Vec3::ZERO, Vec3::ZERO, 40.0).is_none());
    }

    #[test]
    fn positive_yaw_turns_right() {
        let cam = Camera {
            eye: Vec3::ZERO,
            yaw: 90.0,
            pitch: 0.0,
            vfov: 40.0,
        };
        assert!((cam.forward() - Vec3::X).length() < 1e-6);
    }
}
