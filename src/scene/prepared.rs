//! The scene as the tracer runs it: shapes flattened into primitives under a BVH, per
//! object shading data, and what work the scene can skip.

use super::description::{Scene, ShapeDesc};
use crate::first_hit::Candidate;
use crate::geometry::{Aabb, Bvh, Cylinder, Ray, RayQuery, Shape, ShapeHit, Sphere, Triangle};
use crate::light::PointLight;
use crate::light_buffer::LightBuffer;
use crate::material::Material;
use glam::{Vec3, Vec3A};

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
    pub origin: Vec3A,
    /// For polygons: (u, v) in [0, 1] over the polygon's extent in its own plane.
    pub planar_uv: Option<PlanarUv>,
    /// What one crossing of this object's surface lets through to a shadow ray.
    pub shadow_filter: Vec3A,
    /// A polygon or triangle: no inside, so both its sides face out. (A polygon file is
    /// planar within 10⁻⁴ of its extent, file.rs; a fold that small shadowing itself would be
    /// acne, not something to draw.)
    pub flat: bool,
    /// For a solid made of one primitive (a sphere or a capped cylinder: closed and convex)
    /// that no other primitive's box comes near: that primitive. A ray that starts inside
    /// it meets nothing else before it leaves, so its next hit needs no BVH
    /// (`PreparedScene::intersect_inside`).
    pub isolated_solid: Option<u32>,
}

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

    #[inline]
    pub fn uv(&self, p: Vec3A) -> (f32, f32) {
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
    /// Read at every hit and miss, so kept in the hot path's SIMD form.
    pub ambient: Vec3A,
    pub background: Vec3A,
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
                        if tri.normal.dot((face[0] - centroid).into()) < 0.0 {
                            tri = Triangle::new(face[0], face[2], face[1]).expect("validated");
                        }
                        push(Shape::Triangle(tri));
                    }
                }
            }
            objects.push(ObjectData {
                name: object.name.clone(),
                shadow_filter: object.material.shadow_filter().into(),
                material: object.material.clone(),
                origin: object.shape.origin().into(),
                planar_uv,
                flat: matches!(
                    object.shape,
                    ShapeDesc::Polygon { .. } | ShapeDesc::Triangle { .. }
                ),
                isolated_solid: None,
            });
        }
        let bounds: Vec<Aabb> = primitives.iter().map(|p| p.shape.bounds()).collect();
        let (bvh, order) = Bvh::build(&bounds);
        let primitives: Vec<Primitive> = order.iter().map(|&i| primitives[i as usize]).collect();
        mark_isolated_solids(&primitives, &bvh, &mut objects);
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
            ambient: scene.ambient.into(),
            background: scene.background.into(),
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

    /// The nearest hit after `t_min` on `primitive`, an object's `isolated_solid`, of a ray
    /// that starts inside that solid: when it is Some, it is what `intersect(q, t_min, ∞)`
    /// finds. (Any other primitive's hit would lie on the segment from the origin to this
    /// exit, which is inside the solid's box, where no other box comes.) None, when the
    /// origin was not inside after all, leaves the answer to `intersect`.
    #[inline]
    pub fn intersect_inside(
        &self,
        primitive: u32,
        q: &RayQuery,
        t_min: f32,
    ) -> Option<(ShapeHit, u32)> {
        let shape = &self.primitives[primitive as usize].shape;
        let hit = shape.intersect_after(q, t_min, f32::INFINITY)?;
        Some((hit, primitive))
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
        origin: Vec3A,
        leaving: Option<u32>,
        light_buffer: bool,
    ) -> Vec3A {
        let to_light = Vec3A::from(self.lights[light].position) - origin;
        // The shadow ray ends exactly at the light: t = 1 on (light − origin).
        let shadow = |to_light| RayQuery::new(Ray::new(origin, to_light));
        if light_buffer && let Some(listed) = self.light_buffers[light].at((-to_light).into()) {
            let distance_sq = to_light.length_squared();
            let mut q = None;
            let mut light = Vec3A::ONE;
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
    pub fn transmittance(&self, q: &RayQuery, t_max: f32) -> Vec3A {
        let mut light = Vec3A::ONE;
        self.bvh
            .visit(q, t_max, |i| self.pass_through(i, q, t_max, &mut light));
        light
    }

    /// Filters `light` by what primitive `i` lets through along the segment (0, t_max);
    /// false once no light is left.
    #[inline(always)]
    fn pass_through(&self, i: u32, q: &RayQuery, t_max: f32, light: &mut Vec3A) -> bool {
        let prim = &self.primitives[i as usize];
        if !self.any_transmission {
            if prim.shape.intersect(q, t_max).is_some() {
                *light = Vec3A::ZERO;
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
            if *light == Vec3A::ZERO {
                return false;
            }
        }
        true
    }
}

/// How far apart (relative to the size and the coordinates of a solid's box) another box
/// must stay for the solid to count as isolated: far beyond the rounding of a hit point or a
/// ray origin (a few ulps), so a rounded hit on another primitive cannot land inside.
const ISOLATION_MARGIN: f32 = 1e-4;

/// Sets `isolated_solid` for every object that qualifies (see `ObjectData`).
fn mark_isolated_solids(primitives: &[Primitive], bvh: &Bvh, objects: &mut [ObjectData]) {
    let mut sole: Vec<Option<u32>> = vec![None; objects.len()];
    let mut count = vec![0u32; objects.len()];
    for (index, primitive) in primitives.iter().enumerate() {
        let object = primitive.object as usize;
        count[object] += 1;
        if matches!(primitive.shape, Shape::Sphere(_) | Shape::Cylinder(_)) {
            sole[object] = Some(index as u32);
        }
    }
    for (object, data) in objects.iter_mut().enumerate() {
        let Some(index) = sole[object].filter(|_| count[object] == 1) else {
            continue;
        };
        let bounds = primitives[index as usize].shape.bounds();
        if !(bounds.min.is_finite() && bounds.max.is_finite()) {
            continue;
        }
        let scale = bounds.min.abs().max(bounds.max.abs()).max_element()
            + (bounds.max - bounds.min).max_element();
        let margin = Vec3::splat(scale * ISOLATION_MARGIN);
        let near = Aabb {
            min: bounds.min - margin,
            max: bounds.max + margin,
        };
        let mut alone = true;
        // Stops at the first neighbour: among many coincident solids the search is short.
        bvh.overlapping(&near, |other| {
            alone &= other == index || !primitives[other as usize].shape.bounds().overlaps(&near);
            alone
        });
        if alone {
            data.isolated_solid = Some(index);
        }
    }
}
