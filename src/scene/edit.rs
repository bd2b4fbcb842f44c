//! Changes to a loaded scene from outside the file (the viewer's sliders), checked like the
//! file itself: a bad value is refused with a message, never rendered.

use super::description::Scene;
use crate::camera::Camera;
use crate::limits::{ETA, MAX_COORDINATE, MAX_PITCH, VFOV};
use thiserror::Error;

#[derive(Debug, Error, PartialEq)]
pub enum EditError {
    #[error("no object number {0}")]
    NoSuchObject(usize),
    #[error("{object}: eta {value} must be a number from {} to {}", ETA.start(), ETA.end())]
    Eta { object: String, value: f32 },
    #[error("{object}: transparency {value} must be a number from 0 to 1")]
    Transparency { object: String, value: f32 },
    #[error("camera: {0}")]
    Camera(String),
}

impl Scene {
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

    pub fn set_transparency(&mut self, object: usize, t: f32) -> Result<(), EditError> {
        let o = self
            .objects
            .get_mut(object)
            .ok_or(EditError::NoSuchObject(object))?;
        if !(0.0..=1.0).contains(&t) {
            return Err(EditError::Transparency {
                object: o.name.clone(),
                value: t,
            });
        }
        o.material.transparency = t;
        Ok(())
    }
}

/// Checks a camera set by hand: finite, within reach of f32, pitch and field of view in range.
pub fn check_camera(c: &Camera) -> Result<(), EditError> {
    let bad = |m: String| Err(EditError::Camera(m));
    // Like every position, within reach of the scene's origin (limits.rs).
    if !c.eye.is_finite() || c.eye.abs().max_element() as f64 > MAX_COORDINATE {
        return bad(format!(
            "eye {} must be finite and within ±{MAX_COORDINATE:e}",
            c.eye
        ));
    }
    if !c.up.is_finite() || (c.up.length() - 1.0).abs() > 1e-3 {
        return bad(format!("up {} must be a unit vector", c.up));
    }
    if !c.yaw.is_finite() {
        return bad(format!("yaw {} must be a finite number", c.yaw));
    }
    if !(-MAX_PITCH..=MAX_PITCH).contains(&c.pitch) {
        return bad(format!("pitch {} must lie in ±{MAX_PITCH}°", c.pitch));
    }
    if !VFOV.contains(&c.vfov) {
        return bad(format!(
            "field of view {} must lie in {}..{}°",
            c.vfov,
            VFOV.start(),
            VFOV.end()
        ));
    }
    Ok(())
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
        ];
        for c in cases {
            assert!(check_camera(&c).is_err(), "{c:?}");
        }
    }
}
