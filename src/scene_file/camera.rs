//! The `[camera]` table: where it stands, where it looks (a direction, a point, or yaw and
//! pitch), its field of view, its lens and its handedness, checked by `Camera::check`.

use super::error::SceneError;
use super::fixed_array::Fixed;
use super::gltf_scene::GltfCamera;
use super::placement::Placement;
use super::validator::{Item, P3, V3, Validator};
use crate::camera::Camera;
use crate::limits;
use crate::messages::{did_you_mean, quoted};
use serde::Deserialize;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraDef {
    pub(super) eye: P3,
    pub(super) look_at: Option<P3>,
    pub(super) direction: Option<V3>,
    pub(super) yaw: Option<f32>,
    pub(super) pitch: Option<f32>,
    pub(super) up: Option<V3>,
    pub(super) fov: f32,
    pub(super) aperture: Option<f32>,
    pub(super) focus_distance: Option<f32>,
    pub(super) handedness: Option<String>,
}

impl Validator<'_> {
    pub(super) fn camera(&self, c: &Spanned<CameraDef>) -> Result<Camera, SceneError> {
        let at = Item {
            span: c.span(),
            name: "camera",
        };
        let c = c.get_ref();
        let eye = self.position(&at, "eye", c.eye)?;
        let (lo, hi) = (*limits::VFOV.start(), *limits::VFOV.end());
        let vfov = self.in_range(&at, "fov", c.fov, lo, hi)?;
        let ways = [
            c.look_at.is_some(),
            c.direction.is_some(),
            c.yaw.is_some() || c.pitch.is_some(),
        ];
        if ways.iter().filter(|&&w| w).count() > 1 {
            return Err(self.error(
                &at,
                "give only one of `look_at`, `direction`, or `yaw`/`pitch`",
            ));
        }
        let up = self.point(&at, "up", c.up.unwrap_or(Fixed([0.0, 1.0, 0.0])))?;
        let up = crate::numerics::try_normalize(up)
            .ok_or_else(|| self.field_error(&at, "up", "`up` has zero length"))?;
        let direction = if let Some(target) = c.look_at {
            let target = self.position(&at, "look_at", target)?;
            if target == eye {
                return Err(self.field_error(
                    &at,
                    "look_at",
                    "`look_at` equals `eye`: the camera has no direction",
                ));
            }
            target - eye
        } else if let Some(d) = c.direction {
            self.point(&at, "direction", d)?
        } else {
            let yaw = self.number(&at, "yaw", c.yaw.unwrap_or(0.0))?;
            let pitch = self.in_range(
                &at,
                "pitch",
                c.pitch.unwrap_or(0.0),
                *limits::PITCH.start(),
                *limits::PITCH.end(),
            )?;
            let camera = Camera {
                eye,
                yaw,
                pitch,
                vfov,
                up,
                aperture: 0.0,
                focus_distance: 1.0,
                handedness: crate::camera::Handedness::Right,
            };
            return self.lens(&at, c, camera, None);
        };
        // The view is given by `look_at` or by `direction`: point at the one given.
        let view = if c.look_at.is_some() {
            "look_at"
        } else {
            "direction"
        };
        if crate::numerics::try_normalize(direction).is_none() {
            return Err(self.field_error(
                &at,
                view,
                format!("the view direction {direction} has zero length"),
            ));
        }
        let camera = Camera::looking_along_up(eye, direction, up, vfov).ok_or_else(|| {
            self.field_error(
                &at,
                view,
                format!(
                    "the view direction {direction} is within 1° of `up` {up}: choose another `up`"
                ),
            )
        })?;
        // A `look_at` target is in focus unless `focus_distance` says otherwise.
        let target = c
            .look_at
            .map(|_| direction.dot(camera.forward()))
            .filter(|d| d.is_finite() && *d > 0.0);
        self.lens(&at, c, camera, target)
    }

    /// `camera` with the lens `c` gives (`aperture`, `focus_distance`, which defaults to
    /// `target`), checked by the rule every camera follows. (The fields are checked one by
    /// one before it, for messages on their own lines.)
    pub(super) fn lens(
        &self,
        at: &Item,
        c: &CameraDef,
        mut camera: Camera,
        target: Option<f32>,
    ) -> Result<Camera, SceneError> {
        camera.handedness = match c.handedness.as_deref() {
            None | Some("right") => crate::camera::Handedness::Right,
            Some("left") => crate::camera::Handedness::Left,
            Some(other) => {
                return Err(self.field_error(
                    at,
                    "handedness",
                    format!(
                        "`handedness` is \"right\" (prism's coordinates) or \"left\" \
                         (POV-Ray's), got {}{}",
                        quoted(other),
                        did_you_mean(other, ["right", "left"])
                    ),
                ));
            }
        };
        let max = limits::MAX_COORDINATE as f32;
        camera.aperture = self.in_range(at, "aperture", c.aperture.unwrap_or(0.0), 0.0, max)?;
        camera.focus_distance = match (c.focus_distance, target) {
            (Some(d), _) => self.length(at, "focus_distance", d)?,
            (None, Some(d)) => d.max(limits::MIN_LENGTH as f32),
            (None, None) if camera.aperture > 0.0 => {
                return Err(self.field_error(
                    at,
                    "aperture",
                    "an `aperture` needs a `focus_distance` (or a `look_at` to focus on)",
                ));
            }
            (None, None) => 1.0,
        };
        camera
            .check()
            .map(|()| camera)
            .map_err(|m| self.error(at, m))
    }
}

impl Validator<'_> {
    /// The camera of `cameras` (a glTF file's) that mesh entry `at`'s `camera` names, by
    /// its name or its index in the file.
    pub(super) fn gltf_view<'c>(
        &self,
        at: &Item,
        cameras: &'c [GltfCamera],
        choice: &toml::Value,
    ) -> Result<&'c GltfCamera, SceneError> {
        let names: Vec<&str> = cameras.iter().filter_map(|c| c.name.as_deref()).collect();
        let found = match choice {
            toml::Value::String(name) => cameras.iter().find(|c| c.name.as_deref() == Some(name)),
            toml::Value::Integer(i) => cameras.iter().find(|c| c.index as i64 == *i),
            _ => {
                return Err(self.field_error(
                    at,
                    "camera",
                    "`camera` is a camera's name or its index in the glTF file",
                ));
            }
        };
        found.ok_or_else(|| {
            let shown = match choice {
                toml::Value::String(name) => quoted(name),
                other => other.to_string(),
            };
            let hint = match choice {
                toml::Value::String(name) => did_you_mean(name, names.iter().copied()),
                _ => String::new(),
            };
            self.field_error(
                at,
                "camera",
                format!(
                    "the glTF file's scene has no perspective camera {shown} (it has {}){hint}",
                    if cameras.is_empty() {
                        "none".to_string()
                    } else {
                        cameras
                            .iter()
                            .map(|c| match &c.name {
                                Some(n) => format!("{} ({})", quoted(n), c.index),
                                None => c.index.to_string(),
                            })
                            .collect::<Vec<_>>()
                            .join(", ")
                    }
                ),
            )
        })
    }

    /// The scene's camera from glTF camera `view`, placed by mesh entry `at`'s `placement`:
    /// its eye, its −z as the view, its vertical field of view, and its roll (if any); the
    /// lens of the file's `[camera]` (`file`).
    pub(super) fn gltf_camera(
        &self,
        at: &Item,
        view: &GltfCamera,
        placement: &Placement,
        file: &Camera,
    ) -> Result<Camera, SceneError> {
        let eye = self.position(at, "camera", placement.point(Fixed(view.eye.to_array())))?;
        let direction = placement.vector(view.direction);
        // The scene's up unless the camera rolls (its +y leaves the upright plane through
        // its view): then its own +y, the only way prism's camera says roll.
        let scene_up = placement.vector(glam::DVec3::Y);
        let own_up = placement.vector(view.up);
        let side = direction.cross(scene_up).normalize_or_zero();
        let up = if own_up.normalize_or_zero().dot(side).abs() < 1e-4 {
            scene_up
        } else {
            own_up
        };
        let (direction, up) = (direction.as_vec3(), up.as_vec3());
        let vfov = view.yfov.to_degrees();
        let (lo, hi) = (*limits::VFOV.start(), *limits::VFOV.end());
        if !(lo..=hi).contains(&vfov) {
            return Err(self.field_error(
                at,
                "camera",
                format!("the camera's yfov is {vfov}°; a field of view is from {lo}° to {hi}°"),
            ));
        }
        let mut camera = Camera::looking_along_up(eye, direction, up, vfov).ok_or_else(|| {
            self.field_error(at, "camera", "the camera's node leaves it no direction")
        })?;
        camera.aperture = file.aperture;
        camera.focus_distance = file.focus_distance;
        camera
            .check()
            .map_err(|e| self.field_error(at, "camera", e.to_string()))?;
        Ok(camera)
    }
}
