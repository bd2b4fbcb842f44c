//! Changes to a loaded scene from outside the file (the viewer's sliders), checked like the
//! file itself: a bad value is refused with a message, never rendered.

use super::description::Scene;
use crate::camera::Camera;
use crate::limits::{ETA, FRACTION};
use thiserror::Error;

/// Why an edit was refused.
#[derive(Debug, Error, PartialEq)]
pub enum EditError {
    /// The scene has no object with this index.
    #[error("no object number {0}")]
    NoSuchObject(usize),
    /// An eta out of range.
    #[error("{object}: eta {value} must be a number from {} to {}", ETA.start(), ETA.end())]
    Eta {
        /// The object's name.
        object: String,
        /// The value refused.
        value: f32,
    },
    #[error(
        "{object}: transparency {value} must be a number from {} to {}",
        FRACTION.start(),
        FRACTION.end()
    )]
    /// A transparency out of range.
    Transparency {
        /// The object's name.
        object: String,
        /// The value refused.
        value: f32,
    },
    /// A camera that breaks a rule (the message says which).
    #[error("camera: {0}")]
    Camera(String),
}

impl Scene {
    /// Sets object `object`'s index of refraction, within limits.rs's range.
    pub fn set_eta(&mut self, object: usize, eta: f32) -> Result<(), EditError> {
        let o = self
            .objects
            .get_mut(object)
            .ok_or(EditError::NoSuchObject(object))?;
        if !ETA.contains(&eta) {
            return Err(EditError::Eta {
                object: o.name.clone(),
                value: eta,
            });
        }
        o.material.eta = Some(eta);
        Ok(())
    }

    /// Sets object `object`'s transparency, from 0 to 1.
    pub fn set_transparency(&mut self, object: usize, t: f32) -> Result<(), EditError> {
        let o = self
            .objects
            .get_mut(object)
            .ok_or(EditError::NoSuchObject(object))?;
        if !FRACTION.contains(&t) {
            return Err(EditError::Transparency {
                object: o.name.clone(),
                value: t,
            });
        }
        o.material.transparency = t;
        Ok(())
    }
}

/// Checks a camera set by hand, by the rules every camera follows ([`Camera::check`]).
pub fn check_camera(c: &Camera) -> Result<(), EditError> {
    c.check().map_err(EditError::Camera)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn seed() -> Scene {
        crate::seed::scene().unwrap()
    }

    #[test]
    fn eta_edits_are_range_checked() {
        let mut s = seed();
        let glass = s
            .objects
            .iter()
            .position(|o| o.material.eta.is_some())
            .unwrap();
        s.set_eta(glass, 2.0).unwrap();
        assert_eq!(s.objects[glass].material.eta, Some(2.0));
        // The file's range, one definition (limits::ETA): 0.5 and 3.5 are fine, these not.
        s.set_eta(glass, 0.5).unwrap();
        s.set_eta(glass, 3.5).unwrap();
        s.set_eta(glass, 2.0).unwrap();
        for bad in [f32::NAN, f32::INFINITY, 0.05, 10.5, -1.0, 2e19] {
            let e = s.set_eta(glass, bad).unwrap_err();
            assert!(e.to_string().contains("eta"), "{e}");
            assert_eq!(
                s.objects[glass].material.eta,
                Some(2.0),
                "unchanged after {bad}"
            );
        }
        assert_eq!(s.set_eta(999, 1.5), Err(EditError::NoSuchObject(999)));
    }

    #[test]
    fn transparency_edits_are_range_checked() {
        let mut s = seed();
        s.set_transparency(0, 0.25).unwrap();
        for bad in [f32::NAN, -0.1, 1.1, f32::NEG_INFINITY] {
            assert!(s.set_transparency(0, bad).is_err());
        }
        assert_eq!(s.objects[0].material.transparency, 0.25);
    }

    #[test]
    fn cameras_with_bad_numbers_are_refused() {
        let good = seed().camera;
        assert!(check_camera(&good).is_ok());
        let cases = [
            Camera {
                eye: Vec3::new(f32::NAN, 0.0, 0.0),
                ..good
            },
            Camera {
                eye: Vec3::splat(1e30),
                ..good
            },
            Camera {
                yaw: f32::INFINITY,
                ..good
            },
            Camera {
                pitch: 95.0,
                ..good
            },
            Camera { vfov: 0.0, ..good },
            Camera {
                vfov: f32::NAN,
                ..good
            },
            Camera {
                aperture: -1.0,
                ..good
            },
            Camera {
                aperture: f32::INFINITY,
                ..good
            },
            Camera {
                focus_distance: 0.0,
                ..good
            },
        ];
        for c in cases {
            assert!(check_camera(&c).is_err(), "{c:?}");
        }
    }
}
