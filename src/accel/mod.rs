//! The acceleration layer: everything that finds what a ray meets, behind two queries.
//!
//! - [`Accelerator::nearest_hit`]: the nearest surface along a ray, from anywhere, from
//!   inside an isolated solid, or from the eye through a first-hit tile.
//! - [`Accelerator::light_reaching`]: the fraction of a point light's light that reaches a
//!   point, through the light's buffer or the BVH.
//!
//! Which shortcuts exist is decided when the layer is built ([`AccelOptions`]); the
//! integrator asks the same two questions either way and gets the same answers.
//!
//! ```text
//! primitives ──build──▶ BVH (bvh.rs, bvh_build.rs)
//!                       isolated solids (isolated.rs)
//!                       one light buffer per light (light_buffer.rs), its meshes'
//!                         triangles listed in cells of their own (shadow_listing.rs)
//! camera + image size ──view──▶ first-hit tiles (first_hit.rs)
//! ```

mod bvh;
mod bvh_bins;
mod bvh_build;
mod collapse_plan;
mod csg;
mod csg_members;
mod first_hit;
mod instance;
mod isolated;
mod light_buffer;
mod light_faces;
mod mesh_listing;
mod mesh_search;
mod outline;
mod primitive;
mod projected_triangle;
mod shadow_listing;
mod tile_projection;
mod wide_node;

pub use bvh::{Bvh, Coincident};
pub use csg::{Csg, CsgLeaf, CsgNode, CsgOperation};
pub use first_hit::{Candidate, FirstHitTiles, TileCensus};
pub use instance::{Instance, Model};
pub use light_buffer::{LightBuffer, LightBufferCensus, Occluder};
pub use primitive::{CSG_MEMBERS_MATERIAL, Primitive, Surface};

/// The most candidates a first-hit tile lists before it is left to the BVH.
pub use first_hit::MAX_CANDIDATES;
/// The most occluders a light-buffer cell lists before it is left to the BVH.
pub use light_buffer::MAX_OCCLUDERS;

use crate::appearance::ShadowFilters;
use crate::camera::CameraRays;
use crate::geometry::{Aabb, Ray, RayQuery, ShapeHit, SurfacePoint, TriangleOctet, UvFrame};
use glam::{Vec3, Vec3A};
use shadow_listing::Listings;
use std::sync::Arc;

/// Which shortcuts the layer builds. Every one leaves every image unchanged
/// (tests/optimizations.rs); turning one off is for measuring what it buys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccelOptions {
    /// A BVH over the primitives, and hierarchies inside a CSG solid of many members;
    /// off, every ray tests every primitive (one leaf) and every member.
    pub bvh: bool,
    /// Primary rays look up what they can hit first by tile (first_hit.rs).
    pub first_hit_tiles: bool,
    /// The first-hit tiles list a placed mesh's triangles, so that a primary ray tests
    /// those rather than walking the mesh's hierarchy (mesh_listing.rs).
    pub mesh_triangles: bool,
    /// Shadow rays look up what they may meet by their direction from the light
    /// (light_buffer.rs).
    pub light_buffers: bool,
    /// The light buffers list a placed mesh's triangles by finer cells of its own, so that
    /// a shadow ray tests those rather than walking the mesh's hierarchy
    /// (shadow_listing.rs).
    pub light_triangles: bool,
    /// A ray inside an isolated solid tests only that solid (isolated.rs).
    pub isolated_solids: bool,
    /// In a scene where no surface transmits light, a shadow ray stops at the first
    /// occluder without looking at materials.
    pub any_hit_shadows: bool,
}

impl Default for AccelOptions {
    fn default() -> Self {
        Self::ALL
    }
}

impl AccelOptions {
    /// Every shortcut on: what renders use.
    pub const ALL: AccelOptions = AccelOptions {
        bvh: true,
        first_hit_tiles: true,
        mesh_triangles: true,
        light_buffers: true,
        light_triangles: true,
        isolated_solids: true,
        any_hit_shadows: true,
    };
}

/// Where a shadow ray goes: to a point light, or away along a direction to a light
/// infinitely far off.
#[derive(Clone, Copy, Debug)]
pub enum Toward {
    /// A point light at this position; the ray ends there.
    Point(Vec3A),
    /// A directional light, this unit direction away (against the way its light travels).
    Direction(Vec3A),
}

/// The nearest surface a ray meets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Where along the ray, and which part of the shape.
    pub shape: ShapeHit,
    /// Index of the primitive hit, for [`Accelerator::primitive`].
    pub primitive: u32,
}

/// What is known, before a ray is traced, about what it can hit first.
#[derive(Clone, Copy, Debug)]
pub enum Reach<'a> {
    /// Anything beyond this distance.
    After(f32),
    /// The ray starts inside this primitive, an isolated solid
    /// ([`Accelerator::isolated_solid`]), and its hit beyond `t_min` is on it, unless its
    /// origin was not inside after all; then anything beyond `t_min`.
    Inside {
        /// The solid's primitive.
        solid: u32,
        /// Hits at or before this distance do not count.
        t_min: f32,
    },
    /// A primary ray that can only hit these first, nearest box first (a first-hit tile);
    /// an empty list means it hits nothing. The triangles the candidates list are in the
    /// second slice ([`Candidate::listed`]).
    Among(&'a [Candidate], &'a [TriangleOctet]),
}

/// The primitives of a scene and every structure built to find what rays meet among them.
#[derive(Clone, Debug)]
pub struct Accelerator {
    /// In the BVH's order: its leaves index into this.
    primitives: Vec<Primitive>,
    bvh: Bvh,
    /// For each object, its primitive when the object is an isolated solid.
    isolated: Vec<Option<u32>>,
    /// The most surfaces that share one centre (see `largest_coincident`), and their
    /// object.
    coincident: (u32, u32),
    /// One per point light, by the light's index (none for a directional light, and none
    /// without the option).
    light_buffers: Vec<Option<LightBuffer>>,
    options: AccelOptions,
}

impl Accelerator {
    /// Builds the layer over `primitives` (of `object_count` objects) for lights at
    /// `lights` (a point light's position; None for a light with no position).
    pub fn build(
        primitives: Vec<Primitive>,
        object_count: usize,
        lights: &[Option<Vec3>],
        options: AccelOptions,
    ) -> Self {
        Self::build_reusing(primitives, object_count, lights, options, None)
    }

    /// `build`, taking from `previous` (the layer of the scene before an edit) each placed
    /// mesh's lists around a light wherever neither has changed: an edit that moves one
    /// light or one mesh lists only what it moved again. The lists are the same either way.
    pub fn build_reusing(
        primitives: Vec<Primitive>,
        object_count: usize,
        lights: &[Option<Vec3>],
        options: AccelOptions,
        previous: Option<&Accelerator>,
    ) -> Self {
        let bounds: Vec<Aabb> = primitives.iter().map(|p| p.surface.bounds()).collect();
        let (mut bvh, order) = Bvh::build(&bounds);
        let primitives: Vec<Primitive> = order
            .iter()
            .map(|&i| primitives[i as usize].clone())
            .collect();
        let isolated = if options.isolated_solids {
            isolated::isolated_solids(&primitives, &bvh, object_count)
        } else {
            vec![None; object_count]
        };
        let coincident = largest_coincident(&primitives, bvh.coincident);
        if !options.bvh
            && let Some(bounds) = bvh.bounds
        {
            bvh = Bvh::single_leaf(bounds, primitives.len() as u32);
        }
        // One light's buffer at a time would leave a core idle while a buffer lists a
        // single mesh's triangles.
        let light_buffers = if options.light_buffers {
            use rayon::prelude::*;
            let made: Listings = previous
                .into_iter()
                .flat_map(|p| p.light_buffers.iter().flatten())
                .flat_map(|buffer| buffer.mesh_listings())
                .map(|listing| (listing.source().clone(), listing.clone()))
                .collect();
            lights
                .par_iter()
                .map(|light| {
                    light.map(|position| {
                        LightBuffer::new(position, &primitives, options.light_triangles, &made)
                    })
                })
                .collect()
        } else {
            Vec::new()
        };
        Self {
            primitives,
            bvh,
            isolated,
            coincident,
            light_buffers,
            options,
        }
    }

    /// The options the layer was built with.
    pub fn options(&self) -> AccelOptions {
        self.options
    }

    /// Primitive `index`, as a [`Hit`] names it.
    #[inline]
    pub fn primitive(&self, index: u32) -> &Primitive {
        &self.primitives[index as usize]
    }

    /// The surface point of `hit`, found along `q`: where shading happens.
    #[inline]
    pub fn surface(&self, q: &RayQuery, hit: &Hit) -> SurfacePoint {
        self.primitives[hit.primitive as usize]
            .surface
            .surface(q, &hit.shape)
    }

    /// Where shadow rays from `hit` start, with its error bound, when that is not the
    /// surface point: on a smooth mesh, the point lifted onto its corners' tangent planes
    /// (Hanika 2021, "Hacking the shadow terminator").
    #[inline]
    pub fn shadow_point(&self, hit: &Hit) -> Option<(Vec3A, Vec3A)> {
        self.primitives[hit.primitive as usize]
            .surface
            .shadow_point(&hit.shape)
    }

    /// The texture coordinates of `surface`, the surface point of `hit` along `q`.
    #[inline]
    pub fn uv(&self, q: &RayQuery, surface: &SurfacePoint, hit: &Hit) -> (f32, f32) {
        self.primitives[hit.primitive as usize]
            .surface
            .uv(q, surface, &hit.shape)
    }

    /// The texture coordinates of `surface` (the surface point of `hit` along `q`) and
    /// their tangents, for relief.
    #[inline]
    pub fn uv_frame(&self, q: &RayQuery, surface: &SurfacePoint, hit: &Hit) -> UvFrame {
        self.primitives[hit.primitive as usize]
            .surface
            .uv_frame(q, surface, &hit.shape)
    }

    /// The object `hit` is on, and the material its surface takes as the appearance numbers
    /// them (the object's own, or a CSG member's): one look at the primitive for both.
    #[inline]
    pub fn object_and_material(&self, hit: &Hit) -> (u32, u32) {
        let primitive = &self.primitives[hit.primitive as usize];
        let material = match primitive.material {
            CSG_MEMBERS_MATERIAL => match &primitive.surface {
                Surface::Csg(csg) => csg.material_slot(&hit.shape),
                _ => unreachable!("only a combination's members name their materials"),
            },
            own => own,
        };
        (primitive.object, material)
    }

    /// The object `hit` is on.
    #[inline]
    pub fn object(&self, hit: &Hit) -> u32 {
        self.primitives[hit.primitive as usize].object
    }

    /// Every primitive, in the order hits name them.
    pub fn primitives(&self) -> &[Primitive] {
        &self.primitives
    }

    /// The box around every primitive; None for an empty scene.
    pub fn bounds(&self) -> Option<Aabb> {
        self.bvh.bounds
    }

    /// The most surfaces that share one centre, anywhere: the primitives of the scene or
    /// the triangles of one mesh (no split of a hierarchy can part them, so a ray that
    /// reaches them tests each), with the object they are in (or the first of them).
    pub fn largest_coincident(&self) -> (u32, u32) {
        self.coincident
    }

    /// The BVH's node count.
    pub fn bvh_nodes(&self) -> usize {
        self.bvh.nodes.len()
    }

    /// The primitive of `object` when it is an isolated solid: a ray that starts inside
    /// it can ask [`Reach::Inside`].
    #[inline]
    pub fn isolated_solid(&self, object: u32) -> Option<u32> {
        self.isolated[object as usize]
    }

    /// Light `light`'s buffer, when the option built one (point lights only).
    pub fn light_buffer(&self, light: usize) -> Option<&LightBuffer> {
        self.light_buffers.get(light)?.as_ref()
    }

    /// What primary rays of an image of `width` × `height` pixels seen through `rays` can
    /// hit first, by pixel.
    pub fn camera_view(&self, rays: &CameraRays, width: u32, height: u32) -> CameraView {
        CameraView {
            tiles: self.options.first_hit_tiles.then(|| {
                FirstHitTiles::new(
                    &self.primitives,
                    rays,
                    width,
                    height,
                    self.options.mesh_triangles,
                )
            }),
        }
    }

    /// The nearest hit along `q` that `reach` allows.
    #[inline(always)]
    pub fn nearest_hit(&self, q: &RayQuery, reach: Reach) -> Option<Hit> {
        match reach {
            Reach::After(t_min) => self.nearest_after(q, t_min),
            Reach::Inside { solid, t_min } => {
                // Any other primitive's hit would lie on the segment from the origin to
                // this exit, which is inside the solid's box, where no other box comes.
                let shape = &self.primitives[solid as usize].surface;
                match shape.intersect_after(q, t_min, f32::INFINITY) {
                    Some(hit) => Some(Hit {
                        shape: hit,
                        primitive: solid,
                    }),
                    None => self.nearest_after(q, t_min),
                }
            }
            Reach::Among(candidates, listed) => self.nearest_among(q, candidates, listed),
        }
    }

    /// The nearest hit beyond `t_min`, by traversal.
    #[inline(always)]
    fn nearest_after(&self, q: &RayQuery, t_min: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        self.bvh.closest(q, f32::INFINITY, |i, t_max| {
            let hit = self.primitives[i as usize]
                .surface
                .intersect_after(q, t_min, t_max)?;
            best = Some(Hit {
                shape: hit,
                primitive: i,
            });
            Some(hit.t)
        });
        best
    }

    /// For a ray travelling inside `medium` (an object), beyond `t_min`: the nearest hit on
    /// any other object, and the nearest on `medium`'s own surface, by one traversal. Where
    /// one lies beyond the other by more than `slack` (relative: of the nearer's distance
    /// plus the origin's distance from 0, in units of the direction), it may be left out;
    /// within that, both are found, so that the caller can tell surfaces that touch.
    #[inline]
    pub fn nearest_hits_in_medium(
        &self,
        q: &RayQuery,
        t_min: f32,
        medium: u32,
        slack: f32,
    ) -> (Option<Hit>, Option<Hit>) {
        let scale = q.ray.origin_scale();
        let reach = |t: f32| t + (t + scale) * slack;
        let mut other: Option<Hit> = None;
        let mut own: Option<Hit> = None;
        let mut nearest = f32::INFINITY;
        self.bvh.closest(q, f32::INFINITY, |i, _| {
            let primitive = &self.primitives[i as usize];
            let found = if primitive.object == medium {
                &mut own
            } else {
                &mut other
            };
            let t_max = found
                .map_or(f32::INFINITY, |h| h.shape.t)
                .min(reach(nearest));
            let hit = primitive.surface.intersect_after(q, t_min, t_max)?;
            *found = Some(Hit {
                shape: hit,
                primitive: i,
            });
            nearest = nearest.min(hit.t);
            Some(reach(nearest))
        });
        (other, own)
    }

    /// The nearest hit among `candidates`, which hold every primitive the ray can reach,
    /// sorted by a lower bound of the distance at which it can hit them: the same answer
    /// as a traversal from 0.
    #[inline]
    fn nearest_among(
        &self,
        q: &RayQuery,
        candidates: &[Candidate],
        listed: &[TriangleOctet],
    ) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut t_max = f32::INFINITY;
        for c in candidates {
            if c.min_t >= t_max {
                break; // this box and every later one start beyond the nearest hit
            }
            let shape = &self.primitives[c.primitive as usize].surface;
            let found = match (shape, c.listed(listed)) {
                (Surface::Instance(instance), Some(octets)) => {
                    instance.nearest_listed(q, octets, t_max)
                }
                _ => shape.intersect_after(q, 0.0, t_max),
            };
            if let Some(hit) = found {
                t_max = hit.t;
                best = Some(Hit {
                    shape: hit,
                    primitive: c.primitive,
                });
            }
        }
        best
    }

    /// The fraction of the light of light `light` that reaches `origin`: the shadow ray
    /// from `origin` towards it (`toward`), tinted by every transparent surface it crosses
    /// (`filters`). For a point light, the light's buffer answers where it lists the ray's
    /// direction, else the BVH; both give the same answer. A point light's position must be
    /// where the layer was built to see it (a light that moves is a geometry change).
    ///
    /// `leaving` names the object whose surface the ray starts on, when that object is convex
    /// (a sphere, a closed cylinder, a tetrahedron, a convex polygon; not a mesh) and the ray
    /// leaves it from the outside towards a light on that side (or from either side of a
    /// flat object): the object lies wholly behind the plane tangent at the origin and the
    /// ray cannot meet it again, so the buffer's lists skip it. The BVH path tests it regardless, as the reference.
    #[inline]
    pub fn light_reaching(
        &self,
        light: usize,
        toward: Toward,
        origin: Vec3A,
        leaving: Option<u32>,
        filters: &ShadowFilters,
    ) -> Vec3A {
        let opaque = self.options.any_hit_shadows && !filters.any_transmission();
        match toward {
            Toward::Point(position) => {
                self.point_light_reaching(light, position, origin, leaving, opaque, filters)
            }
            Toward::Direction(dir) => {
                let q = RayQuery::new(Ray::new(origin, dir));
                self.transmittance(&q, f32::INFINITY, opaque, filters)
            }
        }
    }

    /// `light_reaching` for point light `light` at `position`.
    #[inline(always)]
    fn point_light_reaching(
        &self,
        light: usize,
        position: Vec3A,
        origin: Vec3A,
        leaving: Option<u32>,
        opaque: bool,
        filters: &ShadowFilters,
    ) -> Vec3A {
        let to_light = position - origin;
        // The shadow ray ends exactly at the light: t = 1 on (light − origin).
        let shadow = |to_light| RayQuery::new(Ray::new(origin, to_light));
        if let Some(Some(buffer)) = self.light_buffers.get(light)
            && let Some((listed, seen)) = buffer.look_up((-to_light).into())
        {
            debug_assert_eq!(
                buffer.position(),
                Vec3::from(position),
                "light {light} moved"
            );
            let distance_sq = to_light.length_squared();
            let mut light = Vec3A::ONE;
            // The list is nearest box first: a box that starts beyond the origin ends it.
            let due = |o: &Occluder| o.min_distance_sq < distance_sq;
            // The ray is built only once something is due for a test, and outside the loop
            // over the list: inside it, the compiler would build it ahead of every shadow ray.
            let Some(first) = listed
                .iter()
                .position(|o| !due(o) || Some(o.object) != leaving)
            else {
                return light; // only the object the ray leaves
            };
            if !due(&listed[first]) {
                return light; // nothing nearer than the origin
            }
            let q = shadow(to_light);
            for o in &listed[first..] {
                if !due(o) {
                    break;
                }
                if Some(o.object) == leaving {
                    continue;
                }
                if opaque
                    && let Some(triangles) = buffer.triangles(o, seen)
                    && let Surface::Instance(mesh) = &self.primitives[o.primitive as usize].surface
                {
                    if mesh.occludes_listed(&q, triangles, 1.0, distance_sq) {
                        return Vec3A::ZERO;
                    }
                    continue;
                }
                if !self.pass_through(o.primitive, &q, 1.0, opaque, filters, &mut light) {
                    break;
                }
            }
            return light;
        }
        self.transmittance(&shadow(to_light), 1.0, opaque, filters)
    }

    /// The fraction of light that reaches the end of the segment (0, t_max) of `q` by
    /// traversal: zero behind any opaque surface, tinted by every transparent one.
    #[inline]
    fn transmittance(
        &self,
        q: &RayQuery,
        t_max: f32,
        opaque: bool,
        filters: &ShadowFilters,
    ) -> Vec3A {
        let mut light = Vec3A::ONE;
        self.bvh.visit(q, t_max, |i| {
            self.pass_through(i, q, t_max, opaque, filters, &mut light)
        });
        light
    }

    /// Filters `light` by what primitive `i` lets through along the segment (0, t_max);
    /// false once no light is left.
    #[inline(always)]
    fn pass_through(
        &self,
        i: u32,
        q: &RayQuery,
        t_max: f32,
        opaque: bool,
        filters: &ShadowFilters,
        light: &mut Vec3A,
    ) -> bool {
        let prim = &self.primitives[i as usize];
        if opaque {
            if prim.surface.occludes(q, t_max) {
                *light = Vec3A::ZERO;
                return false;
            }
            return true;
        }
        let crossings = prim.surface.crossings(q, t_max);
        if crossings > 0 {
            let filter = filters.of(prim.object);
            for _ in 0..crossings {
                *light *= filter;
            }
            if *light == Vec3A::ZERO {
                return false;
            }
        }
        true
    }
}

/// The largest group of surfaces that share one centre, and its object: among
/// `primitives` (stored in the BVH's order, whose largest group is `top`) or among the
/// triangles of any mesh they place, each model counted once.
fn largest_coincident(primitives: &[Primitive], top: Coincident) -> (u32, u32) {
    let top_object = primitives.get(top.first as usize).map_or(0, |p| p.object);
    let mut seen = std::collections::HashSet::new();
    primitives
        .iter()
        .filter_map(|p| match &p.surface {
            Surface::Instance(instance) => {
                let model = instance.model();
                seen.insert(Arc::as_ptr(model))
                    .then(|| (model.coincident().count, p.object))
            }
            Surface::Shape(_) | Surface::Csg(_) => None,
        })
        .fold(
            (top.count, top_object),
            |a, b| if b.0 > a.0 { b } else { a },
        )
}

/// What primary rays through each pixel of one view can hit first.
#[derive(Clone, Debug)]
pub struct CameraView {
    tiles: Option<FirstHitTiles>,
}

impl CameraView {
    /// What the primary rays through pixel (x, y) can hit first.
    #[inline]
    pub fn reach(&self, x: u32, y: u32) -> Reach<'_> {
        self.reach_run(x, y).0
    }

    /// `reach(x, y)`, and the first column past `x` whose reach may differ: the same reach
    /// serves every pixel of row `y` from `x` up to it (the rest of `x`'s tile), so a
    /// pass looks it up once per run of pixels.
    #[inline]
    pub fn reach_run(&self, x: u32, y: u32) -> (Reach<'_>, u32) {
        match &self.tiles {
            Some(tiles) => match tiles.at_run(x, y) {
                (Some(candidates), end) => (Reach::Among(candidates, tiles.listed()), end),
                (None, end) => (Reach::After(0.0), end),
            },
            None => (Reach::After(0.0), u32::MAX),
        }
    }

    /// The first-hit tiles, when the option built them.
    pub fn tiles(&self) -> Option<&FirstHitTiles> {
        self.tiles.as_ref()
    }
}

#[cfg(test)]
mod tests {
    /// The placed bunnies of assets/scenes/bunny.toml, for the tests of the layers that
    /// treat meshes apart (first-hit tiles, light buffers).
    pub(super) fn bunny_scene() -> crate::scene::Scene {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/bunny.toml");
        crate::scene_file::load_scene(&path).unwrap()
    }
}
