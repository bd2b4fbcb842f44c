//! Changes to a loaded scene from outside the file (the viewer's sliders), checked like the
//! file itself: a bad value is refused with a message, never rendered.

use super::description::Scene;
use crate::appearance::{Background, Falloff, Light, LightKind, Material, SpotCone};
use crate::camera::Camera;
use crate::limits::{
    DEPTH, MAX_COORDINATE, MAX_EXTINCTION, MAX_RADIANCE, MIN_LENGTH, RADIANCE_BOUND,
};
use crate::messages::FieldProblem;
use glam::Vec3;
use thiserror::Error;

/// Why an edit was refused.
#[derive(Debug, Error, PartialEq)]
pub enum EditError {
    /// The scene has no object with this index.
    #[error("no object number {0}")]
    NoSuchObject(usize),
    /// The scene has no group with this index.
    #[error("no group number {0}")]
    NoSuchGroup(usize),
    /// A camera that breaks a rule (the message says which).
    #[error("camera: {0}")]
    Camera(String),
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
    /// A material that breaks one of the rules every material follows
    /// ([`Material::check`]).
    #[error("{object}: {problem}")]
    Material {
        /// The object's name.
        object: String,
        /// The field at fault, and what is wrong.
        problem: FieldProblem,
    },
    /// A placement (`translate`, `rotate`, `scale`) that the scene file would refuse: the
    /// entry, and what is wrong.
    #[error("{item}: {message}")]
    Placement {
        /// The entry, as a load's messages name it (`spheres[2] "ball"`).
        item: String,
        /// What is wrong.
        message: String,
    },
    /// A scene-wide value (background, ambient light, depth) out of range, in the scene
    /// file's words.
    #[error("render: {0}")]
    Render(FieldProblem),
}

impl Scene {
    /// Sets object `object`'s index of refraction (the material's other fields kept), by
    /// the rules of [`Scene::set_material`].
    pub fn set_eta(&mut self, object: usize, eta: f32) -> Result<(), EditError> {
        self.edit_material(object, |m| m.eta = Some(eta))
    }

    /// Sets object `object`'s transparency, from 0 to 1.
    pub fn set_transparency(&mut self, object: usize, t: f32) -> Result<(), EditError> {
        self.edit_material(object, |m| m.transparency = t)
    }

    /// Sets object `object`'s roughness, on a material that reflects (or is Fresnel glass).
    pub fn set_roughness(&mut self, object: usize, r: f32) -> Result<(), EditError> {
        self.edit_material(object, |m| m.roughness = r)
    }

    /// Switches object `object`'s Fresnel glass on or off (on needs an eta other than 1).
    pub fn set_fresnel(&mut self, object: usize, on: bool) -> Result<(), EditError> {
        self.edit_material(object, |m| m.fresnel = on)
    }

    /// Object `object`'s material changed by `change`, if the result is one the file takes.
    fn edit_material(
        &mut self,
        object: usize,
        change: impl FnOnce(&mut Material),
    ) -> Result<(), EditError> {
        let mut m = self.object_mut(object)?.material.clone();
        change(&mut m);
        self.set_material(object, m)
    }

    /// Resizes area light `light` about its centre to `size` (`AreaShape::size`).
    pub fn set_light_size(&mut self, light: usize, size: f32) -> Result<(), EditError> {
        self.edit_light(light, |l| {
            let LightKind::Area { shape, .. } = &mut l.kind else {
                return Err("only an area light has a size".into());
            };
            if !crate::limits::LENGTH.contains(&size) {
                return Err(format!(
                    "size {size} must be a number from {MIN_LENGTH:e} to {MAX_COORDINATE:e}"
                ));
            }
            *shape = shape.resized(size / shape.size());
            Ok(())
        })
    }

    /// Sets spotlight `light`'s cone: half-angle in degrees and softness (0..1).
    pub fn set_spot(&mut self, light: usize, angle: f32, softness: f32) -> Result<(), EditError> {
        self.edit_light(light, |l| {
            let LightKind::Spot { cone, .. } = &mut l.kind else {
                return Err("only a spotlight has a cone".into());
            };
            *cone = SpotCone::new(cone.direction, angle, softness);
            Ok(())
        })
    }

    /// Sets the radius of spotlight `light`'s disc: 0 for a point (hard shadows), else a
    /// length (soft shadows).
    pub fn set_spot_radius(&mut self, light: usize, radius: f32) -> Result<(), EditError> {
        self.edit_light(light, |l| {
            let LightKind::Spot { radius: r, .. } = &mut l.kind else {
                return Err("only a spotlight has a disc radius".into());
            };
            *r = radius;
            Ok(())
        })
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

impl Scene {
    /// Replaces object `object`'s material with `material`, if the scene file would take it
    /// ([`Material::check`]).
    pub fn set_material(&mut self, object: usize, material: Material) -> Result<(), EditError> {
        let o = self.object_mut(object)?;
        material.check().map_err(|problem| EditError::Material {
            object: o.name.clone(),
            problem,
        })?;
        o.material = material;
        Ok(())
    }

    /// Replaces light `index`'s colour and, for a light at a point (point, spot, sphere,
    /// rectangle), moves it so that its centre is `center` (relative to the scene's origin).
    pub fn set_light_at(
        &mut self,
        index: usize,
        color: Vec3,
        center: Option<Vec3>,
    ) -> Result<(), EditError> {
        self.edit_light(index, |l| {
            l.color = color;
            if let (Some(to), Some(from)) = (center, l.center()) {
                *l = l.moved_by(to - from);
            }
            Ok(())
        })
    }

    /// Sets the intensity of light `index`, which must fade with inverse-square falloff.
    pub fn set_light_intensity(&mut self, index: usize, intensity: f32) -> Result<(), EditError> {
        self.edit_light(index, |l| match l.falloff_mut() {
            None => Err("only a light with falloff has an intensity".into()),
            Some(Falloff::None) => Err("an intensity needs falloff = \"inverse_square\"".into()),
            Some(Falloff::InverseSquare { intensity: i }) => {
                *i = intensity;
                Ok(())
            }
        })
    }

    /// Light `index` changed by `change` (which refuses a change that does not apply to its
    /// kind), if the result is one the file takes ([`Light::check`]).
    fn edit_light(
        &mut self,
        index: usize,
        change: impl FnOnce(&mut Light) -> Result<(), String>,
    ) -> Result<(), EditError> {
        let refuse = |message: String| EditError::Light {
            light: index,
            message,
        };
        let l = self.light_mut(index)?;
        let mut changed = *l;
        change(&mut changed).map_err(refuse)?;
        changed.check().map_err(|p| refuse(p.message))?;
        *l = changed;
        Ok(())
    }

    /// Sets a one-colour background (replacing a gradient or an image).
    pub fn set_background_color(&mut self, color: Vec3) -> Result<(), EditError> {
        check_radiance("background", color)?;
        self.background = Background::Solid(color);
        Ok(())
    }

    /// Sets the ambient light.
    pub fn set_ambient(&mut self, color: Vec3) -> Result<(), EditError> {
        check_radiance("ambient", color)?;
        self.ambient = color;
        Ok(())
    }

    /// Sets the most secondary bounces along one path.
    pub fn set_max_depth(&mut self, depth: u32) -> Result<(), EditError> {
        if !DEPTH.contains(&depth) {
            return Err(EditError::Render(FieldProblem::new(
                "max_depth",
                format!(
                    "`max_depth` must lie in {}..={}, got {depth}",
                    DEPTH.start(),
                    DEPTH.end()
                ),
            )));
        }
        self.render.max_depth = depth;
        Ok(())
    }
}

impl Scene {
    /// Object `object`, to edit.
    fn object_mut(
        &mut self,
        object: usize,
    ) -> Result<&mut super::description::SceneObject, EditError> {
        self.objects
            .get_mut(object)
            .ok_or(EditError::NoSuchObject(object))
    }

    /// Light `index`, to edit.
    fn light_mut(&mut self, index: usize) -> Result<&mut crate::appearance::Light, EditError> {
        self.lights.get_mut(index).ok_or(EditError::Light {
            light: index,
            message: "no such light".into(),
        })
    }
}

/// A background or ambient colour: radiance, brighter than white allowed within reason.
fn check_radiance(field: &'static str, c: Vec3) -> Result<(), EditError> {
    FieldProblem::check_color(field, c.to_array(), MAX_RADIANCE, RADIANCE_BOUND)
        .map_err(EditError::Render)
}

/// Checks a camera set by hand, by the rules every camera follows ([`Camera::check`]).
pub fn check_camera(c: &Camera) -> Result<(), EditError> {
    c.check().map_err(EditError::Camera)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let mut scene = crate::scene_file::parse_scene(
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

    /// An edit is held to `Material::check`, the rule the file's `[materials]` follow, with
    /// the file's words; a refused material leaves the scene as it was.
    #[test]
    fn a_material_the_file_would_refuse_is_refused_with_its_words() {
        let template = crate::scene_file::parse_scene(
            "[camera]\neye = [0, 0, 0]\nfov = 40\n[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n",
            std::path::Path::new("m.toml"),
            std::path::Path::new("."),
        )
        .unwrap();
        let base = template.objects[0].material.clone();
        let bad = [
            (
                Material {
                    shininess: 10001.0,
                    ..base.clone()
                },
                "spheres 0: `shininess` must lie in [0, 10000], got 10001",
            ),
            (
                Material {
                    roughness: 0.5,
                    ..base.clone()
                },
                "spheres 0: `roughness` spreads mirror reflection and refraction: it needs a \
                 `reflectivity` above 0, `fresnel = true`, or a `transparency` above 0 with an \
                 `eta` other than 1",
            ),
            (
                Material {
                    eta: Some(f32::NAN),
                    ..base.clone()
                },
                "spheres 0: `eta` must be a finite number, got NaN",
            ),
            (
                Material {
                    emission: Vec3::new(-1.0, 0.0, 0.0),
                    ..base.clone()
                },
                "spheres 0: `emission` must not be negative, got [-1.0, 0.0, 0.0]",
            ),
        ];
        for (m, message) in bad {
            let mut scene = template.clone();
            let e = scene.set_material(0, m).unwrap_err();
            assert_eq!(e.to_string(), message);
            assert_eq!(scene, template, "unchanged after a refusal");
        }
        let mut scene = template.clone();
        let glass = Material {
            transparency: 0.9,
            reflectivity: 0.1,
            eta: Some(1.5),
            fresnel: true,
            ..base
        };
        scene.set_material(0, glass.clone()).unwrap();
        assert_eq!(scene.objects[0].material, glass);
    }

    /// A light edit is held to `Light::check`, the rule the file's `[[lights]]` follow, in
    /// the file's words; a refused edit leaves the light as it was.
    #[test]
    fn a_light_the_file_would_refuse_is_refused_with_its_words() {
        let mut s = seed();
        let before = s.clone();
        let e = s
            .set_light_at(0, Vec3::new(0.0, 2.0e4, 0.0), None)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "lights[0]: `color` must lie in [0, 10000] per channel (light may be brighter than \
             white, up to this), got [0.0, 20000.0, 0.0]"
        );
        let e = s
            .set_light_at(0, Vec3::ONE, Some(Vec3::new(0.0, 0.0, -2.0e12)))
            .unwrap_err();
        assert!(
            e.to_string()
                .starts_with("lights[0]: `position` must hold finite numbers within"),
            "{e}"
        );
        assert_eq!(s, before);
    }

    #[test]
    fn light_and_scene_edits_keep_the_files_limits() {
        let mut s = seed();
        let before = s.lights[0].center().unwrap();
        let to = before + Vec3::new(1.0, 2.0, 3.0);
        s.set_light_at(0, Vec3::splat(0.5), Some(to)).unwrap();
        assert_eq!(s.lights[0].center(), Some(to));
        assert_eq!(s.lights[0].color, Vec3::splat(0.5));
        assert!(s.set_light_at(0, Vec3::splat(-0.1), None).is_err());
        assert!(s.set_light_at(0, Vec3::splat(2e4), None).is_err());
        assert!(
            s.set_light_at(0, Vec3::ONE, Some(Vec3::splat(2e12)))
                .is_err()
        );
        assert!(s.set_light_at(0, Vec3::ONE, Some(Vec3::NAN)).is_err());
        assert!(s.set_light_at(99, Vec3::ONE, None).is_err());
        assert_eq!(s.lights[0].center(), Some(to), "unchanged after refusals");
        assert!(
            s.set_light_intensity(0, 2.0).is_err(),
            "the seed's light has no falloff"
        );
        s.set_ambient(Vec3::splat(0.2)).unwrap();
        assert!(s.set_ambient(Vec3::splat(f32::INFINITY)).is_err());
        s.set_background_color(Vec3::new(0.0, 0.0, 0.3)).unwrap();
        assert!(s.set_background_color(Vec3::splat(-1.0)).is_err());
        s.set_max_depth(*DEPTH.end()).unwrap();
        assert!(s.set_max_depth(DEPTH.end() + 1).is_err());
        assert_eq!(s.render.max_depth, *DEPTH.end());
    }
}
