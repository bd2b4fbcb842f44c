//! The camera: where it stands, where it looks, how wide it sees, and its lens: a pinhole,
//! or a thin lens whose aperture blurs what lies off the plane in focus.

use crate::geometry::Ray;
use glam::{Vec3, Vec3A};

/// A pinhole camera. Angles are in degrees, measured about the `up` direction: pitch is the
/// elevation above the plane perpendicular to `up`, yaw turns about `up`, positive to the
/// right. With the seed's up (+y), yaw = pitch = 0 looks down −z and positive yaw turns
/// towards +x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Where the camera stands, relative to the scene's origin.
    pub eye: Vec3,
    /// Turn about `up`, in degrees, positive to the right.
    pub yaw: f32,
    /// Elevation above the plane perpendicular to `up`, in degrees.
    pub pitch: f32,
    /// Vertical field of view.
    pub vfov: f32,
    /// Unit vector that is up on screen when pitch is 0.
    pub up: Vec3,
    /// The thin lens's diameter, in scene units: 0 is a pinhole, everything sharp.
    pub aperture: f32,
    /// How far in front of the eye, along the view axis, the plane in focus lies.
    pub focus_distance: f32,
    /// Which way the scene's coordinates turn: prism's own right-handed ones, or POV-Ray's
    /// left-handed ones, whose numbers then render as POV-Ray shows them.
    pub handedness: Handedness,
}

/// The handedness of a scene's coordinates, as the camera shows them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Handedness {
    /// x right, y up, z towards the viewer (prism's, OpenGL's, pbrt's).
    #[default]
    Right,
    /// x right, y up, z away from the viewer (POV-Ray's): the image is the mirror image
    /// of the right-handed one, left for right.
    Left,
}

use crate::limits::{MAX_COORDINATE, MAX_PITCH, MIN_LENGTH, PITCH, VFOV};

impl Camera {
    /// A camera at `eye` looking along `direction` with +y up; None when `direction` has
    /// no length.
    pub fn looking_along(eye: Vec3, direction: Vec3, vfov: f32) -> Option<Camera> {
        Self::looking_along_up(eye, direction, Vec3::Y, vfov)
    }

    /// A camera at `eye` looking along `direction` with `up` up on screen; None when either
    /// has no length or they are (nearly) parallel.
    pub fn looking_along_up(eye: Vec3, direction: Vec3, up: Vec3, vfov: f32) -> Option<Camera> {
        let d = crate::numerics::try_normalize(direction)?;
        let up = crate::numerics::try_normalize(up)?;
        let (reference, side) = reference_frame(up);
        let pitch = d.dot(up).clamp(-1.0, 1.0).asin().to_degrees();
        if pitch.abs() > MAX_PITCH {
            return None;
        }
        let yaw = d.dot(side).atan2(d.dot(reference)).to_degrees();
        Some(Camera {
            eye,
            yaw,
            pitch,
            vfov,
            up,
            aperture: 0.0,
            focus_distance: 1.0,
            handedness: Handedness::Right,
        })
    }

    /// The rules every camera follows, whether a file, an edit or the mouse set it: the
    /// eye finite and within reach of the scene's origin (like every position), `up` a unit
    /// vector, pitch and field of view within limits.rs's ranges. The message names the
    /// value that breaks one.
    pub fn check(&self) -> Result<(), String> {
        if !self.eye.is_finite() || self.eye.abs().max_element() as f64 > MAX_COORDINATE {
            return Err(format!(
                "eye {} must be finite and within ±{MAX_COORDINATE:e}",
                self.eye
            ));
        }
        if !self.up.is_finite() || (self.up.length() - 1.0).abs() > 1e-3 {
            return Err(format!("up {} must be a unit vector", self.up));
        }
        if !self.yaw.is_finite() {
            return Err(format!("yaw {} must be a finite number", self.yaw));
        }
        if !PITCH.contains(&self.pitch) {
            let (lo, hi) = (PITCH.start(), PITCH.end());
            return Err(format!("pitch {} must lie in {lo}..{hi}°", self.pitch));
        }
        if !(self.aperture.is_finite()
            && self.aperture >= 0.0
            && self.aperture as f64 <= MAX_COORDINATE)
        {
            return Err(format!(
                "aperture {} must be a number from 0 to {MAX_COORDINATE:e}",
                self.aperture
            ));
        }
        if !crate::limits::LENGTH.contains(&self.focus_distance) {
            return Err(format!(
                "focus distance {} must be a number from {MIN_LENGTH:e} to {MAX_COORDINATE:e}",
                self.focus_distance
            ));
        }
        if !VFOV.contains(&self.vfov) {
            let (lo, hi) = (VFOV.start(), VFOV.end());
            return Err(format!(
                "field of view {} must lie in {lo}..{hi}°",
                self.vfov
            ));
        }
        Ok(())
    }

    /// The unit direction the camera looks in.
    pub fn forward(&self) -> Vec3 {
        let (reference, side) = reference_frame(self.up);
        let (sy, cy) = self.yaw.to_radians().sin_cos();
        let (sp, cp) = self.pitch.to_radians().sin_cos();
        (reference * cy + side * sy) * cp + self.up * sp
    }

    /// The unit direction to the right on screen.
    pub fn right(&self) -> Vec3 {
        let (reference, side) = reference_frame(self.up);
        let (sy, cy) = self.yaw.to_radians().sin_cos();
        side * cy - reference * sy
    }

    /// The precomputed frame for an image of `width` × `height` pixels.
    pub fn rays(&self, width: u32, height: u32) -> CameraRays {
        let forward = self.forward();
        let right = self.right();
        let up = right.cross(forward);
        // Left-handed coordinates seen through right-handed rays: the screen's x mirrored.
        let right = match self.handedness {
            Handedness::Right => right,
            Handedness::Left => -right,
        };
        let tan_half = (self.vfov.to_radians() * 0.5).tan();
        let aspect = width as f32 / height as f32;
        CameraRays {
            origin: self.eye.into(),
            forward: forward.into(),
            right: (right * (tan_half * aspect)).into(),
            up: (up * tan_half).into(),
            inv_width: 1.0 / width as f32,
            inv_height: 1.0 / height as f32,
            lens: (self.aperture > 0.0).then(|| Lens {
                radius: self.aperture * 0.5,
                focus_distance: self.focus_distance,
                right: right.into(),
                up: up.into(),
            }),
        }
    }
}

/// For unit `up`: the direction yaw 0 looks along (−z made perpendicular to `up`, or −x
/// when `up` is ±z) and the direction yaw 90° looks along, reference × up.
fn reference_frame(up: Vec3) -> (Vec3, Vec3) {
    let candidate = if up.z.abs() < 0.999 {
        -Vec3::Z
    } else {
        -Vec3::X
    };
    let reference = (candidate - up * candidate.dot(up)).normalize();
    (reference, reference.cross(up))
}

/// Turns image positions into primary rays.
#[derive(Clone, Copy, Debug)]
pub struct CameraRays {
    origin: Vec3A,
    forward: Vec3A,
    right: Vec3A,
    up: Vec3A,
    inv_width: f32,
    inv_height: f32,
    lens: Option<Lens>,
}

/// A thin lens: rays through one image point start anywhere on its disc and meet again on
/// the plane in focus.
#[derive(Clone, Copy, Debug)]
struct Lens {
    radius: f32,
    focus_distance: f32,
    /// Unit vectors spanning the lens's disc.
    right: Vec3A,
    up: Vec3A,
}

impl CameraRays {
    /// The ray through image position (x, y), in pixels from the top-left corner.
    #[inline]
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let sx = 2.0 * x * self.inv_width - 1.0;
        let sy = 1.0 - 2.0 * y * self.inv_height;
        let dir = self.forward + self.right * sx + self.up * sy;
        // dir · (1 / |dir|), as `Vec3::normalize` computes it; `Vec3A::normalize` divides
        // instead, which rounds differently.
        Ray::new(self.origin, dir * dir.length_recip())
    }

    /// Whether the camera has a lens with an aperture: its rays then need a point on it
    /// (`ray_through_lens`), and no longer all start at the eye.
    #[inline]
    pub fn has_lens(&self) -> bool {
        self.lens.is_some()
    }

    /// The ray through image position (x, y) and lens sample `u` (in [0, 1)²): from that point
    /// of the lens's disc, towards where the pinhole ray through (x, y) meets the plane in
    /// focus. Without an aperture, `ray(x, y)`.
    #[inline]
    pub fn ray_through_lens(&self, x: f32, y: f32, u: (f32, f32)) -> Ray {
        let pinhole = self.ray(x, y);
        let Some(lens) = self.lens else {
            return pinhole;
        };
        let (dx, dy) = crate::sampler::concentric_disc(u);
        let focus = pinhole.dir * (lens.focus_distance / pinhole.dir.dot(self.forward));
        let offset = (lens.right * dx + lens.up * dy) * lens.radius;
        let dir = focus - offset;
        Ray::new(self.origin + offset, dir * dir.length_recip())
    }

    /// Where the ray through point `p` crosses the image, in pixels from the top-left
    /// corner (the inverse of `ray`, in f64), and the depth of `p` along the view axis; None
    /// when `p` is not in front of the eye.
    pub fn project(&self, p: glam::DVec3, width: u32, height: u32) -> Option<(f64, f64)> {
        let v = p - self.origin.as_dvec3();
        let depth = v.dot(self.forward.as_dvec3());
        if depth.is_nan() || depth <= 0.0 {
            return None;
        }
        let (right, up) = (self.right.as_dvec3(), self.up.as_dvec3());
        let sx = v.dot(right) / (depth * right.length_squared());
        let sy = v.dot(up) / (depth * up.length_squared());
        Some((
            (sx + 1.0) * 0.5 * width as f64,
            (1.0 - sy) * 0.5 * height as f64,
        ))
    }

    /// The camera's position and viewing direction (unit).
    pub fn eye(&self) -> Vec3 {
        self.origin.into()
    }

    /// The unit direction of the centre of the view.
    pub fn forward(&self) -> Vec3 {
        self.forward.into()
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
            up: Vec3::Y,
            aperture: 0.0,
            focus_distance: 1.0,
            handedness: Default::default(),
        };
        let rays = cam.rays(200, 100);
        let centre = rays.ray(100.0, 50.0);
        assert!((Vec3::from(centre.dir) - -Vec3::Z).length() < 1e-6);
        // Top edge at 45° up (vfov 90°), right edge wider by the aspect ratio.
        let top = Vec3::from(rays.ray(100.0, 0.0).dir);
        assert!((top - Vec3::new(0.0, 1.0, -1.0).normalize()).length() < 1e-6);
        let right = Vec3::from(rays.ray(200.0, 50.0).dir);
        assert!((right - Vec3::new(2.0, 0.0, -1.0).normalize()).length() < 1e-6);
    }

    #[test]
    fn seed_field_of_view_spans_ten_in_forty() {
        let cam = Camera {
            eye: Vec3::ZERO,
            yaw: 0.0,
            pitch: 0.0,
            vfov: 2.0 * (10.0f32 / 40.0).atan().to_degrees(),
            up: Vec3::Y,
            aperture: 0.0,
            focus_distance: 1.0,
            handedness: Default::default(),
        };
        let top = Vec3::from(cam.rays(100, 100).ray(50.0, 0.0).dir);
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

    /// Left-handed coordinates show the mirror image: the ray through a pixel is the
    /// right-handed ray through the pixel mirrored across the image's middle.
    #[test]
    fn left_handedness_mirrors_the_image() {
        let right =
            Camera::looking_along(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.3, -0.2, -1.0), 50.0)
                .unwrap();
        let left = Camera {
            handedness: Handedness::Left,
            ..right
        };
        let (r, l) = (right.rays(200, 100), left.rays(200, 100));
        for (x, y) in [(0.5, 0.5), (37.25, 80.0), (100.0, 50.0), (199.5, 10.0)] {
            let a = Vec3::from(l.ray(x, y).dir);
            let b = Vec3::from(r.ray(200.0 - x, y).dir);
            assert!((a - b).length() < 1e-6, "{x},{y}: {a} {b}");
        }
        assert_eq!(
            Vec3::from(l.ray(100.0, 50.0).dir),
            Vec3::from(r.ray(100.0, 50.0).dir)
        );
    }

    #[test]
    fn positive_yaw_turns_right() {
        let cam = Camera {
            eye: Vec3::ZERO,
            yaw: 90.0,
            pitch: 0.0,
            vfov: 40.0,
            up: Vec3::Y,
            aperture: 0.0,
            focus_distance: 1.0,
            handedness: Default::default(),
        };
        assert!((cam.forward() - Vec3::X).length() < 1e-6);
    }

    /// Every ray through one image point meets the others on the plane in focus, and starts
    /// within the aperture's radius of the eye.
    #[test]
    fn lens_rays_meet_on_the_plane_in_focus() {
        let cam = Camera {
            eye: Vec3::new(1.0, 2.0, 3.0),
            yaw: 20.0,
            pitch: -10.0,
            vfov: 40.0,
            up: Vec3::Y,
            aperture: 0.5,
            focus_distance: 7.0,
            handedness: Default::default(),
        };
        let rays = cam.rays(64, 48);
        assert!(rays.has_lens());
        let pinhole = rays.ray(10.3, 40.7);
        let target = pinhole.origin + pinhole.dir * (7.0 / pinhole.dir.dot(cam.forward().into()));
        for u in [(0.1, 0.9), (0.5, 0.5), (0.99, 0.01), (0.3, 0.6)] {
            let r = rays.ray_through_lens(10.3, 40.7, u);
            assert!((r.origin - Vec3A::from(cam.eye)).length() <= 0.25 + 1e-6);
            assert!((r.dir.length() - 1.0).abs() < 1e-6);
            let t = (target - r.origin).dot(r.dir);
            assert!((r.origin + r.dir * t - target).length() < 1e-5, "{u:?}");
        }
        let pin = Camera {
            aperture: 0.0,
            ..cam
        }
        .rays(64, 48);
        assert!(!pin.has_lens());
        assert_eq!(
            pin.ray_through_lens(3.0, 4.0, (0.2, 0.7)),
            pin.ray(3.0, 4.0)
        );
    }

    #[test]
    fn another_up_rolls_the_image() {
        // With +x up, looking down −z: the top of the image is towards +x, and its right
        // towards forward × up = (−z) × x = −y.
        let cam = Camera::looking_along_up(Vec3::ZERO, -Vec3::Z, Vec3::X, 90.0).unwrap();
        assert!((cam.forward() - -Vec3::Z).length() < 1e-6);
        let rays = cam.rays(100, 100);
        let top = Vec3::from(rays.ray(50.0, 0.0).dir);
        assert!(top.x > 0.7, "the top of the image is towards +x: {top}");
        let right = Vec3::from(rays.ray(100.0, 50.0).dir);
        assert!(right.y < -0.7, "{right}");
        for d in [Vec3::new(0.3, 0.4, -0.5), Vec3::new(-1.0, 0.2, 0.1)] {
            let c =
                Camera::looking_along_up(Vec3::ZERO, d, Vec3::new(0.0, 1.0, 1.0), 40.0).unwrap();
            assert!((c.forward() - d.normalize()).length() < 1e-5, "{d}");
        }
        assert!(Camera::looking_along_up(Vec3::ZERO, Vec3::Y, Vec3::Y, 40.0).is_none());
        assert!(Camera::looking_along_up(Vec3::ZERO, -Vec3::Z, Vec3::ZERO, 40.0).is_none());
    }
}
