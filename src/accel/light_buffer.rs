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
//! boxes cover fall back to the BVH.

use super::primitive::Primitive;
use glam::{DVec3, Vec3};

/// Cells along each side of a cube face.
pub const FACE_CELLS: u32 = 64;

/// A cell covered by more boxes than this is left to the BVH.
pub const MAX_OCCLUDERS: usize = 16;

/// Directions are widened by this much, in units of a face's tangent (a face spans −1..1),
/// on top of the allowance for where a computed shadow ray can stray (`direction_margin`).
const MARGIN: f64 = 1e-4;

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
}

/// The cube of cells around one point light.
#[derive(Clone, Debug)]
pub struct LightBuffer {
    /// Each cell's occluders, as a range of `occluders`; `CROWDED` for a cell covered by
    /// more than `MAX_OCCLUDERS` boxes, left to the BVH.
    cells: Vec<(u32, u32)>,
    occluders: Vec<Occluder>,
    /// Where each face's grid of cells lies.
    windows: [Window; FACES],
    /// The light the buffer was built around.
    position: Vec3,
}

/// The part of a face that its grid of cells covers: tangents `lo..lo + FACE_CELLS / scale`
/// on each of its axes, fitted around the boxes seen through the face. A light far from a
/// small scene sees it through a narrow window, and all its cells go to the scene.
#[derive(Clone, Copy, Debug)]
struct Window {
    lo: [f32; 2],
    scale: [f32; 2],
}

impl Window {
    /// For a face through which no box is seen: beyond the face, so every lookup misses.
    const NOTHING: Window = Window {
        lo: [2.0; 2],
        scale: [1.0; 2],
    };

    /// The window around tangent rectangles (each within −1..1 on both axes).
    fn around(rectangles: &[[(f64, f64); 2]]) -> Window {
        if rectangles.is_empty() {
            return Window::NOTHING;
        }
        let fit = |axis: usize| {
            let lo = rectangles
                .iter()
                .map(|r| r[axis].0)
                .fold(f64::INFINITY, f64::min);
            let hi = rectangles
                .iter()
                .map(|r| r[axis].1)
                .fold(f64::NEG_INFINITY, f64::max);
            // Widened a little so that the top edge maps inside the last cell, whatever the
            // rounding of lo and scale to f32.
            let width = (hi - lo).max(1e-9) * (1.0 + 1e-5) + 1e-9;
            let lo = lo - 1e-9;
            (lo as f32, (FACE_CELLS as f64 / width) as f32)
        };
        let ((lo_u, scale_u), (lo_v, scale_v)) = (fit(0), fit(1));
        Window {
            lo: [lo_u, lo_v],
            scale: [scale_u, scale_v],
        }
    }

    /// The inclusive cells of `axis` that tangents t0..t1 overlap.
    fn cells(&self, axis: usize, (t0, t1): (f64, f64)) -> (u32, u32) {
        let cell = |t: f64| {
            let c = ((t - self.lo[axis] as f64) * self.scale[axis] as f64).floor();
            c.clamp(0.0, (FACE_CELLS - 1) as f64) as u32
        };
        (cell(t0), cell(t1))
    }

    /// The tangents that cell `c` of `axis` spans.
    fn tangents(&self, axis: usize, c: u32) -> (f64, f64) {
        let (lo, step) = (self.lo[axis] as f64, 1.0 / self.scale[axis] as f64);
        (lo + c as f64 * step, lo + (c + 1) as f64 * step)
    }
}

/// A range that slice `get` refuses (it starts after it ends).
const CROWDED: (u32, u32) = (1, 0);

/// The six faces: +x, −x, +y, −y, +z, −z. Face `2k + s` looks along axis k (s = 1: the
/// negative way); its tangent coordinates are axes k + 1 and k + 2 (cyclically), divided
/// by the distance along k.
const FACES: usize = 6;

impl LightBuffer {
    /// The lists around a light at `light` for `primitives`.
    pub fn new(position: Vec3, primitives: &[Primitive]) -> Self {
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
        // The farthest any shading point can be from the light: rounding in a shadow ray's
        // direction grows with its length.
        let farthest = boxes
            .iter()
            .filter(|(lo, hi)| lo.is_finite() && hi.is_finite())
            .map(|(lo, hi)| (*lo - light).abs().max((*hi - light).abs()).length())
            .fold(0.0, f64::max);

        // How each box looks through each face, then each face's window around them.
        let views: Vec<[Option<FaceView>; FACES]> = boxes
            .iter()
            .map(|(lo, hi)| {
                std::array::from_fn(|face| FaceView::new(*lo, *hi, light, face, farthest))
            })
            .collect();
        let windows: [Window; FACES] = std::array::from_fn(|face| {
            let seen: Vec<[(f64, f64); 2]> = views
                .iter()
                .filter_map(|v| v[face].as_ref().map(|view| view.tangents))
                .collect();
            Window::around(&seen)
        });

        // The lists' total length, before any is made: past the budget, crowds of
        // overlapping boxes (thousands at one spot) would cost time and memory that grow
        // with their square, and every cell would be left to the BVH anyway.
        let listed: u64 = views
            .iter()
            .flat_map(|faces| faces.iter().enumerate())
            .filter_map(|(face, view)| {
                let view = view.as_ref()?;
                let (u0, u1) = windows[face].cells(0, view.tangents[0]);
                let (v0, v1) = windows[face].cells(1, view.tangents[1]);
                Some(
                    (u1 as u64 + 1).saturating_sub(u0 as u64)
                        * (v1 as u64 + 1).saturating_sub(v0 as u64),
                )
            })
            .sum();
        let budget = (MAX_OCCLUDERS * cell_count) as u64
            + crate::limits::LISTINGS_PER_PRIMITIVE * boxes.len() as u64;
        if listed > budget {
            return Self {
                cells: vec![CROWDED; cell_count],
                occluders: Vec::new(),
                windows,
                position,
            };
        }

        let mut per_cell: Vec<Vec<Occluder>> = vec![Vec::new(); cell_count];
        for (index, ((lo, hi), faces)) in boxes.iter().zip(&views).enumerate() {
            let box_distance_sq = lower_bound_distance_sq(light, *lo, *hi);
            for (face, view) in faces.iter().enumerate() {
                let Some(view) = view else { continue };
                let window = &windows[face];
                let (u0, u1) = window.cells(0, view.tangents[0]);
                let (v0, v1) = window.cells(1, view.tangents[1]);
                for v in v0..=v1 {
                    for u in u0..=u1 {
                        let within =
                            view.distance_sq_within(window.tangents(0, u), window.tangents(1, v));
                        per_cell[cell_index(face, u, v)].push(Occluder {
                            primitive: index as u32,
                            object: primitives[index].object,
                            min_distance_sq: round_down(within.max(box_distance_sq)),
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
            position,
        }
    }

    /// The light the buffer was built around.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// The occluders a shadow ray may meet on the segment from the light to a point at
    /// `from_light` from it, nearest box first; None when its cell is left to the BVH (or
    /// the point is the light itself).
    #[inline]
    pub fn at(&self, from_light: Vec3) -> Option<&[Occluder]> {
        let Vec3 { x, y, z } = from_light;
        let a = from_light.abs();
        // The major axis picks the face, the other two (in cyclic order) the cell; ties go
        // to the lower axis, and `FaceView`'s margin covers either choice.
        let (face, major, t_u, t_v) = if a.x >= a.y && a.x >= a.z {
            ((x < 0.0) as usize, a.x, y, z)
        } else if a.y >= a.z {
            (2 + (y < 0.0) as usize, a.y, z, x)
        } else {
            (4 + (z < 0.0) as usize, a.z, x, y)
        };
        // Zero at the light itself. The sum is infinite or NaN when a component is (or when
        // huge finite ones overflow; the BVH then answers, as for a crowded cell).
        if major == 0.0
            || (a.x + a.y + a.z).partial_cmp(&f32::INFINITY) != Some(std::cmp::Ordering::Less)
        {
            return None;
        }
        let window = &self.windows[face];
        let inv_major = 1.0 / major;
        let u = (t_u * inv_major - window.lo[0]) * window.scale[0];
        let v = (t_v * inv_major - window.lo[1]) * window.scale[1];
        let cells = FACE_CELLS as f32;
        if !(u >= 0.0 && u < cells && v >= 0.0 && v < cells) {
            // Outside the window: no box is seen in this direction.
            return Some(&[]);
        }
        let (start, end) = self.cells[cell_index(face, u as u32, v as u32)];
        // A crowded cell's range is empty-backwards, which `get` refuses.
        self.occluders.get(start as usize..end as usize)
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
        census
    }
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
}

#[inline]
fn cell_index(face: usize, u: u32, v: u32) -> usize {
    let r = FACE_CELLS as usize;
    face * r * r + v as usize * r + u as usize
}

/// How far, in tangent units, a computed shadow ray can stray from the direction of a
/// point on it at `distance` from the light. The ray starts at its shading point and runs
/// along the rounded difference (light − origin), so its points near the light stray the
/// most: by about one rounding of a length up to `farthest`, seen from `distance` away.
fn direction_margin(distance: f64, farthest: f64) -> f64 {
    MARGIN + STRAY_ULPS * f32::EPSILON as f64 * farthest / distance
}

/// How far, in f32 roundings of the largest distance in the scene, a point of a computed
/// shadow ray can lie from the exact segment (a generous bound: the ray's origin and
/// direction are each one rounding off, its points a few more).
const STRAY_ULPS: f64 = 16.0;

/// One box as seen from the light through one face, in the face's coordinates relative to
/// the light: depth along the face's axis, then the two tangent axes.
struct FaceView {
    /// The box's depth range, and its ranges along the tangent axes; None when the box
    /// reaches round to the light's plane (or is unbounded): then only its distance from the
    /// light bounds how near it starts.
    extent: Option<[(f64, f64); 3]>,
    /// How far a shadow ray's direction may stray, in tangent units (`direction_margin`).
    margin: f64,
    /// The tangents (widened by the margin, within −1..1) of the directions that may meet
    /// the box.
    tangents: [(f64, f64); 2],
}

impl FaceView {
    /// None when no direction through face `face` meets the box lo..hi.
    fn new(lo: DVec3, hi: DVec3, light: DVec3, face: usize, farthest: f64) -> Option<Self> {
        let whole_face = Self {
            extent: None,
            margin: 0.0,
            tangents: [(-1.0, 1.0); 2],
        };
        if !(lo.is_finite() && hi.is_finite()) {
            return Some(whole_face);
        }
        let (axis, negative) = (face / 2, face % 2 == 1);
        let (lo, hi) = ((lo - light).to_array(), (hi - light).to_array());
        // The box's extent along the face's axis, measured the way the face looks.
        let depth = if negative {
            (-hi[axis], -lo[axis])
        } else {
            (lo[axis], hi[axis])
        };
        if depth.1 <= 0.0 {
            return None; // wholly behind the face's plane: no direction through it gets there
        }
        let (u_axis, v_axis) = ((axis + 1) % 3, (axis + 2) % 3);
        if depth.0 <= 0.0 {
            // The box reaches round to the light's plane, where t / depth is unbounded, but
            // on each axis the part of it in front of the plane still lies on one side of
            // the light or spans it: t / depth ≥ t_lo / far when t_lo > 0 (less the
            // positions' rounding), and likewise below.
            let stray = STRAY_ULPS * f32::EPSILON as f64 * farthest;
            let far = depth.1 + stray;
            let tangent_range = |k: usize| {
                let low = if lo[k] - stray > 0.0 {
                    (lo[k] - stray) / far - MARGIN
                } else {
                    -1.0
                };
                let high = if hi[k] + stray < 0.0 {
                    (hi[k] + stray) / far + MARGIN
                } else {
                    1.0
                };
                (low.max(-1.0), high.min(1.0))
            };
            let tangents = [tangent_range(u_axis), tangent_range(v_axis)];
            if tangents.iter().any(|(low, high)| low > high) {
                return None;
            }
            return Some(Self {
                extent: None,
                margin: 0.0,
                tangents,
            });
        }
        let margin = direction_margin(depth.0, farthest);
        // t / depth over the box is extreme at its corners: it is monotone in t, and in
        // depth for depth > 0.
        let tangent_range = |k: usize| {
            let quotients = [
                lo[k] / depth.0,
                lo[k] / depth.1,
                hi[k] / depth.0,
                hi[k] / depth.1,
            ];
            let min = quotients.iter().copied().fold(f64::INFINITY, f64::min);
            let max = quotients.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (min - margin, max + margin)
        };
        let (u_min, u_max) = tangent_range(u_axis);
        let (v_min, v_max) = tangent_range(v_axis);
        if u_max < -1.0 || u_min > 1.0 || v_max < -1.0 || v_min > 1.0 {
            return None;
        }
        Some(Self {
            extent: Some([depth, (lo[u_axis], hi[u_axis]), (lo[v_axis], hi[v_axis])]),
            margin,
            tangents: [
                (u_min.max(-1.0), u_max.min(1.0)),
                (v_min.max(-1.0), v_max.min(1.0)),
            ],
        })
    }

    /// A lower bound of the squared distance from the light to the part of the box that
    /// directions with tangents in `u_cell` × `v_cell` (widened by the margin) can reach.
    /// Tighter than the distance to the whole box: seen from the light, a floor lies farther
    /// away in each cell than the objects standing on it, so their shadow rays need not test
    /// it.
    fn distance_sq_within(&self, u_cell: (f64, f64), v_cell: (f64, f64)) -> f64 {
        let Some([depth, u_extent, v_extent]) = self.extent else {
            return 0.0;
        };
        let widen = |(c0, c1): (f64, f64)| (c0 - self.margin, c1 + self.margin);
        let (u_cell, v_cell) = (widen(u_cell), widen(v_cell));
        // The depth z at which a direction with tangent in c0..c1 can reach a coordinate in
        // lo..hi: c1·z ≥ lo and c0·z ≤ hi, each a lower bound on z when lo > 0 or hi < 0.
        let least_depth = |(c0, c1): (f64, f64), (lo, hi): (f64, f64)| {
            let mut z: f64 = 0.0;
            if lo > 0.0 && c1 > 0.0 {
                z = z.max(lo / c1);
            }
            if hi < 0.0 && c0 < 0.0 {
                z = z.max(hi / c0);
            }
            z
        };
        let z = depth
            .0
            .max(least_depth(u_cell, u_extent))
            .max(least_depth(v_cell, v_extent));
        // Along a direction with tangents (a, b), distance = depth·√(1 + a² + b²).
        let least_tangent_sq = |(c0, c1): (f64, f64)| {
            if c0 <= 0.0 && c1 >= 0.0 {
                0.0
            } else {
                (c0 * c0).min(c1 * c1)
            }
        };
        z * z * (1.0 + least_tangent_sq(u_cell) + least_tangent_sq(v_cell))
    }
}

/// The squared distance from `light` to the box lo..hi (0 for an unbounded box).
fn lower_bound_distance_sq(light: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0;
    }
    (lo - light)
        .max(light - hi)
        .max(DVec3::ZERO)
        .length_squared()
}

/// A squared distance rounded down by a relative 10⁻⁴ and then to f32, so that no computed
/// squared length of a shadow ray that reaches that far is smaller.
fn round_down(distance_sq: f64) -> f32 {
    crate::numerics::f32_at_most(distance_sq * (1.0 - 1e-4))
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
            let buffer = LightBuffer::new(light, scene.primitives());
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
        let buffer = LightBuffer::new(Vec3::ZERO, &beads);
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
        let census = LightBuffer::new(light, scene.primitives()).census();
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
        let buffer = LightBuffer::new(light, &[around]);
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
        let buffer = LightBuffer::new(light, &primitives);
        for (i, d) in directions.iter().enumerate() {
            let listed = buffer.at(*d * 20.0).unwrap();
            assert!(listed.iter().any(|o| o.primitive == i as u32), "{d}");
        }
    }

    #[test]
    fn the_light_itself_and_non_finite_directions_have_no_cell() {
        let (scene, light) = seed();
        let buffer = LightBuffer::new(light, scene.primitives());
        assert!(buffer.at(Vec3::ZERO).is_none());
        assert!(buffer.at(Vec3::new(f32::INFINITY, 0.0, 1.0)).is_none());
        assert!(buffer.at(Vec3::new(f32::NAN, 0.0, 1.0)).is_none());
    }
}
