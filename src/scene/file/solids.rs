//! `[[boxes]]`, `[[discs]]`, `[[planes]]`, `[[cones]]` and `[[tori]]`: each read, checked,
//! and placed by its own parameters when the placement does not turn it and keeps its kind
//! (a box scaled any way, a cone scaled evenly across, a disc or torus scaled evenly), else
//! under a transform, so that a turned shape's texture turns with it. A plane is always
//! placed by its own point and normal.

use super::placement::Placement;
use super::{Item, P3, V3, Validator};
use crate::limits;
use crate::messages::number;
use crate::scene::description::ShapeDesc;
use crate::scene::error::SceneError;
use glam::Vec3;
use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BoxDef {
    pub(super) name: Option<String>,
    min: P3,
    max: P3,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DiscDef {
    pub(super) name: Option<String>,
    center: P3,
    normal: V3,
    radius: f32,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PlaneDef {
    pub(super) name: Option<String>,
    point: P3,
    normal: V3,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ConeDef {
    pub(super) name: Option<String>,
    base: P3,
    radius: f32,
    top_radius: Option<f32>,
    height: f32,
    caps: Option<bool>,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TorusDef {
    pub(super) name: Option<String>,
    center: P3,
    major_radius: f32,
    minor_radius: f32,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

impl Validator<'_> {
    /// A unit normal from a non-zero finite vector.
    fn normal(&self, at: &Item, field: &str, v: V3) -> Result<Vec3, SceneError> {
        let v = self.point(at, field, v)?.as_dvec3();
        let length = v.length();
        if !(length > 0.0 && length.is_finite()) {
            return Err(self.field_error(
                at,
                field,
                format!("`{field}` must not be zero, got {:?}", v.to_array()),
            ));
        }
        Ok((v / length).as_vec3())
    }

    /// Refuses `what`, an extent (a box's side, a cone's or cylinder's height) of `extent`
    /// at `distance` from the camera, when single precision cannot resolve it there: one
    /// rule for every shape with such an extent.
    pub(super) fn resolvable(
        &self,
        at: &Item,
        field: &str,
        what: &str,
        extent: f32,
        distance: f32,
    ) -> Result<(), SceneError> {
        let least = distance * limits::MIN_RELATIVE_EXTENT;
        if extent >= least && extent > 0.0 {
            return Ok(());
        }
        Err(self.field_error(
            at,
            field,
            format!(
                "{what} is too thin to hold in single precision this far from the camera: \
                 {} across at a distance of {}; make it at least {} (2^-20 of the distance), \
                 or place the camera nearer",
                number(extent.max(0.0)),
                number(distance),
                number(least.max(f32::MIN_POSITIVE))
            ),
        ))
    }

    /// A length that may also be zero (a cone's point).
    fn length_or_zero(&self, at: &Item, field: &str, v: f32) -> Result<f32, SceneError> {
        if v == 0.0 {
            return Ok(0.0);
        }
        self.length(at, field, v)
    }

    pub(super) fn cuboid(
        &self,
        at: &Item,
        d: &BoxDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        for axis in 0..3 {
            // A NaN is left to the position check, which names it.
            if d.min[axis] >= d.max[axis] {
                let name = ["x", "y", "z"][axis];
                return Err(self.field_error(
                    at,
                    "max",
                    format!(
                        "a box needs `min` below `max` on every axis, got {} and {} on {name}",
                        d.min[axis], d.max[axis]
                    ),
                ));
            }
        }
        let axis_aligned = placement.keeps_axes();
        let (lo, hi) = if axis_aligned {
            (placement.point(d.min), placement.point(d.max))
        } else {
            (d.min, d.max)
        };
        let min = self.position(at, "min", lo)?;
        let max = self.position(at, "max", hi)?;
        let distance = min.abs().max(max.abs()).max_element();
        for axis in 0..3 {
            let name = ["x", "y", "z"][axis];
            let what = format!("the box along {name}");
            self.resolvable(at, "max", &what, max[axis] - min[axis], distance)?;
        }
        let cuboid = ShapeDesc::Cuboid { min, max };
        if axis_aligned {
            Ok(cuboid)
        } else {
            self.transformed(at, cuboid, placement)
        }
    }

    pub(super) fn disc(
        &self,
        at: &Item,
        d: &DiscDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let normal = self.normal(at, "normal", d.normal)?;
        match placement.uniform_scale() {
            Some(s) => Ok(ShapeDesc::Disc {
                center: self.position(at, "center", placement.point(d.center))?,
                normal,
                radius: self.length(at, "radius", (d.radius as f64 * s) as f32)?,
            }),
            None => {
                let disc = ShapeDesc::Disc {
                    center: self.position(at, "center", d.center)?,
                    normal,
                    radius: self.length(at, "radius", d.radius)?,
                };
                self.transformed(at, disc, placement)
            }
        }
    }

    pub(super) fn plane(
        &self,
        at: &Item,
        d: &PlaneDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let normal = self.normal(at, "normal", d.normal)?;
        Ok(ShapeDesc::Plane {
            point: self.position(at, "point", placement.point(d.point))?,
            normal: placement.turned_normal(normal),
        })
    }

    pub(super) fn cone(
        &self,
        at: &Item,
        d: &ConeDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let upright = placement.upright_scale();
        let (across, along) = upright.unwrap_or((1.0, 1.0));
        let base = if upright.is_some() {
            placement.point(d.base)
        } else {
            d.base
        };
        let radius = self.length_or_zero(at, "radius", (d.radius as f64 * across) as f32)?;
        let top = d.top_radius.unwrap_or(0.0);
        let top_radius = self.length_or_zero(at, "top_radius", (top as f64 * across) as f32)?;
        if radius == 0.0 && top_radius == 0.0 {
            return Err(self.field_error(
                at,
                "radius",
                "a cone needs a `radius` or a `top_radius` greater than zero",
            ));
        }
        let height = self.length(at, "height", (d.height as f64 * along) as f32)?;
        let mut top_point = base;
        top_point[1] += height as f64;
        let top = self.position(at, "height", top_point)?;
        let relative_base = self.position(at, "base", base)?;
        let distance = relative_base.abs().max(top.abs()).max_element();
        self.resolvable(
            at,
            "height",
            "the cone's height",
            top.y - relative_base.y,
            distance,
        )?;
        let cone = ShapeDesc::Cone {
            base: relative_base,
            radius,
            top_radius,
            height,
            caps: d.caps.unwrap_or(true),
        };
        match upright {
            Some(_) => Ok(cone),
            None => self.transformed(at, cone, placement),
        }
    }

    pub(super) fn torus(
        &self,
        at: &Item,
        d: &TorusDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let direct = placement.uniform_scale().is_some();
        let s = placement.uniform_scale().unwrap_or(1.0);
        let major_radius = self.length(at, "major_radius", (d.major_radius as f64 * s) as f32)?;
        let minor_radius = self.length(at, "minor_radius", (d.minor_radius as f64 * s) as f32)?;
        if minor_radius >= major_radius {
            return Err(self.field_error(
                at,
                "minor_radius",
                format!(
                    "a torus needs `minor_radius` below `major_radius` (else it has no hole \
                     and passes through itself), got {} and {}",
                    number(d.minor_radius),
                    number(d.major_radius)
                ),
            ));
        }
        let center = if direct {
            placement.point(d.center)
        } else {
            d.center
        };
        let torus = ShapeDesc::Torus {
            center: self.position(at, "center", center)?,
            major_radius,
            minor_radius,
        };
        if direct {
            Ok(torus)
        } else {
            self.transformed(at, torus, placement)
        }
    }
}

impl Placement {
    /// A unit normal, carried by the placement (by its inverse transpose, so it stays
    /// perpendicular to a surface scaled unevenly).
    pub(super) fn turned_normal(&self, n: Vec3) -> Vec3 {
        let carried = self.normal_matrix() * n.as_dvec3();
        (carried / carried.length()).as_vec3()
    }
}
