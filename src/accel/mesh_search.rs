//! A mesh's triangles searched for a ray: by walking its hierarchy (the nearest hit, or
//! any hit on a segment), or, for a primary ray, among the triangles a first-hit tile lists
//! (mesh_listing.rs); for a shadow ray, among the triangles a light's cell lists
//! (shadow_listing.rs). A leaf's groups are tested two at a time in eight lanes
//! (`GroupPair`), a tile's triangles eight at a time (`TriangleOctet`), compiled for AVX2
//! where the processor has it.

use super::bvh::Bvh;
use crate::geometry::{
    GroupPair, GroupRay, HitDetail, LaneRay, RayQuery, ShapeHit, TriangleGroup, TriangleHit,
    TriangleOctet,
};
#[cfg(target_arch = "x86_64")]
use crate::simd::Avx;
use crate::simd::Lanes8;

/// A leaf's groups, two at a time while two are left (a leaf holds one or two groups, more
/// only where many triangles share one centre).
enum LeafGroups<'g> {
    Pair(GroupPair<'g>),
    One(&'g TriangleGroup),
}

/// The groups of a leaf (`leaf`), in order, two at a time.
#[inline(always)]
fn in_pairs(leaf: &[TriangleGroup]) -> impl Iterator<Item = LeafGroups<'_>> {
    leaf.chunks(2).map(|groups| match groups {
        [first, second] => LeafGroups::Pair(GroupPair { first, second }),
        [one] => LeafGroups::One(one),
        _ => unreachable!("chunks of one or two"),
    })
}

/// The hit `hit` on triangle `triangle` of the mesh, held by its group `group`.
#[inline(always)]
fn mesh_hit(triangle: u32, group: u32, hit: TriangleHit) -> ShapeHit {
    ShapeHit {
        t: hit.t,
        detail: HitDetail::Mesh {
            triangle,
            group,
            b: hit.b,
        },
    }
}

/// The nearest hit along `q` with t in (t_min, t_max) on the mesh of `bvh` and `groups`,
/// walked in the lanes of `l`: a leaf's groups are tested two at a time (`GroupPair`), each
/// pair finding what its groups find one after the other.
#[inline(always)]
pub(super) fn mesh_closest<L: Lanes8>(
    l: L,
    bvh: &Bvh,
    groups: &[TriangleGroup],
    q: &RayQuery,
    t_min: f32,
    t_max: f32,
) -> Option<ShapeHit> {
    let ray = GroupRay::new(q);
    let pair_ray = LaneRay::in_lanes(l, q);
    let mut best = None;
    bvh.closest_with(
        l,
        q,
        t_max,
        #[inline(always)]
        |leaf, mut t_max| {
            let mut nearest = None;
            // The index of the pair's (or the lone group's) first group.
            let mut index = leaf.start;
            for groups in in_pairs(&groups[leaf.start as usize..leaf.end as usize]) {
                let (found, group) = match groups {
                    LeafGroups::Pair(pair) => {
                        let found = pair.closest(l, q, &pair_ray, t_min, t_max);
                        let second = found
                            .is_some_and(|(triangle, _)| triangle >= pair.second.triangles().start);
                        (found, index + second as u32)
                    }
                    LeafGroups::One(group) => (group.closest(q, &ray, t_min, t_max), index),
                };
                index += 2;
                if let Some((triangle, hit)) = found {
                    t_max = hit.t;
                    nearest = Some(hit.t);
                    best = Some(mesh_hit(triangle, group, hit));
                }
            }
            nearest
        },
    );
    best
}

/// The nearest hit along `q` with t in (0, t_max) among the triangles of `listed` (a
/// first-hit tile's octets, nearest first), eight at a time in the lanes of `l`.
#[inline(always)]
fn listed_closest<L: Lanes8>(
    l: L,
    listed: &[TriangleOctet],
    q: &RayQuery,
    mut t_max: f32,
) -> Option<ShapeHit> {
    let ray = LaneRay::in_lanes(l, q);
    let mut best = None;
    for octet in listed {
        if octet.nearest >= t_max {
            break; // this octet and every later one start beyond the nearest hit
        }
        if let Some(((triangle, group), hit)) = octet.closest(l, q, &ray, 0.0, t_max) {
            t_max = hit.t;
            best = Some(mesh_hit(triangle, group, hit));
        }
    }
    best
}

/// `listed_closest` in the widest lanes the processor has.
pub(super) fn listed_closest_here(
    listed: &[TriangleOctet],
    q: &RayQuery,
    t_max: f32,
) -> Option<ShapeHit> {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx) = crate::isa::avx2_lanes() {
        // SAFETY: an `Avx` exists only where the processor has AVX2.
        return unsafe { listed_closest_avx2(avx, listed, q, t_max) };
    }
    listed_closest(crate::simd::Halves, listed, q, t_max)
}

/// `listed_closest` compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn listed_closest_avx2(
    avx: Avx,
    listed: &[TriangleOctet],
    q: &RayQuery,
    t_max: f32,
) -> Option<ShapeHit> {
    listed_closest(avx, listed, q, t_max)
}

/// Whether any triangle of `listed` (a light cell's octets, nearest to the light first)
/// lies on the segment (0, t_max) of `q`, a shadow ray whose shading point lies at a
/// squared distance `distance_sq` from the light, tested eight at a time in the lanes of
/// `l`.
#[inline(always)]
fn listed_any<L: Lanes8>(
    l: L,
    listed: &[TriangleOctet],
    q: &RayQuery,
    t_max: f32,
    distance_sq: f32,
) -> bool {
    let ray = LaneRay::in_lanes(l, q);
    listed
        .iter()
        // This octet and every later one start beyond the shading point.
        .take_while(|octet| octet.nearest < distance_sq)
        .any(|octet| octet.any(l, q, &ray, 0.0, t_max))
}

/// `listed_any` in the widest lanes the processor has.
pub(super) fn listed_any_here(
    listed: &[TriangleOctet],
    q: &RayQuery,
    t_max: f32,
    distance_sq: f32,
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx) = crate::isa::avx2_lanes() {
        // SAFETY: an `Avx` exists only where the processor has AVX2.
        return unsafe { listed_any_avx2(avx, listed, q, t_max, distance_sq) };
    }
    listed_any(crate::simd::Halves, listed, q, t_max, distance_sq)
}

/// `listed_any` compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn listed_any_avx2(
    avx: Avx,
    listed: &[TriangleOctet],
    q: &RayQuery,
    t_max: f32,
    distance_sq: f32,
) -> bool {
    listed_any(avx, listed, q, t_max, distance_sq)
}

/// `mesh_closest` compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) fn mesh_closest_avx2(
    avx: Avx,
    bvh: &Bvh,
    groups: &[TriangleGroup],
    q: &RayQuery,
    t_min: f32,
    t_max: f32,
) -> Option<ShapeHit> {
    mesh_closest(avx, bvh, groups, q, t_min, t_max)
}

/// Whether anything of the mesh of `bvh` and `groups` lies on the segment (0, t_max) of
/// `q`, walked as `mesh_closest` walks it.
#[inline(always)]
pub(super) fn mesh_occludes<L: Lanes8>(
    l: L,
    bvh: &Bvh,
    groups: &[TriangleGroup],
    q: &RayQuery,
    t_max: f32,
) -> bool {
    let ray = GroupRay::new(q);
    let pair_ray = LaneRay::in_lanes(l, q);
    let mut hit = false;
    bvh.visit_with(
        l,
        q,
        t_max,
        #[inline(always)]
        |leaf| {
            hit =
                in_pairs(&groups[leaf.start as usize..leaf.end as usize]).any(
                    |groups| match groups {
                        LeafGroups::Pair(pair) => pair.any(l, q, &pair_ray, 0.0, t_max),
                        LeafGroups::One(group) => group.any(q, &ray, 0.0, t_max),
                    },
                );
            !hit
        },
    );
    hit
}

/// `mesh_occludes` compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub(super) fn mesh_occludes_avx2(
    avx: Avx,
    bvh: &Bvh,
    groups: &[TriangleGroup],
    q: &RayQuery,
    t_max: f32,
) -> bool {
    mesh_occludes(avx, bvh, groups, q, t_max)
}
