//! Four triangles against one ray at once: their corners side by side in SIMD lanes
//! (structure of arrays, as Embree's triangle4 leaves), each lane running exactly the
//! operations of the scalar watertight test (triangle.rs) in the same order. A group
//! therefore finds bit for bit what testing its triangles one by one finds: the lanes'
//! hits are taken in lane order, each against the nearest distance found before it, as
//! the scalar loop takes them. Where the processor has AVX2, two groups of one leaf are
//! tested at once in eight lanes (`GroupPair`), by the same test (`lane_hits`), generic
//! over the lanes' width.

use super::ray::{Axes, RayQuery};
use super::triangle::{TriangleHit, watertight};
use crate::numerics::gamma;
use crate::simd::{F32x4, Four, Lanes, Lanes8};
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

/// A ray's constants for the lane test, in every lane of an engine: its origin on the
/// permuted axes and its shear (RayQuery's `axes` and `shear`).
pub struct LaneRay<L: Lanes> {
    origin: [L::V; 3],
    shear: [L::V; 3],
    axes: Axes,
}

/// A ray's constants for one group's test, in four lanes.
pub type GroupRay = LaneRay<Four>;

impl<L: Lanes> LaneRay<L> {
    /// The constants of `q`'s ray in the lanes of `l`.
    #[inline(always)]
    pub fn in_lanes(l: L, q: &RayQuery) -> Self {
        let [ox, oy, oz] = q.axes.permute(q.ray.origin);
        Self {
            origin: [l.splat(ox), l.splat(oy), l.splat(oz)],
            shear: [l.splat(q.shear.x), l.splat(q.shear.y), l.splat(q.shear.z)],
            axes: q.axes,
        }
    }
}

impl GroupRay {
    /// The constants of `q`'s ray, for one group.
    #[inline(always)]
    pub fn new(q: &RayQuery) -> Self {
        Self::in_lanes(Four, q)
    }
}

/// What the lanes found, before the nearest is chosen.
struct LaneHits<A> {
    /// Bit i set where lane i's triangle is hit within (t_min, t_max).
    mask: u32,
    t: A,
    t_scaled: A,
    det: A,
    /// The edge functions, which divided by `det` are the barycentric weights.
    uvw: [A; 3],
}

/// Where any lane needs the scalar test: an edge function of exactly zero is decided in
/// f64 there, a rare case not worth lanes of its own.
const NEEDS_SCALAR: u32 = u32::MAX;

/// A corner of the lanes' triangles (`corner`: its coordinates on the ray's permuted axes)
/// relative to the ray's origin, sheared. (Functions, not closures, here and below: a
/// closure would be compiled apart from the AVX2 function this is inlined into, and each
/// lane operation in it would be a call.)
#[inline(always)]
fn lane_corner<L: Lanes>(l: L, corner: &[L::V; 3], ray: &LaneRay<L>) -> (L::V, L::V, L::V) {
    let [s_x, s_y, _] = ray.shear;
    let (px, py, pz) = (
        l.sub(corner[0], ray.origin[0]),
        l.sub(corner[1], ray.origin[1]),
        l.sub(corner[2], ray.origin[2]),
    );
    (l.sub(px, l.mul(s_x, pz)), l.sub(py, l.mul(s_y, pz)), pz)
}

/// The largest magnitude of `a`, `b` and `c`, lane by lane.
#[inline(always)]
fn largest<L: Lanes>(l: L, a: L::V, b: L::V, c: L::V) -> L::V {
    l.max_or(l.max_or(l.abs(a), l.abs(b)), l.abs(c))
}

/// The watertight test of the triangles in the lanes (`corners[k][a]`: corner k's
/// coordinate on the ray's permuted axis a) whose bits are set in `live`, with t in (t_min, t_max); `mask` is
/// NEEDS_SCALAR where the scalar test must decide.
#[inline(always)]
fn lane_hits<L: Lanes>(
    l: L,
    corners: &[[L::V; 3]; 3],
    mut live: u32,
    ray: &LaneRay<L>,
    t_min: f32,
    t_max: f32,
) -> LaneHits<L::Array> {
    let zero = l.splat(0.0);
    let s_z = ray.shear[2];
    let (ax, ay, a_z) = lane_corner(l, &corners[0], ray);
    let (bx, by, b_z) = lane_corner(l, &corners[1], ray);
    let (cx, cy, c_z) = lane_corner(l, &corners[2], ray);
    let u = l.sub(l.mul(cx, by), l.mul(cy, bx));
    let v = l.sub(l.mul(ax, cy), l.mul(ay, cx));
    let w = l.sub(l.mul(bx, ay), l.mul(by, ax));
    let zeros = l.to_array(zero);
    let mut hits = LaneHits {
        mask: 0,
        t: zeros,
        t_scaled: zeros,
        det: zeros,
        uvw: [l.to_array(u), l.to_array(v), l.to_array(w)],
    };
    if (l.eq_mask(u, zero) | l.eq_mask(v, zero) | l.eq_mask(w, zero)) & live != 0 {
        hits.mask = NEEDS_SCALAR;
        return hits;
    }
    let negative = l.lt_mask(u, zero) | l.lt_mask(v, zero) | l.lt_mask(w, zero);
    let positive = l.lt_mask(zero, u) | l.lt_mask(zero, v) | l.lt_mask(zero, w);
    live &= !(negative & positive);
    if live == 0 {
        return hits;
    }
    let det = l.add(l.add(u, v), w);
    live &= !l.eq_mask(det, zero);
    let az = l.mul(s_z, a_z);
    let bz = l.mul(s_z, b_z);
    let cz = l.mul(s_z, c_z);
    let t_scaled = l.add(l.add(l.mul(u, az), l.mul(v, bz)), l.mul(w, cz));
    // t = t_scaled / det must lie in (0, t_max); compared without dividing.
    let limit = l.mul(l.splat(t_max), det);
    let det_negative = l.lt_mask(det, zero);
    let det_positive = l.lt_mask(zero, det);
    live &= !(det_negative & (l.le_mask(zero, t_scaled) | l.lt_mask(t_scaled, limit)));
    live &= !(det_positive & (l.le_mask(t_scaled, zero) | l.lt_mask(limit, t_scaled)));
    if live == 0 {
        return hits;
    }
    let inv_det = l.div(l.splat(1.0), det);
    let t = l.mul(t_scaled, inv_det);
    live &= !(l.le_mask(t, l.splat(t_min)) | l.le_mask(l.splat(t_max), t) | l.nan_mask(t));
    if live == 0 {
        return hits;
    }
    // The distance's error bound (triangle.rs, after pbrt-v4 6.5.3), lane by lane.
    let max_x = largest(l, ax, bx, cx);
    let max_y = largest(l, ay, by, cy);
    let max_z = largest(l, az, bz, cz);
    let max_z_unscaled = largest(l, a_z, b_z, c_z);
    let (g2, g3, g5) = (l.splat(gamma(2)), l.splat(gamma(3)), l.splat(gamma(5)));
    let delta_x = l.mul(g5, l.add(max_x, max_z_unscaled));
    let delta_y = l.mul(g5, l.add(max_y, max_z_unscaled));
    let delta_z = l.mul(g3, max_z);
    let delta_e = l.mul(
        l.splat(2.0),
        l.add(
            l.add(l.mul(l.mul(g2, max_x), max_y), l.mul(delta_y, max_x)),
            l.mul(delta_x, max_y),
        ),
    );
    let max_e = largest(l, u, v, w);
    let delta_t = l.mul(
        l.mul(
            l.splat(3.0),
            l.add(
                l.add(l.mul(l.mul(g3, max_e), max_z), l.mul(delta_e, max_z)),
                l.mul(delta_z, max_e),
            ),
        ),
        l.abs(inv_det),
    );
    live &= !l.le_mask(t, delta_t);
    hits.mask = live;
    hits.t = l.to_array(t);
    hits.t_scaled = l.to_array(t_scaled);
    hits.det = l.to_array(det);
    hits
}

impl<A: std::ops::Index<usize, Output = f32>> LaneHits<A> {
    /// The nearest of the lanes' hits nearer than `t_max`, taken in lane order, each against
    /// the nearest found before it, as the scalar loop takes them: its lane and the hit.
    #[inline(always)]
    fn nearest(&self, mut t_max: f32) -> Option<(usize, TriangleHit)> {
        let mut best = None;
        let mut mask = self.mask;
        while mask != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            // The tests that depend on t_max, again against the nearest so far.
            let (t, t_scaled, det) = (self.t[i], self.t_scaled[i], self.det[i]);
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
        let inv_det = 1.0 / self.det[i];
        Some((
            i,
            TriangleHit {
                t: self.t[i],
                b: [
                    self.uvw[0][i] * inv_det,
                    self.uvw[1][i] * inv_det,
                    self.uvw[2][i] * inv_det,
                ],
            },
        ))
    }
}

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
    #[inline(always)]
    fn lane_corners(&self, i: usize) -> [Vec3A; 3] {
        std::array::from_fn(|k| {
            let c = &self.corners[k];
            Vec3A::new(c[0].lane(i), c[1].lane(i), c[2].lane(i))
        })
    }

    /// The corners of `triangle`, one of those it holds: the mesh's vertices, bit for bit.
    #[inline(always)]
    pub fn corners_of(&self, triangle: u32) -> [Vec3A; 3] {
        debug_assert!(self.triangles().contains(&triangle));
        self.lane_corners((triangle.wrapping_sub(self.first) as usize) & (GROUP_WIDTH - 1))
    }

    /// The lanes in use, as a mask.
    #[inline(always)]
    fn live(&self) -> u32 {
        (1u32 << self.count) - 1
    }

    /// The lanes' watertight tests, with t in (t_min, t_max).
    #[inline(always)]
    fn lanes(&self, ray: &GroupRay, t_min: f32, t_max: f32) -> LaneHits<[f32; 4]> {
        let (x, y, z) = (ray.axes.x, ray.axes.y, ray.axes.z);
        let c = &self.corners;
        let permuted = [
            [c[0][x], c[0][y], c[0][z]],
            [c[1][x], c[1][y], c[1][z]],
            [c[2][x], c[2][y], c[2][z]],
        ];
        lane_hits(Four, &permuted, self.live(), ray, t_min, t_max)
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
        let (i, hit) = hits.nearest(t_max)?;
        Some((self.first + i as u32, hit))
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

/// Two groups of one leaf, tested at once in eight lanes (lanes 0..4 the first's, 4..8 the
/// second's): the pair finds bit for bit what the two groups find one after the other.
#[derive(Clone, Copy)]
pub struct GroupPair<'g> {
    /// The group whose triangles come first.
    pub first: &'g TriangleGroup,
    /// The group after it in the leaf.
    pub second: &'g TriangleGroup,
}

/// Corner k of both groups (`first[a]`, `second[a]`: its coordinate on axis a), in eight
/// lanes, on the permuted axes `axes`.
#[inline(always)]
fn joined<L: Lanes8>(l: L, first: &[F32x4; 3], second: &[F32x4; 3], axes: Axes) -> [L::V; 3] {
    [
        l.join(first[axes.x], second[axes.x]),
        l.join(first[axes.y], second[axes.y]),
        l.join(first[axes.z], second[axes.z]),
    ]
}

impl GroupPair<'_> {
    /// The lanes' watertight tests, with t in (t_min, t_max).
    #[inline(always)]
    fn lanes<L: Lanes8>(
        &self,
        l: L,
        ray: &LaneRay<L>,
        t_min: f32,
        t_max: f32,
    ) -> LaneHits<[f32; 8]> {
        let (f, g) = (&self.first.corners, &self.second.corners);
        let corners = [
            joined(l, &f[0], &g[0], ray.axes),
            joined(l, &f[1], &g[1], ray.axes),
            joined(l, &f[2], &g[2], ray.axes),
        ];
        let live = self.first.live() | (self.second.live() << GROUP_WIDTH);
        lane_hits(l, &corners, live, ray, t_min, t_max)
    }

    /// The nearest hit with t in (t_min, t_max), and whose it is: what the first group's
    /// `closest` and then the second's, against the nearest the first found, return.
    #[inline(always)]
    pub fn closest<L: Lanes8>(
        &self,
        l: L,
        q: &RayQuery,
        ray: &LaneRay<L>,
        t_min: f32,
        t_max: f32,
    ) -> Option<(u32, TriangleHit)> {
        let hits = self.lanes(l, ray, t_min, t_max);
        if hits.mask == NEEDS_SCALAR {
            let group_ray = GroupRay::new(q);
            let first = self.first.closest(q, &group_ray, t_min, t_max);
            let t_max = first.map_or(t_max, |(_, hit)| hit.t);
            return self.second.closest(q, &group_ray, t_min, t_max).or(first);
        }
        let (i, hit) = hits.nearest(t_max)?;
        let triangle = if i < GROUP_WIDTH {
            self.first.first + i as u32
        } else {
            self.second.first + (i - GROUP_WIDTH) as u32
        };
        Some((triangle, hit))
    }

    /// Whether the segment (t_min, t_max) crosses any of their triangles.
    #[inline(always)]
    pub fn any<L: Lanes8>(
        &self,
        l: L,
        q: &RayQuery,
        ray: &LaneRay<L>,
        t_min: f32,
        t_max: f32,
    ) -> bool {
        let hits = self.lanes(l, ray, t_min, t_max);
        if hits.mask == NEEDS_SCALAR {
            let group_ray = GroupRay::new(q);
            return self.first.any(q, &group_ray, t_min, t_max)
                || self.second.any(q, &group_ray, t_min, t_max);
        }
        hits.mask != 0
    }
}

/// Triangles per `TriangleOctet`.
pub const OCTET_WIDTH: usize = 8;

/// A triangle of a mesh in a sorted list (a first-hit tile's, a light cell's): the list's
/// key, the group that holds the triangle, and its index in the mesh.
pub type ListedTriangle = (f32, u32, u32);

/// Up to eight triangles of a mesh, any of them (a first-hit tile's or a light cell's, in
/// the order of their lists), corner
/// by corner and axis by axis in eight lanes, tested at once by the same lane test as a
/// group: the octet finds bit for bit what testing its triangles one by one in lane order
/// finds. Unused lanes repeat the last triangle and are masked off.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct TriangleOctet {
    /// `corners[k][a][i]`: corner k's coordinate on axis a, of lane i's triangle.
    corners: [[[f32; 8]; 3]; 3],
    /// Lane i's triangle, and the group that holds it in the mesh.
    triangles: [(u32, u32); 8],
    /// The lanes in use, 1..=8.
    count: u32,
    /// The key its list is sorted by, no greater than any of its triangles' (in a first-hit
    /// tile, the least distance from the eye to a hit; in a light's cell, the least squared
    /// distance from the light).
    pub nearest: f32,
}

/// A corner of an octet's triangles (`corner[a]`: its coordinate on axis a) in eight lanes,
/// on the permuted axes `axes`.
#[inline(always)]
fn loaded<L: Lanes8>(l: L, corner: &[[f32; 8]; 3], axes: Axes) -> [L::V; 3] {
    [
        l.load(&corner[axes.x]),
        l.load(&corner[axes.y]),
        l.load(&corner[axes.z]),
    ]
}

impl TriangleOctet {
    /// The octet of the triangles (index, group) `triangles` whose corners are `corners`
    /// (one to eight), whose list key is `nearest`.
    pub fn new(triangles: &[(u32, u32)], corners: &[[Vec3A; 3]], nearest: f32) -> Self {
        assert!((1..=8).contains(&corners.len()) && triangles.len() == corners.len());
        let lane = |i: usize| i.min(corners.len() - 1);
        Self {
            corners: std::array::from_fn(|k| {
                std::array::from_fn(|a| std::array::from_fn(|i| corners[lane(i)][k][a]))
            }),
            triangles: std::array::from_fn(|i| triangles[lane(i)]),
            count: corners.len() as u32,
            nearest,
        }
    }

    /// The triangles of `listed` (sorted by key; their corners read from the mesh's
    /// `groups`), eight to an octet in order, onto `octets`: each octet's key is its first
    /// triangle's.
    pub fn pack(groups: &[TriangleGroup], listed: &[ListedTriangle], octets: &mut Vec<Self>) {
        for chunk in listed.chunks(OCTET_WIDTH) {
            let mut ids = [(0, 0); OCTET_WIDTH];
            let mut corners = [[Vec3A::ZERO; 3]; OCTET_WIDTH];
            for (i, &(_, group, triangle)) in chunk.iter().enumerate() {
                ids[i] = (triangle, group);
                corners[i] = groups[group as usize].corners_of(triangle);
            }
            let n = chunk.len();
            octets.push(Self::new(&ids[..n], &corners[..n], chunk[0].0));
        }
    }

    /// Lane `i`'s corners.
    fn lane_corners(&self, i: usize) -> [Vec3A; 3] {
        std::array::from_fn(|k| {
            let c = &self.corners[k];
            Vec3A::new(c[0][i], c[1][i], c[2][i])
        })
    }

    /// The lanes' watertight tests, with t in (t_min, t_max).
    #[inline(always)]
    fn lanes<L: Lanes8>(
        &self,
        l: L,
        ray: &LaneRay<L>,
        t_min: f32,
        t_max: f32,
    ) -> LaneHits<[f32; 8]> {
        let c = &self.corners;
        let corners = [
            loaded(l, &c[0], ray.axes),
            loaded(l, &c[1], ray.axes),
            loaded(l, &c[2], ray.axes),
        ];
        let live = (1u32 << self.count) - 1;
        lane_hits(l, &corners, live, ray, t_min, t_max)
    }

    /// The nearest hit with t in (t_min, t_max), and whose it is (triangle, group): what
    /// testing the triangles in lane order, each against the nearest found before it,
    /// returns.
    #[inline(always)]
    pub fn closest<L: Lanes8>(
        &self,
        l: L,
        q: &RayQuery,
        ray: &LaneRay<L>,
        t_min: f32,
        mut t_max: f32,
    ) -> Option<((u32, u32), TriangleHit)> {
        let hits = self.lanes(l, ray, t_min, t_max);
        if hits.mask == NEEDS_SCALAR {
            let mut best = None;
            for i in 0..self.count as usize {
                if let Some(hit) = watertight(&self.lane_corners(i), q, t_min, t_max) {
                    t_max = hit.t;
                    best = Some((self.triangles[i], hit));
                }
            }
            return best;
        }
        let (i, hit) = hits.nearest(t_max)?;
        Some((self.triangles[i], hit))
    }

    /// Whether the segment (t_min, t_max) crosses any of its triangles.
    #[inline(always)]
    pub fn any<L: Lanes8>(
        &self,
        l: L,
        q: &RayQuery,
        ray: &LaneRay<L>,
        t_min: f32,
        t_max: f32,
    ) -> bool {
        let hits = self.lanes(l, ray, t_min, t_max);
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

    /// Case `case` of the tests below: `n` triangles in a fan around one centre, so that
    /// neighbours share edges and rays graze them, at one of three scales and shifts, and a
    /// ray at them (from a corner or an edge now and then: the rays that shadow rays are;
    /// some aimed between the centre and triangle `aim`'s corner), with its t_min and t_max.
    fn fan_case(
        rng: &mut XorShift32,
        case: usize,
        n: usize,
        aim: usize,
    ) -> (Vec<[Vec3A; 3]>, RayQuery, f32, f32) {
        let scale = [1.0, 1e-3, 1e4][case % 3];
        let shift = point(rng, scale * [0.0, 10.0, 1e3][case / 3 % 3]);
        let centre = point(rng, scale) + shift;
        let mut tris: Vec<[Vec3A; 3]> = Vec::new();
        let mut prev = point(rng, scale) + shift;
        for _ in 0..n {
            let next = point(rng, scale) + shift;
            tris.push([centre, prev, next]);
            prev = next;
        }
        let origin = match case % 4 {
            0 => tris[0][1],
            1 => (tris[0][0] + tris[0][1]) * 0.5,
            _ => point(rng, scale * 4.0) + shift,
        };
        let target = match case % 5 {
            0 => tris[n - 1][2],
            1 => centre,
            2 => (centre + tris[aim][1]) * 0.5,
            _ => centre + point(rng, scale * 0.5),
        };
        let q = RayQuery::new(Ray::new(
            glam::Vec3::from(origin),
            glam::Vec3::from(target - origin),
        ));
        let t_min = if case.is_multiple_of(7) { 0.3 } else { 0.0 };
        let t_max = if case.is_multiple_of(6) {
            0.9
        } else {
            f32::INFINITY
        };
        (tris, q, t_min, t_max)
    }

    /// On random triangles, shared edges and corners, rays through them and rays starting
    /// on them, groups of every size answer bit for bit what the scalar test answers.
    #[test]
    fn a_group_finds_what_its_triangles_find_one_by_one() {
        let mut rng = XorShift32::new(0x1234_5678);
        let mut hit = 0;
        for case in 0..20_000 {
            let n = 1 + case % GROUP_WIDTH;
            let (tris, q, t_min, t_max) = fan_case(&mut rng, case, n, 0);
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

    /// Two groups tested at once, in either engine, against the two one after the other;
    /// whether they hit.
    fn assert_pair_as_two<L: Lanes8>(
        l: L,
        first: &TriangleGroup,
        second: &TriangleGroup,
        q: &RayQuery,
        t_min: f32,
        t_max: f32,
    ) -> bool {
        let ray = GroupRay::new(q);
        let one = first.closest(q, &ray, t_min, t_max);
        let two = second.closest(q, &ray, t_min, one.map_or(t_max, |(_, h)| h.t));
        let expected = two.or(one);
        let pair = GroupPair { first, second };
        let pair_ray = LaneRay::in_lanes(l, q);
        assert_eq!(
            bits(pair.closest(l, q, &pair_ray, t_min, t_max)),
            bits(expected)
        );
        let any = first.any(q, &ray, t_min, t_max) || second.any(q, &ray, t_min, t_max);
        assert_eq!(pair.any(l, q, &pair_ray, t_min, t_max), any);
        expected.is_some()
    }

    /// On the cases above, split into two groups of every pair of sizes, a pair finds bit
    /// for bit what its groups find one after the other, with the baseline's halves and
    /// with AVX2 where the processor has it.
    #[test]
    fn a_pair_of_groups_finds_what_the_two_find_in_turn() {
        let mut rng = XorShift32::new(0x8765_4321);
        let mut hit = 0;
        for case in 0..20_000 {
            let n = 2 + case % (2 * GROUP_WIDTH - 1);
            let split =
                (1 + (case / 7) % (n - 1).min(GROUP_WIDTH)).max(n.saturating_sub(GROUP_WIDTH));
            let (tris, q, t_min, t_max) = fan_case(&mut rng, case, n, split);
            let first = TriangleGroup::new(100, &tris[..split]);
            let second = TriangleGroup::new(100 + split as u32, &tris[split..]);
            hit +=
                assert_pair_as_two(crate::simd::Halves, &first, &second, &q, t_min, t_max) as u32;
            #[cfg(target_arch = "x86_64")]
            if let Some(avx) = crate::simd::Avx::new() {
                assert_pair_as_two(avx, &first, &second, &q, t_min, t_max);
            }
        }
        assert!(hit > 5_000, "{hit}");
    }

    /// On the fan cases, with one to eight triangles in lanes in any order (here reversed,
    /// with made-up indices and groups), an octet finds bit for bit what its triangles one
    /// by one in lane order find, with the baseline's halves and with AVX2 where the
    /// processor has it; unused lanes are never hit.
    #[test]
    fn an_octet_finds_what_its_triangles_find_one_by_one() {
        let mut rng = XorShift32::new(0x0bad_cafe);
        let mut hit = 0;
        for case in 0..20_000 {
            let n = 1 + case % 8;
            let (mut tris, q, t_min, t_max) = fan_case(&mut rng, case, n, case % n);
            tris.reverse();
            let ids: Vec<(u32, u32)> = (0..n as u32).map(|i| (1000 + 3 * i, 50 + i)).collect();
            let octet = TriangleOctet::new(&ids, &tris, 0.0);
            let (expected, _) = one_by_one(&tris, &q, t_min, t_max);
            let lane = |found: Option<((u32, u32), TriangleHit)>| {
                found.map(|((t, g), h)| {
                    let i = ids.iter().position(|&id| id == (t, g)).unwrap();
                    (i as u32, h)
                })
            };
            let halves = crate::simd::Halves;
            let found = octet.closest(halves, &q, &LaneRay::in_lanes(halves, &q), t_min, t_max);
            assert_eq!(bits(lane(found)), bits(expected), "case {case}");
            #[cfg(target_arch = "x86_64")]
            if let Some(avx) = crate::simd::Avx::new() {
                let found = octet.closest(avx, &q, &LaneRay::in_lanes(avx, &q), t_min, t_max);
                assert_eq!(bits(lane(found)), bits(expected), "case {case}, AVX2");
            }
            hit += expected.is_some() as u32;
        }
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
