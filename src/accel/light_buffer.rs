//! What a shadow ray can meet on its way to a point light, looked up by its direction as
//! seen from the light.
//!
//! Every shadow ray toward a point light ends at the light, so the primitives that can
//! block it are known before it is traced: those whose bounding box, seen from the light,
//! covers its direction. This is the light buffer of Haines and Greenberg (1986): a cube
//! around each light, each face divided into cells, each cell listing the primitives whose
//! boxes it sees, nearest box first. A shadow ray stops reading its list at the first box
//! that starts beyond its own far end (its shading point), and a ray whose list is empty
//! up to there reaches the light without a single test. On the seed scene most shadow rays
//! start on the floor under an empty sky (docs/benchmarks/README.md). Cells that too many
//! boxes cover fall back to the BVH. A placed mesh is one box here; its triangles are
//! listed in finer cells of its own (shadow_listing.rs), so that a shadow ray that reaches
//! it need not walk its hierarchy either.

use super::instance::{Instance, Model};
use super::light_faces::{
    CROWDED, FACES, FaceView, Seen, Window, farthest, lower_bound_distance_sq,
};
use super::primitive::{Primitive, Surface};
use super::shadow_listing::{ListingSource, Listings, MAX_LISTED_TRIANGLES, MeshShadowListing};
use crate::geometry::TriangleOctet;
use glam::{DVec3, Vec3};
use std::sync::Arc;

/// Cells along each side of a cube face.
pub const FACE_CELLS: u32 = 64;

/// A cell covered by more boxes than this is left to the BVH.
pub const MAX_OCCLUDERS: usize = 16;

/// One primitive that shadow rays through a cell may meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Occluder {
    /// Index into `PreparedScene::primitives`.
    pub primitive: u32,
    /// The object the primitive belongs to.
    pub object: u32,
    /// No point of the primitive lies nearer to the light than the square root of this: the
    /// squared distance from the light to its box, rounded down by a relative 10⁻⁴ to cover
    /// the rounding of a shadow ray's computed length.
    pub min_distance_sq: f32,
    /// Which of the buffer's meshes listed triangle by triangle the primitive is
    /// (`LightBuffer::triangles`); `UNLISTED` for any other primitive.
    pub triangles: u32,
}

/// `Occluder::triangles` of a primitive whose triangles are not listed.
pub const UNLISTED: u32 = u32::MAX;

/// The cube of cells around one point light.
#[derive(Clone, Debug)]
pub struct LightBuffer {
    /// Each cell's occluders, as a range of `occluders`; `CROWDED` for a cell covered by
    /// more than `MAX_OCCLUDERS` boxes, left to the BVH.
    cells: Vec<(u32, u32)>,
    occluders: Vec<Occluder>,
    /// Where each face's grid of cells lies.
    windows: [Window; FACES],
    /// The placed meshes listed triangle by triangle (`Occluder::triangles`).
    meshes: Vec<Arc<MeshShadowListing>>,
    /// The light the buffer was built around.
    position: Vec3,
}

impl LightBuffer {
    /// The lists around a light at `position` for `primitives`; with `mesh_triangles`, the
    /// triangles of each placed mesh listed by its own finer cells too, taken from `made`
    /// where it holds them.
    pub(super) fn new(
        position: Vec3,
        primitives: &[Primitive],
        mesh_triangles: bool,
        made: &Listings,
    ) -> Self {
        let r = FACE_CELLS as usize;
        let cell_count = FACES * r * r;
        let light = position.as_dvec3();
        let boxes: Vec<(DVec3, DVec3)> = primitives
            .iter()
            .map(|p| {
                let b = p.surface.bounds();
                (b.min.as_dvec3(), b.max.as_dvec3())
            })
            .collect();
        let farthest = farthest(light, boxes.iter().copied());

        // How each box looks through each face, then each face's window around them.
        let views: Vec<[Option<FaceView>; FACES]> = boxes
            .iter()
            .map(|(lo, hi)| {
                std::array::from_fn(|face| FaceView::new(*lo, *hi, light, face, farthest))
            })
            .collect();
        let windows: [Window; FACES] = std::array::from_fn(|face| {
            let seen = views
                .iter()
                .filter_map(|v| Some(v[face].as_ref()?.tangents));
            Window::around(seen, |_| FACE_CELLS)
        });

        // The lists' total length, before any is made: past the budget, crowds of
        // overlapping boxes (thousands at one spot) would cost time and memory that grow
        // with their square, and every cell would be left to the BVH anyway.
        let listed: u64 = views
            .iter()
            .flat_map(|faces| faces.iter().enumerate())
            .filter_map(|(face, view)| {
                let (u0, v0, u1, v1) = view.as_ref()?.cells(&windows[face]);
                Some((u1 - u0 + 1) as u64 * (v1 - v0 + 1) as u64)
            })
            .sum();
        let budget = (MAX_OCCLUDERS * cell_count) as u64
            + crate::limits::LISTINGS_PER_PRIMITIVE * boxes.len() as u64;
        if listed > budget {
            return Self {
                cells: vec![CROWDED; cell_count],
                occluders: Vec::new(),
                windows,
                meshes: Vec::new(),
                position,
            };
        }

        let (meshes, listing_of) = if mesh_triangles {
            list_meshes(primitives, light, farthest, made)
        } else {
            (Vec::new(), vec![UNLISTED; primitives.len()])
        };
        let mut per_cell: Vec<Vec<Occluder>> = vec![Vec::new(); cell_count];
        for (index, ((lo, hi), faces)) in boxes.iter().zip(&views).enumerate() {
            let box_distance_sq = lower_bound_distance_sq(light, *lo, *hi);
            let triangles = listing_of[index];
            for (face, view) in faces.iter().enumerate() {
                let Some(view) = view else { continue };
                let window = &windows[face];
                let (u0, v0, u1, v1) = view.cells(window);
                for v in v0..=v1 {
                    for u in u0..=u1 {
                        per_cell[cell_index(face, u, v)].push(Occluder {
                            primitive: index as u32,
                            object: primitives[index].object,
                            min_distance_sq: view.key_within(window, u, v, box_distance_sq),
                            triangles,
                        });
                    }
                }
            }
        }

        let mut cells = Vec::with_capacity(cell_count);
        let mut occluders = Vec::new();
        for mut list in per_cell {
            if list.len() > MAX_OCCLUDERS {
                cells.push(CROWDED);
            } else {
                // Stable, so equal distances keep the primitives' order.
                list.sort_by(|a, b| a.min_distance_sq.total_cmp(&b.min_distance_sq));
                let start = occluders.len() as u32;
                occluders.extend_from_slice(&list);
                cells.push((start, occluders.len() as u32));
            }
        }
        Self {
            cells,
            occluders,
            windows,
            meshes,
            position,
        }
    }

    /// The light the buffer was built around.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// The placed meshes listed triangle by triangle.
    pub(super) fn mesh_listings(&self) -> &[Arc<MeshShadowListing>] {
        &self.meshes
    }

    /// The occluders a shadow ray may meet on the segment from the light to a point at
    /// `from_light` from it, nearest box first; None when its cell is left to the BVH (or
    /// the point is the light itself).
    #[inline]
    pub fn at(&self, from_light: Vec3) -> Option<&[Occluder]> {
        Some(self.look_up(from_light)?.0)
    }

    /// `at`, and how the light sees the direction, for `triangles`.
    #[inline(always)]
    pub(super) fn look_up(&self, from_light: Vec3) -> Option<(&[Occluder], Seen)> {
        let seen = Seen::new(from_light)?;
        let Some((u, v)) = self.windows[seen.face].cell_of(seen.tangents) else {
            // Outside the window: no box is seen in this direction.
            return Some((&[], seen));
        };
        let (start, end) = self.cells[cell_index(seen.face, u, v)];
        // A crowded cell's range is empty-backwards, which `get` refuses.
        Some((self.occluders.get(start as usize..end as usize)?, seen))
    }

    /// The octets of occluder `occluder`'s triangles (a placed mesh's) that a shadow ray
    /// seen as `seen` may meet, nearest first; None when the mesh is not listed triangle by
    /// triangle there, and its hierarchy answers.
    #[inline(always)]
    pub(super) fn triangles(&self, occluder: &Occluder, seen: Seen) -> Option<&[TriangleOctet]> {
        self.meshes.get(occluder.triangles as usize)?.at(seen)
    }

    /// How many cells there are, and how many are empty, listed and left to the BVH.
    pub fn census(&self) -> LightBufferCensus {
        let mut census = LightBufferCensus::default();
        for &(start, end) in &self.cells {
            census.cells += 1;
            if (start, end) == CROWDED {
                census.crowded += 1;
            } else if start == end {
                census.empty += 1;
            }
        }
        for mesh in &self.meshes {
            let (cells, crowded, octets) = mesh.census();
            census.listed_meshes += 1;
            census.mesh_cells += cells;
            census.mesh_crowded += crowded;
            census.mesh_octets += octets;
        }
        census
    }
}

/// The placed meshes of `primitives` listed triangle by triangle around a light at `light`
/// (no shading point farther from it than `farthest`), built in parallel, and each
/// primitive's index among them (`UNLISTED` for the others). Meshes are taken in the
/// primitives' order while their triangles, counted once per instance, fit in
/// `MAX_LISTED_TRIANGLES`: every instance of a mesh has lists of its own, made unless
/// `made` holds them.
fn list_meshes(
    primitives: &[Primitive],
    light: DVec3,
    farthest: f64,
    made: &Listings,
) -> (Vec<Arc<MeshShadowListing>>, Vec<u32>) {
    use rayon::prelude::*;
    let mut left = MAX_LISTED_TRIANGLES;
    let chosen: Vec<(usize, &Arc<Instance>)> = primitives
        .iter()
        .enumerate()
        .filter_map(|(index, primitive)| {
            let Surface::Instance(instance) = &primitive.surface else {
                return None;
            };
            let Model::Mesh { mesh, .. } = &**instance.model() else {
                return None;
            };
            let count = mesh.triangle_count();
            (count <= left).then(|| {
                left -= count;
                (index, instance)
            })
        })
        .collect();
    let built: Vec<(usize, Option<Arc<MeshShadowListing>>)> = chosen
        .into_par_iter()
        .map(|(index, instance)| {
            let source = ListingSource::new(instance, light, farthest);
            let listing = match made.get(&source) {
                Some(listing) => Some(listing.clone()),
                None => MeshShadowListing::new(instance, source).map(Arc::new),
            };
            (index, listing)
        })
        .collect();
    let mut listing_of = vec![UNLISTED; primitives.len()];
    let mut meshes = Vec::new();
    for (index, listing) in built {
        if let Some(listing) = listing {
            listing_of[index] = meshes.len() as u32;
            meshes.push(listing);
        }
    }
    (meshes, listing_of)
}

/// How a light buffer's cells are spent (for tests and the bench).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LightBufferCensus {
    /// Cells in all.
    pub cells: usize,
    /// Cells that see no box: lit without a test.
    pub empty: usize,
    /// Cells that see too many boxes, left to the BVH.
    pub crowded: usize,
    /// Placed meshes listed triangle by triangle in cells of their own.
    pub listed_meshes: usize,
    /// Their cells in all.
    pub mesh_cells: usize,
    /// Their cells that see too many triangles, left to the meshes' hierarchies.
    pub mesh_crowded: usize,
    /// The octets of triangles their cells list, in all.
    pub mesh_octets: usize,
}

#[inline]
fn cell_index(face: usize, u: u32, v: u32) -> usize {
    let r = FACE_CELLS as usize;
    face * r * r + v as usize * r + u as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{AccelOptions, Accelerator, Surface};
    use crate::geometry::{Ray, RayQuery, Shape, Sphere};
    use crate::scene::Geometry;

    /// The seed's primitives, and its light.
    fn seed() -> (Accelerator, Vec3) {
        let scene = crate::seed::scene().unwrap();
        let geometry = Geometry::new(&scene, AccelOptions::ALL);
        (
            geometry.accel().clone(),
            scene.lights[0].position().unwrap(),
        )
    }

    /// A small deterministic generator for test points.
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f32 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    /// Shadow rays from points all over `scene`'s box (and a little beyond it) toward each
    /// of `lights`: every primitive a ray meets is listed in its cell, before its far end.
    fn assert_every_occluder_listed(scene: &Accelerator, lights: &[Vec3]) {
        let bounds = scene.bounds().unwrap();
        for &light in lights {
            let buffer = LightBuffer::new(light, scene.primitives(), true, &Listings::new());
            let mut rng = Lcg(7);
            let mut blocked = 0;
            for _ in 0..20_000 {
                let f = Vec3::new(rng.next(), rng.next(), rng.next()) * 1.2 - 0.1;
                let origin = bounds.min + (bounds.max - bounds.min) * f;
                let to_light = light - origin;
                let q = RayQuery::new(Ray::new(origin, to_light));
                let listed = buffer.at(-to_light).expect("no cell is crowded");
                let distance_sq = to_light.length_squared();
                for (i, p) in scene.primitives().iter().enumerate() {
                    if p.surface.intersect(&q, 1.0).is_some() {
                        blocked += 1;
                        let entry = listed.iter().find(|o| o.primitive == i as u32);
                        let entry =
                            entry.unwrap_or_else(|| panic!("{i} missing for {origin} ({light})"));
                        assert!(entry.min_distance_sq < distance_sq);
                    }
                }
                assert!(listed.is_sorted_by(|a, b| a.min_distance_sq <= b.min_distance_sq));
            }
            assert!(
                blocked > 1000,
                "the test must meet occluders: {blocked} ({light})"
            );
        }
    }

    #[test]
    fn every_primitive_a_shadow_ray_meets_is_listed_before_its_far_end() {
        // The seed's light above the scene, one among its objects (boxes straddle its
        // cube's planes), and one far off to the side (a narrow window).
        let (scene, seed_light) = seed();
        let lights = [
            seed_light,
            Vec3::new(0.0, -5.0, -70.0),
            Vec3::new(-900.0, 30.0, 400.0),
        ];
        assert_every_occluder_listed(&scene, &lights);
    }

    /// The three placed bunnies of assets/scenes/bunny.toml on their floor, and the light.
    fn bunnies() -> (Accelerator, Vec3) {
        let scene = crate::accel::tests::bunny_scene();
        let geometry = Geometry::new(&scene, AccelOptions::ALL);
        let light = scene.lights.iter().find_map(|l| l.position()).unwrap();
        (geometry.accel().clone(), light)
    }

    #[test]
    fn every_placed_mesh_a_shadow_ray_meets_is_listed() {
        // Placed meshes, each listed as one occluder: the scene's light, one among the
        // bunnies (their boxes straddle its cube's planes) and one far off.
        let (scene, light) = bunnies();
        let lights = [
            light,
            Vec3::new(-6.0, -8.0, -75.0),
            Vec3::new(700.0, 90.0, -300.0),
        ];
        assert_every_occluder_listed(&scene, &lights);
    }

    #[test]
    fn the_triangles_listed_around_a_light_stay_within_one_budget() {
        // Thirty instances of a bunny (3,674 triangles each): each has lists of its own, so
        // only as many as fit in the budget are listed; the others keep their walks.
        let (scene, light) = bunnies();
        let bunny = scene
            .primitives()
            .iter()
            .find(|p| match &p.surface {
                Surface::Instance(instance) => matches!(**instance.model(), Model::Mesh { .. }),
                _ => false,
            })
            .unwrap();
        let Surface::Instance(instance) = &bunny.surface else {
            unreachable!()
        };
        // In a row along x, each to its own cells of the light buffer.
        let herd: Vec<Primitive> = (0..30)
            .map(|i| {
                let shift = glam::Affine3A::from_translation(Vec3::new(i as f32 * 12.0, 0.0, 0.0));
                let transform = instance.transform().then(shift).unwrap();
                Primitive {
                    surface: Surface::Instance(std::sync::Arc::new(Instance::new(
                        instance.model().clone(),
                        transform,
                    ))),
                    ..bunny.clone()
                }
            })
            .collect();
        let census = LightBuffer::new(light, &herd, true, &Listings::new()).census();
        assert_eq!(
            census.listed_meshes,
            MAX_LISTED_TRIANGLES / 3674,
            "{census:?}"
        );
        assert!(census.mesh_octets > 1000, "{census:?}");
        let census = LightBuffer::new(light, &herd, false, &Listings::new()).census();
        assert_eq!((census.listed_meshes, census.mesh_octets), (0, 0));
    }

    #[test]
    fn a_far_light_spends_its_cells_on_the_scene() {
        // 25 beads in a 10 × 10 patch 1000 units from the light: a 0.01 wide patch of
        // tangents, a third of one cell of the whole face. The face's window fits round the
        // patch, so the beads spread over many cells and none is crowded.
        let beads: Vec<Primitive> = (0..25)
            .map(|i| Primitive {
                surface: Surface::Shape(Shape::Sphere(Sphere::new(
                    Vec3::new(
                        (i % 5) as f32 * 2.0 - 4.0,
                        (i / 5) as f32 * 2.0 - 4.0,
                        -1000.0,
                    ),
                    0.5,
                ))),
                object: i,
                material: i,
            })
            .collect();
        let buffer = LightBuffer::new(Vec3::ZERO, &beads, true, &Listings::new());
        let census = buffer.census();
        assert_eq!(census.cells, FACES * (FACE_CELLS * FACE_CELLS) as usize);
        assert_eq!(census.crowded, 0, "{census:?}");
        let face = (FACE_CELLS * FACE_CELLS) as usize;
        let used = census.cells - census.empty;
        assert!(used > face / 4 && used <= face, "{census:?}");
        // Each bead's own direction finds it, alone or nearly so; between them, nothing.
        for (i, bead) in beads.iter().enumerate() {
            let Surface::Shape(Shape::Sphere(sphere)) = bead.surface else {
                unreachable!()
            };
            let listed = buffer.at(sphere.center.into()).unwrap();
            assert!(listed.iter().any(|o| o.primitive == i as u32));
            assert!(listed.len() <= 4, "{listed:?}");
        }
        assert_eq!(buffer.at(Vec3::new(1.0, 1.0, -1000.0)).unwrap(), &[]);
        assert_eq!(buffer.at(Vec3::new(0.0, 0.0, 1000.0)).unwrap(), &[]);
        // The seed's light sees its scene with no crowded cell either.
        let (scene, light) = seed();
        let census = LightBuffer::new(light, scene.primitives(), true, &Listings::new()).census();
        assert_eq!(census.crowded, 0, "{census:?}");
    }

    #[test]
    fn a_box_around_the_light_is_listed_in_every_cell() {
        let light = Vec3::new(1.0, 2.0, 3.0);
        let around = Primitive {
            surface: Surface::Shape(Shape::Sphere(Sphere::new(
                light + Vec3::new(0.5, 0.0, 0.0),
                2.0,
            ))),
            object: 0,
            material: 0,
        };
        let buffer = LightBuffer::new(light, &[around], true, &Listings::new());
        let census = buffer.census();
        assert_eq!((census.empty, census.crowded), (0, 0));
        let listed = buffer.at(Vec3::new(-3.0, 0.1, 0.2)).unwrap();
        assert_eq!(listed[0].min_distance_sq, 0.0);
    }

    #[test]
    fn directions_on_face_edges_and_corners_find_the_box_they_point_at() {
        // Small spheres placed exactly on the diagonals between faces, and along the axes.
        let light = Vec3::ZERO;
        let mut directions = Vec::new();
        for x in [-1.0f32, 0.0, 1.0] {
            for y in [-1.0f32, 0.0, 1.0] {
                for z in [-1.0f32, 0.0, 1.0] {
                    if (x, y, z) != (0.0, 0.0, 0.0) {
                        directions.push(Vec3::new(x, y, z));
                    }
                }
            }
        }
        let primitives: Vec<Primitive> = directions
            .iter()
            .map(|d| Primitive {
                surface: Surface::Shape(Shape::Sphere(Sphere::new(*d * 10.0, 0.01))),
                object: 0,
                material: 0,
            })
            .collect();
        let buffer = LightBuffer::new(light, &primitives, true, &Listings::new());
        for (i, d) in directions.iter().enumerate() {
            let listed = buffer.at(*d * 20.0).unwrap();
            assert!(listed.iter().any(|o| o.primitive == i as u32), "{d}");
        }
    }

    #[test]
    fn the_light_itself_and_non_finite_directions_have_no_cell() {
        let (scene, light) = seed();
        let buffer = LightBuffer::new(light, scene.primitives(), true, &Listings::new());
        assert!(buffer.at(Vec3::ZERO).is_none());
        assert!(buffer.at(Vec3::new(f32::INFINITY, 0.0, 1.0)).is_none());
        assert!(buffer.at(Vec3::new(f32::NAN, 0.0, 1.0)).is_none());
    }
}
