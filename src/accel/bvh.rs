//! The hierarchy that rays traverse: the binary SAH tree of `bvh_build.rs` collapsed into
//! nodes of eight children whose boxes one ray tests at once, one child per SIMD lane (as
//! Embree's BVH8 does). The lanes are one AVX register where the processor has AVX2 and
//! two SSE2 halves elsewhere (`isa.rs`); both find the same distances, so the traversal
//! takes the same steps either way.

pub use super::bvh_bins::LeafCost;
pub use super::bvh_build::Coincident;
use super::bvh_build::{BinaryBvh, MAX_DEPTH};
use super::collapse_plan::CollapsePlan;
pub use super::wide_node::{Child, WIDTH, WideNode};
use super::wide_node::{LANE, WideRay};
use crate::geometry::{Aabb, RayQuery};
#[cfg(target_arch = "x86_64")]
use crate::simd::Avx;
use crate::simd::{Halves, Lanes8};
use glam::Vec3A;
use std::mem::MaybeUninit;

/// Whether traversal can follow the ray: a finite origin and direction. A NaN in either
/// would keep every slab interval open (`enter` leaves an interval alone where a
/// comparison fails), so the ray would "enter" unused lanes and follow their dummy index.
/// Validation keeps such rays from being made; this keeps a slip from being a panic.
#[inline(always)]
fn traceable(q: &RayQuery) -> bool {
    q.ray.origin.is_finite() && q.ray.dir.is_finite()
}

/// A fixed-capacity stack that costs nothing to create (a zeroed array would be a memset
/// per ray): a slot is always written by `push` before `pop` reads it.
struct Stack<T: Copy, const N: usize> {
    items: [MaybeUninit<T>; N],
    len: usize,
}

impl<T: Copy, const N: usize> Stack<T, N> {
    #[inline(always)]
    fn new() -> Self {
        Self {
            items: [const { MaybeUninit::uninit() }; N],
            len: 0,
        }
    }

    #[inline(always)]
    fn push(&mut self, item: T) {
        // Indexing is checked: overflow would be a bug in the depth bound, never a wrong image.
        self.items[self.len].write(item);
        self.len += 1;
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<T> {
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        // SAFETY: slots below `len` were all written by `push`.
        Some(unsafe { self.items[self.len].assume_init() })
    }
}

/// Each node pushes at most all its children and pops one, and a path has at most
/// MAX_DEPTH + 1 nodes.
const STACK_SIZE: usize = (WIDTH - 1) * (MAX_DEPTH + 1) + WIDTH;

/// `Bvh::closest_with`'s leaf test for `hit`, which tests one primitive: each of the
/// leaf's in order, against the nearest hit found before it.
#[inline(always)]
fn each_item(
    mut hit: impl FnMut(u32, f32) -> Option<f32>,
) -> impl FnMut(std::ops::Range<u32>, f32) -> Option<f32> {
    #[inline(always)]
    move |items, mut t_max| {
        let mut nearest = None;
        for i in items {
            if let Some(t) = hit(i, t_max) {
                t_max = t;
                nearest = Some(t);
            }
        }
        nearest
    }
}

/// `Bvh::visit_with`'s leaf visit for `visit`, which is offered one primitive: each of the
/// leaf's in order, until it returns false.
#[inline(always)]
fn every_item(mut visit: impl FnMut(u32) -> bool) -> impl FnMut(std::ops::Range<u32>) -> bool {
    #[inline(always)]
    move |mut items| items.all(&mut visit)
}

/// A child waiting on the closest-hit stack, with the distance at which the ray enters it.
#[derive(Clone, Copy)]
struct Pending {
    t_enter: f32,
    child: u32,
    count: u32,
}

/// The wide BVH over a scene's primitives (in their stored order).
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// The nodes; the root is the first.
    pub nodes: Vec<WideNode>,
    /// The box around every primitive.
    pub bounds: Option<Aabb>,
    /// The most primitives that share one centre, and the first of them (in stored
    /// order): no split can part them, so a ray that reaches them tests every one.
    pub coincident: Coincident,
}

impl Bvh {
    /// Builds over primitives with the given bounds; returns the tree and the order in
    /// which the primitives must be stored (leaf ranges index into that order).
    pub fn build(bounds: &[Aabb]) -> (Bvh, Vec<u32>) {
        Self::build_for(bounds, LeafCost::SINGLE)
    }

    /// Builds as `build` does, for leaves whose primitives are tested as `leaf` says.
    pub fn build_for(bounds: &[Aabb], leaf: LeafCost) -> (Bvh, Vec<u32>) {
        let (binary, order, coincident) = BinaryBvh::build(bounds, leaf);
        (Bvh::collapsed(&binary, coincident), order)
    }

    /// The eight-wide tree of a binary one (`coincident` is its largest group of one
    /// centre).
    pub fn collapsed(binary: &BinaryBvh, coincident: Coincident) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(binary.nodes.len() / 2 + 1),
            bounds: binary.nodes.first().map(|n| n.bounds),
            coincident,
        };
        if !binary.nodes.is_empty() {
            let plan = CollapsePlan::new(binary);
            bvh.collapse(binary, &plan, 0);
        }
        bvh
    }

    /// One leaf holding primitives 0..count: the unoptimised list, for comparisons.
    pub fn single_leaf(bounds: Aabb, count: u32) -> Bvh {
        let mut root = WideNode::EMPTY;
        root.set(0, bounds, Child::Leaf(0..count));
        Bvh {
            nodes: vec![root],
            bounds: Some(bounds),
            coincident: Coincident::default(),
        }
    }

    /// Re-points every leaf at what stands for its primitives: `f(range)` gives, for the
    /// primitives `range` of a leaf, the range of the items that replace them (a mesh's
    /// triangle groups). Called leaf by leaf in node order.
    pub fn map_leaves(&mut self, mut f: impl FnMut(std::ops::Range<u32>) -> std::ops::Range<u32>) {
        for node in &mut self.nodes {
            for lane in 0..WIDTH {
                if let Child::Leaf(range) = node.child(lane) {
                    let items = f(range);
                    assert!(!items.is_empty(), "a leaf stands for at least one item");
                    (node.child[lane], node.count[lane]) = (items.start, items.end - items.start);
                }
            }
        }
    }

    /// Makes binary node `node` into a wide node (appended), whose lanes are the descendants
    /// that `plan` chose for it.
    fn collapse(&mut self, binary: &BinaryBvh, plan: &CollapsePlan, node: usize) -> u32 {
        let index = self.nodes.len();
        self.nodes.push(WideNode::EMPTY);
        let mut lanes = Vec::with_capacity(WIDTH);
        if binary.nodes[node].count > 0 {
            lanes.push(node); // a root that is a leaf
        } else {
            plan.lanes_of_node(binary, node, &mut lanes);
        }
        let mut wide = WideNode::EMPTY;
        for (lane, &b) in lanes.iter().enumerate() {
            let n = binary.nodes[b];
            let child = if n.count > 0 {
                Child::Leaf(n.first..n.first + n.count)
            } else {
                Child::Node(self.collapse(binary, plan, b))
            };
            wide.set(lane, n.bounds, child);
        }
        self.nodes[index] = wide;
        index as u32
    }

    /// Finds the closest hit. `hit(i, t_max)` tests primitive `i` (in stored order) and
    /// returns its distance when it is nearer than `t_max`. Children are visited nearest
    /// first, and one the ray enters beyond the current nearest hit is skipped. The same
    /// calls in the same order with every instruction set.
    #[inline(always)]
    pub fn closest(
        &self,
        q: &RayQuery,
        t_max: f32,
        hit: impl FnMut(u32, f32) -> Option<f32>,
    ) -> f32 {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx) = crate::isa::avx2_lanes() {
            // SAFETY: an `Avx` exists only where the processor has AVX2.
            return unsafe { self.closest_avx2(avx, q, t_max, hit) };
        }
        self.closest_with(Halves, q, t_max, each_item(hit))
    }

    /// `closest` compiled for AVX2, whose instructions the box tests inline.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn closest_avx2(
        &self,
        avx: Avx,
        q: &RayQuery,
        t_max: f32,
        hit: impl FnMut(u32, f32) -> Option<f32>,
    ) -> f32 {
        self.closest_with(avx, q, t_max, each_item(hit))
    }

    /// `closest` in the lanes of `l`, a leaf at a time: `leaf(primitives, t_max)` tests the
    /// primitives of a leaf (a range, in stored order) and returns the distance of the
    /// nearest hit it found nearer than `t_max`.
    #[inline(always)]
    pub(super) fn closest_with<L: Lanes8>(
        &self,
        l: L,
        q: &RayQuery,
        mut t_max: f32,
        mut leaf: impl FnMut(std::ops::Range<u32>, f32) -> Option<f32>,
    ) -> f32 {
        if self.nodes.is_empty() || !traceable(q) {
            return t_max;
        }
        let ray = WideRay::new(l, q);
        let mut stack = Stack::<Pending, STACK_SIZE>::new();
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            let (mask, t_enter) = n.enter(l, &ray, t_max);
            // `lane & LANE` is the lane itself: it only spares the indexing its bounds check.
            let pending = |lane: usize| Pending {
                t_enter: t_enter[lane & LANE],
                child: n.child[lane & LANE],
                count: n.count[lane & LANE],
            };
            // The nearest child entered is taken at once; the others are pushed farthest
            // first, so the nearest of them ends on top (ties: the higher lane first). A
            // child just entered needs no test against t_max: `enter` found it nearer.
            let rest = mask & mask.wrapping_sub(1);
            let mut next = if mask == 0 {
                None
            } else if rest == 0 {
                Some(pending(mask.trailing_zeros() as usize))
            } else if rest & (rest - 1) == 0 {
                // Two children, the common case: the farther is pushed.
                let (first, second) = (
                    mask.trailing_zeros() as usize,
                    rest.trailing_zeros() as usize,
                );
                let (near, far) = if t_enter[first & LANE] < t_enter[second & LANE] {
                    (first, second)
                } else {
                    (second, first)
                };
                stack.push(pending(far));
                Some(pending(near))
            } else {
                let mut entered = [0usize; WIDTH];
                let mut k = 0;
                let mut mask = mask;
                while mask != 0 {
                    let lane = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    let mut j = k;
                    while j > 0 && t_enter[entered[j - 1] & LANE] < t_enter[lane & LANE] {
                        entered[j] = entered[j - 1];
                        j -= 1;
                    }
                    entered[j] = lane;
                    k += 1;
                }
                for &lane in &entered[..k - 1] {
                    stack.push(pending(lane));
                }
                Some(pending(entered[k - 1]))
            };
            // Test leaves as they come, until an inner node is due.
            loop {
                let p = match next.take() {
                    Some(p) => p,
                    None => loop {
                        match stack.pop() {
                            Some(p) if p.t_enter > t_max => {}
                            Some(p) => break p,
                            None => return t_max,
                        }
                    },
                };
                if p.count == 0 {
                    node = p.child as usize;
                    break;
                }
                if let Some(t) = leaf(p.child..p.child + p.count, t_max) {
                    t_max = t;
                }
            }
        }
    }

    /// Visits every primitive whose leaf the segment (0, t_max) reaches, in no particular
    /// order, until `visit` returns false.
    #[inline(always)]
    pub fn visit(&self, q: &RayQuery, t_max: f32, visit: impl FnMut(u32) -> bool) {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx) = crate::isa::avx2_lanes() {
            // SAFETY: an `Avx` exists only where the processor has AVX2.
            return unsafe { self.visit_avx2(avx, q, t_max, visit) };
        }
        self.visit_with(Halves, q, t_max, every_item(visit))
    }

    /// `visit` compiled for AVX2, whose instructions the box tests inline.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn visit_avx2(&self, avx: Avx, q: &RayQuery, t_max: f32, visit: impl FnMut(u32) -> bool) {
        self.visit_with(avx, q, t_max, every_item(visit))
    }

    /// `visit` in the lanes of `l`, a leaf at a time: `leaf(primitives)` is offered the
    /// primitives of a leaf (a range, in stored order) and returns false to end the walk.
    #[inline(always)]
    pub(super) fn visit_with<L: Lanes8>(
        &self,
        l: L,
        q: &RayQuery,
        t_max: f32,
        mut leaf: impl FnMut(std::ops::Range<u32>) -> bool,
    ) {
        if self.nodes.is_empty() || !traceable(q) {
            return;
        }
        let ray = WideRay::new(l, q);
        let mut stack = Stack::<u32, STACK_SIZE>::new();
        let mut node = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            let (mut mask, _) = n.enter(l, &ray, t_max);
            // The last inner child entered is the next node, taken at once rather than
            // pushed and popped: the same order.
            let mut next = None;
            while mask != 0 {
                let lane = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if n.count[lane & LANE] == 0 {
                    if let Some(earlier) = next.replace(n.child[lane & LANE]) {
                        stack.push(earlier);
                    }
                } else {
                    let first = n.child[lane & LANE];
                    if !leaf(first..first + n.count[lane & LANE]) {
                        return;
                    }
                }
            }
            match next.or_else(|| stack.pop()) {
                Some(next) => node = next,
                None => return,
            }
        }
    }

    /// Visits every primitive in a leaf whose box holds point `p` (on its faces counts), in
    /// no particular order, until `visit` returns true; whether one did. Without
    /// allocation: for point queries per ray.
    #[inline]
    pub fn any_containing(&self, p: Vec3A, mut visit: impl FnMut(u32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = Stack::<u32, STACK_SIZE>::new();
        let mut node = 0u32;
        loop {
            let n = &self.nodes[node as usize];
            let mut inside = n.holding(p);
            while inside != 0 {
                let lane = inside.trailing_zeros() as usize;
                inside &= inside - 1;
                match n.child(lane) {
                    Child::Empty => {}
                    Child::Node(c) => stack.push(c),
                    Child::Leaf(mut range) => {
                        if range.any(&mut visit) {
                            return true;
                        }
                    }
                }
            }
            match stack.pop() {
                Some(next) => node = next,
                None => return false,
            }
        }
    }

    /// Calls `visit` with every primitive in a leaf whose box overlaps `b` (touching
    /// counts), in no particular order, until it returns false. For scene preparation,
    /// not for rays.
    pub fn overlapping(&self, b: &Aabb, mut visit: impl FnMut(u32) -> bool) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = vec![0u32];
        while let Some(node) = stack.pop() {
            let n = &self.nodes[node as usize];
            for lane in 0..WIDTH {
                if !n.bounds(lane).overlaps(b) {
                    continue;
                }
                match n.child(lane) {
                    Child::Empty => {}
                    Child::Node(c) => stack.push(c),
                    Child::Leaf(mut range) => {
                        if !range.all(&mut visit) {
                            return;
                        }
                    }
                }
            }
        }
    }

    /// The number of nodes on the longest path from the root.
    pub fn depth(&self) -> usize {
        fn depth_of(nodes: &[WideNode], i: usize) -> usize {
            1 + (0..WIDTH)
                .filter_map(|lane| match nodes[i].child(lane) {
                    Child::Node(c) => Some(depth_of(nodes, c as usize)),
                    _ => None,
                })
                .max()
                .unwrap_or(0)
        }
        if self.nodes.is_empty() {
            0
        } else {
            depth_of(&self.nodes, 0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Ray, Sphere};
    use glam::Vec3;

    /// The build stores boxes of one centre side by side, so the largest group is found
    /// among any others, whatever their sizes.
    #[test]
    fn the_largest_group_of_one_centre_is_found() {
        let around = |c: Vec3, r: f32| Aabb {
            min: c - Vec3::splat(r),
            max: c + Vec3::splat(r),
        };
        let mut bounds: Vec<Aabb> = (0..300)
            .map(|i| around(Vec3::new(i as f32, (i % 7) as f32, 0.0), 0.4))
            .collect();
        for k in 0..40 {
            bounds.insert(
                k * 7,
                around(Vec3::new(3.5, 2.0, 1.0), 0.1 + k as f32 * 0.01),
            );
        }
        bounds.extend((0..12).map(|_| around(Vec3::new(-9.0, 0.0, 0.0), 1.0)));
        let (bvh, order) = Bvh::build(&bounds);
        assert_eq!(bvh.coincident.count, 40);
        let first = order[bvh.coincident.first as usize] as usize;
        assert_eq!(bounds[first].centroid(), Vec3::new(3.5, 2.0, 1.0));
    }

    fn grid_spheres(n: usize) -> Vec<Sphere> {
        (0..n)
            .map(|i| {
                let x = (i % 100) as f32 * 3.0;
                let y = ((i / 100) % 100) as f32 * 3.0;
                let z = -10.0 - (i / 10_000) as f32 * 3.0;
                Sphere::new(Vec3::new(x, y, z), 1.0)
            })
            .collect()
    }

    /// The BVH answers exactly what a brute-force loop over all primitives answers.
    #[test]
    fn closest_hit_matches_brute_force() {
        let spheres = grid_spheres(2000);
        let bounds: Vec<Aabb> = spheres.iter().map(|s| s.bounds()).collect();
        let (bvh, order) = Bvh::build(&bounds);
        assert!(bvh.depth() < STACK_SIZE);
        let stored: Vec<Sphere> = order.iter().map(|&i| spheres[i as usize]).collect();
        let mut rng = crate::xorshift::XorShift32::new(12345);
        let mut next = || rng.next_f32();
        for _ in 0..2000 {
            let origin = Vec3::new(next() * 300.0, next() * 60.0, 20.0);
            let dir = Vec3::new(next() - 0.5, next() - 0.5, -1.0);
            let ray = Ray::new(origin, dir);
            let q = RayQuery::new(ray);
            let brute = spheres
                .iter()
                .filter_map(|s| s.intersect(&ray, f32::INFINITY))
                .fold(f32::INFINITY, f32::min);
            let fast = bvh.closest(&q, f32::INFINITY, |i, t_max| {
                stored[i as usize].intersect(&ray, t_max)
            });
            assert_eq!(brute, fast);
        }
    }

    #[test]
    fn visit_reaches_every_primitive_on_the_segment() {
        let spheres = grid_spheres(500);
        let bounds: Vec<Aabb> = spheres.iter().map(|s| s.bounds()).collect();
        let (bvh, order) = Bvh::build(&bounds);
        let ray = Ray::new(Vec3::new(-5.0, 3.0, -10.0), Vec3::X);
        let q = RayQuery::new(ray);
        let mut seen = 0;
        bvh.visit(&q, f32::INFINITY, |i| {
            seen += spheres[order[i as usize] as usize].crossings(&ray, f32::INFINITY);
            true
        });
        assert_eq!(
            seen, 200,
            "the row y = 3 has 100 spheres, each crossed twice"
        );
    }

    /// Every primitive lies in exactly one leaf, inside the box of every lane above it.
    #[test]
    fn leaves_cover_every_primitive_once_inside_their_boxes() {
        let spheres = grid_spheres(3000);
        let bounds: Vec<Aabb> = spheres.iter().map(|s| s.bounds()).collect();
        let (bvh, order) = Bvh::build(&bounds);
        let mut seen = vec![0u32; spheres.len()];
        fn walk(
            bvh: &Bvh,
            node: usize,
            order: &[u32],
            bounds: &[Aabb],
            seen: &mut [u32],
            outer: &[Aabb],
        ) {
            for lane in 0..WIDTH {
                let b = bvh.nodes[node].bounds(lane);
                match bvh.nodes[node].child(lane) {
                    Child::Empty => assert!(b.is_empty()),
                    Child::Node(c) => {
                        let mut chain = outer.to_vec();
                        chain.push(b);
                        walk(bvh, c as usize, order, bounds, seen, &chain);
                    }
                    Child::Leaf(range) => {
                        for i in range {
                            let prim = bounds[order[i as usize] as usize];
                            for outer in outer.iter().chain([&b]) {
                                assert_eq!(outer.union(prim), *outer);
                            }
                            seen[order[i as usize] as usize] += 1;
                        }
                    }
                }
            }
        }
        walk(&bvh, 0, &order, &bounds, &mut seen, &[]);
        assert!(seen.iter().all(|&n| n == 1));
        assert!(bvh.depth() <= MAX_DEPTH + 1);
    }

    /// A ray with a NaN in it (which validation keeps from ever being traced) must still
    /// not send traversal through an unused lane's dummy index.
    #[test]
    fn rays_with_nan_traverse_without_panicking() {
        // Five primitives leave unused lanes in the collapsed nodes.
        for n in [1, 5, 3000] {
            let spheres = grid_spheres(n);
            let bounds: Vec<Aabb> = spheres.iter().map(|s| s.bounds()).collect();
            let (bvh, _) = Bvh::build(&bounds);
            for (origin, dir) in [
                (Vec3::new(f32::NAN, 0.0, 0.0), Vec3::NEG_Z),
                (Vec3::ZERO, Vec3::new(f32::NAN, f32::NAN, f32::NAN)),
                (Vec3::splat(f32::INFINITY), Vec3::NEG_Z),
            ] {
                let q = RayQuery::new(Ray::new(origin, dir));
                let mut tested = 0;
                bvh.closest(&q, f32::INFINITY, |i, _| {
                    assert!((i as usize) < n);
                    tested += 1;
                    None
                });
                bvh.visit(&q, f32::INFINITY, |i| {
                    assert!((i as usize) < n);
                    true
                });
                assert!(tested <= n);
            }
        }
    }

    /// A box query visits every primitive whose box overlaps the query box (and, being
    /// by leaf, possibly a few more).
    #[test]
    fn overlapping_finds_every_primitive_box_that_meets_the_query() {
        let spheres = grid_spheres(3000);
        let bounds: Vec<Aabb> = spheres.iter().map(|s| s.bounds()).collect();
        let (bvh, order) = Bvh::build(&bounds);
        let queries = [
            Aabb::from_points(&[Vec3::new(-1.0, -1.0, -11.0), Vec3::new(1.0, 1.0, -9.0)]),
            Aabb::from_points(&[Vec3::new(2.0, 2.0, -11.0), Vec3::new(40.0, 7.0, -9.0)]),
            // Touching sphere 1's box (x from 2 to 4) at x = 2 only.
            Aabb::from_points(&[Vec3::new(1.5, -0.5, -10.0), Vec3::new(2.0, 0.5, -10.0)]),
            Aabb::from_points(&[Vec3::new(1.2, 50.0, -10.0), Vec3::new(1.8, 60.0, -10.0)]),
            Aabb::EMPTY,
        ];
        for query in queries {
            let mut found = Vec::new();
            bvh.overlapping(&query, |i| {
                let original = order[i as usize] as usize;
                if bounds[original].overlaps(&query) {
                    found.push(original);
                }
                true
            });
            found.sort();
            let brute: Vec<usize> = (0..bounds.len())
                .filter(|&i| bounds[i].overlaps(&query))
                .collect();
            assert_eq!(found, brute, "{query:?}");
        }
        let mut touching = 0;
        bvh.overlapping(&queries[2], |i| {
            touching += (order[i as usize] == 1) as u32;
            true
        });
        assert_eq!(touching, 1);
        // A visitor that says stop is called no more.
        let mut calls = 0;
        bvh.overlapping(&queries[0], |_| {
            calls += 1;
            false
        });
        assert_eq!(calls, 1);
    }

    /// The AVX2 traversal makes the same calls, in the same order, with the same distance
    /// bounds, as the baseline: for closest hits, for any-hit visits, for rays along box
    /// faces, from inside boxes and with NaN in them.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx2_traversal_takes_the_baseline_steps() {
        let Some(avx) = Avx::new() else {
            eprintln!("no AVX2 on this processor: only the baseline traversal runs here");
            return;
        };
        let spheres = grid_spheres(3000);
        let bounds: Vec<Aabb> = spheres.iter().map(|s| s.bounds()).collect();
        let (bvh, order) = Bvh::build(&bounds);
        let stored: Vec<Sphere> = order.iter().map(|&i| spheres[i as usize]).collect();
        let mut rng = crate::xorshift::XorShift32::new(7);
        let mut next = || rng.next_f32();
        let mut rays: Vec<Ray> = (0..3000)
            .map(|_| {
                let origin = Vec3::new(next() * 320.0 - 10.0, next() * 80.0 - 10.0, 20.0);
                Ray::new(origin, Vec3::new(next() - 0.5, next() - 0.5, -1.0))
            })
            .collect();
        rays.extend([
            // Leaving a box from its face (entry and exit both 0), along the faces of a
            // row of boxes, from inside one, and with NaN.
            Ray::new(Vec3::new(1.0, 0.0, -10.0), Vec3::X),
            Ray::new(Vec3::new(-5.0, 1.0, -10.0), Vec3::X),
            Ray::new(Vec3::new(0.0, 0.0, -10.0), Vec3::Y),
            Ray::new(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::NEG_Z),
        ]);
        for ray in rays {
            let q = RayQuery::new(ray);
            let steps = |calls: &mut Vec<(u32, u32)>, i: u32, t_max: f32| {
                calls.push((i, t_max.to_bits()));
                stored[i as usize].intersect(&ray, t_max)
            };
            let (mut baseline, mut wide) = (Vec::new(), Vec::new());
            let a = bvh.closest_with(
                Halves,
                &q,
                f32::INFINITY,
                each_item(|i, t| steps(&mut baseline, i, t)),
            );
            // SAFETY: `avx` exists, so the processor has AVX2.
            let b =
                unsafe { bvh.closest_avx2(avx, &q, f32::INFINITY, |i, t| steps(&mut wide, i, t)) };
            assert_eq!((a.to_bits(), &baseline), (b.to_bits(), &wide), "{ray:?}");
            let (mut baseline, mut wide) = (Vec::new(), Vec::new());
            bvh.visit_with(
                Halves,
                &q,
                400.0,
                every_item(|i| {
                    baseline.push(i);
                    true
                }),
            );
            // SAFETY: as above.
            unsafe {
                bvh.visit_avx2(avx, &q, 400.0, |i| {
                    wide.push(i);
                    true
                })
            };
            assert_eq!(baseline, wide, "{ray:?}");
        }
    }

    #[test]
    fn empty_and_single() {
        let (bvh, order) = Bvh::build(&[]);
        assert!(order.is_empty());
        let q = RayQuery::new(Ray::new(Vec3::ZERO, Vec3::Z));
        assert_eq!(bvh.closest(&q, 7.0, |_, _| Some(1.0)), 7.0);
        let s = Sphere::new(Vec3::new(0.0, 0.0, 5.0), 1.0);
        let (bvh, _) = Bvh::build(&[s.bounds()]);
        assert_eq!(
            bvh.closest(&q, f32::INFINITY, |_, t| s.intersect(&q.ray, t)),
            4.0
        );
    }
}
