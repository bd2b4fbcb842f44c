//! A scene's geometry as the tracer runs it: its shapes flattened into primitives under the
//! acceleration layer, and what shading needs to know of each object's shape. Built when
//! geometry changes, and never for an appearance edit.

use super::description::{Scene, ShapeDesc};
use crate::accel::{
    AccelOptions, Accelerator, CSG_MEMBERS_MATERIAL, Csg, CsgLeaf, CsgNode, CsgOperation, Instance,
    Model, Primitive, Surface,
};
use crate::geometry::{Disc, Mesh, Shape, Triangle, UvFrame, picture_axes};
use crate::limits;
use glam::{DMat3, Mat3A, Vec3, Vec3A};
use std::collections::HashMap;
use std::sync::Arc;

/// What shading needs to know about the shape of the object a primitive belongs to.
#[derive(Clone, Debug)]
pub struct ObjectGeometry {
    /// The object's name, as the scene file gives it.
    pub name: String,
    /// Procedural textures are evaluated relative to this point.
    pub origin: Vec3A,
    /// The inverse of the object's `rotate` and `scale` (its entry's placement), which turn
    /// and scale its solid textures with it; None when it neither turns nor scales.
    pub texture_axes: Option<Mat3A>,
    /// For polygons: (u, v) in [0, 1] over the polygon's extent in its own plane.
    pub planar_uv: Option<PlanarUv>,
    /// A polygon or triangle: no inside, so both its sides face out. (A polygon file is
    /// planar within 10⁻⁴ of its extent, file.rs; a fold that small shadowing itself would be
    /// acne, not something to draw.)
    pub flat: bool,
    /// A convex solid or a flat convex polygon: a ray leaving its outside cannot meet it
    /// again (not a mesh, whose bumps may shadow each other).
    pub convex: bool,
    /// An infinite plane (traced as a disc far wider than the scene): no light can sample
    /// its area.
    pub unbounded: bool,
}

impl ObjectGeometry {
    /// Where scene point `p` lies in the object's solid textures: relative to its origin,
    /// turned and scaled back by its placement (so a pattern turns and scales with it).
    #[inline]
    pub fn texture_point(&self, p: Vec3A) -> Vec3A {
        let local = p - self.origin;
        match self.texture_axes {
            None => local,
            Some(m) => m * local,
        }
    }

    /// A gradient taken in the object's solid textures (per unit of `texture_point`), as a
    /// gradient in the scene's space: the chain rule through `texture_point`.
    #[inline]
    pub fn texture_gradient_to_scene(&self, g: Vec3A) -> Vec3A {
        match self.texture_axes {
            None => g,
            Some(m) => m.transpose() * g,
        }
    }
}

/// The inverse of `linear` (an object's turn and scale, its groups' included); None when
/// it neither turns nor scales.
fn texture_axes(linear: DMat3) -> Option<Mat3A> {
    (linear != DMat3::IDENTITY).then(|| Mat3A::from(linear.inverse().as_mat3()))
}

/// Texture coordinates over a polygon's extent in its own plane.
#[derive(Clone, Copy, Debug)]
pub struct PlanarUv {
    origin: Vec3A,
    u_axis: Vec3A,
    v_axis: Vec3A,
}

impl PlanarUv {
    fn new(vertices: &[Vec3], normal: Vec3) -> Self {
        let u_dir = (vertices[1] - vertices[0]).normalize();
        let v_dir = normal.cross(u_dir);
        let (mut lo, mut hi) = (glam::Vec2::splat(f32::MAX), glam::Vec2::splat(f32::MIN));
        for &p in vertices {
            let q = glam::Vec2::new((p - vertices[0]).dot(u_dir), (p - vertices[0]).dot(v_dir));
            lo = lo.min(q);
            hi = hi.max(q);
        }
        let size = hi - lo;
        Self {
            origin: (vertices[0] + u_dir * lo.x + v_dir * lo.y).into(),
            u_axis: (u_dir / size.x).into(),
            v_axis: (v_dir / size.y).into(),
        }
    }

    /// Texture coordinates over a plane through `point` facing `normal`: one repeat of a
    /// picture per unit of length, upright as its front is seen (as a disc's).
    fn unit(point: Vec3, normal: Vec3) -> Self {
        let (right, up) = picture_axes(normal);
        Self {
            origin: point.into(),
            u_axis: right.into(),
            v_axis: up.into(),
        }
    }

    /// (u, v) of point `p` in the polygon's plane: u along the first edge, v from the far
    /// side down to it, so that a polygon whose corners run counter-clockwise from its
    /// bottom-left (as its front is seen) shows a picture upright (an image's v runs down).
    #[inline]
    pub fn uv(&self, p: Vec3A) -> (f32, f32) {
        let d = p - self.origin;
        (d.dot(self.u_axis), 1.0 - d.dot(self.v_axis))
    }

    /// (u, v) of `p` and their tangents (constant over the plane).
    #[inline]
    pub fn uv_frame(&self, p: Vec3A) -> UvFrame {
        UvFrame::planar(self.uv(p), self.u_axis, self.v_axis)
    }
}

/// The radius of the disc that stands for an infinite plane: `limits::PLANE_REACH` times
/// the scene's extent from the eye (its objects', its lights' and its planes' distances), so
/// that the image does not change with the scene's scale.
fn plane_reach(scene: &Scene) -> f32 {
    let mut extent: f32 = 0.0;
    for object in &scene.objects {
        let d = match &object.shape {
            ShapeDesc::Plane { point, normal } => point.dot(*normal).abs(),
            shape => {
                let b = shape.bounds();
                b.min.abs().max(b.max.abs()).max_element()
            }
        };
        extent = extent.max(d);
    }
    for light in &scene.lights {
        if let Some(p) = light.anchor() {
            extent = extent.max(p.abs().max_element());
        }
    }
    // Only planes through the eye: seen edge on, any width will do.
    let extent = if extent > 0.0 { extent } else { 1.0 };
    (extent * limits::PLANE_REACH).min(f32::MAX.sqrt() * 0.5)
}

/// The surface of a CSG member (or a whole CSG solid) on its own: a closed shape, a plane
/// (as a disc of radius `reach`), a transformed shape, or a combination; with the material
/// of a lone solid's surface. `materials` gives each solid's material in the tree's order
/// and is consumed as the solids are; `hierarchies` gives a combination of many members
/// its hierarchies (`Csg::new`).
fn csg_member_surface(
    desc: &ShapeDesc,
    reach: f32,
    materials: &mut impl Iterator<Item = u32>,
    hierarchies: bool,
) -> (Surface, u32) {
    let lone = |materials: &mut dyn Iterator<Item = u32>| materials.next().expect("a material");
    match csg_leaf(desc, reach) {
        Some(CsgLeaf::Shape(shape)) => (Surface::Shape(shape), lone(materials)),
        Some(CsgLeaf::HalfSpace(disc)) => (Surface::Shape(Shape::Disc(disc)), lone(materials)),
        Some(CsgLeaf::Instance(instance)) => {
            (Surface::Instance(Arc::new(*instance)), lone(materials))
        }
        None => {
            let (mut leaves, mut slots) = (Vec::new(), Vec::new());
            let root = csg_node(desc, reach, &mut leaves);
            slots.extend(materials.take(leaves.len()));
            // A combination's hits name their members' materials themselves.
            let csg = Csg::new(root, leaves, slots, hierarchies);
            (Surface::Csg(Arc::new(csg)), CSG_MEMBERS_MATERIAL)
        }
    }
}

/// A CSG member as a leaf; None for a combination.
fn csg_leaf(desc: &ShapeDesc, reach: f32) -> Option<CsgLeaf> {
    Some(match desc {
        ShapeDesc::Plane { point, normal } => {
            CsgLeaf::HalfSpace(Disc::new(*normal * point.dot(*normal), *normal, reach))
        }
        ShapeDesc::Transformed { shape, transform } => {
            let model = shape.solid().expect("a transformed shape is one shape");
            CsgLeaf::Instance(Box::new(Instance::new(
                Arc::new(Model::Shape(model)),
                *transform,
            )))
        }
        ShapeDesc::Csg { .. } => return None,
        solid => CsgLeaf::Shape(solid.solid().expect("a CSG member is a closed shape")),
    })
}

/// The tree of CSG member `desc`, its leaves appended to `leaves` in the tree's order.
fn csg_node(desc: &ShapeDesc, reach: f32, leaves: &mut Vec<CsgLeaf>) -> CsgNode {
    match desc {
        ShapeDesc::Csg { operation, members } => CsgNode::combine(
            *operation,
            members
                .iter()
                .map(|m| csg_node(&m.shape, reach, leaves))
                .collect(),
        ),
        leaf => {
            leaves.push(csg_leaf(leaf, reach).expect("a leaf"));
            CsgNode::Leaf(leaves.len() as u32 - 1)
        }
    }
}

/// The primitives of a scene's objects, the acceleration layer over them, and each object's
/// shape data.
#[derive(Clone, Debug)]
pub struct Geometry {
    accel: Accelerator,
    objects: Vec<ObjectGeometry>,
    /// Each mesh's model (its hierarchy and triangle groups), by the scene's mesh, which
    /// is held so that its address names it while this lives (`Geometry::rebuilt`).
    models: Vec<(Arc<Mesh>, Arc<Model>)>,
}

impl Geometry {
    /// Whether `a` and `b` prepare to the same geometry: the same groups, the same objects'
    /// names, shapes and groups, and the same lights' shadow-ray end points (the light
    /// buffers' centres), everything [`Geometry::new`] reads. Then an edit between them need rebuild none of it.
    pub fn same_for(a: &Scene, b: &Scene) -> bool {
        a.origin == b.origin
            && a.groups == b.groups
            && a.objects.len() == b.objects.len()
            && a.objects
                .iter()
                .zip(&b.objects)
                .all(|(x, y)| x.name == y.name && x.shape == y.shape && x.group == y.group)
            && a.lights.len() == b.lights.len()
            && a.lights
                .iter()
                .zip(&b.lights)
                .all(|(x, y)| x.position() == y.position())
    }

    /// Flattens `scene`'s shapes and builds the acceleration layer with `options`.
    pub fn new(scene: &Scene, options: AccelOptions) -> Self {
        Self::build(scene, options, None)
    }

    /// `scene` (an edit of the scene `previous` was made from) prepared with `previous`'s
    /// options, taking from it what the edit left as it was: each mesh's model, and each
    /// placed mesh's lists around a light (`Accelerator::build_reusing`). The same as
    /// `Geometry::new` makes, in less time.
    pub fn rebuilt(scene: &Scene, previous: &Geometry) -> Self {
        Self::build(scene, previous.accel.options(), Some(previous))
    }

    fn build(scene: &Scene, options: AccelOptions, previous: Option<&Geometry>) -> Self {
        let mut primitives = Vec::new();
        let mut objects = Vec::with_capacity(scene.objects.len());
        // One model per mesh, however many objects place it, and the one made before where
        // the scene still holds the mesh: the previous geometry holds it too, so its
        // address cannot have been taken by another.
        let mut models: HashMap<*const Mesh, (Arc<Mesh>, Arc<Model>)> = previous
            .into_iter()
            .flat_map(|p| &p.models)
            .map(|(mesh, model)| (Arc::as_ptr(mesh), (mesh.clone(), model.clone())))
            .collect();
        let mut used: HashMap<*const Mesh, (Arc<Mesh>, Arc<Model>)> = HashMap::new();
        let plane_reach = plane_reach(scene);
        // CSG members with materials of their own are numbered after the objects' own, in
        // the order `Scene::member_materials` lists them.
        let mut next_material = scene.objects.len() as u32;
        for (index, object) in scene.objects.iter().enumerate() {
            let id = index as u32;
            let mut planar_uv = None;
            let mut member_materials = Vec::new();
            object.shape.csg_leaves(&mut |_, material| {
                member_materials.push(match material {
                    Some(_) => {
                        next_material += 1;
                        next_material - 1
                    }
                    None => id,
                })
            });
            let mut member_materials = member_materials.into_iter();
            let mut push_with = |surface, material| {
                primitives.push(Primitive {
                    surface,
                    object: id,
                    material,
                })
            };
            let mut push_surface = |surface| push_with(surface, id);
            let mut push = |shape| push_surface(Surface::Shape(shape));
            match &object.shape {
                ShapeDesc::Plane { point, normal } => {
                    // Seen from the eye (at the frame's origin), a disc this wide is a plane:
                    // its rim lies below the horizon by less than a pixel.
                    let foot = *normal * point.dot(*normal);
                    let uv = PlanarUv::unit(*point, *normal);
                    planar_uv = Some(uv);
                    push(Shape::Disc(Disc::new(foot, *normal, plane_reach)))
                }
                shape @ (ShapeDesc::Sphere { .. }
                | ShapeDesc::Cylinder { .. }
                | ShapeDesc::Capsule { .. }
                | ShapeDesc::Cuboid { .. }
                | ShapeDesc::Disc { .. }
                | ShapeDesc::Cone { .. }
                | ShapeDesc::Torus { .. }) => push(shape.solid().expect("one shape")),
                ShapeDesc::Triangle {
                    vertices: [a, b, c],
                } => push(Shape::Triangle(
                    Triangle::new(*a, *b, *c).expect("validated"),
                )),
                ShapeDesc::Polygon { vertices } => {
                    let normal = (vertices[1] - vertices[0])
                        .cross(vertices[2] - vertices[1])
                        .normalize();
                    planar_uv = Some(PlanarUv::new(vertices, normal));
                    for i in 1..vertices.len() - 1 {
                        if let Some(t) = Triangle::new(vertices[0], vertices[i], vertices[i + 1]) {
                            push(Shape::Triangle(t));
                        }
                    }
                }
                ShapeDesc::Tetrahedron { vertices } => {
                    let centroid = vertices.iter().sum::<Vec3>() / 4.0;
                    for skip in 0..4 {
                        let mut face = [Vec3::ZERO; 3];
                        let mut k = 0;
                        for (i, v) in vertices.iter().enumerate() {
                            if i != skip {
                                face[k] = *v;
                                k += 1;
                            }
                        }
                        let mut tri = Triangle::new(face[0], face[1], face[2]).expect("validated");
                        // Wind every face so its normal points away from the inside.
                        if tri.normal.dot((face[0] - centroid).into()) < 0.0 {
                            tri = Triangle::new(face[0], face[2], face[1]).expect("validated");
                        }
                        push(Shape::Triangle(tri));
                    }
                }
                ShapeDesc::Mesh { mesh, transform } => {
                    let (_, model) = used.entry(Arc::as_ptr(mesh)).or_insert_with(|| {
                        models
                            .remove(&Arc::as_ptr(mesh))
                            .unwrap_or_else(|| (mesh.clone(), Arc::new(Model::mesh(mesh))))
                    });
                    push_surface(Surface::Instance(Arc::new(Instance::new(
                        model.clone(),
                        *transform,
                    ))));
                }
                ShapeDesc::Transformed { shape, transform } => {
                    let model = shape.solid().expect("a transformed shape is one shape");
                    push_surface(Surface::Instance(Arc::new(Instance::new(
                        Arc::new(Model::Shape(model)),
                        *transform,
                    ))));
                }
                // A union shows every member's whole surface: its members are primitives
                // of one object, found through the hierarchy like any other.
                ShapeDesc::Csg {
                    operation: CsgOperation::Union,
                    members,
                } => {
                    for member in members {
                        let (surface, material) = csg_member_surface(
                            &member.shape,
                            plane_reach,
                            &mut member_materials,
                            options.bvh,
                        );
                        push_with(surface, material);
                    }
                }
                csg @ ShapeDesc::Csg { .. } => {
                    let (surface, material) =
                        csg_member_surface(csg, plane_reach, &mut member_materials, options.bvh);
                    push_with(surface, material);
                }
            }
            objects.push(ObjectGeometry {
                name: object.name.clone(),
                origin: object.shape.origin().into(),
                texture_axes: texture_axes(scene.object_linear(index)),
                planar_uv,
                flat: object.shape.is_flat(),
                convex: object.shape.is_convex(),
                unbounded: matches!(object.shape, ShapeDesc::Plane { .. }),
            });
        }
        let lights: Vec<Option<Vec3>> = scene.lights.iter().map(|l| l.position()).collect();
        let accel = Accelerator::build_reusing(
            primitives,
            objects.len(),
            &lights,
            options,
            previous.map(|p| &p.accel),
        );
        Self {
            accel,
            objects,
            models: used.into_values().collect(),
        }
    }

    /// The acceleration layer: the primitives and how to find what rays meet.
    #[inline]
    pub fn accel(&self) -> &Accelerator {
        &self.accel
    }

    /// Object `object`'s shape data.
    #[inline]
    pub fn object(&self, object: u32) -> &ObjectGeometry {
        &self.objects[object as usize]
    }

    /// Every object's shape data, in the scene's order.
    pub fn objects(&self) -> &[ObjectGeometry] {
        &self.objects
    }

    /// The index of the object named `name`, if there is one.
    pub fn find(&self, name: &str) -> Option<u32> {
        self.objects
            .iter()
            .position(|o| o.name == name)
            .map(|i| i as u32)
    }
}
