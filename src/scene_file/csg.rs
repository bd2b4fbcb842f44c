//! `[[csg]]`: closed solids combined (`union`, `intersection`, `difference`, `merge`), each
//! member a table of its own (`[[csg.members]]`) with a `type` and that shape's fields,
//! placed by its own `translate`, `rotate` and `scale` and then by the whole's. Members may
//! be combinations themselves, and may name a `material` of their own for their part of the
//! surface. Shapes with no inside (discs, polygons, triangles, open tubes
//! and cones, meshes) are refused; a plane is the half of space behind it.

use super::entry_def::EntryDef;
use super::error::SceneError;
use super::placement::Placement;
use super::shapes::{BoxDef, CapsuleDef, ConeDef, CylinderDef, PlaneDef, SphereDef, TorusDef};
use super::validator::{Item, P3, V3, Validator};
use crate::accel::CsgOperation;
use crate::appearance::Material;
use crate::geometry::Transform;
use crate::limits;
use crate::messages::{did_you_mean, quoted};
use crate::scene::{CsgMember, ShapeDesc};
use serde::Deserialize;
use serde::de::DeserializeOwned;
use toml::Spanned;

/// A `[[csg]]` entry, its members' tables as read with their place in the file; a
/// combination nested in a member is read from its table, where places are not kept
/// (`NestedCsgDef`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CsgDef<M = Spanned<toml::Table>> {
    pub(super) name: Option<String>,
    operation: String,
    members: Vec<M>,
    pub(super) material: Option<String>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

/// A combination nested as a member.
pub(super) type NestedCsgDef = CsgDef<toml::Table>;

/// A member's table, and where it is in the file when that is known.
trait MemberTable {
    fn fields(&self) -> &toml::Table;
    fn span(&self) -> Option<std::ops::Range<usize>>;
}

impl MemberTable for Spanned<toml::Table> {
    fn fields(&self) -> &toml::Table {
        self.get_ref()
    }
    fn span(&self) -> Option<std::ops::Range<usize>> {
        Some(Spanned::span(self))
    }
}

impl MemberTable for toml::Table {
    fn fields(&self) -> &toml::Table {
        self
    }
    fn span(&self) -> Option<std::ops::Range<usize>> {
        None
    }
}

/// The kinds a member may be, by its `type`.
const MEMBER_TYPES: [&str; 8] = [
    "sphere", "box", "cylinder", "cone", "torus", "capsule", "plane", "csg",
];

/// Kinds that bound no inside, and why each cannot be a member.
const NOT_SOLID: [(&str, &str); 5] = [
    ("disc", "a disc is flat: it has no inside"),
    ("polygon", "a polygon is flat: it has no inside"),
    ("triangle", "a triangle is flat: it has no inside"),
    (
        "tetrahedron",
        "a tetrahedron cannot be a member yet (a box, turned, often serves)",
    ),
    (
        "mesh",
        "a mesh cannot be a member: prism cannot tell its inside",
    ),
];

impl Validator<'_> {
    /// A `[[csg]]` entry, placed.
    pub(super) fn csg(
        &self,
        at: &Item,
        d: &CsgDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let mut leaves = 0;
        self.combination(at, d, placement, 1, &mut leaves)
    }

    /// Combination `d` at nesting `depth`, its members' shapes placed by their own
    /// placement and then by `outer`; `leaves` counts the solids read so far.
    fn combination<M: MemberTable>(
        &self,
        at: &Item,
        d: &CsgDef<M>,
        outer: &Placement,
        depth: usize,
        leaves: &mut usize,
    ) -> Result<ShapeDesc, SceneError> {
        if depth > limits::MAX_CSG_DEPTH {
            return Err(self.error(
                at,
                format!("combinations nest at most {} deep", limits::MAX_CSG_DEPTH),
            ));
        }
        let operation = CsgOperation::named(&d.operation).ok_or_else(|| {
            let hint = did_you_mean(&d.operation, CsgOperation::NAMES);
            self.field_error(
                at,
                "operation",
                format!(
                    "no operation {}{hint}: one of union, intersection, difference, merge",
                    quoted(&d.operation)
                ),
            )
        })?;
        if d.members.len() < 2 {
            return Err(self.field_error(
                at,
                "members",
                format!(
                    "a combination needs two or more members, got {} (each a \
                     `[[csg.members]]` table)",
                    d.members.len()
                ),
            ));
        }
        let outer = outer_transform(self, at, outer)?;
        let mut members = Vec::with_capacity(d.members.len());
        for (i, member) in d.members.iter().enumerate() {
            let label = format!("{} members[{i}]", at.name);
            // A nested combination's members are found at the combination's table.
            let at = Item {
                span: member.span().unwrap_or_else(|| at.span.clone()),
                name: &label,
            };
            // A union at the top is traced as its members, each a combination of its own.
            let mut own = 0;
            let counted = if depth == 1 && operation == CsgOperation::Union {
                &mut own
            } else {
                &mut *leaves
            };
            let shape = self.member(&at, member.fields(), depth, counted)?;
            let material = self.member_material(&at, member.fields())?;
            let shape = match &outer {
                Some(t) => placed_by(shape, t).ok_or_else(|| {
                    self.field_error(&at, "scale", "the placement cannot be inverted")
                })?,
                None => shape,
            };
            members.push(CsgMember { shape, material });
        }
        let csg = ShapeDesc::Csg { operation, members };
        self.within_reach(at, "combination", &csg.bounds())?;
        Ok(csg)
    }

    /// One member, placed by its own placement.
    fn member(
        &self,
        at: &Item,
        table: &toml::Table,
        depth: usize,
        leaves: &mut usize,
    ) -> Result<ShapeDesc, SceneError> {
        let kind = match table.get("type") {
            Some(toml::Value::String(s)) => s.as_str(),
            Some(_) => return Err(self.field_error(at, "type", "`type` must be a string")),
            None => {
                return Err(self.error(
                    at,
                    "a member needs a `type`: sphere, box, cylinder, cone, torus, capsule, \
                     plane or csg",
                ));
            }
        };
        if let Some((_, why)) = NOT_SOLID.iter().find(|(k, _)| *k == kind) {
            return Err(self.field_error(
                at,
                "type",
                format!("{why}; a member must be a closed solid"),
            ));
        }
        if !MEMBER_TYPES.contains(&kind) {
            let hint = did_you_mean(kind, MEMBER_TYPES);
            return Err(self.field_error(
                at,
                "type",
                format!("no member type {}{hint}", quoted(kind)),
            ));
        }
        for (field, why) in [
            ("name", "a member has no name of its own: name the whole"),
            ("shadow", "the whole casts a shadow or does not"),
            (
                "group",
                "a member is placed in the whole's frame: give the whole a group",
            ),
        ] {
            if table.contains_key(field) {
                return Err(self.field_error(at, field, format!("`{field}` in a member: {why}")));
            }
        }
        if kind != "csg" {
            *leaves += 1;
            if *leaves > limits::MAX_CSG_MEMBERS {
                return Err(self.error(
                    at,
                    format!(
                        "a combination holds at most {} solids, nested ones included (a \
                         union at the top counts each member apart)",
                        limits::MAX_CSG_MEMBERS
                    ),
                ));
            }
        }
        let mut fields = table.clone();
        fields.remove("type");
        match kind {
            "sphere" => {
                self.placed_member(at, fields, |at, d: &SphereDef, p| self.sphere(at, d, p))
            }
            "box" => self.placed_member(at, fields, |at, d: &BoxDef, p| self.cuboid(at, d, p)),
            "cylinder" => self.placed_member(at, fields, |at, d: &CylinderDef, p| {
                self.closed(at, d.caps, "an open tube")?;
                self.cylinder(at, d, p)
            }),
            "cone" => self.placed_member(at, fields, |at, d: &ConeDef, p| {
                self.closed(at, d.caps, "an open cone")?;
                self.cone(at, d, p)
            }),
            "torus" => self.placed_member(at, fields, |at, d: &TorusDef, p| self.torus(at, d, p)),
            "capsule" => {
                self.placed_member(at, fields, |at, d: &CapsuleDef, p| self.capsule(at, d, p))
            }
            "plane" => self.placed_member(at, fields, |at, d: &PlaneDef, p| self.plane(at, d, p)),
            _ => self.placed_member(at, fields, |at, d: &NestedCsgDef, p| {
                self.combination(at, d, p, depth + 1, leaves)
            }),
        }
    }

    /// A member's fields read as the entry `D` and made into a shape by `read` under the
    /// member's own placement.
    fn placed_member<D: DeserializeOwned + EntryDef>(
        &self,
        at: &Item,
        fields: toml::Table,
        read: impl FnOnce(&Item, &D, &Placement) -> Result<ShapeDesc, SceneError>,
    ) -> Result<ShapeDesc, SceneError> {
        let d: D = toml::Value::Table(fields)
            .try_into()
            .map_err(|e: toml::de::Error| {
                self.error(at, crate::messages::plain_type_words(e.message()))
            })?;
        let placement = self.placement(at, &d)?;
        read(at, &d, &placement)
    }

    /// A member's own `material`, found in the file's `[materials]`; None without one (or
    /// when the entry is placed again for an edit, which keeps its members' materials).
    fn member_material(
        &self,
        at: &Item,
        table: &toml::Table,
    ) -> Result<Option<Material>, SceneError> {
        let name = match table.get("material") {
            None => return Ok(None),
            Some(toml::Value::String(name)) => name,
            Some(_) => {
                return Err(self.field_error(at, "material", "`material` must be a string"));
            }
        };
        let Some(materials) = self.materials.get() else {
            return Ok(None);
        };
        match materials.get(name) {
            Some(m) => Ok(Some(m.clone())),
            None => Err(self.field_error(
                at,
                "material",
                format!(
                    "no material named {} (see [materials]){}",
                    quoted(name),
                    did_you_mean(name, materials.keys().map(String::as_str))
                ),
            )),
        }
    }

    /// That a cylinder or cone member is closed (`caps` is not false).
    fn closed(&self, at: &Item, caps: Option<bool>, what: &str) -> Result<(), SceneError> {
        if caps == Some(false) {
            return Err(self.field_error(
                at,
                "caps",
                format!("{what} has no inside; a member must be a closed solid"),
            ));
        }
        Ok(())
    }
}

/// The whole's placement as a transform of its members (None when it moves nothing).
fn outer_transform(
    v: &Validator,
    at: &Item,
    placement: &Placement,
) -> Result<Option<Transform>, SceneError> {
    if placement.is_identity() {
        return Ok(None);
    }
    match placement.relative(v.origin) {
        Some(t) => Ok(Some(t)),
        None => Err(v.field_error(at, "scale", "the placement cannot be inverted")),
    }
}

/// Member `shape` (relative to the scene's origin) moved by `t`, which maps positions
/// relative to the origin to where the whole's placement puts them; None when the two
/// transforms together cannot be inverted in single precision.
fn placed_by(shape: ShapeDesc, t: &Transform) -> Option<ShapeDesc> {
    Some(match shape {
        ShapeDesc::Plane { point, normal } => ShapeDesc::Plane {
            point: t.to_scene().transform_point3(point),
            normal: t.normal_to_scene(normal.into()).into(),
        },
        ShapeDesc::Transformed { shape, transform } => ShapeDesc::Transformed {
            shape,
            transform: transform.then(t.to_scene())?,
        },
        ShapeDesc::Csg { operation, members } => ShapeDesc::Csg {
            operation,
            members: members
                .into_iter()
                .map(|m| {
                    Some(CsgMember {
                        shape: placed_by(m.shape, t)?,
                        material: m.material,
                    })
                })
                .collect::<Option<_>>()?,
        },
        solid => ShapeDesc::Transformed {
            shape: Box::new(solid),
            transform: *t,
        },
    })
}
