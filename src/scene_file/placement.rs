//! Where an object is put: `scale`, then `rotate` (degrees about x, then y, then z,
//! right-handed, as POV-Ray's `rotate`), then `translate`, in the scene file's own (world)
//! coordinates and in f64, so that a transform of a far-off scene keeps its precision.

use super::entry_def::EntryDef;
use super::error::SceneError;
use super::fixed_array::Fixed;
use super::validator::{Item, P3, Validator};
use crate::geometry::Transform;
use crate::limits;
use crate::messages::number;
use crate::scene::ObjectPlacement;
use glam::{Affine3A, DMat3, DVec3, Mat3A, Vec3A};

/// An object's placement in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Placement {
    scale: DVec3,
    rotation: DMat3,
    translate: DVec3,
    /// The values as the entry writes them.
    written: ObjectPlacement,
}

impl Placement {
    pub(super) const IDENTITY: Placement = Placement {
        scale: DVec3::ONE,
        rotation: DMat3::IDENTITY,
        translate: DVec3::ZERO,
        written: ObjectPlacement::IDENTITY,
    };

    /// The entry's `translate`, `rotate` and `scale`, as written.
    pub(super) fn written(&self) -> ObjectPlacement {
        self.written
    }

    /// Whether it changes nothing (however it is written: a whole turn is none).
    fn is_identity(&self) -> bool {
        self.scale == DVec3::ONE
            && self.rotation == DMat3::IDENTITY
            && self.translate == DVec3::ZERO
    }

    fn linear(&self) -> DMat3 {
        self.rotation * DMat3::from_diagonal(self.scale)
    }

    /// A world point, placed (exactly itself, signs of zero included, without a placement).
    pub(super) fn point(&self, p: P3) -> P3 {
        if self.is_identity() {
            return p;
        }
        Fixed((self.linear() * DVec3::from(p) + self.translate).to_array())
    }

    /// For a shape its own parameters can place (no turn, which would turn its texture,
    /// and the same scale on every axis): the factor.
    pub(super) fn uniform_scale(&self) -> Option<f64> {
        (self.keeps_axes() && self.scale.x == self.scale.y && self.scale.y == self.scale.z)
            .then_some(self.scale.x)
    }

    /// Whether the placement keeps the axes' directions (no turn), so a box stays
    /// axis-aligned.
    pub(super) fn keeps_axes(&self) -> bool {
        self.rotation == DMat3::IDENTITY
    }

    /// The map of normals: the inverse transpose of the linear part.
    pub(super) fn normal_matrix(&self) -> DMat3 {
        self.linear().inverse().transpose()
    }

    /// For an upright shape (a cylinder, a cone) that stays upright and round (no turn, the
    /// same scale across it): the factors of its radius and its height.
    pub(super) fn upright_scale(&self) -> Option<(f64, f64)> {
        (self.keeps_axes() && self.scale.x == self.scale.z).then_some((self.scale.x, self.scale.y))
    }

    /// The transform of a shape given relative to the scene's origin `origin` (as every
    /// `Scene` position is) to where the placement puts it, also relative to `origin`:
    /// r ↦ L·r + (L·origin + t − origin).
    pub(super) fn relative(&self, origin: DVec3) -> Option<Transform> {
        let l = self.linear();
        self.affine(l * origin + self.translate - origin)
    }

    /// The transform of a model in its own coordinates (a mesh file's) to the scene's,
    /// relative to `origin`: m ↦ L·m + t − origin.
    pub(super) fn model(&self, origin: DVec3) -> Option<Transform> {
        self.affine(self.translate - origin)
    }

    fn affine(&self, translation: DVec3) -> Option<Transform> {
        let l = self.linear().as_mat3();
        let affine = Affine3A {
            matrix3: Mat3A::from(l),
            translation: Vec3A::from(translation.as_vec3()),
        };
        Transform::new(affine)
    }
}

impl Validator<'_> {
    /// The placement that an object entry's `translate`, `rotate` and `scale` give.
    pub(super) fn placement(&self, at: &Item, d: &dyn EntryDef) -> Result<Placement, SceneError> {
        let (translate, rotate, scale) = d.placement();
        let mut out = Placement::IDENTITY;
        if let Some(t) = translate {
            let t = DVec3::from(t);
            if !(t.is_finite() && t.abs().max_element() <= limits::MAX_COORDINATE) {
                return Err(self.field_error(
                    at,
                    "translate",
                    format!(
                        "`translate` must hold finite numbers of at most {:e}, got {:?}",
                        limits::MAX_COORDINATE,
                        t.to_array()
                    ),
                ));
            }
            out.translate = t;
            out.written.translate = t;
        }
        if let Some(r) = rotate {
            let given = self.point(at, "rotate", r)?;
            out.written.rotate = given;
            let degrees = given.as_dvec3();
            // Whole turns are exact; the rest is taken in [0, 360) for precision.
            let turned = degrees.to_array().map(|d| d.rem_euclid(360.0));
            let [x, y, z] = turned.map(f64::to_radians);
            out.rotation =
                DMat3::from_rotation_z(z) * DMat3::from_rotation_y(y) * DMat3::from_rotation_x(x);
        }
        if let Some(value) = scale {
            let factors: Option<[f64; 3]> = match value {
                toml::Value::Float(f) => Some([*f; 3]),
                toml::Value::Integer(i) => Some([*i as f64; 3]),
                toml::Value::Array(a) if a.len() == 3 => {
                    let v: Vec<Option<f64>> = a
                        .iter()
                        .map(|x| match x {
                            toml::Value::Float(f) => Some(*f),
                            toml::Value::Integer(i) => Some(*i as f64),
                            _ => None,
                        })
                        .collect();
                    v.iter()
                        .all(Option::is_some)
                        .then(|| [v[0].unwrap(), v[1].unwrap(), v[2].unwrap()])
                }
                _ => None,
            };
            let Some(factors) = factors else {
                return Err(self.field_error(
                    at,
                    "scale",
                    "`scale` must be a number (the same on every axis) or [sx, sy, sz]",
                ));
            };
            let (lo, hi) = (*limits::SCALE.start(), *limits::SCALE.end());
            if let Some(bad) = factors.iter().find(|f| !(lo..=hi).contains(*f)) {
                return Err(self.field_error(
                    at,
                    "scale",
                    format!(
                        "`scale` must be greater than zero, from {lo:e} to {hi:e} on every axis, \
                         got {}",
                        number(*bad as f32)
                    ),
                ));
            }
            out.scale = DVec3::from(factors);
            out.written.scale = out.scale;
        }
        Ok(out)
    }
}
