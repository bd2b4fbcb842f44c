//! A placed mesh's triangles listed by the cells of the cube around a point light: for each
//! cell, the triangles that a shadow ray whose direction falls in it may meet, nearest to
//! the light first, eight to an octet. A shadow ray then tests those octets instead of
//! walking the mesh's hierarchy, and stops at the first octet that starts beyond its
//! shading point. Whether a shadow ray meets the mesh does not depend on the order of the
//! tests, and the list holds every triangle it can meet, so the answer is the walk's.
//!
//! The mesh has its own grid on each face, fitted around its triangles and finer than the
//! light buffer's, so that a cell holds a few of them (light_buffer.rs lists the mesh as a
//! whole).

use super::instance::{Instance, Model};
use super::light_faces::{
    CROWDED, FACES, FaceOutline, FaceView, Seen, Window, lower_bound_distance_sq,
};
use crate::geometry::{GROUP_WIDTH, ListedTriangle, OCTET_WIDTH, TriangleOctet};
use glam::{DAffine3, DVec3, Vec3, Vec3A};
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

/// A cell whose triangles fill more than this many octets is left to the mesh's hierarchy.
const MAX_OCTETS: usize = 4;

/// A face's grid has about this many cells for each triangle seen through it.
const CELLS_PER_TRIANGLE: f64 = 1.0;

/// The most cells along a side of a face's grid.
const MAX_SIDE: u32 = 512;

/// Each triangle may be listed in this many cells on average; a mesh that needs more (a
/// crowd of triangles around the light, or long thin ones across many cells) is left to its
/// hierarchy, so the lists' memory stays in proportion to the mesh's.
const LISTINGS_PER_TRIANGLE: usize = 16;

/// The most triangles listed around one light, over all the placed meshes (each instance
/// of a mesh counts its triangles again): the lists take some 400 bytes per triangle, out
/// of proportion to a mesh's own memory, and beyond the processor's caches they cost more
/// than the walks they spare.
pub(super) const MAX_LISTED_TRIANGLES: usize = 1 << 16;

/// A triangle as one face of the cube sees it.
struct Sighting {
    view: FaceView,
    /// Its outline through the face, when known.
    outline: Option<FaceOutline>,
    /// The squared distance from the light to its box.
    box_distance_sq: f64,
    face: usize,
    group: u32,
    triangle: u32,
}

/// What a mesh's listing is made from: the model, where it is placed, the light, and how
/// far from the light shading points may lie. A scene built again after an edit reuses
/// the listing wherever it finds the same (its unchanged meshes around its unchanged
/// lights). The model is held, not only its address, so that no other model can take that
/// address while the listing lives; its placement is its map to the scene's space, from
/// which `Transform` derives the rest.
#[derive(Clone, Debug)]
pub(super) struct ListingSource {
    model: Arc<Model>,
    to_scene: [u32; 12],
    light: DVec3,
    farthest: f64,
}

impl ListingSource {
    pub(super) fn new(instance: &Instance, light: DVec3, farthest: f64) -> Self {
        Self {
            model: instance.model().clone(),
            to_scene: instance
                .transform()
                .to_scene()
                .to_cols_array()
                .map(f32::to_bits),
            light,
            farthest,
        }
    }

    /// The numbers compared and hashed, bit for bit.
    fn bits(&self) -> (*const Model, [u32; 12], [u64; 3], u64) {
        (
            Arc::as_ptr(&self.model),
            self.to_scene,
            self.light.to_array().map(f64::to_bits),
            self.farthest.to_bits(),
        )
    }
}

impl PartialEq for ListingSource {
    fn eq(&self, other: &Self) -> bool {
        self.bits() == other.bits()
    }
}

impl Eq for ListingSource {}

impl Hash for ListingSource {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.bits().hash(state);
    }
}

/// Listings already made, by what they were made from (`ListingSource`).
pub(super) type Listings = HashMap<ListingSource, Arc<MeshShadowListing>>;

/// A placed mesh's triangles listed by the cells of the cube around one light.
#[derive(Clone, Debug)]
pub(super) struct MeshShadowListing {
    /// What it was made from.
    source: ListingSource,
    /// Where each face's grid lies.
    windows: [Window; FACES],
    /// Where each face's cells start in `cells`.
    face_start: [u32; FACES],
    /// Each cell's octets, as a range of `octets`, row by row; `CROWDED` for a cell whose
    /// triangles fill more than `MAX_OCTETS`.
    cells: Vec<(u32, u32)>,
    octets: Vec<TriangleOctet>,
}

impl MeshShadowListing {
    /// The triangles of the mesh placed by `instance` listed around the light of `source`
    /// (made from `instance`), no shading point farther from it than its `farthest`; None
    /// for a shape, or for a mesh too crowded around the light to list.
    pub(super) fn new(instance: &Instance, source: ListingSource) -> Option<Self> {
        let Model::Mesh { mesh, groups, .. } = &**instance.model() else {
            return None;
        };
        let (light, farthest) = (source.light, source.farthest);
        let transform = instance.transform();
        let to_scene = transform.to_scene();
        let to_scene = DAffine3::from_cols_array(&to_scene.to_cols_array().map(f64::from));
        // A triangle is hit in the model's space by the shadow ray taken there, which strays
        // from the scene's ray by the rounding of the map: each box is widened by the bound
        // on that rounding anywhere in the model's box.
        let pad = instance
            .model()
            .bounds()
            .corners()
            .into_iter()
            .map(|p| transform.point_to_scene(p.into(), Vec3A::ZERO).1)
            .fold(Vec3A::ZERO, Vec3A::max);
        let pad = Vec3::from(pad).as_dvec3();
        let pad_most = pad.max_element();

        // Each triangle's box in the scene's space, with its group and index.
        let mut boxes = Vec::with_capacity(mesh.triangle_count());
        for (index, group) in groups.iter().enumerate() {
            for triangle in group.triangles() {
                let corners = group
                    .corners_of(triangle)
                    .map(|c| to_scene.transform_point3(Vec3::from(c).as_dvec3()));
                let lo = corners[0].min(corners[1]).min(corners[2]) - pad;
                let hi = corners[0].max(corners[1]).max(corners[2]) + pad;
                boxes.push((lo, hi, corners, index as u32, triangle));
            }
        }
        debug_assert!(boxes.len() <= groups.len() * GROUP_WIDTH);

        // How each triangle is seen through each face that sees it, once.
        let seen: Vec<Sighting> = boxes
            .iter()
            .flat_map(|&(lo, hi, corners, group, triangle)| {
                (0..FACES).filter_map(move |face| {
                    let view = FaceView::new(lo, hi, light, face, farthest)?;
                    Some(Sighting {
                        outline: view.outline(&corners, light, face, pad_most),
                        box_distance_sq: lower_bound_distance_sq(light, lo, hi),
                        view,
                        face,
                        group,
                        triangle,
                    })
                })
            })
            .collect();
        // Each face's grid, fitted around the triangles seen through it, with about
        // `CELLS_PER_TRIANGLE` cells for each.
        let windows: [Window; FACES] = std::array::from_fn(|face| {
            let tangents = seen
                .iter()
                .filter(|s| s.face == face)
                .map(|s| s.view.tangents);
            Window::around(tangents, |count| {
                ((count as f64 * CELLS_PER_TRIANGLE).sqrt().ceil() as u32).clamp(1, MAX_SIDE)
            })
        });
        let mut face_start = [0; FACES];
        let mut cell_count = 0;
        for (face, window) in windows.iter().enumerate() {
            face_start[face] = cell_count;
            cell_count += window.side() * window.side();
        }
        // Calls `list` with each cell that a sighting's outline may cover.
        let covered = |sighting: &Sighting, list: &mut dyn FnMut(u32, u32, u32)| {
            let window = &windows[sighting.face];
            let (u0, v0, u1, v1) = sighting.view.cells(window);
            for v in v0..=v1 {
                for u in u0..=u1 {
                    if sighting
                        .outline
                        .as_ref()
                        .is_none_or(|o| o.may_cover(window, u, v))
                    {
                        list(face_start[sighting.face] + v * window.side() + u, u, v);
                    }
                }
            }
        };

        // Each listing once, in the sightings' order, with the cell it goes to; then put in
        // its cell's list by counting, which keeps that order within each list.
        let mut entries: Vec<(u32, ListedTriangle)> = Vec::new();
        let mut start = vec![0u32; cell_count as usize + 1];
        for sighting in &seen {
            let window = &windows[sighting.face];
            covered(sighting, &mut |cell, u, v| {
                let key = sighting
                    .view
                    .key_within(window, u, v, sighting.box_distance_sq);
                entries.push((cell, (key, sighting.group, sighting.triangle)));
                start[cell as usize + 1] += 1;
            });
            if entries.len() > LISTINGS_PER_TRIANGLE * boxes.len() {
                return None;
            }
        }
        for cell in 0..cell_count as usize {
            start[cell + 1] += start[cell];
        }
        let mut filled = start.clone();
        let mut listings: Vec<ListedTriangle> = vec![(0.0, 0, 0); entries.len()];
        for (cell, listed) in entries {
            listings[filled[cell as usize] as usize] = listed;
            filled[cell as usize] += 1;
        }

        let lists =
            (0..cell_count as usize).map(|cell| start[cell] as usize..start[cell + 1] as usize);
        let octet_count = lists
            .clone()
            .filter(|list| list.len() <= MAX_OCTETS * OCTET_WIDTH)
            .map(|list| list.len().div_ceil(OCTET_WIDTH))
            .sum();
        let mut cells = Vec::with_capacity(cell_count as usize);
        let mut octets = Vec::with_capacity(octet_count);
        for list in lists {
            let list = &mut listings[list];
            if list.len() > MAX_OCTETS * OCTET_WIDTH {
                cells.push(CROWDED);
                continue;
            }
            // Stable, so equal keys keep the mesh's order.
            list.sort_by(|a, b| a.0.total_cmp(&b.0));
            let first = octets.len() as u32;
            TriangleOctet::pack(groups, list, &mut octets);
            cells.push((first, octets.len() as u32));
        }
        Some(Self {
            source,
            windows,
            face_start,
            cells,
            octets,
        })
    }

    /// The octets of the triangles that a shadow ray seen as `seen` may meet, nearest to
    /// the light first (`TriangleOctet::nearest`: a squared distance from the light); None
    /// where too many are, and the mesh's hierarchy must be walked.
    #[inline(always)]
    pub(super) fn at(&self, seen: Seen) -> Option<&[TriangleOctet]> {
        let window = &self.windows[seen.face];
        let Some((u, v)) = window.cell_of(seen.tangents) else {
            return Some(&[]); // outside the window: no triangle is seen this way
        };
        let cell = self.face_start[seen.face] + v * window.side() + u;
        let (start, end) = self.cells[cell as usize];
        // A crowded cell's range is empty-backwards, which `get` refuses.
        self.octets.get(start as usize..end as usize)
    }

    /// What the listing was made from.
    pub(super) fn source(&self) -> &ListingSource {
        &self.source
    }

    /// How many cells there are, how many are left to the hierarchy, and how many octets
    /// the others hold (for tests and the bench).
    pub(super) fn census(&self) -> (usize, usize, usize) {
        let crowded = self.cells.iter().filter(|&&c| c == CROWDED).count();
        (self.cells.len(), crowded, self.octets.len())
    }
}

#[cfg(test)]
mod tests {
    use super::{MeshShadowListing, Model};
    use crate::accel::{AccelOptions, Reach, Surface, Toward};
    use crate::geometry::{Ray, RayQuery};
    use crate::numerics::offset_ray_origin;
    use crate::scene::PreparedScene;
    use crate::scene::{Geometry, ShapeDesc};
    use crate::xorshift::XorShift32;
    use glam::{Vec3, Vec3A};
    use std::sync::Arc;

    /// Shadow rays toward five lights (the scene's, one among the bunnies, one far off, one
    /// just above a bunny's back and one inside a bunny's box) from points all over the three placed bunnies of
    /// assets/scenes/bunny.toml (turned and scaled), made opaque so that shadow rays stop at
    /// the first hit: from their surfaces (as the integrator leaves them), and from anywhere
    /// in and around their boxes. Each reaches its light exactly as far with the meshes'
    /// triangles listed as when their hierarchies are walked, and as without light buffers.
    #[test]
    fn shadow_rays_through_listed_triangles_find_what_the_walk_finds() {
        let mut scene = crate::accel::tests::bunny_scene();
        for object in &mut scene.objects {
            object.material.transparency = 0.0;
        }
        let light = scene.lights[0];
        scene.lights = [
            Vec3::ZERO,
            Vec3::new(-9.0, -48.0, -68.0),
            Vec3::new(-600.0, 50.0, 300.0),
            Vec3::new(-18.0, -29.0, -70.0),
        ]
        .map(|offset| light.moved_by(offset))
        .to_vec();
        // And a fifth inside a bunny's box: its triangles straddle the cube's planes.
        let inside = PreparedScene::new(&scene)
            .geometry
            .accel()
            .primitives()
            .iter()
            .find(|p| match &p.surface {
                crate::accel::Surface::Instance(instance) => {
                    matches!(**instance.model(), Model::Mesh { .. })
                }
                _ => false,
            })
            .unwrap()
            .surface
            .bounds()
            .centroid();
        scene
            .lights
            .push(light.moved_by(inside - light.position().unwrap()));
        let positions: Vec<Vec3A> = scene
            .lights
            .iter()
            .map(|l| l.position().unwrap().into())
            .collect();
        let prepare = |options| PreparedScene::with_options(&scene, options);
        let listed = prepare(AccelOptions::ALL);
        let walked = prepare(AccelOptions {
            light_triangles: false,
            ..AccelOptions::ALL
        });
        let unbuffered = prepare(AccelOptions {
            light_buffers: false,
            ..AccelOptions::ALL
        });
        let filters = listed.appearance.shadow_filters();
        let accel = listed.geometry.accel();
        for light in 0..4 {
            let census = accel.light_buffer(light).unwrap().census();
            assert_eq!(census.listed_meshes, 3, "light {light}: {census:?}");
            assert!(census.mesh_octets > 1000, "light {light}: {census:?}");
        }

        // The bunnies' box (without the floor), a little widened.
        let bunnies = (0..accel.primitives().len() as u32)
            .map(|i| accel.primitive(i))
            .filter(|p| match &p.surface {
                crate::accel::Surface::Instance(instance) => {
                    matches!(**instance.model(), Model::Mesh { .. })
                }
                _ => false,
            })
            .fold(crate::geometry::Aabb::EMPTY, |b, p| {
                b.union(p.surface.bounds())
            });
        let (lo, hi) = (Vec3A::from(bunnies.min), Vec3A::from(bunnies.max));
        let mut rng = XorShift32::new(5);
        let mut point = |widen: f32| {
            let f = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            lo + (hi - lo) * (f * (1.0 + 2.0 * widen) - widen)
        };
        let (mut on_surface, mut blocked, mut lit) = (0, 0, 0);
        for _ in 0..20_000 {
            // A ray between two points about the bunnies: its first hit, if any, is a
            // shading point; the ray's own origin is another.
            let (from, to) = (point(0.2), point(0.0));
            let q = RayQuery::new(Ray::new(from, to - from));
            let mut origins = vec![(from, None)];
            if let Some(hit) = accel.nearest_hit(&q, Reach::After(0.0)) {
                let surface = accel.surface(&q, &hit);
                origins.push((surface.point, Some(surface)));
            }
            for (light, &position) in positions.iter().enumerate() {
                for &(origin, at) in &origins {
                    // Off the surface on the light's side, as the integrator leaves it.
                    let origin = match at {
                        Some(surface) => {
                            on_surface += 1;
                            let l = position - origin;
                            let n = surface.normal;
                            let n = if n.dot(l) < 0.0 { -n } else { n };
                            offset_ray_origin(origin, surface.error, n, l)
                        }
                        None => origin,
                    };
                    let reaching = |prepared: &PreparedScene| {
                        prepared.geometry.accel().light_reaching(
                            light,
                            Toward::Point(position),
                            origin,
                            None,
                            filters,
                        )
                    };
                    let found = reaching(&listed);
                    assert_eq!(found, reaching(&walked), "{origin} toward light {light}");
                    assert_eq!(
                        found,
                        reaching(&unbuffered),
                        "{origin} toward light {light}"
                    );
                    if found == Vec3A::ZERO {
                        blocked += 1;
                    } else {
                        lit += 1;
                    }
                }
            }
        }
        assert!(on_surface > 10_000, "{on_surface}");
        assert!(
            blocked > 10_000 && lit > 10_000,
            "{blocked} blocked, {lit} lit"
        );
    }

    /// The lists of each light of `geometry`, in the lights' order.
    fn listings(geometry: &Geometry) -> Vec<Vec<Arc<MeshShadowListing>>> {
        (0..2)
            .map(|light| {
                let buffer = geometry.accel().light_buffer(light).unwrap();
                buffer.mesh_listings().to_vec()
            })
            .collect()
    }

    /// Whether `a` and `b` hold the same lists, light by light and mesh by mesh.
    fn same_lists(a: &[Vec<Arc<MeshShadowListing>>], b: &[Vec<Arc<MeshShadowListing>>]) -> bool {
        let lists = |l: &Arc<MeshShadowListing>| {
            (l.windows, l.face_start, l.cells.clone(), l.octets.clone())
        };
        a.len() == b.len()
            && a.iter().zip(b).all(|(a, b)| {
                a.len() == b.len() && a.iter().zip(b).all(|(a, b)| lists(a) == lists(b))
            })
    }

    /// Whether `listing` is one of `made` (the same allocation).
    fn one_of(listing: &Arc<MeshShadowListing>, made: &[Vec<Arc<MeshShadowListing>>]) -> bool {
        made.iter().flatten().any(|m| Arc::ptr_eq(m, listing))
    }

    /// A scene built again after an edit takes from the scene before it the lists of the
    /// meshes and lights the edit left alone, and lists again those it moved: moving a light
    /// lists its meshes again and no other light's; moving a mesh lists it again around
    /// every light and no other mesh. Each time the lists are those a fresh build makes.
    #[test]
    fn an_edit_lists_again_only_what_it_moved() {
        let mut scene = crate::accel::tests::bunny_scene();
        for object in &mut scene.objects {
            object.material.transparency = 0.0;
        }
        let light = scene.lights[0];
        scene.lights = vec![light, light.moved_by(Vec3::new(-9.0, 30.0, 20.0))];
        let before = Geometry::new(&scene, AccelOptions::ALL);
        let made_before = listings(&before);
        assert_eq!(made_before.iter().map(Vec::len).collect::<Vec<_>>(), [3, 3]);

        // The second light moved: its meshes are listed again, the first light's are not.
        let mut lit = scene.clone();
        lit.lights[1] = lit.lights[1].moved_by(Vec3::new(1.0, 1.0, 0.0));
        let after = Geometry::rebuilt(&lit, &before);
        let made_after = listings(&after);
        let fresh = listings(&Geometry::new(&lit, AccelOptions::ALL));
        assert!(same_lists(&made_after, &fresh));
        assert!(made_after[0].iter().all(|l| one_of(l, &made_before)));
        assert!(!made_after[1].iter().any(|l| one_of(l, &made_before)));

        // The second bunny moved: it is listed again around both lights, and the others
        // are not; every bunny keeps its model.
        let mut moved = lit.clone();
        let bunnies: Vec<usize> = (0..moved.objects.len())
            .filter(|&i| matches!(moved.objects[i].shape, ShapeDesc::Mesh { .. }))
            .collect();
        let second = bunnies[1];
        let ShapeDesc::Mesh { mesh, transform } = &moved.objects[second].shape else {
            unreachable!("a bunny is a mesh");
        };
        let shifted = transform
            .then(glam::Affine3A::from_translation(Vec3::new(0.5, 0.0, 0.0)))
            .unwrap();
        moved.objects[second].shape = ShapeDesc::Mesh {
            mesh: mesh.clone(),
            transform: shifted,
        };
        let last = Geometry::rebuilt(&moved, &after);
        let made_last = listings(&last);
        let fresh = listings(&Geometry::new(&moved, AccelOptions::ALL));
        assert!(same_lists(&made_last, &fresh));
        let moved_bunny =
            |l: &Arc<MeshShadowListing>| l.source().to_scene == shifted_bits(&shifted);
        for listing in made_last.iter().flatten() {
            assert_eq!(one_of(listing, &made_after), !moved_bunny(listing));
        }
        assert_eq!(
            made_last
                .iter()
                .flatten()
                .filter(|l| moved_bunny(l))
                .count(),
            2
        );
        // The bunnies' models (smooth and faceted), made once and kept since.
        let mesh_models = |geometry: &Geometry| -> Vec<Arc<Model>> {
            let mut models: Vec<Arc<Model>> = Vec::new();
            for primitive in geometry.accel().primitives() {
                if let Surface::Instance(instance) = &primitive.surface
                    && matches!(**instance.model(), Model::Mesh { .. })
                    && !models.iter().any(|m| Arc::ptr_eq(m, instance.model()))
                {
                    models.push(instance.model().clone());
                }
            }
            models
        };
        let (kept, first) = (mesh_models(&last), mesh_models(&before));
        assert_eq!((kept.len(), first.len()), (2, 2));
        assert!(kept.iter().all(|k| first.iter().any(|f| Arc::ptr_eq(k, f))));
    }

    fn shifted_bits(transform: &crate::geometry::Transform) -> [u32; 12] {
        transform.to_scene().to_cols_array().map(f32::to_bits)
    }
}
