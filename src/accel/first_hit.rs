//! What a primary ray can hit first, looked up by where it crosses the image.
//!
//! Every primary ray leaves the eye, so the primitives it can meet are known before it is
//! traced: those whose bounding box, seen from the eye, covers its pixel. This is the item
//! buffer of Weghorst, Hooper and Greenberg (1984) at the granularity of 8×8-pixel tiles. A
//! tile's list is sorted by the distance from the eye to each box, so the search stops at
//! the first box that lies beyond the nearest hit so far; a tile that no box covers is
//! background without a single test. On the seed scene this replaces the BVH traversal of
//! every primary ray (docs/benchmarks/README.md). Tiles that too many boxes cover fall
//! back to the BVH, which then does better.
//!
//! A primitive is listed only in the tiles its surface may cover, not in its whole box's
//! rectangle: a triangle by its projected outline, a mesh by the rectangles of the boxes of
//! its own hierarchy, down to boxes a few tiles wide. Around a mesh's silhouette the tiles
//! its box covers but no part of it does are then background, with no ray traced.

use super::instance::Instance;
use super::mesh_listing::MeshListing;
use super::outline::{CellRectangle, mesh_coverage};
use super::primitive::{Primitive, Surface};
use super::projected_triangle::ProjectedTriangle;
use super::tile_projection::{ImageProjection, TILE, lower_bound_distance, tile_area};
use crate::camera::CameraRays;
use crate::geometry::{Aabb, Shape, TriangleOctet};

/// A tile covered by more boxes than this is left to the BVH.
pub const MAX_CANDIDATES: usize = 12;

/// One primitive that primary rays through a tile may hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    /// Index into `PreparedScene::primitives`.
    pub primitive: u32,
    /// No hit on the primitive lies nearer to the eye than this, along a unit direction:
    /// the distance from the eye to its box, rounded down by a relative 10⁻⁴ to cover the
    /// rounding of a computed hit distance.
    pub min_t: f32,
    /// For a placed mesh, the triangles that the tile's rays may meet are those of the
    /// octets `FirstHitTiles::listed[listed_start..][..listed_len]`, nearest box first;
    /// none (`listed_len` 0) where its own hierarchy is searched instead.
    pub listed_start: u32,
    /// See `listed_start`.
    pub listed_len: u32,
}

impl Candidate {
    /// Its listed octets among the tiles' `listed`, if it has any.
    #[inline(always)]
    pub fn listed<'a>(&self, listed: &'a [TriangleOctet]) -> Option<&'a [TriangleOctet]> {
        (self.listed_len > 0).then(|| {
            &listed[self.listed_start as usize..(self.listed_start + self.listed_len) as usize]
        })
    }
}

/// For each tile of an image, the primitives a primary ray through it may hit first,
/// nearest box first.
#[derive(Clone, Debug)]
pub struct FirstHitTiles {
    tiles_x: u32,
    tiles_y: u32,
    /// Tile i's candidates are `candidates[start[i]..start[i + 1]]`.
    start: Vec<u32>,
    candidates: Vec<Candidate>,
    /// Tiles covered by more than `MAX_CANDIDATES` boxes, left to the BVH.
    crowded: Vec<bool>,
    /// The triangles of placed meshes listed for tiles, eight to an octet
    /// (`Candidate::listed_start`).
    listed: Vec<TriangleOctet>,
}

impl FirstHitTiles {
    /// The lists for an image of `width` × `height` pixels seen through `rays`; with
    /// `mesh_triangles`, placed meshes list their triangles as well (mesh_listing.rs).
    pub fn new(
        primitives: &[Primitive],
        rays: &CameraRays,
        width: u32,
        height: u32,
        mesh_triangles: bool,
    ) -> Self {
        let tiles_x = width.div_ceil(TILE);
        let tiles_y = height.div_ceil(TILE);
        let tile_count = tiles_x as usize * tiles_y as usize;
        let projection = ImageProjection::new(rays, width, height);
        let eye = projection.eye;

        // A box's tile rectangle (inclusive), or None when no primary ray can reach it.
        let rectangle_of = |b: &Aabb| {
            let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
            if !(lo.is_finite() && hi.is_finite()) {
                Some((0, 0, tiles_x - 1, tiles_y - 1))
            } else {
                projection.box_tiles(lo, hi)
            }
        };
        // Each primitive's.
        let rectangles: Vec<Option<CellRectangle>> = primitives
            .iter()
            .map(|primitive| rectangle_of(&primitive.surface.bounds()))
            .collect();
        // The lists' total length is at most the rectangles' total area. Past the budget,
        // crowds of overlapping boxes would cost time and memory that grow with their
        // square, and every tile would be left to the BVH anyway.
        let listed: u64 = rectangles
            .iter()
            .flatten()
            .map(|&(x0, y0, x1, y1)| (x1 - x0 + 1) as u64 * (y1 - y0 + 1) as u64)
            .sum();
        let budget = (MAX_CANDIDATES * tile_count) as u64
            + crate::limits::LISTINGS_PER_PRIMITIVE * primitives.len() as u64;
        if listed > budget {
            return Self {
                tiles_x,
                tiles_y,
                start: vec![0; tile_count + 1],
                candidates: Vec::new(),
                crowded: vec![true; tile_count],
                listed: Vec::new(),
            };
        }

        // Placed meshes' triangles by tile, where it pays (mesh_listing.rs).
        let listings: Vec<Option<MeshListing>> = primitives
            .iter()
            .zip(&rectangles)
            .map(
                |(primitive, rectangle)| match (&primitive.surface, rectangle) {
                    (Surface::Instance(instance), Some(rectangle)) if mesh_triangles => {
                        MeshListing::new(instance, *rectangle, &projection)
                    }
                    _ => None,
                },
            )
            .collect();
        let mut listed = Vec::with_capacity(
            listings
                .iter()
                .flatten()
                .map(MeshListing::octet_count)
                .sum(),
        );
        let mut per_tile: Vec<Vec<Candidate>> = vec![Vec::new(); tile_count];
        for (index, (primitive, rectangle)) in primitives.iter().zip(&rectangles).enumerate() {
            let bounds = primitive.surface.bounds();
            let (lo, hi) = (bounds.min.as_dvec3(), bounds.max.as_dvec3());
            let Some((x0, y0, x1, y1)) = *rectangle else {
                continue;
            };
            let candidate = Candidate {
                primitive: index as u32,
                min_t: lower_bound_distance(eye, lo, hi),
                listed_start: 0,
                listed_len: 0,
            };
            if let Some(listing) = &listings[index] {
                for ty in y0..=y1 {
                    for tx in x0..=x1 {
                        let mut candidate = candidate;
                        match listing.at(tx, ty) {
                            Some([]) => continue, // nothing of it here
                            Some(triangles) => {
                                let start = listed.len();
                                listing.push_octets(triangles, &mut listed);
                                candidate.listed_start = start as u32;
                                candidate.listed_len = (listed.len() - start) as u32;
                            }
                            None => {} // too many triangles: the walk
                        }
                        per_tile[(ty * tiles_x + tx) as usize].push(candidate);
                    }
                }
                continue;
            }
            // A triangle covers only part of its box's rectangle: half of it, for each of
            // the two triangles of a quad such as the seed's floor. A mesh covers the
            // rectangles of its leaves' boxes.
            let outline = match &primitive.surface {
                Surface::Shape(Shape::Triangle(t)) => {
                    let corners = t.p.map(|p| glam::Vec3::from(p).as_dvec3());
                    projection.triangle(&corners).map(Outline::Triangle)
                }
                Surface::Instance(instance) => {
                    mesh_outline(instance, (x0, y0, x1, y1), rectangle_of)
                }
                _ => None,
            };
            for ty in y0..=y1 {
                for tx in x0..=x1 {
                    if outline.as_ref().is_none_or(|o| o.may_cover_tile(tx, ty)) {
                        per_tile[(ty * tiles_x + tx) as usize].push(candidate);
                    }
                }
            }
        }

        let mut start = Vec::with_capacity(tile_count + 1);
        let mut candidates = Vec::new();
        let mut crowded = vec![false; tile_count];
        start.push(0);
        for (tile, mut list) in per_tile.into_iter().enumerate() {
            if list.len() > MAX_CANDIDATES {
                crowded[tile] = true;
            } else {
                // Stable, so equal distances keep the primitives' order.
                list.sort_by(|a, b| a.min_t.total_cmp(&b.min_t));
                candidates.extend_from_slice(&list);
            }
            start.push(candidates.len() as u32);
        }
        Self {
            tiles_x,
            tiles_y,
            start,
            candidates,
            crowded,
            listed,
        }
    }

    /// The octets of placed meshes' triangles that candidates list (`Candidate::listed`).
    #[inline(always)]
    pub fn listed(&self) -> &[TriangleOctet] {
        &self.listed
    }

    /// The candidates for pixel (x, y), nearest box first; None when the tile is left to
    /// the BVH.
    #[inline]
    pub fn at(&self, x: u32, y: u32) -> Option<&[Candidate]> {
        let (tx, ty) = (x / TILE, y / TILE);
        debug_assert!(tx < self.tiles_x && ty < self.tiles_y);
        let tile = (ty * self.tiles_x + tx) as usize;
        if self.crowded[tile] {
            return None;
        }
        Some(&self.candidates[self.start[tile] as usize..self.start[tile + 1] as usize])
    }

    /// `at(x, y)`, and the first column past `x` that lies in another tile: every pixel of
    /// row `y` before it has the same candidates.
    #[inline]
    pub fn at_run(&self, x: u32, y: u32) -> (Option<&[Candidate]>, u32) {
        (self.at(x, y), (x / TILE + 1) * TILE)
    }

    /// How many tiles there are, how many are empty and left to the BVH, and how many
    /// candidates the listed tiles hold in all.
    pub fn census(&self) -> TileCensus {
        let mut census = TileCensus::default();
        for tile in 0..self.crowded.len() {
            census.tiles += 1;
            if self.crowded[tile] {
                census.crowded += 1;
            } else {
                let list =
                    &self.candidates[self.start[tile] as usize..self.start[tile + 1] as usize];
                census.empty += list.is_empty() as usize;
                census.candidates += list.len();
                for c in list.iter().filter(|c| c.listed_len > 0) {
                    census.listing += 1;
                    census.listed_octets += c.listed_len as usize;
                }
            }
        }
        census
    }
}

/// How a view's first-hit tiles are spent (for tests and the bench).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TileCensus {
    /// Tiles in all.
    pub tiles: usize,
    /// Tiles that no box covers: background without a test.
    pub empty: usize,
    /// Tiles covered by too many boxes, left to the BVH.
    pub crowded: usize,
    /// Candidates summed over the tiles that are not crowded.
    pub candidates: usize,
    /// Those of them that list a placed mesh's triangles (`Candidate::listed`).
    pub listing: usize,
    /// The octets of triangles they list, in all.
    pub listed_octets: usize,
}

/// Where within its box's tile rectangle a primitive's surface may lie, where that is
/// known more tightly than the whole rectangle.
#[derive(Clone, Debug)]
enum Outline {
    /// A triangle's own outline.
    Triangle(ProjectedTriangle),
    /// The tiles of the rectangle whose first corner is (x0, y0), `columns` wide, that the
    /// boxes of a mesh's hierarchy cover, row by row.
    Tiles {
        x0: u32,
        y0: u32,
        columns: u32,
        covered: Vec<bool>,
    },
}

impl Outline {
    /// Whether the surface may cover tile (tx, ty), one of its box's rectangle.
    fn may_cover_tile(&self, tx: u32, ty: u32) -> bool {
        match self {
            Outline::Triangle(triangle) => triangle.may_cover(tile_area(tx, ty)),
            Outline::Tiles {
                x0,
                y0,
                columns,
                covered,
            } => covered[((ty - y0) * columns + (tx - x0)) as usize],
        }
    }
}

/// The tiles of `rectangle` (the instance's box's) that the boxes of a placed mesh's
/// hierarchy cover (`outline::mesh_coverage`), each box's found by `rectangle_of` as any
/// primitive's; None for a shape, or a rectangle too small to be worth it.
fn mesh_outline(
    instance: &Instance,
    rectangle: (u32, u32, u32, u32),
    rectangle_of: impl Fn(&Aabb) -> Option<CellRectangle>,
) -> Option<Outline> {
    let covered = mesh_coverage(instance, rectangle, rectangle_of)?;
    let (x0, y0, x1, _) = rectangle;
    Some(Outline::Tiles {
        x0,
        y0,
        columns: x1 - x0 + 1,
        covered,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{AccelOptions, Accelerator, Reach};
    use crate::camera::Camera;
    use crate::geometry::RayQuery;
    use crate::scene::{Geometry, Scene};
    use glam::Vec3;

    fn prepare(scene: &Scene) -> Accelerator {
        Geometry::new(scene, AccelOptions::ALL).accel().clone()
    }

    fn seed() -> (Accelerator, Camera) {
        let scene = crate::seed::scene().unwrap();
        (prepare(&scene), scene.camera)
    }

    /// For subsample positions all over every pixel (corners included), the candidates give
    /// exactly the BVH's nearest hit: the same primitive at the same distance, or none.
    /// Returns the census of the tiles it tested.
    fn assert_matches_bvh(
        scene: &Accelerator,
        camera: Camera,
        width: u32,
        height: u32,
    ) -> TileCensus {
        let rays = camera.rays(width, height);
        let tiles = FirstHitTiles::new(scene.primitives(), &rays, width, height, true);
        let offsets = [0.0, 0.5, 0.999_999, 0.25];
        let mut hits = 0;
        for y in 0..height {
            for x in 0..width {
                let Some(candidates) = tiles.at(x, y) else {
                    continue;
                };
                for (i, &dx) in offsets.iter().enumerate() {
                    let dy = offsets[(i + 1) % offsets.len()];
                    let q = RayQuery::new(rays.ray(x as f32 + dx, y as f32 + dy));
                    let expected = scene.nearest_hit(&q, Reach::After(0.0));
                    let found = scene.nearest_hit(&q, Reach::Among(candidates, tiles.listed()));
                    // The same triangle of a mesh, with the same weights, too.
                    assert_eq!(found, expected, "pixel ({x}, {y}) + ({dx}, {dy})");
                    hits += expected.is_some() as u32;
                }
            }
        }
        assert!(
            hits > 0,
            "the view must see something for the test to mean anything"
        );
        tiles.census()
    }

    #[test]
    fn the_seed_view_finds_every_nearest_hit_the_bvh_finds() {
        let (scene, camera) = seed();
        assert_matches_bvh(&scene, camera, 200, 150);
        // Sizes that are not multiples of the tile side leave partial tiles at the edges.
        assert_matches_bvh(&scene, camera, 203, 77);
    }

    /// A run's candidates are those of every pixel in it, the run ends at a tile's edge,
    /// and the runs from each pixel of a row cover it whole: what a pass looks up once
    /// per run is what it would look up per pixel.
    #[test]
    fn a_run_has_the_candidates_of_every_pixel_in_it() {
        let (scene, camera) = seed();
        for (width, height) in [(200, 150), (203, 77)] {
            let tiles = FirstHitTiles::new(
                scene.primitives(),
                &camera.rays(width, height),
                width,
                height,
                true,
            );
            let same = |a: Option<&[Candidate]>, b: Option<&[Candidate]>| match (a, b) {
                (Some(a), Some(b)) => std::ptr::eq(a, b),
                (None, None) => true,
                _ => false,
            };
            for y in 0..height {
                let mut x = 0;
                while x < width {
                    let (run, end) = tiles.at_run(x, y);
                    assert!(end > x && end % TILE == 0, "({x}, {y}): {end}");
                    for inside in x..end.min(width) {
                        assert!(same(run, tiles.at(inside, y)), "({inside}, {y})");
                        // A run may be entered anywhere in it.
                        assert_eq!(tiles.at_run(inside, y).1, end);
                    }
                    x = end;
                }
            }
        }
    }

    #[test]
    fn a_floor_tile_lists_only_the_floor_triangle_it_sees() {
        // The floor is a quad split along a diagonal into two triangles whose boxes are
        // the same: only tiles near the diagonal's image list both.
        let description = crate::seed::scene().unwrap();
        let geometry = Geometry::new(&description, AccelOptions::ALL);
        let (scene, camera) = (geometry.accel(), description.camera);
        let floor = geometry.find("floor").unwrap();
        let triangles: Vec<u32> = (0..scene.primitives().len() as u32)
            .filter(|&i| scene.primitive(i).object == floor)
            .collect();
        assert_eq!(triangles.len(), 2);
        let (w, h) = (200, 150);
        let tiles = FirstHitTiles::new(scene.primitives(), &camera.rays(w, h), w, h, true);
        let (mut one, mut both) = (0, 0);
        for ty in 0..h.div_ceil(TILE) {
            for tx in 0..w.div_ceil(TILE) {
                let listed = tiles.at(tx * TILE, ty * TILE).unwrap();
                let n = triangles
                    .iter()
                    .filter(|&&t| listed.iter().any(|c| c.primitive == t))
                    .count();
                one += (n == 1) as u32;
                both += (n == 2) as u32;
            }
        }
        assert!(both > 0 && one > 4 * both, "one {one}, both {both}");
    }

    #[test]
    fn views_from_inside_and_around_the_objects_find_the_same_hits() {
        let (scene, seed_camera) = seed();
        let views = [
            // Inside the mirror sphere's box, looking at the others.
            (
                Vec3::new(-5.0, 0.0, -100.0),
                Vec3::new(1.0, -0.2, 1.0),
                60.0,
            ),
            // On the floor, among the objects: boxes straddle the eye's plane.
            (
                Vec3::new(0.0, -14.0, -66.0),
                Vec3::new(-1.0, 0.1, -0.3),
                90.0,
            ),
            // From behind, looking back at the seed camera: every box behind it is culled.
            (Vec3::new(0.0, 5.0, -230.0), Vec3::new(0.0, -0.1, 1.0), 40.0),
            // Steeply down from above, wide.
            (
                Vec3::new(0.0, 60.0, -80.0),
                Vec3::new(0.3, -1.0, 0.0),
                120.0,
            ),
        ];
        for (eye, dir, fov) in views {
            let camera = Camera::looking_along(eye, dir, fov).unwrap();
            assert_ne!(camera, seed_camera);
            assert_matches_bvh(&scene, camera, 96, 64);
        }
    }

    #[test]
    fn the_seed_view_is_mostly_cheap_tiles() {
        let (scene, camera) = seed();
        let tiles = FirstHitTiles::new(scene.primitives(), &camera.rays(800, 600), 800, 600, true);
        let census = tiles.census();
        assert_eq!(census.tiles, 100 * 75);
        assert_eq!(census.crowded, 0);
        // The black sky above the objects: about a third of the image.
        assert!(census.empty > census.tiles / 4, "{census:?}");
        // A non-empty tile lists few primitives: one floor triangle, not both (outlines),
        // and rarely more than an object or two in front of it. (1.59 on average; 2.15
        // when each triangle took its box's whole rectangle.)
        let listed = census.tiles - census.empty - census.crowded;
        let mean = census.candidates as f64 / listed as f64;
        assert!(mean < 1.8, "{mean} candidates per listed tile: {census:?}");
        // The floor lies under every tile below the horizon, and the mirror sphere's tiles
        // list it after the floor only where the floor's box is nearer.
        let bottom = tiles.at(400, 599).unwrap();
        assert!(!bottom.is_empty());
        assert!(bottom.windows(2).all(|w| w[0].min_t <= w[1].min_t));
    }

    #[test]
    fn boxes_behind_the_eye_are_in_no_tile_and_crowds_go_to_the_bvh() {
        use crate::scene::{Scene, SceneObject, ShapeDesc};
        let (_, camera) = seed();
        let template = crate::seed::scene().unwrap();
        let material = template.objects[0].material.clone();
        let sphere = |center: Vec3| SceneObject {
            casts_shadow: true,
            placement: Default::default(),
            group: None,
            node: None,
            name: "s".into(),
            shape: ShapeDesc::Sphere {
                center,
                radius: 1.0,
            },
            material: material.clone(),
        };
        // The seed camera looks down −z from the origin.
        let mut objects = vec![sphere(Vec3::new(0.0, 0.0, 10.0))];
        objects.extend((0..20).map(|i| sphere(Vec3::new(0.0, 0.0, -20.0 - i as f32))));
        let scene = prepare(&Scene {
            objects,
            ..template
        });
        let tiles = FirstHitTiles::new(scene.primitives(), &camera.rays(160, 120), 160, 120, true);
        let behind = scene
            .primitives()
            .iter()
            .position(|p| p.surface.bounds().min.z > 0.0)
            .unwrap() as u32;
        for y in 0..120 {
            for x in 0..160 {
                if let Some(list) = tiles.at(x, y) {
                    assert!(list.iter().all(|c| c.primitive != behind));
                }
            }
        }
        // Twenty spheres one behind the other cover the centre: left to the BVH.
        assert!(tiles.at(80, 60).is_none());
        assert!(tiles.census().crowded > 0);
        assert_matches_bvh(&scene, camera, 160, 120);
    }

    #[test]
    fn views_of_meshes_find_every_nearest_hit_the_bvh_finds() {
        // Three placed bunnies (one turned half round, one glass) on a floor, from the
        // scene's camera, from close to one (its box straddles the eye's plane) and from
        // above at an odd size.
        let description = crate::accel::tests::bunny_scene();
        let scene = prepare(&description);
        assert_matches_bvh(&scene, description.camera, 200, 150);
        for (eye, dir, fov) in [
            (
                Vec3::new(-8.0, -9.0, -72.0),
                Vec3::new(0.2, -0.3, -1.0),
                70.0,
            ),
            (
                Vec3::new(0.0, 30.0, -70.0),
                Vec3::new(0.1, -1.0, -0.4),
                50.0,
            ),
        ] {
            let camera = Camera::looking_along(eye, dir, fov).unwrap();
            assert_matches_bvh(&scene, camera, 161, 97);
        }
    }

    #[test]
    fn meshes_listed_triangle_by_triangle_give_every_nearest_hit_the_bvh_gives() {
        // Large enough images for the bunnies' triangles to be listed (mesh_listing.rs): the
        // same triangle at the same distance with the same weights as the walk of each
        // mesh's hierarchy, for the scene's camera, for a view from close by (boxes across
        // the eye's plane, triangles a tile wide) and for one from above.
        let description = crate::accel::tests::bunny_scene();
        let scene = prepare(&description);
        let views = [
            (description.camera, 480, 360),
            // The clay bunny large, the glass one beside it.
            (
                Camera::looking_along(
                    Vec3::new(-4.0, -2.0, -40.0),
                    Vec3::new(-0.1, -0.25, -1.0),
                    50.0,
                )
                .unwrap(),
                480,
                360,
            ),
            (
                Camera::looking_along(
                    Vec3::new(-8.0, -9.0, -72.0),
                    Vec3::new(0.2, -0.3, -1.0),
                    70.0,
                )
                .unwrap(),
                403,
                301,
            ),
            (
                Camera::looking_along(
                    Vec3::new(0.0, 30.0, -70.0),
                    Vec3::new(0.1, -1.0, -0.4),
                    50.0,
                )
                .unwrap(),
                400,
                300,
            ),
        ];
        for (camera, width, height) in views {
            let census = assert_matches_bvh(&scene, camera, width, height);
            assert!(census.listing > 0, "{census:?}");
        }
    }

    #[test]
    fn a_mesh_is_listed_only_in_the_tiles_its_boxes_cover() {
        // The clay bunny's box covers a rectangle of tiles; its leaves' boxes leave out the
        // corners around its silhouette, and those tiles are background.
        let description = crate::accel::tests::bunny_scene();
        let geometry = Geometry::new(&description, AccelOptions::ALL);
        let scene = geometry.accel();
        let bunny = geometry.find("clay bunny").unwrap();
        let index = (0..scene.primitives().len() as u32)
            .find(|&i| scene.primitive(i).object == bunny)
            .unwrap();
        let (w, h) = (400, 300);
        let rays = description.camera.rays(w, h);
        let tiles = FirstHitTiles::new(scene.primitives(), &rays, w, h, true);
        let bounds = scene.primitive(index).surface.bounds();
        let (lo, hi) = (bounds.min.as_dvec3(), bounds.max.as_dvec3());
        let (x0, y0, x1, y1) = ImageProjection::new(&rays, w, h).box_tiles(lo, hi).unwrap();
        let rectangle = (x1 - x0 + 1) * (y1 - y0 + 1);
        let mut listed = 0;
        for ty in 0..h.div_ceil(TILE) {
            for tx in 0..w.div_ceil(TILE) {
                let list = tiles.at(tx * TILE, ty * TILE).unwrap();
                if list.iter().any(|c| c.primitive == index) {
                    assert!((x0..=x1).contains(&tx) && (y0..=y1).contains(&ty));
                    listed += 1;
                }
            }
        }
        assert!(
            listed > rectangle / 3 && listed * 10 < rectangle * 8,
            "listed in {listed} of its rectangle's {rectangle} tiles"
        );
    }
}
