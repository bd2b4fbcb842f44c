//! A node of the wide BVH (`bvh.rs`): the boxes of up to eight children side by side, one
//! per SIMD lane, and the slab test that one ray runs on all of them at once (`enter`), in
//! any of the lane engines (`simd/eight.rs`), which find the same distances.

use crate::geometry::{Aabb, RayQuery};
use crate::numerics::gamma;
use crate::simd::{Halves, Lanes, Lanes8};
use glam::Vec3A;

/// Children per node: one per lane of the box test.
pub const WIDTH: usize = 8;

/// Eight children: their boxes per axis side by side (structure of arrays), and what each
/// child is. 256 bytes, four cache lines.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub struct WideNode {
    /// The boxes' sides, low then high on x, then on y, then on z (`plane`). One array, so
    /// that a ray picks its near and far sides by index (`WideRay::near`) without a branch.
    planes: [[f32; WIDTH]; 6],
    /// An inner node's index, a leaf's first primitive, or `NO_CHILD`.
    pub(super) child: [u32; WIDTH],
    /// A leaf's number of primitives; 0 for inner nodes and unused lanes.
    pub(super) count: [u32; WIDTH],
}

const NO_CHILD: u32 = u32::MAX;

/// `lane & LANE` is `lane` for any lane below WIDTH, a power of two.
pub(super) const LANE: usize = WIDTH - 1;

/// `WideNode::planes[plane(axis, side)]` is a side of the boxes, LO or HI, on an axis. The
/// two sides of an axis are neighbours: `^ FLIP` turns one's index into the other's.
const LO: usize = 0;
const HI: usize = 1;
const FLIP: usize = 1;

#[inline(always)]
const fn plane(axis: usize, side: usize) -> usize {
    2 * axis + side
}

/// What one lane of a node holds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Child {
    Empty,
    Node(u32),
    Leaf(std::ops::Range<u32>),
}

impl WideNode {
    /// Every lane unused, with an empty box that no ray enters.
    pub(super) const EMPTY: WideNode = WideNode {
        planes: [
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        child: [NO_CHILD; WIDTH],
        count: [0; WIDTH],
    };

    pub(super) fn set(&mut self, lane: usize, bounds: Aabb, child: Child) {
        for axis in 0..3 {
            self.planes[plane(axis, LO)][lane] = bounds.min[axis];
            self.planes[plane(axis, HI)][lane] = bounds.max[axis];
        }
        (self.child[lane], self.count[lane]) = match child {
            Child::Empty => (NO_CHILD, 0),
            Child::Node(i) => (i, 0),
            Child::Leaf(r) => (r.start, r.end - r.start),
        };
    }

    pub fn child(&self, lane: usize) -> Child {
        match (self.child[lane], self.count[lane]) {
            (NO_CHILD, _) => Child::Empty,
            (i, 0) => Child::Node(i),
            (first, n) => Child::Leaf(first..first + n),
        }
    }

    /// The box of one lane (empty for unused lanes).
    pub fn bounds(&self, lane: usize) -> Aabb {
        let get = |side: usize| {
            glam::Vec3::from_array(std::array::from_fn(|a| self.planes[plane(a, side)][lane]))
        };
        Aabb {
            min: get(LO),
            max: get(HI),
        }
    }

    /// Which lanes' boxes hold point `p` (bit i for lane i; on a face counts).
    #[inline(always)]
    pub(super) fn holding(&self, p: Vec3A) -> u32 {
        let l = Halves;
        let mut mask = (1 << WIDTH) - 1;
        for axis in 0..3 {
            let at = l.splat(p[axis]);
            mask &= l.le_mask(l.load(&self.planes[plane(axis, LO)]), at)
                & l.le_mask(at, l.load(&self.planes[plane(axis, HI)]));
        }
        mask
    }

    /// Which lanes' boxes the ray enters before `t_max` (bit i for lane i), and the entry
    /// distances. Robust against rounding: the far distances are widened by 2γ(3) (pbrt-v4
    /// 6.1.2), and an axis on which the ray runs exactly in a slab's boundary plane
    /// (0·∞ = NaN) leaves the interval alone (`max_or`/`min_or` keep the other operand).
    #[inline(always)]
    pub(super) fn enter<L: Lanes8>(
        &self,
        l: L,
        ray: &WideRay<L>,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]) {
        let mut t_enter = l.splat(0.0);
        let mut t_exit = l.splat(t_max);
        for axis in 0..3 {
            // The near plane is the low one for a ray going up the axis: no min/max needed,
            // and an empty box (lo = +∞, hi = −∞) is missed by every ray.
            let near = ray.near[axis] as usize;
            // SAFETY: `WideRay::new` makes `near` a side's index, below 6, and `^ FLIP`
            // keeps it so; unchecked, as the test runs twice per axis per node.
            let (near, far) = unsafe {
                (
                    l.load(self.planes.get_unchecked(near)),
                    l.load(self.planes.get_unchecked(near ^ FLIP)),
                )
            };
            let t_near = l.mul(l.sub(near, ray.origin[axis]), ray.inv_dir[axis]);
            let t_far = l.mul(l.sub(far, ray.origin[axis]), ray.inv_dir_far[axis]);
            t_enter = l.max_or(t_near, t_enter);
            t_exit = l.min_or(t_far, t_exit);
        }
        (l.le_mask(t_enter, t_exit), l.to_array(t_enter))
    }
}

/// The ray's constants for `WideNode::enter`, in every lane.
pub(super) struct WideRay<L: Lanes8> {
    origin: [L::V; 3],
    inv_dir: [L::V; 3],
    /// `inv_dir` scaled by 1 + 2γ(3): the far distances' rounding allowance.
    inv_dir_far: [L::V; 3],
    /// Per axis, the index in `WideNode::planes` of the side the ray meets first: the high
    /// side where it runs down the axis.
    near: [u8; 3],
}

impl<L: Lanes8> WideRay<L> {
    #[inline(always)]
    pub(super) fn new(l: L, q: &RayQuery) -> Self {
        let widen = 1.0 + 2.0 * gamma(3);
        Self {
            // Spelled out: a closure would be compiled apart from the AVX2 function this is
            // inlined into, and each lane operation in it would be a call where not inlined.
            origin: [
                l.splat(q.ray.origin.x),
                l.splat(q.ray.origin.y),
                l.splat(q.ray.origin.z),
            ],
            inv_dir: [
                l.splat(q.inv_dir.x),
                l.splat(q.inv_dir.y),
                l.splat(q.inv_dir.z),
            ],
            inv_dir_far: [
                l.splat(q.inv_dir.x * widen),
                l.splat(q.inv_dir.y * widen),
                l.splat(q.inv_dir.z * widen),
            ],
            // The sign bit, so that a −0 component (inverse −∞) counts as negative.
            near: std::array::from_fn(|a| {
                plane(
                    a,
                    if q.inv_dir[a].is_sign_negative() {
                        HI
                    } else {
                        LO
                    },
                ) as u8
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;
    use glam::Vec3;

    /// The entry distance into lane 0's box and whether the ray enters it before `t_max`.
    fn enter_one(b: Aabb, q: &RayQuery, t_max: f32) -> Option<f32> {
        let mut node = WideNode::EMPTY;
        node.set(0, b, Child::Leaf(0..1));
        let (mask, t) = node.enter(Halves, &WideRay::new(Halves, q), t_max);
        (mask & 1 != 0).then_some(t[0])
    }

    #[test]
    fn slab_test_hits_and_misses() {
        let b = Aabb::from_points(&[Vec3::splat(-1.0), Vec3::splat(1.0)]);
        let q = RayQuery::new(Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z));
        assert_eq!(enter_one(b, &q, f32::INFINITY), Some(4.0));
        assert_eq!(enter_one(b, &q, 3.0), None);
        let miss = RayQuery::new(Ray::new(Vec3::new(2.0, 0.0, 5.0), -Vec3::Z));
        assert_eq!(enter_one(b, &miss, f32::INFINITY), None);
        let inside = RayQuery::new(Ray::new(Vec3::ZERO, Vec3::X));
        assert_eq!(enter_one(b, &inside, f32::INFINITY), Some(0.0));
    }

    #[test]
    fn flat_box_is_hit_by_axis_parallel_ray_on_its_face() {
        // A box of zero thickness (a floor polygon) seen edge-on along its own plane:
        // 0·∞ = NaN on y, which the lanes' NaN rule leaves out.
        let b = Aabb::from_points(&[Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0)]);
        let q = RayQuery::new(Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X));
        assert_eq!(enter_one(b, &q, f32::INFINITY), Some(4.0));
    }
}
