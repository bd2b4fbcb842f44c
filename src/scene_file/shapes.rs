//! Every shape's table: `[[spheres]]`, `[[cylinders]]`, `[[polygons]]`, `[[triangles]]` and
//! `[[tetrahedra]]`, given by their points, and `[[boxes]]`, `[[discs]]`, `[[planes]]`,
//! `[[cones]]` and `[[tori]]`, each read, checked for what single precision can hold, and
//! placed by its own parameters when the placement does not turn it and keeps its kind (a
//! box scaled any way, a cone scaled evenly across, a disc or torus scaled evenly), else
//! under a transform, so that a turned shape's texture turns with it. A plane is always
//! placed by its own point and normal.

use super::error::SceneError;
use super::fixed_array::Fixed;
use super::placement::Placement;
use super::validator::{Item, P3, V3, Validator};
use crate::limits;
use crate::messages::number;
use crate::scene::ShapeDesc;
use glam::Vec3;
use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SphereDef {
    pub(super) name: Option<String>,
    pub(super) center: P3,
    pub(super) radius: f32,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CylinderDef {
    pub(super) name: Option<String>,
    pub(super) base: P3,
    pub(super) radius: f32,
    pub(super) height: f32,
    pub(super) caps: Option<bool>,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CapsuleDef {
    pub(super) name: Option<String>,
    pub(super) base: P3,
    pub(super) radius: f32,
    pub(super) height: f32,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PolygonDef {
    pub(super) name: Option<String>,
    pub(super) vertices: Vec<P3>,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TriangleDef {
    pub(super) name: Option<String>,
    pub(super) vertices: Fixed<P3, 3>,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TetrahedronDef {
    pub(super) name: Option<String>,
    pub(super) vertices: Fixed<P3, 4>,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

impl Validator<'_> {
    /// A `[[spheres]]` entry, placed.
    pub(super) fn sphere(
        &self,
        at: &Item,
        d: &SphereDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        match placement.uniform_scale() {
            Some(s) => Ok(ShapeDesc::Sphere {
                center: self.position(at, "center", placement.point(d.center))?,
                radius: self.length(at, "radius", (d.radius as f64 * s) as f32)?,
            }),
            None => {
                let sphere = ShapeDesc::Sphere {
                    center: self.position(at, "center", d.center)?,
                    radius: self.length(at, "radius", d.radius)?,
                };
                self.transformed(at, sphere, placement)
            }
        }
    }

    /// A `[[cylinders]]` entry, placed.
    pub(super) fn cylinder(
        &self,
        at: &Item,
        d: &CylinderDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let upright = placement.upright_scale();
        let (a, b) = upright.unwrap_or((1.0, 1.0));
        let base = if upright.is_some() {
            placement.point(d.base)
        } else {
            d.base
        };
        let (relative_base, height) =
            self.upright_axis(at, base, d.height as f64 * b, "the cylinder's height")?;
        let cylinder = ShapeDesc::Cylinder {
            base: relative_base,
            radius: self.length(at, "radius", (d.radius as f64 * a) as f32)?,
            height,
            caps: d.caps.unwrap_or(true),
        };
        match upright {
            Some(_) => Ok(cylinder),
            None => self.transformed(at, cylinder, placement),
        }
    }

    /// An upright shape's axis from `base` up `height` (`what` names it in messages): the
    /// base relative to the scene's origin and the height, checked as lengths and positions
    /// (the top end is a position too) and as an extent single precision resolves there.
    fn upright_axis(
        &self,
        at: &Item,
        base: P3,
        height: f64,
        what: &str,
    ) -> Result<(Vec3, f32), SceneError> {
        let relative_base = self.position(at, "base", base)?;
        let height = self.length(at, "height", height as f32)?;
        let mut top = base;
        top[1] += height as f64;
        let top = self.position(at, "height", top)?;
        let distance = relative_base.abs().max(top.abs()).max_element();
        let extent = top.y - relative_base.y;
        self.resolvable(at, "height", what, extent, distance)?;
        Ok((relative_base, height))
    }

    /// A `[[capsules]]` entry, placed: by its own parameters while it stays upright and is
    /// scaled evenly (its ends stay hemispheres), else under a transform.
    pub(super) fn capsule(
        &self,
        at: &Item,
        d: &CapsuleDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let even = placement.upright_scale().filter(|(a, b)| a == b);
        let s = even.map_or(1.0, |(a, _)| a);
        let base = if even.is_some() {
            placement.point(d.base)
        } else {
            d.base
        };
        let (relative_base, height) =
            self.upright_axis(at, base, d.height as f64 * s, "the capsule's height")?;
        let capsule = ShapeDesc::Capsule {
            base: relative_base,
            radius: self.length(at, "radius", (d.radius as f64 * s) as f32)?,
            height,
        };
        match even {
            Some(_) => Ok(capsule),
            None => self.transformed(at, capsule, placement),
        }
    }

    /// A `[[polygons]]` entry, placed.
    pub(super) fn polygon(
        &self,
        at: &Item,
        d: &PolygonDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let placed: Vec<P3> = d.vertices.iter().map(|&v| placement.point(v)).collect();
        let vertices = self.flat_corners(at, &placed)?;
        Ok(ShapeDesc::Polygon { vertices })
    }

    /// A `[[triangles]]` entry, placed.
    pub(super) fn triangle(
        &self,
        at: &Item,
        d: &TriangleDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let v = self.flat_corners(at, &d.vertices.map(|v| placement.point(v)))?;
        Ok(ShapeDesc::Triangle {
            vertices: [v[0], v[1], v[2]],
        })
    }

    /// A `[[tetrahedra]]` entry, placed.
    pub(super) fn tetrahedron(
        &self,
        at: &Item,
        d: &TetrahedronDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let v = self.vertices(at, &d.vertices.map(|v| placement.point(v)))?;
        if !has_volume(&v) {
            return Err(self.field_error(
                at,
                "vertices",
                "the four vertices lie in one plane (no volume)",
            ));
        }
        let faces = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];
        if !faces
            .iter()
            .all(|&[a, b, c]| representable(v[a], v[b], v[c]))
        {
            return Err(self.field_error(at, "vertices", TOO_SMALL));
        }
        Ok(ShapeDesc::Tetrahedron {
            vertices: [v[0], v[1], v[2], v[3]],
        })
    }

    /// `shape` (relative to the scene's origin) under `placement`, when its own parameters
    /// cannot express it; it must stay within `MAX_COORDINATE` of the camera.
    pub(super) fn transformed(
        &self,
        at: &Item,
        shape: ShapeDesc,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let Some(transform) = placement.relative(self.origin) else {
            return Err(self.field_error(at, "scale", "the placement cannot be inverted"));
        };
        self.within_reach(at, "shape", &transform.bounds_to_scene(&shape.bounds()))?;
        Ok(ShapeDesc::Transformed {
            shape: Box::new(shape),
            transform,
        })
    }

    /// That `what`, placed within `bounds`, lies within the coordinate limit of the camera
    /// (the placement's `scale` took it there, or its turn and move).
    pub(super) fn within_reach(
        &self,
        at: &Item,
        what: &str,
        bounds: &crate::geometry::Aabb,
    ) -> Result<(), SceneError> {
        let reach = bounds.min.abs().max(bounds.max.abs()).max_element() as f64;
        if reach.is_nan() || reach > limits::MAX_COORDINATE {
            return Err(self.field_error(
                at,
                "scale",
                format!(
                    "the {what}, placed, reaches {reach:e} from the camera, more than {:e}",
                    limits::MAX_COORDINATE
                ),
            ));
        }
        Ok(())
    }

    /// The corners of a flat convex shape (a polygon or a triangle), checked as one.
    pub(super) fn flat_corners(&self, at: &Item, vs: &[P3]) -> Result<Vec<Vec3>, SceneError> {
        let vertices = self.vertices(at, vs)?;
        check_polygon(&vertices).map_err(|m| self.field_error(at, "vertices", m))?;
        Ok(vertices)
    }

    pub(super) fn vertices(&self, at: &Item, vs: &[P3]) -> Result<Vec<Vec3>, SceneError> {
        vs.iter()
            .enumerate()
            .map(|(i, &v)| self.position(at, &format!("vertices[{i}]"), v))
            .collect()
    }
}

/// The points moved to their first and scaled by their largest extent along any axis, in
/// f64: the checks below then use tolerances relative to the shape's own size, whatever its
/// scale or distance.
pub(super) fn normalized(v: &[Vec3]) -> Vec<glam::DVec3> {
    let b = crate::geometry::Aabb::from_points(v);
    let extent = (b.max.as_dvec3() - b.min.as_dvec3()).max_element();
    let scale = if extent > 0.0 { 1.0 / extent } else { 0.0 };
    v.iter()
        .map(|p| (p.as_dvec3() - v[0].as_dvec3()) * scale)
        .collect()
}

/// Whether four corners enclose a volume: beyond the rounding of f32 vertices (relative to
/// the tetrahedron's extent, so at any scale).
pub(super) fn has_volume(v: &[Vec3]) -> bool {
    let p = normalized(v);
    let volume6 = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]).abs();
    volume6 > 1e-5
}

/// Why these corners do not make a planar convex polygon, if they do not. Tolerances are
/// relative to the polygon's extent, and a corner counts as straight when its vertex lies
/// within that tolerance of its neighbours' line, so a regular polygon of many sides passes
/// at any scale.
pub fn check_polygon(vertices: &[Vec3]) -> Result<(), String> {
    if vertices.len() < 3 {
        return Err(format!(
            "a polygon needs at least 3 vertices, got {}",
            vertices.len()
        ));
    }
    let v = normalized(vertices);
    let n = v.len();
    // f32 vertices are rounded to about 6e-8 of their extent; these are well beyond that.
    const COINCIDENT: f64 = 1e-6;
    for i in 0..n {
        let j = (i + 1) % n;
        if (v[j] - v[i]).length() <= COINCIDENT {
            return Err(format!("vertices {i} and {j} coincide"));
        }
    }
    // Newell's normal: robust for any planar polygon, and its length is twice the area.
    let mut normal = glam::DVec3::ZERO;
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        normal += glam::DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    let area2 = normal.length();
    if area2.is_nan() || area2 <= 1e-6 {
        return Err("the vertices are collinear (the polygon has no area)".into());
    }
    let normal = normal / area2;
    for (i, p) in v.iter().enumerate() {
        if (*p - v[0]).dot(normal).abs() > 1e-4 {
            return Err(format!("vertex {i} is not in the plane of the others"));
        }
    }
    for i in 0..n {
        let (a, b, c) = (v[i], v[(i + 1) % n], v[(i + 2) % n]);
        let (e1, e2) = (b - a, c - b);
        let turn = e1.cross(e2);
        // About the distance of the middle vertex from the line through the other two.
        if turn.length() <= COINCIDENT * e1.length().max(e2.length()) {
            return Err(format!(
                "vertices {i}, {}, {} are collinear",
                (i + 1) % n,
                (i + 2) % n
            ));
        }
        if turn.dot(normal) < 0.0 {
            return Err(format!(
                "the polygon is not convex at vertex {}",
                (i + 1) % n
            ));
        }
    }
    // What the tracer builds from it, in f32: the fan of triangles and the plane's normal.
    let fan_ok = (1..n - 1).all(|i| representable(vertices[0], vertices[i], vertices[i + 1]));
    let normal_ok = crate::numerics::try_normalize(
        (vertices[1] - vertices[0]).cross(vertices[2] - vertices[1]),
    )
    .is_some();
    if !(fan_ok && normal_ok) {
        return Err(TOO_SMALL.into());
    }
    Ok(())
}

pub(super) const TOO_SMALL: &str = "the shape is too small for f32: its edges' cross products underflow \
                         (scale the scene up)";

/// Whether f32 can hold the triangle the tracer builds from these corners (a normal of
/// non-zero length).
pub(super) fn representable(a: Vec3, b: Vec3, c: Vec3) -> bool {
    crate::geometry::Triangle::new(a, b, c).is_some()
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BoxDef {
    pub(super) name: Option<String>,
    min: P3,
    max: P3,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
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
    /// The group it is placed in.
    pub(super) group: Option<String>,
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
    /// The group it is placed in.
    pub(super) group: Option<String>,
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
    pub(super) caps: Option<bool>,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
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
    /// The group it is placed in.
    pub(super) group: Option<String>,
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
