//! The scene as the tracer runs it: shapes flattened into primitives under a BVH, per
//! object shading data, and what work the scene can skip.

use super::description::{Scene, ShapeDesc};
use crate::first_hit::Candidate;
use crate::geometry::{Aabb, Bvh, Cylinder, Ray, RayQuery, Shape, ShapeHit, Sphere, Triangle};
use crate::light::PointLight;
use crate::light_buffer::LightBuffer;
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
    /// A polygon or triangle: no inside, so both its sides face out. (A polygon file is
    /// planar within 10⁻⁴ of its extent, file.rs; a fold that small shadowing itself would be
    /// acne, not something to draw.)
    pub flat: bool,
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
    /// For each light, what a shadow ray toward it may meet, by direction (light_buffer.rs).
    pub light_buffers: Vec<LightBuffer>,
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
                flat: matches!(
                    object.shape,
                    ShapeDesc::Polygon { .. } | ShapeDesc::Triangle { .. }
                ),
            });
        }
        let bounds: Vec<Aabb> = primitives.iter().map(|p| p.shape.bounds()).collect();
        let (bvh, order) = Bvh::build(&bounds);
        let primitives: Vec<Primitive> = order.iter().map(|&i| primitives[i as usize]).collect();
        let any_transmission = objects.iter().any(|o| o.material.transparency > 0.0);
        let light_buffers = scene
            .lights
            .iter()
            .map(|light| LightBuffer::new(light.position, &primitives))
            .collect();
        Self {
            primitives,
            bvh,
            objects,
            lights: scene.lights.clone(),
            light_buffers,
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

    /// The fraction of light `light` (an index into `lights`) sends that reaches `origin`:
    /// the shadow ray from `origin` to the light. With `light_buffer` the ray tests only
    /// what the light's buffer lists for its direction (none at all when nothing lies
    /// between), else it traverses the BVH; both give the same answer.
    ///
    /// `leaving` names the object whose surface the ray starts on, when it leaves from the
    /// outside towards a light on that side (or from either side of a flat object). Every
    /// object is convex (a sphere, a closed cylinder, a tetrahedron, a convex polygon), so it
    /// lies wholly behind the plane tangent at the origin and the ray cannot meet it again:
    /// the buffer's lists skip it. The BVH path tests it regardless, as the reference.
    #[inline]
    pub fn light_reaching(
        &self,
        light: usize,
        origin: Vec3,
        leaving: Option<u32>,
        light_buffer: bool,
    ) -> Vec3 {
        let to_light = self.lights[light].position - origin;
        // The shadow ray ends exactly at the light: t = 1 on (light − origin).
        let shadow = |to_light| RayQuery::new(Ray::new(origin, to_light));
        if light_buffer && let Some(listed) = self.light_buffers[light].at(-to_light) {
            let distance_sq = to_light.length_squared();
            let mut q = None;
            let mut light = Vec3::ONE;
            for o in listed {
                if o.min_distance_sq >= distance_sq {
                    break; // this box and every later one start beyond the origin
                }
                if Some(o.object) == leaving {
                    continue;
                }
                // Built only for a ray that has something to test.
                let q = q.get_or_insert_with(|| shadow(to_light));
                if !self.pass_through(o.primitive, q, 1.0, &mut light) {
                    break;
                }
            }
            return light;
        }
        self.transmittance(&shadow(to_light), 1.0)
    }

    /// The fraction of light that reaches the end of the segment (0, t_max): zero behind
    /// any opaque surface, and tinted by every transparent surface crossed.
    #[inline]
    pub fn transmittance(&self, q: &RayQuery, t_max: f32) -> Vec3 {
        let mut light = Vec3::ONE;
        self.bvh
            .visit(q, t_max, |i| self.pass_through(i, q, t_max, &mut light));
        light
    }

    /// Filters `light` by what primitive `i` lets through along the segment (0, t_max);
    /// false once no light is left.
    #[inline(always)]
    fn pass_through(&self, i: u32, q: &RayQuery, t_max: f32, light: &mut Vec3) -> bool {
        let prim = &self.primitives[i as usize];
        if !self.any_transmission {
            if prim.shape.intersect(q, t_max).is_some() {
                *light = Vec3::ZERO;
                return false;
            }
            return true;
        }
        let crossings = prim.shape.crossings(q, t_max);
        if crossings > 0 {
            let filter = self.objects[prim.object as usize].shadow_filter;
            *light *= filter;
            if crossings == 2 {
                *light *= filter;
            }
            if *light == Vec3::ZERO {
                return false;
            }
        }
        true
    }
}
