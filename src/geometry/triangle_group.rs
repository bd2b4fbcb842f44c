//! Four triangles against one ray at once: their corners side by side in SIMD lanes
//! (structure of arrays, as Embree's triangle4 leaves), each lane running exactly the
//! operations of the scalar watertight test (triangle.rs) in the same order. A group
//! therefore finds bit for bit what testing its triangles one by one finds: the lanes'
//! hits are taken in lane order, each against the nearest distance found before it, as
//! the scalar loop takes them.

use super::ray::{Axes, RayQuery};
use super::triangle::{TriangleHit, watertight};
use crate::numerics::gamma;
use crate::simd::F32x4;
use glam::Vec3A;

/// Triangles per group: one per lane.
pub const GROUP_WIDTH: usize = 4;

/// Up to four consecutive triangles of a mesh (in its stored order), corner by corner and
/// axis by axis. Unused lanes repeat the last triangle and are masked off.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct TriangleGroup {
    /// `corners[k][a]`: corner k's coordinate on axis a, one triangle per lane.
    corners: [[F32x4; 3]; 3],
    /// The first triangle's index; lane i holds triangle `first + i`.
    first: u32,
    /// The lanes in use, 1..=4.
    count: u32,
}

/// A ray's constants for the group test, in every lane: its origin on the permuted axes
/// and its shear (RayQuery's `axes` and `shear`).
pub struct GroupRay {
    origin: [F32x4; 3],
    shear: [F32x4; 3],
    axes: Axes,
}

impl GroupRay {
    /// The constants of `q`'s ray.
    #[inline(always)]
    pub fn new(q: &RayQuery) -> Self {
        let [ox, oy, oz] = q.axes.permute(q.ray.origin);
        Self {
            origin: [F32x4::splat(ox), F32x4::splat(oy), F32x4::splat(oz)],
            shear: [
                F32x4::splat(q.shear.x),
                F32x4::splat(q.shear.y),
                F32x4::splat(q.shear.z),
            ],
            axes: q.axes,
        }
    }
}

/// What the lanes found, before the nearest is chosen.
struct LaneHits {
    /// Bit i set where lane i's triangle is hit within (t_min, t_max).
    mask: u32,
    t: [f32; 4],
    t_scaled: [f32; 4],
    det: [f32; 4],
    /// The edge functions, which divided by `det` are the barycentric weights.
    uvw: [[f32; 4]; 3],
}

/// Where any lane needs the scalar test: an edge function of exactly zero is decided in
/// f64 there, a rare case not worth lanes of its own.
const NEEDS_SCALAR: u32 = u32::MAX;

impl TriangleGroup {
    /// The group of triangles `first ..` whose corners are `corners` (one to four).
    pub fn new(first: u32, corners: &[[Vec3A; 3]]) -> Self {
        assert!((1..=GROUP_WIDTH).contains(&corners.len()));
        let lane = |i: usize| corners[i.min(corners.len() - 1)];
        Self {
            corners: std::array::from_fn(|k| {
                std::array::from_fn(|a| F32x4::from_array(std::array::from_fn(|i| lane(i)[k][a])))
            }),
            first,
            count: corners.len() as u32,
        }
    }

    /// The triangles it holds.
    pub fn triangles(&self) -> std::ops::Range<u32> {
        self.first..self.first + self.count
    }

    /// Lane `i`'s corners.
    fn lane_corners(&self, i: usize) -> [Vec3A; 3] {
        std::array::from_fn(|k| {
            let c = &self.corners[k];
            Vec3A::new(c[0].to_array()[i], c[1].to_array()[i], c[2].to_array()[i])
        })
    }

    /// The lanes' watertight tests, with t in (t_min, t_max); `mask` is NEEDS_SCALAR
    /// where the scalar test must decide.
    #[inline(always)]
    fn lanes(&self, ray: &GroupRay, t_min: f32, t_max: f32) -> LaneHits {
        let zero = F32x4::splat(0.0);
        let mut live = (1u32 << self.count) - 1;
        let (x, y, z) = (ray.axes.x, ray.axes.y, ray.axes.z);
        let [s_x, s_y, s_z] = ray.shear;
        // Each corner relative to the origin, on the permuted axes, sheared.
        let corner = |k: usize| {
            let c = &self.corners[k];
            let (px, py, pz) = (
                c[x] - ray.origin[0],
                c[y] - ray.origin[1],
                c[z] - ray.origin[2],
            );
            (px - s_x * pz, py - s_y * pz, pz)
        };
        let (ax, ay, a_z) = corner(0);
        let (bx, by, b_z) = corner(1);
        let (cx, cy, c_z) = corner(2);
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let mut hits = LaneHits {
            mask: 0,
            t: [0.0; 4],
            t_scaled: [0.0; 4],
            det: [0.0; 4],
            uvw: [u.to_array(), v.to_array(), w.to_array()],
        };
        if (u.eq_mask(zero) | v.eq_mask(zero) | w.eq_mask(zero)) & live != 0 {
            hits.mask = NEEDS_SCALAR;
            return hits;
        }
        let negative = u.lt_mask(zero) | v.lt_mask(zero) | w.lt_mask(zero);
        let positive = zero.lt_mask(u) | zero.lt_mask(v) | zero.lt_mask(w);
        live &= !(negative & positive);
        if live == 0 {
            return hits;
        }
        let det = u + v + w;
        live &= !det.eq_mask(zero);
        let az = s_z * a_z;
        let bz = s_z * b_z;
        let cz = s_z * c_z;
        let t_scaled = u * az + v * bz + w * cz;
        // t = t_scaled / det must lie in (0, t_max); compared without dividing.
        let limit = F32x4::splat(t_max) * det;
        let det_negative = det.lt_mask(zero);
        let det_positive = zero.lt_mask(det);
        live &= !(det_negative & (zero.le_mask(t_scaled) | t_scaled.lt_mask(limit)));
        live &= !(det_positive & (t_scaled.le_mask(zero) | limit.lt_mask(t_scaled)));
        if live == 0 {
            return hits;
        }
        let inv_det = F32x4::splat(1.0) / det;
        let t = t_scaled * inv_det;
        live &= !(t.le_mask(F32x4::splat(t_min)) | F32x4::splat(t_max).le_mask(t) | t.nan_mask());
        if live == 0 {
            return hits;
        }
        // The distance's error bound (triangle.rs, after pbrt-v4 6.5.3), lane by lane.
        let largest = |a: F32x4, b: F32x4, c: F32x4| a.abs().max_or(b.abs()).max_or(c.abs());
        let max_x = largest(ax, bx, cx);
        let max_y = largest(ay, by, cy);
        let max_z = largest(az, bz, cz);
        let max_z_unscaled = largest(a_z, b_z, c_z);
        let (g2, g3, g5) = (
            F32x4::splat(gamma(2)),
            F32x4::splat(gamma(3)),
            F32x4::splat(gamma(5)),
        );
        let delta_x = g5 * (max_x + max_z_unscaled);
        let delta_y = g5 * (max_y + max_z_unscaled);
        let delta_z = g3 * max_z;
        let delta_e = F32x4::splat(2.0) * (g2 * max_x * max_y + delta_y * max_x + delta_x * max_y);
        let max_e = largest(u, v, w);
        let delta_t = F32x4::splat(3.0)
            * (g3 * max_e * max_z + delta_e * max_z + delta_z * max_e)
            * inv_det.abs();
        live &= !t.le_mask(delta_t);
        hits.mask = live;
        hits.t = t.to_array();
        hits.t_scaled = t_scaled.to_array();
        hits.det = det.to_array();
        hits
    }

    /// The nearest hit with t in (t_min, t_max), and whose it is: what testing the
    /// triangles in order, each against the nearest found before it, returns.
    #[inline(always)]
    pub fn closest(
        &self,
        q: &RayQuery,
        ray: &GroupRay,
        t_min: f32,
        mut t_max: f32,
    ) -> Option<(u32, TriangleHit)> {
        let hits = self.lanes(ray, t_min, t_max);
        if hits.mask == NEEDS_SCALAR {
            let mut best = None;
            for i in 0..self.count as usize {
                if let Some(hit) = watertight(&self.lane_corners(i), q, t_min, t_max) {
                    t_max = hit.t;
                    best = Some((self.first + i as u32, hit));
                }
            }
            return best;
        }
        let mut best = None;
        let mut mask = hits.mask;
        while mask != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            // The tests that depend on t_max, again against the nearest so far.
            let (t, t_scaled, det) = (hits.t[i], hits.t_scaled[i], hits.det[i]);
            let limit = t_max * det;
            let outside = if det < 0.0 {
                t_scaled < limit
            } else {
                t_scaled > limit
            };
            if outside || t >= t_max {
                continue;
            }
            t_max = t;
            best = Some(i);
        }
        let i = best?;
        let inv_det = 1.0 / hits.det[i];
        Some((
            self.first + i as u32,
            TriangleHit {
                t: hits.t[i],
                b: [
                    hits.uvw[0][i] * inv_det,
                    hits.uvw[1][i] * inv_det,
                    hits.uvw[2][i] * inv_det,
                ],
            },
        ))
    }

    /// How many of its triangles the segment (t_min, t_max) crosses.
    #[inline(always)]
    pub fn crossings(&self, q: &RayQuery, ray: &GroupRay, t_min: f32, t_max: f32) -> u32 {
        let hits = self.lanes(ray, t_min, t_max);
        if hits.mask == NEEDS_SCALAR {
            return (0..self.count as usize)
                .filter(|&i| watertight(&self.lane_corners(i), q, t_min, t_max).is_some())
                .count() as u32;
        }
        hits.mask.count_ones()
    }

    /// Whether the segment (t_min, t_max) crosses any of its triangles.
    #[inline(always)]
    pub fn any(&self, q: &RayQuery, ray: &GroupRay, t_min: f32, t_max: f32) -> bool {
        let hits = self.lanes(ray, t_min, t_max);
        if hits.mask == NEEDS_SCALAR {
            return (0..self.count as usize)
                .any(|i| watertight(&self.lane_corners(i), q, t_min, t_max).is_some());
        }
        hits.mask != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;

    use crate::xorshift::XorShift32;

    /// A point in the cube of side `scale` about the origin.
    fn point(rng: &mut XorShift32, scale: f32) -> Vec3A {
        let mut next = || rng.next_f32() - 0.5;
        Vec3A::new(next(), next(), next()) * scale
    }

    /// The scalar loop the group stands in for.
    fn one_by_one(
        tris: &[[Vec3A; 3]],
        q: &RayQuery,
        t_min: f32,
        mut t_max: f32,
    ) -> (Option<(u32, TriangleHit)>, u32) {
        let mut best = None;
        let crossings = tris
            .iter()
            .filter(|p| watertight(p, q, t_min, t_max).is_some())
            .count() as u32;
        for (i, p) in tris.iter().enumerate() {
            if let Some(hit) = watertight(p, q, t_min, t_max) {
                t_max = hit.t;
                best = Some((i as u32, hit));
            }
        }
        (best, crossings)
    }

    fn bits(hit: Option<(u32, TriangleHit)>) -> Option<(u32, u32, [u32; 3])> {
        hit.map(|(i, h)| (i, h.t.to_bits(), h.b.map(f32::to_bits)))
    }

    /// On random triangles, shared edges and corners, rays through them and rays starting
    /// on them, groups of every size answer bit for bit what the scalar test answers.
    #[test]
    fn a_group_finds_what_its_triangles_find_one_by_one() {
        let mut rng = XorShift32::new(0x1234_5678);
        let mut hit = 0;
        for case in 0..20_000 {
            let n = 1 + case % GROUP_WIDTH;
            let scale = [1.0, 1e-3, 1e4][case % 3];
            let shift = point(&mut rng, scale * [0.0, 10.0, 1e3][case / 3 % 3]);
            // A fan around one centre, so that neighbours share edges and rays graze them.
            let centre = point(&mut rng, scale) + shift;
            let mut tris: Vec<[Vec3A; 3]> = Vec::new();
            let mut prev = point(&mut rng, scale) + shift;
            for _ in 0..n {
                let next = point(&mut rng, scale) + shift;
                tris.push([centre, prev, next]);
                prev = next;
            }
            let origin = match case % 4 {
                // From a corner or an edge: the rays that shadow rays are.
                0 => tris[0][1],
                1 => (tris[0][0] + tris[0][1]) * 0.5,
                _ => point(&mut rng, scale * 4.0) + shift,
            };
            let target = match case % 5 {
                0 => tris[n - 1][2],
                1 => centre,
                2 => (centre + tris[0][1]) * 0.5,
                _ => centre + point(&mut rng, scale * 0.5),
            };
            let q = RayQuery::new(Ray::new(
                glam::Vec3::from(origin),
                glam::Vec3::from(target - origin),
            ));
            let t_min = if case % 7 == 0 { 0.3 } else { 0.0 };
            let t_max = if case % 6 == 0 { 0.9 } else { f32::INFINITY };
            let group = TriangleGroup::new(100, &tris);
            let ray = GroupRay::new(&q);
            let (expected, crossings) = one_by_one(&tris, &q, t_min, t_max);
            let found = group
                .closest(&q, &ray, t_min, t_max)
                .map(|(i, h)| (i - 100, h));
            assert_eq!(bits(found), bits(expected), "case {case}");
            assert_eq!(group.crossings(&q, &ray, t_min, t_max), crossings);
            assert_eq!(group.any(&q, &ray, t_min, t_max), expected.is_some());
            hit += expected.is_some() as u32;
        }
        // The cases test hits as well as misses.
        assert!(hit > 5_000, "{hit}");
    }

    #[test]
    fn unused_lanes_are_never_hit() {
        let tri = [
            Vec3A::new(-1.0, -1.0, 0.0),
            Vec3A::new(1.0, -1.0, 0.0),
            Vec3A::new(0.0, 1.0, 0.0),
        ];
        let group = TriangleGroup::new(7, &[tri]);
        let q = RayQuery::new(Ray::new(glam::Vec3::new(0.0, 0.0, 5.0), -glam::Vec3::Z));
        let ray = GroupRay::new(&q);
        let (i, hit) = group.closest(&q, &ray, 0.0, f32::INFINITY).unwrap();
        assert_eq!((i, hit.t), (7, 5.0));
        assert_eq!(group.crossings(&q, &ray, 0.0, f32::INFINITY), 1);
        assert_eq!(group.triangles(), 7..8);
    }
}
