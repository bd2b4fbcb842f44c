//! A validated scene: what is where, made of what. Every value here has passed the checks
//! of the scene file loader, so preparing a `Scene` cannot fail.

use super::group::{SceneGroup, group_chain, group_frame};
use super::placement::ObjectPlacement;
use crate::accel::CsgOperation;
use crate::appearance::Material;
use crate::appearance::{Background, Fog, Light};
use crate::camera::Camera;
use crate::geometry::{
    Aabb, Capsule, Cone, Cuboid, Cylinder, Disc, Mesh, Shape, Sphere, Torus, Transform,
};
use glam::{Affine3A, DAffine3, DMat3, DVec3, Quat, Vec3};
use std::sync::Arc;

/// Every position in a `Scene` (camera, lights, shapes) is relative to `origin`, which is
/// kept in f64: world position = origin + position. The loader puts the origin at the
/// camera's eye, so f32 keeps its full precision around the viewer however far from the
/// world's origin the scene sits (camera-relative rendering).
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The world position of the frame every other position is relative to.
    pub origin: DVec3,
    /// The view.
    pub camera: Camera,
    /// The image settings the file suggests.
    pub render: RenderDefaults,
    /// What a ray that leaves the scene sees.
    pub background: Background,
    /// Ambient light, multiplied by each material's `ambient` factor and colour.
    pub ambient: Vec3,
    /// The lights.
    pub lights: Vec<Light>,
    /// Fog filling the scene, if any.
    pub fog: Option<Fog>,
    /// The objects, in the file's order.
    pub objects: Vec<SceneObject>,
    /// The groups objects and lights are placed in, each after its parent.
    pub groups: Vec<SceneGroup>,
}

/// Image settings a scene file may suggest; the command line overrides them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderDefaults {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Anti-aliasing level N (N×N subsamples per pixel).
    pub aa: u32,
    /// The most secondary bounces (reflection or refraction) along one path.
    pub max_depth: u32,
    /// Subsamples per pixel when a scene asks for more (or fewer) than the N×N grid:
    /// soft shadows, depth of field and glossy reflection converge with more.
    pub samples: Option<u32>,
    /// How the image's linear colours are stored in a file (`encoding`, `exposure`).
    pub encoding: crate::color::Encoding,
    /// Which light transport the scene is rendered with.
    pub integrator: crate::integrator::kind::IntegratorKind,
}

impl Default for RenderDefaults {
    fn default() -> Self {
        Self {
            width: 800,
            height: 600,
            aa: 2,
            max_depth: 5,
            samples: None,
            encoding: crate::color::Encoding::default(),
            integrator: crate::integrator::kind::IntegratorKind::Whitted,
        }
    }
}

/// One object: a named shape of one material.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneObject {
    /// The name the file gives it (or one made from its table and index).
    pub name: String,
    /// Its shape.
    pub shape: ShapeDesc,
    /// What it is made of.
    pub material: Material,
    /// Whether it blocks light on its way to other surfaces (false: a lamp's bulb that
    /// does not shadow its own light). Its own surface is shaded either way.
    pub casts_shadow: bool,
    /// How its entry in the scene file places it (`shape` is already placed): what an
    /// editor shows and changes, and what a save writes back. In its group's frame.
    pub placement: ObjectPlacement,
    /// The group it is placed in (an index into `Scene::groups`); None for the world.
    pub group: Option<usize>,
    /// For a part of a glTF file, the node it hangs from (a `GroupKind::FileNode` group,
    /// whose chain of parents ends at the file's frame); None otherwise.
    pub node: Option<usize>,
}

/// Every kind of shape a scene file describes (a closed set).
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeDesc {
    /// A sphere.
    Sphere {
        /// Its centre.
        center: Vec3,
        /// Its radius.
        radius: f32,
    },
    /// Along +y from the centre of its bottom cap, closed at both ends or open.
    Cylinder {
        /// The centre of its bottom cap.
        base: Vec3,
        /// Its radius.
        radius: f32,
        /// Its height.
        height: f32,
        /// Whether both ends are closed.
        caps: bool,
    },
    /// Along +y: the points within `radius` of the segment from `base` up `height` (a
    /// side closed by hemispheres).
    Capsule {
        /// The centre of its bottom hemisphere.
        base: Vec3,
        /// Its radius.
        radius: f32,
        /// The length of its axis segment.
        height: f32,
    },
    /// A solid axis-aligned box.
    Cuboid {
        /// Its corner with the smallest coordinates.
        min: Vec3,
        /// Its corner with the largest coordinates.
        max: Vec3,
    },
    /// A flat disc.
    Disc {
        /// Its centre.
        center: Vec3,
        /// Its front's unit normal.
        normal: Vec3,
        /// Its radius.
        radius: f32,
    },
    /// An infinite plane.
    Plane {
        /// A point on it.
        point: Vec3,
        /// Its front's unit normal.
        normal: Vec3,
    },
    /// Along +y from the centre of its base: a cone, or a frustum with a top radius.
    Cone {
        /// The centre of its base.
        base: Vec3,
        /// The radius at its base.
        radius: f32,
        /// The radius at its top (0 for a point).
        top_radius: f32,
        /// Its height.
        height: f32,
        /// Whether its base and top are closed.
        caps: bool,
    },
    /// A torus about an axis along +y.
    Torus {
        /// Its centre.
        center: Vec3,
        /// From the centre to the middle of the tube.
        major_radius: f32,
        /// The tube's radius.
        minor_radius: f32,
    },
    /// A planar convex polygon, corners in order.
    Polygon {
        /// At least three corners.
        vertices: Vec<Vec3>,
    },
    /// A triangle.
    Triangle {
        /// Its corners, in winding order.
        vertices: [Vec3; 3],
    },
    /// Four corners; the faces are oriented outwards whatever their order.
    Tetrahedron {
        /// Its corners.
        vertices: [Vec3; 4],
    },
    /// A triangle mesh in its own space, placed by `transform`. Objects that share one
    /// `Arc` (one file's mesh, placed many times) share its hierarchy too.
    Mesh {
        /// The mesh (smooth or faceted as the file asked).
        mesh: Arc<Mesh>,
        /// From the mesh's space to the scene's.
        transform: Transform,
    },
    /// Closed solids combined (POV-Ray's CSG), each member placed in the scene's space: a
    /// sphere, a capped cylinder or cone, a box, a torus, a capsule, a plane (the half of
    /// space behind it), one of those transformed, or another combination.
    Csg {
        /// How the members combine.
        operation: CsgOperation,
        /// Two or more members.
        members: Vec<CsgMember>,
    },
    /// A shape in its own space under a transform its own parameters cannot express (a
    /// sphere scaled unevenly into an ellipsoid, a tilted cylinder).
    Transformed {
        /// The shape, in its own space: any but a polygon, triangle, tetrahedron, plane or
        /// mesh (which are placed point by point).
        shape: Box<ShapeDesc>,
        /// From the shape's space to the scene's.
        transform: Transform,
    },
}

/// A member of a CSG combination: its shape (placed in the scene's space) and the material
/// its surface takes, when it gives one of its own.
#[derive(Clone, Debug, PartialEq)]
pub struct CsgMember {
    /// The shape: a closed solid, a plane, a transformed solid or a combination.
    pub shape: ShapeDesc,
    /// Its own material: for its surface, or a combination's for its members that give
    /// none. None takes the enclosing combination's (at the top, the object's).
    pub material: Option<Material>,
}

impl ShapeDesc {
    /// Visits a combination's solids in its tree's order (the order its hits number them),
    /// each with the material its surface takes: its own, or the nearest enclosing
    /// member's; None where that is the object's own. Nothing for any other shape.
    pub fn csg_leaves<'s>(&'s self, visit: &mut impl FnMut(&'s ShapeDesc, Option<&'s Material>)) {
        fn walk<'s>(
            members: &'s [CsgMember],
            inherited: Option<&'s Material>,
            visit: &mut impl FnMut(&'s ShapeDesc, Option<&'s Material>),
        ) {
            for member in members {
                let material = member.material.as_ref().or(inherited);
                match &member.shape {
                    ShapeDesc::Csg { members, .. } => walk(members, material, visit),
                    leaf => visit(leaf, material),
                }
            }
        }
        if let ShapeDesc::Csg { members, .. } = self {
            walk(members, None, visit);
        }
    }

    /// Gives a combination's members the materials of `old`'s (the same combination,
    /// placed elsewhere), member by member; nothing for any other shape.
    pub fn keep_member_materials(&mut self, old: &ShapeDesc) {
        if let (ShapeDesc::Csg { members, .. }, ShapeDesc::Csg { members: was, .. }) = (self, old) {
            for (member, old) in members.iter_mut().zip(was) {
                member.material = old.material.clone();
                member.shape.keep_member_materials(&old.shape);
            }
        }
    }

    /// The object's own origin, to which procedural textures are attached.
    pub fn origin(&self) -> Vec3 {
        match self {
            ShapeDesc::Sphere { center, .. } => *center,
            ShapeDesc::Cylinder { base, .. }
            | ShapeDesc::Cone { base, .. }
            | ShapeDesc::Capsule { base, .. } => *base,
            ShapeDesc::Cuboid { min, .. } => *min,
            ShapeDesc::Disc { center, .. } | ShapeDesc::Torus { center, .. } => *center,
            ShapeDesc::Plane { point, .. } => *point,
            ShapeDesc::Polygon { vertices } => vertices[0],
            ShapeDesc::Triangle { vertices } => vertices[0],
            ShapeDesc::Tetrahedron { vertices } => vertices.iter().sum::<Vec3>() / 4.0,
            // A mesh's file has its own origin; a transformed shape's is where its own
            // origin is placed.
            ShapeDesc::Mesh { transform, .. } => transform.to_scene().translation.into(),
            ShapeDesc::Transformed { shape, transform } => {
                transform.to_scene().transform_point3(shape.origin())
            }
            ShapeDesc::Csg { members, .. } => members[0].shape.origin(),
        }
    }

    /// The one shape it is by its own parameters, in the scene's space (or in its own,
    /// under a `Transformed`'s transform); None for a shape made of several (a polygon, a
    /// tetrahedron), for a plane (traced as a disc sized to the scene, geometry.rs) and for
    /// a mesh or a transformed shape.
    pub fn solid(&self) -> Option<Shape> {
        Some(match *self {
            ShapeDesc::Sphere { center, radius } => Shape::Sphere(Sphere::new(center, radius)),
            ShapeDesc::Cylinder {
                base,
                radius,
                height,
                caps,
            } => Shape::Cylinder(Cylinder::new(base, radius, height).with_caps(caps)),
            ShapeDesc::Capsule {
                base,
                radius,
                height,
            } => Shape::Capsule(Capsule::new(base, radius, height)),
            ShapeDesc::Cuboid { min, max } => Shape::Cuboid(Cuboid::new(min, max)),
            ShapeDesc::Disc {
                center,
                normal,
                radius,
            } => Shape::Disc(Disc::new(center, normal, radius)),
            ShapeDesc::Cone {
                base,
                radius,
                top_radius,
                height,
                caps,
            } => Shape::Cone(Cone {
                base,
                radius,
                top_radius,
                height,
                caps,
            }),
            ShapeDesc::Torus {
                center,
                major_radius,
                minor_radius,
            } => Shape::Torus(Torus {
                center,
                major_radius,
                minor_radius,
            }),
            _ => return None,
        })
    }

    /// The box around the shape, from its description alone (nothing is prepared). A plane,
    /// having none, gives the box around its point.
    pub fn bounds(&self) -> Aabb {
        let around = |points: &[Vec3]| Aabb {
            min: points.iter().copied().fold(Vec3::INFINITY, Vec3::min),
            max: points.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max),
        };
        match self {
            ShapeDesc::Plane { point, .. } => around(&[*point]),
            ShapeDesc::Polygon { vertices } => around(vertices),
            ShapeDesc::Triangle { vertices } => around(vertices),
            ShapeDesc::Tetrahedron { vertices } => around(vertices),
            ShapeDesc::Mesh { mesh, transform } => transform.bounds_to_scene(&mesh.bounds()),
            ShapeDesc::Transformed { shape, transform } => {
                transform.bounds_to_scene(&shape.bounds())
            }
            ShapeDesc::Csg { operation, members } => {
                let mut boxes = members.iter().map(|m| m.shape.bounds());
                match operation {
                    CsgOperation::Union | CsgOperation::Merge => {
                        boxes.fold(Aabb::EMPTY, |a, b| a.union(b))
                    }
                    CsgOperation::Difference => boxes.next().unwrap_or(Aabb::EMPTY),
                    // Within every member's box; a plane's (its point's) bounds nothing.
                    CsgOperation::Intersection => members
                        .iter()
                        .filter(|m| !matches!(m.shape, ShapeDesc::Plane { .. }))
                        .map(|m| m.shape.bounds())
                        .reduce(|a, b| Aabb {
                            min: a.min.max(b.min),
                            max: a.max.min(b.max),
                        })
                        .unwrap_or_else(|| members[0].shape.bounds()),
                }
            }
            one => one.solid().expect("every other kind is one shape").bounds(),
        }
    }

    /// The shape scaled about the frame's origin by `scale`, then moved by `offset`.
    pub fn transformed(&self, scale: f32, offset: Vec3) -> ShapeDesc {
        let p = |v: Vec3| v * scale + offset;
        match self {
            ShapeDesc::Sphere { center, radius } => ShapeDesc::Sphere {
                center: p(*center),
                radius: radius * scale,
            },
            ShapeDesc::Cylinder {
                base,
                radius,
                height,
                caps,
            } => ShapeDesc::Cylinder {
                base: p(*base),
                radius: radius * scale,
                height: height * scale,
                caps: *caps,
            },
            ShapeDesc::Capsule {
                base,
                radius,
                height,
            } => ShapeDesc::Capsule {
                base: p(*base),
                radius: radius * scale,
                height: height * scale,
            },
            ShapeDesc::Cuboid { min, max } => ShapeDesc::Cuboid {
                min: p(*min),
                max: p(*max),
            },
            ShapeDesc::Disc {
                center,
                normal,
                radius,
            } => ShapeDesc::Disc {
                center: p(*center),
                normal: *normal,
                radius: radius * scale,
            },
            ShapeDesc::Plane { point, normal } => ShapeDesc::Plane {
                point: p(*point),
                normal: *normal,
            },
            ShapeDesc::Cone {
                base,
                radius,
                top_radius,
                height,
                caps,
            } => ShapeDesc::Cone {
                base: p(*base),
                radius: radius * scale,
                top_radius: top_radius * scale,
                height: height * scale,
                caps: *caps,
            },
            ShapeDesc::Torus {
                center,
                major_radius,
                minor_radius,
            } => ShapeDesc::Torus {
                center: p(*center),
                major_radius: major_radius * scale,
                minor_radius: minor_radius * scale,
            },
            ShapeDesc::Polygon { vertices } => ShapeDesc::Polygon {
                vertices: vertices.iter().map(|&v| p(v)).collect(),
            },
            ShapeDesc::Triangle { vertices } => ShapeDesc::Triangle {
                vertices: vertices.map(p),
            },
            ShapeDesc::Tetrahedron { vertices } => ShapeDesc::Tetrahedron {
                vertices: vertices.map(p),
            },
            ShapeDesc::Mesh { mesh, transform } => ShapeDesc::Mesh {
                mesh: mesh.clone(),
                transform: moved(transform, scale, offset),
            },
            ShapeDesc::Transformed { shape, transform } => ShapeDesc::Transformed {
                shape: shape.clone(),
                transform: moved(transform, scale, offset),
            },
            ShapeDesc::Csg { operation, members } => ShapeDesc::Csg {
                operation: *operation,
                members: members
                    .iter()
                    .map(|m| CsgMember {
                        shape: m.shape.transformed(scale, offset),
                        material: m.material.clone(),
                    })
                    .collect(),
            },
        }
    }
}

impl ShapeDesc {
    /// Whether a ray that leaves its outside cannot meet it again: a closed convex solid or
    /// a flat convex shape (not a mesh, an open tube or cone, or a torus).
    pub fn is_convex(&self) -> bool {
        match self {
            ShapeDesc::Cylinder { caps, .. } | ShapeDesc::Cone { caps, .. } => *caps,
            ShapeDesc::Mesh { .. } | ShapeDesc::Torus { .. } => false,
            ShapeDesc::Transformed { shape, .. } => shape.is_convex(),
            // Only convex solids' common part is convex.
            ShapeDesc::Csg { operation, members } => {
                *operation == CsgOperation::Intersection
                    && members.iter().all(|m| m.shape.is_convex())
            }
            ShapeDesc::Sphere { .. }
            | ShapeDesc::Capsule { .. }
            | ShapeDesc::Cuboid { .. }
            | ShapeDesc::Disc { .. }
            | ShapeDesc::Plane { .. }
            | ShapeDesc::Polygon { .. }
            | ShapeDesc::Triangle { .. }
            | ShapeDesc::Tetrahedron { .. } => true,
        }
    }

    /// Whether it has no inside, so both its sides face out.
    pub fn is_flat(&self) -> bool {
        match self {
            ShapeDesc::Polygon { .. }
            | ShapeDesc::Triangle { .. }
            | ShapeDesc::Disc { .. }
            | ShapeDesc::Plane { .. } => true,
            ShapeDesc::Transformed { shape, .. } => shape.is_flat(),
            _ => false,
        }
    }
}

/// `transform` followed by a scale about the origin and a move.
fn moved(transform: &Transform, scale: f32, offset: Vec3) -> Transform {
    let outer =
        Affine3A::from_scale_rotation_translation(Vec3::splat(scale), Quat::IDENTITY, offset);
    // Scaling by a positive finite factor keeps a valid transform valid, unless the scale is
    // so extreme that it overflows; then the shape is left where it was.
    transform.then(outer).unwrap_or(*transform)
}

impl Scene {
    /// The materials of the CSG members that give one of their own (or take an enclosing
    /// member's), in the order a prepared scene numbers them: after the objects' own, object
    /// by object, each combination's solids in its tree's order.
    pub fn member_materials(&self) -> Vec<Material> {
        let mut out = Vec::new();
        for object in &self.objects {
            object.shape.csg_leaves(&mut |_, material| {
                if let Some(m) = material {
                    out.push(m.clone());
                }
            });
        }
        out
    }

    /// The box around every object (relative to `origin`); None without objects.
    pub fn bounds(&self) -> Option<Aabb> {
        self.objects
            .iter()
            .map(|o| o.shape.bounds())
            .reduce(|a, b| Aabb {
                min: a.min.min(b.min),
                max: a.max.max(b.max),
            })
    }

    /// The same scene uniformly scaled about the world origin by `scale`, then moved by `offset`,
    /// camera and lights included: it must render the same image (the numerical stress
    /// tests rely on this). A light without falloff keeps its colour; an inverse-square one
    /// scales its intensity with the square of the scale.
    pub fn transformed(&self, scale: f32, offset: DVec3) -> Scene {
        let mut scene = self.clone();
        // world' = world·s + offset, so origin' = origin·s + offset and relative' = relative·s.
        scene.origin = self.origin * scale as f64 + offset;
        scene.camera.eye = self.camera.eye * scale;
        for light in &mut scene.lights {
            *light = light.scaled(scale);
        }
        scene.fog = self.fog.map(|f| f.scaled(scale));
        scene.camera.focus_distance *= scale;
        scene.camera.aperture *= scale;
        for object in &mut scene.objects {
            object.shape = object.shape.transformed(scale, Vec3::ZERO);
            object.material.texture = object.material.texture.scaled(scale);
            object.material.relief = object.material.relief.as_ref().map(|r| r.scaled(scale));
            // Absorption is per unit length: a larger object absorbs as much over its length.
            object.material.absorption /= scale;
            // `placement` stays the file's: this scene is a test's variant, never saved.
        }
        scene
    }
}

impl Scene {
    /// The map from group `group`'s frame to the world's (`group::group_frame`).
    pub fn group_frame(&self, group: Option<usize>) -> DAffine3 {
        group_frame(&self.groups, group)
    }

    /// The scale and turn that object `object`'s placement and its groups' give it
    /// together: what its solid textures turn and scale with.
    pub fn object_linear(&self, object: usize) -> DMat3 {
        let o = &self.objects[object];
        self.group_frame(o.group).matrix3 * o.placement.linear()
    }

    /// Whether group `group` is `ancestor` or lies within it.
    pub fn group_within(&self, group: usize, ancestor: usize) -> bool {
        self.group_chain(Some(group)).contains(&ancestor)
    }

    /// The groups from `group` out to the world: it, its parent, and so on.
    pub fn group_chain(&self, group: Option<usize>) -> Vec<usize> {
        group_chain(&self.groups, group)
    }
}
