//! Where an entry is put: `scale`, then `rotate` (degrees about x, then y, then z,
//! right-handed, as POV-Ray's `rotate`), then `translate`, in its group's frame (groups.rs)
//! or the world's, in f64 so that a transform of a far-off scene keeps its precision.

use super::entry_def::EntryDef;
use super::error::SceneError;
use super::fixed_array::Fixed;
use super::validator::{Item, P3, V3, Validator};
use crate::geometry::Transform;
use crate::limits;
use crate::messages::number;
use crate::scene::ObjectPlacement;
use glam::{Affine3A, DAffine3, DMat3, DVec3, Mat3A, Vec3A};

/// An entry's placement: its own `translate`, `rotate` and `scale` (as written), carried
/// into the world's frame by its group's, if it is in one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Placement {
    /// From the entry's own coordinates to the world's.
    frame: DAffine3,
    /// The entry's own values, as written.
    written: ObjectPlacement,
    /// The group it is placed in (an index into the scene's groups).
    group: Option<usize>,
}

impl Placement {
    /// `written` in the frame that `outer` maps to the world's (group `group`'s).
    pub(super) fn new(written: ObjectPlacement, outer: DAffine3, group: Option<usize>) -> Self {
        let own = written.affine();
        let frame = if outer == DAffine3::IDENTITY {
            own
        } else {
            outer * own
        };
        Self {
            frame,
            written,
            group,
        }
    }

    /// The group it is placed in.
    pub(super) fn group(&self) -> Option<usize> {
        self.group
    }

    /// The entry's `translate`, `rotate` and `scale`, as written.
    pub(super) fn written(&self) -> ObjectPlacement {
        self.written
    }

    /// Whether it changes nothing (however it is written: a whole turn is none).
    pub(super) fn is_identity(&self) -> bool {
        self.frame == DAffine3::IDENTITY
    }

    fn linear(&self) -> DMat3 {
        self.frame.matrix3
    }

    /// A world point, placed (exactly itself, signs of zero included, without a placement).
    pub(super) fn point(&self, p: P3) -> P3 {
        if self.is_identity() {
            return p;
        }
        Fixed((self.linear() * DVec3::from(p) + self.frame.translation).to_array())
    }

    /// A direction (a light's), carried by the placement's scale and turn.
    pub(super) fn vector(&self, v: DVec3) -> DVec3 {
        self.linear() * v
    }

    /// The factors along x, y and z when the placement keeps the axes' directions (no
    /// turn), so a box stays axis-aligned; None when it turns them.
    fn axis_factors(&self) -> Option<DVec3> {
        let m = self.linear();
        let diagonal = DVec3::new(m.x_axis.x, m.y_axis.y, m.z_axis.z);
        let off = [
            m.x_axis.y, m.x_axis.z, m.y_axis.x, m.y_axis.z, m.z_axis.x, m.z_axis.y,
        ];
        (off.iter().all(|&o| o == 0.0) && diagonal.min_element() > 0.0).then_some(diagonal)
    }

    /// For a shape its own parameters can place (no turn, which would turn its texture,
    /// and the same scale on every axis): the factor.
    pub(super) fn uniform_scale(&self) -> Option<f64> {
        self.axis_factors()
            .filter(|s| s.x == s.y && s.y == s.z)
            .map(|s| s.x)
    }

    /// Whether the placement keeps the axes' directions (no turn), so a box stays
    /// axis-aligned.
    pub(super) fn keeps_axes(&self) -> bool {
        self.axis_factors().is_some()
    }

    /// The factor a length is scaled by when the placement scales every direction alike
    /// (turned or not); None when it stretches some more than others.
    pub(super) fn even_scale(&self) -> Option<f64> {
        let m = self.linear();
        let lengths = [m.x_axis, m.y_axis, m.z_axis].map(DVec3::length);
        let orthogonal = m.x_axis.dot(m.y_axis).abs()
            + m.y_axis.dot(m.z_axis).abs()
            + m.z_axis.dot(m.x_axis).abs();
        let s = lengths[0];
        // A product of turns and even scales is even up to rounding.
        let close = |a: f64| (a - s).abs() <= 1e-9 * s;
        (close(lengths[1]) && close(lengths[2]) && orthogonal <= 1e-9 * s * s).then_some(s)
    }

    /// The map of normals: the inverse transpose of the linear part.
    pub(super) fn normal_matrix(&self) -> DMat3 {
        self.linear().inverse().transpose()
    }

    /// For an upright shape (a cylinder, a cone) that stays upright and round (no turn, the
    /// same scale across it): the factors of its radius and its height.
    pub(super) fn upright_scale(&self) -> Option<(f64, f64)> {
        self.axis_factors()
            .filter(|s| s.x == s.z)
            .map(|s| (s.x, s.y))
    }

    /// The transform of a shape given relative to the scene's origin `origin` (as every
    /// `Scene` position is) to where the placement puts it, also relative to `origin`:
    /// r ↦ L·r + (L·origin + t − origin).
    pub(super) fn relative(&self, origin: DVec3) -> Option<Transform> {
        let l = self.linear();
        self.affine(l * origin + self.frame.translation - origin)
    }

    /// The transform of a model in its own coordinates (a mesh file's) to the scene's,
    /// relative to `origin`: m ↦ L·m + t − origin.
    pub(super) fn model(&self, origin: DVec3) -> Option<Transform> {
        self.affine(self.frame.translation - origin)
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
    /// The placement that an entry's `translate`, `rotate` and `scale` give in its
    /// `group`'s frame.
    pub(super) fn placement(&self, at: &Item, d: &dyn EntryDef) -> Result<Placement, SceneError> {
        let written = self.own_placement(at, d.placement())?;
        let (group, frame) = self.group_frame(at, d.group())?;
        Ok(Placement::new(written, frame, group))
    }

    /// An entry's own `translate`, `rotate` and `scale`, checked.
    pub(super) fn own_placement(
        &self,
        at: &Item,
        (translate, rotate, scale): (Option<P3>, Option<V3>, Option<&toml::Value>),
    ) -> Result<ObjectPlacement, SceneError> {
        let mut out = ObjectPlacement::IDENTITY;
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
        }
        if let Some(r) = rotate {
            out.rotate = self.point(at, "rotate", r)?;
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
        }
        Ok(out)
    }
}
