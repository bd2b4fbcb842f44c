//! The second level of the hierarchy: a model in its own space (a mesh under its own BVH,
//! or one shape) and instances of it placed in the scene by transforms. A ray meets an
//! instance by being taken into the model's space, without renormalising its direction, so
//! distances along it mean the same in both spaces.

use super::bvh::{Bvh, LeafCost};
use super::bvh_build::BinaryBvh;
use super::mesh_search::{listed_any_here, listed_closest_here, mesh_closest, mesh_occludes};
#[cfg(target_arch = "x86_64")]
use super::mesh_search::{mesh_closest_avx2, mesh_occludes_avx2};
use crate::geometry::{
    Aabb, GROUP_WIDTH, GroupRay, HitDetail, Mesh, Ray, RayQuery, Shape, ShapeHit, SurfacePoint,
    Transform, TriangleGroup, TriangleOctet, UvFrame,
};
use crate::simd::Halves;
use glam::Vec3A;
use std::sync::Arc;

/// A mesh's leaves hold its triangles in groups of four, and a leaf's groups are tested two
/// at a time (`GroupPair`, eight lanes): a leaf of up to eight triangles costs one test, so
/// the SAH never splits one. (Costed by the group of four, with sets of five to eight split
/// for a second test, the bunnies' passes took 1–2% longer and their trees longer to build.)
const GROUPED: LeafCost = LeafCost {
    group: 2 * GROUP_WIDTH,
    max: 2 * GROUP_WIDTH,
};

/// What an instance places: built once, shared by every instance of it.
#[derive(Clone, Debug)]
pub enum Model {
    /// A triangle mesh, its triangles stored in the order of its hierarchy's leaves.
    Mesh {
        /// The mesh.
        mesh: Mesh,
        /// The hierarchy over its triangles, whose leaves hold groups.
        bvh: Bvh,
        /// Each leaf's triangles in groups of up to four, tested at once.
        groups: Vec<TriangleGroup>,
    },
    /// One shape, for a shape under a transform that its own parameters cannot express
    /// (an ellipsoid, a tilted cylinder).
    Shape(Shape),
}

impl Model {
    /// The model of `mesh` (a copy, its triangles in the hierarchy's order), with the
    /// hierarchy over its triangles built.
    pub fn mesh(mesh: &Mesh) -> Self {
        use rayon::prelude::*;
        let bounds: Vec<Aabb> = (0..mesh.triangle_count() as u32)
            .into_par_iter()
            .map(|i| mesh.triangle_bounds(i))
            .collect();
        let (binary, order, coincident) = BinaryBvh::build(&bounds, GROUPED);
        // The wide tree and the triangles in the tree's order are made side by side.
        let (mut bvh, mesh) = rayon::join(
            || Bvh::collapsed(&binary, coincident),
            || mesh.reordered(&order),
        );
        // Each leaf's triangles become groups of up to four, numbered in leaf order: the
        // numbering is cheap and in order, the groups are made in parallel after.
        let mut spans: Vec<(u32, u32)> =
            Vec::with_capacity(mesh.triangle_count().div_ceil(GROUP_WIDTH));
        bvh.map_leaves(|triangles| {
            let start = spans.len() as u32;
            for first in triangles.clone().step_by(GROUP_WIDTH) {
                spans.push((first, (triangles.end - first).min(GROUP_WIDTH as u32)));
            }
            start..spans.len() as u32
        });
        let groups: Vec<TriangleGroup> = spans
            .into_par_iter()
            .map(|(first, count)| {
                let corners: [[Vec3A; 3]; GROUP_WIDTH] =
                    std::array::from_fn(|k| mesh.corners(first + (k as u32).min(count - 1)));
                TriangleGroup::new(first, &corners[..count as usize])
            })
            .collect();
        Model::Mesh { mesh, bvh, groups }
    }

    /// The box around it in its own space.
    pub fn bounds(&self) -> Aabb {
        match self {
            Model::Mesh { bvh, .. } => bvh.bounds.unwrap_or(Aabb::EMPTY),
            Model::Shape(shape) => shape.bounds(),
        }
    }

    /// The largest group of its triangles that share one centre (none for a shape).
    pub fn coincident(&self) -> super::bvh::Coincident {
        match self {
            Model::Mesh { bvh, .. } => bvh.coincident,
            Model::Shape(_) => super::bvh::Coincident::default(),
        }
    }

    /// The bytes its acceleration data takes beyond the mesh's vertices: the triangles'
    /// corner lists and the hierarchy's nodes (0 for a shape).
    pub fn index_bytes(&self) -> usize {
        match self {
            Model::Mesh { mesh, bvh, groups } => {
                mesh.triangle_bytes() + size_of_val(&bvh.nodes[..]) + size_of_val(&groups[..])
            }
            Model::Shape(_) => 0,
        }
    }

    // Not inlined: one copy of the traversal serves placed and unplaced instances.
    #[inline(never)]
    fn intersect_after(&self, q: &RayQuery, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match self {
            Model::Mesh { bvh, groups, .. } => {
                #[cfg(target_arch = "x86_64")]
                if let Some(avx) = crate::isa::avx2_lanes() {
                    // SAFETY: an `Avx` exists only where the processor has AVX2.
                    return unsafe { mesh_closest_avx2(avx, bvh, groups, q, t_min, t_max) };
                }
                mesh_closest(Halves, bvh, groups, q, t_min, t_max)
            }
            Model::Shape(shape) => shape.intersect_after(q, t_min, t_max),
        }
    }

    /// The nearest hit with t in (0, t_max) among the triangles of `listed` (a first-hit
    /// tile's octets of this mesh's triangles, nearest first): what `intersect_after` from
    /// 0 finds.
    #[inline(never)]
    fn nearest_listed(
        &self,
        q: &RayQuery,
        listed: &[TriangleOctet],
        t_max: f32,
    ) -> Option<ShapeHit> {
        debug_assert!(
            matches!(self, Model::Mesh { .. }),
            "only a mesh lists triangles"
        );
        // Two triangles can both be hit at one distance only where the ray meets the edge
        // (or corner) they share, exactly: a barycentric weight of 0 on each. Which of them
        // a search returns then depends on the order it tests them in, so the hierarchy's
        // walk, the reference, answers such a ray.
        match listed_closest_here(listed, q, t_max) {
            Some(ShapeHit {
                detail: HitDetail::Mesh { b, .. },
                ..
            }) if b.contains(&0.0) => self.intersect_after(q, 0.0, t_max),
            found => found,
        }
    }

    /// Whether any of the triangles `listed` (a light cell's octets of this mesh's
    /// triangles, nearest to the light first) lies on the segment (0, t_max), for a shadow
    /// ray from a point at a squared distance `distance_sq` from the light: what `occludes`
    /// finds.
    #[inline(never)]
    fn occludes_listed(
        &self,
        q: &RayQuery,
        listed: &[TriangleOctet],
        t_max: f32,
        distance_sq: f32,
    ) -> bool {
        debug_assert!(
            matches!(self, Model::Mesh { .. }),
            "only a mesh lists triangles"
        );
        listed_any_here(listed, q, t_max, distance_sq)
    }

    #[inline(never)]
    fn occludes(&self, q: &RayQuery, t_max: f32) -> bool {
        match self {
            Model::Mesh { bvh, groups, .. } => {
                #[cfg(target_arch = "x86_64")]
                if let Some(avx) = crate::isa::avx2_lanes() {
                    // SAFETY: an `Avx` exists only where the processor has AVX2.
                    return unsafe { mesh_occludes_avx2(avx, bvh, groups, q, t_max) };
                }
                mesh_occludes(Halves, bvh, groups, q, t_max)
            }
            Model::Shape(shape) => shape.intersect(q, t_max).is_some(),
        }
    }

    #[inline(never)]
    fn crossings(&self, q: &RayQuery, t_max: f32) -> u32 {
        match self {
            Model::Mesh { bvh, groups, .. } => {
                let ray = GroupRay::new(q);
                let mut crossings = 0;
                bvh.visit(q, t_max, |g| {
                    crossings += groups[g as usize].crossings(q, &ray, 0.0, t_max);
                    true
                });
                crossings
            }
            Model::Shape(shape) => shape.crossings(q, t_max),
        }
    }

    /// The surface point of `hit` in the model's space; `local` gives the ray there, which
    /// only a shape needs (a mesh's point comes from its weights).
    #[inline]
    fn surface(&self, local: impl FnOnce() -> RayQuery, hit: &ShapeHit) -> SurfacePoint {
        match (self, hit.detail) {
            (Model::Mesh { mesh, groups, .. }, HitDetail::Mesh { triangle, group, b }) => {
                mesh.surface_of(triangle, &groups[group as usize].corners_of(triangle), b)
            }
            (Model::Shape(shape), _) => shape.surface(&local(), hit),
            (_, detail) => unreachable!("hit {detail:?} does not belong to a mesh"),
        }
    }

    #[inline]
    fn uv(&self, local: impl FnOnce() -> RayQuery, hit: &ShapeHit) -> (f32, f32) {
        match (self, hit.detail) {
            (Model::Mesh { mesh, .. }, HitDetail::Mesh { triangle, b, .. }) => mesh.uv(triangle, b),
            (Model::Shape(shape), _) => shape.uv(&shape.surface(&local(), hit), hit),
            (_, detail) => unreachable!("hit {detail:?} does not belong to a mesh"),
        }
    }

    #[inline]
    fn uv_frame(&self, local: impl FnOnce() -> RayQuery, hit: &ShapeHit) -> UvFrame {
        match (self, hit.detail) {
            (Model::Mesh { mesh, .. }, HitDetail::Mesh { triangle, b, .. }) => {
                mesh.uv_frame(triangle, b)
            }
            (Model::Shape(shape), _) => shape.uv_frame(&shape.surface(&local(), hit), hit),
            (_, detail) => unreachable!("hit {detail:?} does not belong to a mesh"),
        }
    }
}

/// A model placed in the scene by a transform.
#[derive(Clone, Debug)]
pub struct Instance {
    model: Arc<Model>,
    transform: Transform,
    /// Whether `transform` is the identity: then rays, points and their error bounds are
    /// the same in both spaces and need no carrying across (a mesh placed as modelled).
    identity: bool,
    /// The box around it in the scene's space.
    bounds: Aabb,
    /// Whether `transform` only translates.
    translation_only: bool,
}

/// Whether `a` and `b` are the same bits, lane by lane.
#[inline(always)]
fn same_bits(a: Vec3A, b: Vec3A) -> bool {
    a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)
}

impl Instance {
    /// `model` placed by `transform` (from the model's space to the scene's).
    pub fn new(model: Arc<Model>, transform: Transform) -> Self {
        let bounds = transform.bounds_to_scene(&model.bounds());
        Self {
            model,
            identity: transform.to_scene() == glam::Affine3A::IDENTITY,
            translation_only: transform.to_scene().matrix3 == glam::Mat3A::IDENTITY,
            transform,
            bounds,
        }
    }

    /// What it places.
    pub fn model(&self) -> &Arc<Model> {
        &self.model
    }

    /// How it is placed: from the model's space to the scene's.
    pub fn transform(&self) -> &Transform {
        &self.transform
    }

    /// The box around it in the scene's space.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The query along `q`'s ray in the model's space.
    #[inline(always)]
    fn local(&self, q: &RayQuery) -> RayQuery {
        let ray: Ray = self.transform.ray_to_object(&q.ray);
        // A placement that moves without turning or scaling (every mesh placed as modelled
        // is one, once the scene is centred on the eye) maps the direction to itself, and
        // what a query derives from its direction alone is then the same: only the origin
        // is new. Compared bit for bit, so a −0 that the map turned into +0 is rebuilt.
        if self.translation_only && same_bits(ray.dir, q.ray.dir) {
            return RayQuery { ray, ..*q };
        }
        RayQuery::new(ray)
    }

    /// The nearest hit with t in (t_min, t_max).
    #[inline]
    pub fn intersect_after(&self, q: &RayQuery, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        if self.identity {
            return self.model.intersect_after(q, t_min, t_max);
        }
        self.model.intersect_after(&self.local(q), t_min, t_max)
    }

    /// The nearest hit with t in (0, t_max) among its model's triangles `listed`.
    #[inline]
    pub fn nearest_listed(
        &self,
        q: &RayQuery,
        listed: &[TriangleOctet],
        t_max: f32,
    ) -> Option<ShapeHit> {
        if self.identity {
            return self.model.nearest_listed(q, listed, t_max);
        }
        self.model.nearest_listed(&self.local(q), listed, t_max)
    }

    /// Whether anything of it lies on the segment (0, t_max).
    #[inline]
    pub fn occludes(&self, q: &RayQuery, t_max: f32) -> bool {
        if self.identity {
            return self.model.occludes(q, t_max);
        }
        self.model.occludes(&self.local(q), t_max)
    }

    /// Whether any of its model's triangles `listed` lies on the segment (0, t_max), for a
    /// shadow ray from a point at a squared distance `distance_sq` from the light.
    #[inline]
    pub fn occludes_listed(
        &self,
        q: &RayQuery,
        listed: &[TriangleOctet],
        t_max: f32,
        distance_sq: f32,
    ) -> bool {
        if self.identity {
            return self.model.occludes_listed(q, listed, t_max, distance_sq);
        }
        self.model
            .occludes_listed(&self.local(q), listed, t_max, distance_sq)
    }

    /// How many times the segment (0, t_max) crosses its surface.
    #[inline]
    pub fn crossings(&self, q: &RayQuery, t_max: f32) -> u32 {
        if self.identity {
            return self.model.crossings(q, t_max);
        }
        self.model.crossings(&self.local(q), t_max)
    }

    /// Whether scene point `p` lies inside the solid the model bounds (a shape's; a mesh
    /// has none that this knows of).
    #[inline]
    pub fn contains(&self, p: Vec3A) -> bool {
        match &*self.model {
            Model::Shape(shape) => shape.contains(self.transform.point_to_object(p)),
            Model::Mesh { .. } => false,
        }
    }

    /// The surface point of `hit` in the scene's space, its error bound carried across.
    #[inline]
    pub fn surface(&self, q: &RayQuery, hit: &ShapeHit) -> SurfacePoint {
        let local = self.model.surface(|| self.local(q), hit);
        if self.identity {
            return local;
        }
        let (point, error) = self.transform.point_to_scene(local.point, local.error);
        let normal = self.transform.normal_to_scene(local.normal);
        let shading = if local.shading == local.normal {
            normal
        } else {
            self.transform.normal_to_scene(local.shading)
        };
        SurfacePoint {
            point,
            error,
            normal,
            shading,
        }
    }

    /// Where shadow rays from `hit` start on a smooth mesh, in the scene's space, with its
    /// error bound ([`Mesh::shadow_point`]); None on anything else.
    #[inline]
    pub fn shadow_point(&self, hit: &ShapeHit) -> Option<(Vec3A, Vec3A)> {
        match (&*self.model, hit.detail) {
            (Model::Mesh { mesh, groups, .. }, HitDetail::Mesh { triangle, group, b }) => {
                let corners = groups[group as usize].corners_of(triangle);
                let (point, error) = mesh.shadow_point_of(triangle, &corners, b)?;
                if self.identity {
                    return Some((point, error));
                }
                Some(self.transform.point_to_scene(point, error))
            }
            _ => None,
        }
    }

    /// The texture coordinates of `hit`, from the model's own surface (a turned sphere's
    /// map turns with it).
    #[inline]
    pub fn uv(&self, q: &RayQuery, hit: &ShapeHit) -> (f32, f32) {
        self.model.uv(|| self.local(q), hit)
    }

    /// The texture coordinates of `hit` and their tangents, carried into the scene's space.
    #[inline]
    pub fn uv_frame(&self, q: &RayQuery, hit: &ShapeHit) -> UvFrame {
        self.model
            .uv_frame(|| self.local(q), hit)
            .mapped(|v| self.transform.vector_to_scene(v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Sphere;
    use glam::{Vec2, Vec3};

    fn unit_cube_mesh() -> Mesh {
        let p: Vec<Vec3> = (0..8)
            .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
            .collect();
        // Outward-wound faces.
        let quads = [
            [0, 2, 3, 1], // z = 0
            [4, 5, 7, 6], // z = 1
            [0, 1, 5, 4], // y = 0
            [2, 6, 7, 3], // y = 1
            [0, 4, 6, 2], // x = 0
            [1, 3, 7, 5], // x = 1
        ];
        let tris = quads
            .iter()
            .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
            .collect();
        Mesh::new(p, Vec::new(), Vec::<Vec2>::new(), tris).unwrap()
    }

    /// A placement that only translates takes a ray into the model's space as any other
    /// does: the same query, field by field and bit for bit, with zero components of
    /// either sign in the direction.
    #[test]
    fn a_translated_query_is_the_query_rebuilt() {
        let model = Arc::new(Model::mesh(&unit_cube_mesh()));
        let moved = Transform::new(glam::Affine3A::from_translation(Vec3::new(
            0.0, -5.0, -22.0,
        )));
        let instance = Instance::new(model, moved.unwrap());
        assert!(instance.translation_only && !instance.identity);
        let bits = |q: &RayQuery| {
            let v = |v: Vec3A| v.to_array().map(f32::to_bits);
            (
                v(q.ray.origin),
                v(q.ray.dir),
                v(q.inv_dir),
                v(q.shear),
                q.axes,
            )
        };
        for dir in [
            Vec3A::new(0.3, -0.2, -1.0),
            Vec3A::new(-0.0, 0.5, -1.0),
            Vec3A::new(0.0, -0.0, 1.0),
            Vec3A::new(1e-30, -2.0, 0.25),
        ] {
            let q = RayQuery::new(Ray::new(Vec3A::new(0.1, 5.2, 21.7), dir));
            let rebuilt = RayQuery::new(instance.transform.ray_to_object(&q.ray));
            assert_eq!(bits(&instance.local(&q)), bits(&rebuilt), "{dir}");
        }
    }

    /// A mesh's hierarchy finds what a loop over every triangle finds.
    #[test]
    fn mesh_hits_match_brute_force() {
        let mesh = unit_cube_mesh().subdivided().subdivided();
        let model = Model::mesh(&mesh);
        let Model::Mesh { mesh: stored, .. } = &model else {
            unreachable!()
        };
        let mut seed = 7u32;
        let mut next = || {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            (seed >> 8) as f32 / (1 << 24) as f32
        };
        for _ in 0..500 {
            let origin = Vec3::new(next() * 3.0 - 1.0, next() * 3.0 - 1.0, 3.0);
            let target = Vec3::new(next(), next(), next());
            let q = RayQuery::new(Ray::new(origin, target - origin));
            let brute = (0..stored.triangle_count() as u32)
                .filter_map(|i| stored.intersect(i, &q, 0.0, f32::INFINITY))
                .map(|h| h.t)
                .fold(f32::INFINITY, f32::min);
            let fast = model.intersect_after(&q, 0.0, f32::INFINITY).map(|h| h.t);
            assert_eq!(fast, Some(brute));
            // A closed mesh is crossed twice by a ray through it, and occludes it.
            assert_eq!(model.crossings(&q, f32::INFINITY), 2);
            assert!(model.occludes(&q, f32::INFINITY));
        }
    }

    /// A mesh hit names the group that holds its triangle, in either lane engine, and the
    /// surface point made from that group's corners is bit for bit the one made from the
    /// mesh's vertices, on a flat mesh and a smooth one (whose shadow point too).
    #[test]
    fn a_hits_group_holds_its_triangle_and_gives_its_surface() {
        let flat = unit_cube_mesh().subdivided().subdivided().subdivided();
        let normals: Vec<Vec3> = flat
            .positions()
            .iter()
            .map(|&p| (Vec3::from(p) - Vec3::splat(0.5)).normalize())
            .collect();
        let smooth = Mesh::new(
            flat.positions().iter().map(|&p| p.into()).collect(),
            normals,
            Vec::<Vec2>::new(),
            flat.triangles().to_vec(),
        )
        .unwrap();
        let bits = |v: Vec3A| v.to_array().map(f32::to_bits);
        for mesh in [flat, smooth] {
            let model = Model::mesh(&mesh);
            let Model::Mesh {
                mesh: stored,
                bvh,
                groups,
            } = &model
            else {
                unreachable!()
            };
            let mut seed = 11u32;
            let mut next = || {
                seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
                (seed >> 8) as f32 / (1 << 24) as f32
            };
            // The groups that come second in a pair of a leaf.
            let mut second_of_pair = vec![false; groups.len()];
            for node in &bvh.nodes {
                for lane in 0..super::super::bvh::WIDTH {
                    if let super::super::bvh::Child::Leaf(range) = node.child(lane) {
                        for g in range.skip(1).step_by(2) {
                            second_of_pair[g as usize] = true;
                        }
                    }
                }
            }
            let mut seconds = 0;
            for _ in 0..2000 {
                let origin = Vec3::new(next() * 3.0 - 1.0, next() * 3.0 - 1.0, 3.0);
                let target = Vec3::new(next(), next(), next());
                let q = RayQuery::new(Ray::new(origin, target - origin));
                let portable = mesh_closest(Halves, bvh, groups, &q, 0.0, f32::INFINITY);
                #[cfg(target_arch = "x86_64")]
                if let Some(avx) = crate::isa::avx2_lanes() {
                    // SAFETY: an `Avx` exists only where the processor has AVX2.
                    let wide =
                        unsafe { mesh_closest_avx2(avx, bvh, groups, &q, 0.0, f32::INFINITY) };
                    assert_eq!(wide, portable);
                }
                let hit = portable.expect("every ray aims into the cube");
                let HitDetail::Mesh { triangle, group, b } = hit.detail else {
                    unreachable!()
                };
                let holder = &groups[group as usize];
                assert!(holder.triangles().contains(&triangle));
                seconds += second_of_pair[group as usize] as u32;
                let from_group = model.surface(|| q, &hit);
                let from_vertices = stored.surface(triangle, b);
                assert_eq!(bits(from_group.point), bits(from_vertices.point));
                assert_eq!(bits(from_group.error), bits(from_vertices.error));
                assert_eq!(bits(from_group.normal), bits(from_vertices.normal));
                assert_eq!(bits(from_group.shading), bits(from_vertices.shading));
                let instance = Instance::new(
                    Arc::new(model.clone()),
                    Transform::new(glam::Affine3A::IDENTITY).unwrap(),
                );
                assert_eq!(
                    instance.shadow_point(&hit).map(|(p, e)| (bits(p), bits(e))),
                    stored
                        .shadow_point(triangle, b)
                        .map(|(p, e)| (bits(p), bits(e)))
                );
            }
            // Hits in a leaf's second group were among them.
            assert!(seconds > 100, "{seconds}");
        }
    }

    /// Every triangle of a mesh is in exactly one group, each group in one leaf of at most
    /// two groups, inside that leaf's box; groups are full but for a leaf's last.
    #[test]
    fn a_meshs_leaves_hold_its_triangles_in_groups_once() {
        use super::super::bvh::Child;
        let model = Model::mesh(&unit_cube_mesh().subdivided().subdivided().subdivided());
        let Model::Mesh { mesh, bvh, groups } = &model else {
            unreachable!()
        };
        let mut seen = vec![0u32; mesh.triangle_count()];
        for node in &bvh.nodes {
            for lane in 0..super::super::bvh::WIDTH {
                let Child::Leaf(range) = node.child(lane) else {
                    continue;
                };
                assert!(range.len() <= GROUPED.max / GROUP_WIDTH, "{range:?}");
                let b = node.bounds(lane);
                for (k, g) in range.clone().enumerate() {
                    let triangles = groups[g as usize].triangles();
                    if k + 1 < range.len() {
                        assert_eq!(triangles.len(), GROUP_WIDTH);
                    }
                    for t in triangles {
                        seen[t as usize] += 1;
                        assert_eq!(b.union(mesh.triangle_bounds(t)), b);
                    }
                }
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
        // The SAH fills groups: far fewer groups than triangles.
        assert!(
            groups.len() * 3 < mesh.triangle_count() * 2,
            "{}",
            groups.len()
        );
    }

    /// Placed by the identity, an instance skips carrying rays and points across spaces
    /// (`identity`); it finds what carrying them finds, with an error bound no wider.
    #[test]
    fn an_unplaced_instance_finds_what_a_placed_one_does() {
        let model = Arc::new(Model::mesh(&unit_cube_mesh().subdivided()));
        let identity = Transform::new(glam::Affine3A::IDENTITY).unwrap();
        let fast = Instance::new(model.clone(), identity);
        assert!(fast.identity);
        let carried = Instance {
            identity: false,
            ..fast.clone()
        };
        let mut seed = 11u32;
        let mut next = || {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            (seed >> 8) as f32 / (1 << 24) as f32
        };
        let mut hits = 0;
        for _ in 0..500 {
            let origin = Vec3::new(next() * 4.0 - 1.5, next() * 4.0 - 1.5, 3.0);
            let target = Vec3::new(next(), next(), next());
            let q = RayQuery::new(Ray::new(origin, target - origin));
            let (a, b) = (
                fast.intersect_after(&q, 0.0, f32::INFINITY),
                carried.intersect_after(&q, 0.0, f32::INFINITY),
            );
            assert_eq!(a.map(|h| (h.t, h.detail)), b.map(|h| (h.t, h.detail)));
            assert_eq!(fast.occludes(&q, 10.0), carried.occludes(&q, 10.0));
            assert_eq!(fast.crossings(&q, 10.0), carried.crossings(&q, 10.0));
            if let Some(hit) = a {
                hits += 1;
                let (s, t) = (fast.surface(&q, &hit), carried.surface(&q, &hit));
                assert_eq!((s.point, s.normal), (t.point, t.normal));
                assert!(s.error.cmple(t.error).all(), "{} {}", s.error, t.error);
            }
        }
        assert!(hits > 100, "{hits}");
    }

    /// A sphere scaled by (2, 1, 1) is an ellipsoid: hit where x²/4 + y² + z² = 1, with
    /// the normal of that surface.
    #[test]
    fn scaled_sphere_is_an_ellipsoid() {
        let model = Arc::new(Model::Shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0))));
        let t = Transform::from_scale_rotation_translation(
            Vec3::new(2.0, 1.0, 1.0),
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, -10.0),
        )
        .unwrap();
        let instance = Instance::new(model, t);
        // Along x at height y = 0.6: x = ±2·0.8.
        let q = RayQuery::new(Ray::new(Vec3::new(-5.0, 0.6, -10.0), Vec3::X));
        let hit = instance.intersect_after(&q, 0.0, f32::INFINITY).unwrap();
        assert!((hit.t - (5.0 - 1.6)).abs() < 1e-5, "{}", hit.t);
        let s = instance.surface(&q, &hit);
        assert!((s.point - Vec3A::new(-1.6, 0.6, -10.0)).length() < 1e-5);
        // The gradient of x²/4 + y² + z² is (x/2, 2y, 2z).
        let expected = Vec3A::new(-0.8, 1.2, 0.0).normalize();
        assert!((s.normal - expected).length() < 1e-5, "{}", s.normal);
        assert!(s.error.cmpge(Vec3A::ZERO).all() && s.error.max_element() < 1e-4);
        assert_eq!(instance.crossings(&q, f32::INFINITY), 2);
        let b = instance.bounds();
        assert!(b.min.x <= -2.0 && b.max.x >= 2.0 && b.max.y < 1.01);
    }
}
