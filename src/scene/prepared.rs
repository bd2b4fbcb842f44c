//! The scene as the tracer runs it: shapes flattened into primitives under a BVH, per
//! object shading data, and what work the scene can skip.

use super::description::{Scene, ShapeDesc};
use crate::first_hit::Candidate;
use crate::geometry::{Aabb, Bvh, Cylinder, RayQuery, Shape, ShapeHit, Sphere, Triangle};
use crate::light::PointLight;
use crate::material::Material;
use glam::Vec3;

/// One intersectable piece of an object (a polygon becomes a fan of triangles, a
/// tetrahedron four).
#[derive(Clone, Copy, Debug)]
pub struct Primitive {
    pub shape: Shape,
    pub object: u32,
}

/// What shading needs to know about the object a primitive belongs to.
#[derive(Clone, Debug)]
pub struct ObjectData {
    pub name: String,
    pub material: Material,
    /// Procedural textures are evaluated relative to this point.
    pub origin: Vec3,
    /// For polygons: (u, v) in [0, 1] over the polygon's extent in its own plane.
    pub planar_uv: Option<PlanarUv>,
    /// What one crossing of this object's surface lets through to a shadow ray.
    pub shadow_filter: Vec3,
}

#[derive(Clone, Copy, Debug)]
pub struct PlanarUv {
    origin: Vec3,
    u_axis: Vec3,
    v_axis: Vec3,
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
            origin: vertices[0] + u_dir * lo.x + v_dir * lo.y,
            u_axis: u_dir / size.x,
            v_axis: v_dir / size.y,
        }
    }

    #[inline]
    pub fn uv(&self, p: Vec3) -> (f32, f32) {
        let d = p - self.origin;
        (d.dot(self.u_axis), d.dot(self.v_axis))
    }
}

#[derive(Clone, Debug)]
pub struct PreparedScene {
    pub primitives: Vec<Primitive>,
    pub bvh: Bvh,
    pub objects: Vec<ObjectData>,
    pub lights: Vec<PointLight>,
    pub ambient: Vec3,
    pub background: Vec3,
    pub max_depth: u32,
    /// Whether any surface transmits light; when none does, shadow rays stop at the first
    /// occluder without looking at materials.
    pub any_transmission: bool,
}

impl PreparedScene {
    pub fn new(scene: &Scene) -> Self {
        let mut primitives = Vec::new();
        let mut objects = Vec::with_capacity(scene.objects.len());
        for (index, object) in scene.objects.iter().enumerate() {
            let id = index as u32;
            let mut planar_uv = None;
            let mut push = |shape| primitives.push(Primitive { shape, object: id });
            match &object.shape {
                ShapeDesc::Sphere { center, radius } => {
                    push(Shape::Sphere(Sphere::new(*center, *radius)))
                }
                ShapeDesc::Cylinder {
                    base,
                    radius,
                    height,
                } => push(Shape::Cylinder(Cylinder::new(*base, *radius, *height))),
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
                        if tri.normal.dot(face[0] - centroid) < 0.0 {
                            tri = Triangle::new(face[0], face[2], face[1]).expect("validated");
                        }
                        push(Shape::Triangle(tri));
                    }
                }
            }
            objects.push(ObjectData {
                name: object.name.clone(),
                shadow_filter: object.material.shadow_filter(),
                material: object.material.clone(),
                origin: object.shape.origin(),
                planar_uv,
            });
        }
        let bounds: Vec<Aabb> = primitives.iter().map(|p| p.shape.bounds()).collect();
        let (bvh, order) = Bvh::build(&bounds);
        let primitives = order.iter().map(|&i| primitives[i as usize]).collect();
        let any_transmission = objects.iter().any(|o| o.material.transparency > 0.0);
        Self {
            primitives,
            bvh,
            objects,
            lights: scene.lights.clone(),
            ambient: scene.ambient,
            background: scene.background,
            max_depth: scene.render.max_depth,
            any_transmission,
        }
    }

    /// The nearest hit in (t_min, t_max) and the index of the primitive hit.
    #[inline]
    pub fn intersect(&self, q: &RayQuery, t_min: f32, t_max: f32) -> Option<(ShapeHit, u32)> {
        let mut best: Option<(ShapeHit, u32)> = None;
        self.bvh.closest(q, t_max, |i, t_max| {
            let hit = self.primitives[i as usize]
                .shape
                .intersect_after(q, t_min, t_max)?;
            best = Some((hit, i));
            Some(hit.t)
        });
        best
    }

    /// The nearest hit among `candidates`, which hold every primitive the ray can reach,
    /// sorted by a lower bound of the distance at which it can hit them (first_hit.rs): the
    /// same answer as `intersect(q, 0, ∞)`.
    #[inline]
    pub fn intersect_among(
        &self,
        q: &RayQuery,
        candidates: &[Candidate],
    ) -> Option<(ShapeHit, u32)> {
        let mut best: Option<(ShapeHit, u32)> = None;
        let mut t_max = f32::INFINITY;
        for c in candidates {
            if c.min_t >= t_max {
                break; // this box and every later one start beyond the nearest hit
            }
            let shape = &self.primitives[c.primitive as usize].shape;
            if let Some(hit) = shape.intersect_after(q, 0.0, t_max) {
                t_max = hit.t;
                best = Some((hit, c.primitive));
            }
        }
        best
    }

    /// The fraction of light that reaches the end of the segment (0, t_max): zero behind
    /// any opaque surface, and tinted by every transparent surface crossed.
    #[inline]
    pub fn transmittance(&self, q: &RayQuery, t_max: f32) -> Vec3 {
        let mut light = Vec3::ONE;
        self.bvh.visit(q, t_max, |i| {
            let prim = &self.primitives[i as usize];
            if !self.any_transmission {
                if prim.shape.intersect(q, t_max).is_some() {
                    light = Vec3::ZERO;
                    return false;
                }
                return true;
            }
            let crossings = prim.shape.crossings(q, t_max);
            if crossings > 0 {
                let filter = self.objects[prim.object as usize].shadow_filter;
                light *= filter;
                if crossings == 2 {
                    light *= filter;
                }
                if light == Vec3::ZERO {
                    return false;
                }
            }
            true
        });
        light
    }
}
