//! Changes to a loaded scene from outside the file (the viewer's sliders), checked like the
//! file itself: a bad value is refused with a message, never rendered.

use super::description::Scene;
use crate::appearance::{LightKind, SpotCone};
use crate::camera::Camera;
use crate::limits::{
    ETA, FRACTION, MAX_COORDINATE, MAX_EXTINCTION, MIN_LENGTH, ROUGHNESS, SPOT_ANGLE,
};
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
    /// A roughness out of range, or on a material that does not reflect.
    #[error("{object}: roughness {value} must be a number from {} to {} on a reflective material", ROUGHNESS.start(), ROUGHNESS.end())]
    Roughness {
        /// The object's name.
        object: String,
        /// The value refused.
        value: f32,
    },
    /// Fresnel asked of a material that does not refract.
    #[error("{object}: Fresnel glass needs an eta other than 1")]
    Fresnel {
        /// The object's name.
        object: String,
    },
    /// A light's number or value refused (the message says which).
    #[error("lights[{light}]: {message}")]
    Light {
        /// The light's index.
        light: usize,
        /// What is wrong.
        message: String,
    },
    /// A fog density out of range, or fog in a scene without any.
    #[error("fog: {0}")]
    Fog(String),
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

impl Scene {
    /// Sets object `object`'s roughness, on a material that reflects (or is Fresnel glass).
    pub fn set_roughness(&mut self, object: usize, r: f32) -> Result<(), EditError> {
        let o = self
            .objects
            .get_mut(object)
            .ok_or(EditError::NoSuchObject(object))?;
        let reflects = o.material.reflectivity > 0.0 || o.material.fresnel;
        if !(ROUGHNESS.contains(&r) && (reflects || r == 0.0)) {
            return Err(EditError::Roughness {
                object: o.name.clone(),
                value: r,
            });
        }
        o.material.roughness = r;
        Ok(())
    }

    /// Switches object `object`'s Fresnel glass on or off (on needs an eta other than 1).
    pub fn set_fresnel(&mut self, object: usize, on: bool) -> Result<(), EditError> {
        let o = self
            .objects
            .get_mut(object)
            .ok_or(EditError::NoSuchObject(object))?;
        if on && !matches!(o.material.eta, Some(e) if e != 1.0) {
            return Err(EditError::Fresnel {
                object: o.name.clone(),
            });
        }
        o.material.fresnel = on;
        Ok(())
    }

    /// Resizes area light `light` about its centre to `size` (`AreaShape::size`).
    pub fn set_light_size(&mut self, light: usize, size: f32) -> Result<(), EditError> {
        let refuse = |message: String| EditError::Light { light, message };
        let l = self
            .lights
            .get_mut(light)
            .ok_or_else(|| refuse("no such light".into()))?;
        let LightKind::Area { shape, .. } = &mut l.kind else {
            return Err(refuse("only an area light has a size".into()));
        };
        let factor = size / shape.size();
        let resized = shape.resized(factor);
        let ok = size.is_finite()
            && size as f64 >= MIN_LENGTH
            && resized.size().is_finite()
            && resized.center().abs().max_element() as f64 <= MAX_COORDINATE
            && resized.size() as f64 <= MAX_COORDINATE;
        if !ok {
            return Err(refuse(format!(
                "size {size} must be a number from {MIN_LENGTH:e} to {MAX_COORDINATE:e}"
            )));
        }
        *shape = resized;
        Ok(())
    }

    /// Sets spotlight `light`'s cone: half-angle in degrees and softness (0..1).
    pub fn set_spot(&mut self, light: usize, angle: f32, softness: f32) -> Result<(), EditError> {
        let refuse = |message: String| EditError::Light { light, message };
        let l = self
            .lights
            .get_mut(light)
            .ok_or_else(|| refuse("no such light".into()))?;
        let LightKind::Spot { cone, .. } = &mut l.kind else {
            return Err(refuse("only a spotlight has a cone".into()));
        };
        if !SPOT_ANGLE.contains(&angle) || !(0.0..=1.0).contains(&softness) {
            return Err(refuse(format!(
                "angle {angle} must lie in {}..={}° and softness {softness} in 0..=1",
                SPOT_ANGLE.start(),
                SPOT_ANGLE.end()
            )));
        }
        *cone = SpotCone::new(cone.direction, angle, softness);
        Ok(())
    }

    /// Sets the fog's density (`Fog::density`), in a scene that has fog.
    pub fn set_fog_density(&mut self, density: f32) -> Result<(), EditError> {
        let Some(fog) = &mut self.fog else {
            return Err(EditError::Fog("the scene has no fog".into()));
        };
        if !(density > 0.0 && density <= MAX_EXTINCTION) {
            return Err(EditError::Fog(format!(
                "density {density} must be above 0 and at most {MAX_EXTINCTION:e}"
            )));
        }
        *fog = fog.with_density(density);
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
    fn effect_edits_keep_the_files_rules() {
        let mut scene = crate::scene::parse_scene(
            "[camera]\neye = [0, 0, 0]\nfov = 40\n[fog]\ndensity = 0.1\n\
             [[lights]]\ntype = \"area\"\ncorner = [0, 5, 0]\nedge_u = [2, 0, 0]\nedge_v = [0, 0, 2]\n\
             [[lights]]\ntype = \"spot\"\nposition = [0, 5, 0]\ndirection = [0, -1, 0]\nangle = 20\n\
             [materials.glass]\ntransparency = 0.9\neta = 1.5\n[materials.matte]\nspecular = 0\n\
             [[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nmaterial = \"glass\"\n\
             [[spheres]]\ncenter = [3, 0, -5]\nradius = 1\nmaterial = \"matte\"\n",
            std::path::Path::new("edit.toml"),
            std::path::Path::new("."),
        )
        .unwrap();
        assert!(scene.set_fresnel(0, true).is_ok());
        assert!(scene.set_fresnel(1, true).is_err(), "no eta");
        assert!(
            scene.set_roughness(0, 0.4).is_ok(),
            "Fresnel glass reflects"
        );
        assert!(
            scene.set_roughness(1, 0.4).is_err(),
            "a matte surface does not"
        );
        assert!(scene.set_roughness(0, 1.5).is_err());
        let before = scene.lights[0].center();
        assert!(scene.set_light_size(0, 3.0).is_ok());
        assert_eq!(scene.lights[0].center(), before, "resized about its centre");
        let crate::appearance::LightKind::Area { shape, .. } = scene.lights[0].kind else {
            panic!()
        };
        assert!((shape.size() - 3.0).abs() < 1e-5);
        assert!(scene.set_light_size(0, 0.0).is_err());
        assert!(
            scene.set_light_size(1, 1.0).is_err(),
            "a spotlight has no size"
        );
        assert!(scene.set_spot(1, 35.0, 0.3).is_ok());
        assert!(scene.set_spot(1, 200.0, 0.3).is_err());
        assert!(scene.set_spot(0, 35.0, 0.3).is_err());
        assert!(scene.set_fog_density(0.5).is_ok());
        assert_eq!(scene.fog.unwrap().density(), 0.5);
        assert!(scene.set_fog_density(-1.0).is_err());
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
