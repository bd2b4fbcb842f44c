//! A bounding volume hierarchy built with the binned surface area heuristic (Wald 2007),
//! flattened into an array, and traversed nearest child first with a fixed stack.

use super::aabb::Aabb;
use super::ray::RayQuery;

/// Interior nodes have `count == 0` and their children at `first` and `first + 1`; leaves
/// hold primitives `first .. first + count` of the reordered primitive array.
#[derive(Clone, Copy, Debug)]
pub struct BvhNode {
    pub bounds: Aabb,
    pub first: u32,
    pub count: u32,
}

#[derive(Clone, Debug, Default)]
pub struct Bvh {
    pub nodes: Vec<BvhNode>,
}

const BINS: usize = 12;
const MAX_LEAF: usize = 8;
/// Cost of a box test relative to a primitive test, for the SAH.
const TRAVERSAL_COST: f32 = 1.0;
const STACK_SIZE: usize = 64;
const MAX_DEPTH: usize = STACK_SIZE - 4;

struct BuildItem {
    bounds: Aabb,
    centroid: glam::Vec3,
    index: u32,
}

impl Bvh {
    /// Builds over primitives with the given bounds; returns the tree and the order in
    /// which the primitives must be stored (leaf ranges index into that order).
    pub fn build(bounds: &[Aabb]) -> (Bvh, Vec<u32>) {
        let mut items: Vec<BuildItem> = bounds
            .iter()
            .enumerate()
            .map(|(i, b)| BuildItem {
                bounds: *b,
                centroid: b.centroid(),
                index: i as u32,
            })
            .collect();
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * bounds.len().max(1)),
        };
        if items.is_empty() {
            return (bvh, Vec::new());
        }
        let root_bounds = items.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
        bvh.nodes.push(BvhNode {
            bounds: root_bounds,
            first: 0,
            count: items.len() as u32,
        });
        bvh.subdivide(0, &mut items, 0, 1);
        let order = items.iter().map(|it| it.index).collect();
        (bvh, order)
    }

    fn subdivide(&mut self, node: usize, items: &mut [BuildItem], offset: usize, depth: usize) {
        let n = items.len();
        // A leaf at the depth limit, however large, keeps traversal within its fixed stack.
        if depth >= MAX_DEPTH {
            return;
        }
        let bounds = self.nodes[node].bounds;
        let leaf_cost = n as f32;
        if n <= 1 {
            return;
        }
        let centroid_bounds = items.iter().fold(Aabb::EMPTY, |b, it| b.grow(it.centroid));
        let extent = centroid_bounds.max - centroid_bounds.min;
        let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, split bin)
        for axis in 0..3 {
            if extent[axis] <= 0.0 {
                continue;
            }
            let scale = BINS as f32 / extent[axis];
            let bin_of = |it: &BuildItem| {
                (((it.centroid[axis] - centroid_bounds.min[axis]) * scale) as usize).min(BINS - 1)
            };
            let mut bin_bounds = [Aabb::EMPTY; BINS];
            let mut bin_count = [0usize; BINS];
            for it in items.iter() {
                let b = bin_of(it);
                bin_bounds[b] = bin_bounds[b].union(it.bounds);
                bin_count[b] += 1;
            }
            // Sweep from the right to know the cost of every right-hand side.
            let mut right_area = [0.0f32; BINS];
            let mut right_count = [0usize; BINS];
            let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
            for b in (1..BINS).rev() {
                acc = acc.union(bin_bounds[b]);
                cnt += bin_count[b];
                right_area[b] = acc.half_area();
                right_count[b] = cnt;
            }
            let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
            for split in 1..BINS {
                acc = acc.union(bin_bounds[split - 1]);
                cnt += bin_count[split - 1];
                if cnt == 0 || right_count[split] == 0 {
                    continue;
                }
                let cost = TRAVERSAL_COST
                    + (acc.half_area() * cnt as f32
                        + right_area[split] * right_count[split] as f32)
                        / bounds.half_area().max(f32::MIN_POSITIVE);
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, split));
                }
            }
        }
        let mid = match best {
            Some((cost, axis, split)) if cost < leaf_cost || n > MAX_LEAF => {
                let scale = BINS as f32 / extent[axis];
                let min = centroid_bounds.min[axis];
                partition(items, |it| {
                    ((((it.centroid[axis] - min) * scale) as usize).min(BINS - 1)) < split
                })
            }
            Some(_) => return,
            // All centroids coincide: split in the middle if the leaf would be too large.
            None if n > MAX_LEAF => n / 2,
            None => return,
        };
        let (left_items, right_items) = items.split_at_mut(mid);
        let left = self.nodes.len();
        for part in [&*left_items, &*right_items] {
            let b = part.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
            self.nodes.push(BvhNode {
                bounds: b,
                first: 0,
                count: 0,
            });
        }
        self.nodes[left].first = offset as u32;
        self.nodes[left].count = left_items.len() as u32;
        self.nodes[left + 1].first = (offset + mid) as u32;
        self.nodes[left + 1].count = right_items.len() as u32;
        self.nodes[node].first = left as u32;
        self.nodes[node].count = 0;
        self.subdivide(left, left_items, offset, depth + 1);
        self.subdivide(left + 1, right_items, offset + mid, depth + 1);
    }

    /// Finds the closest hit. `hit(i, t_max)` tests primitive `i` (in stored order) and
    /// returns its distance when it is nearer than `t_max`.
    #[inline]
    pub fn closest(
        &self,
        q: &RayQuery,
        mut t_max: f32,
        mut hit: impl FnMut(u32, f32) -> Option<f32>,
    ) -> f32 {
        let Some(root) = self.nodes.first() else {
            return t_max;
        };
        if root.bounds.hit(q, t_max).is_none() {
            return t_max;
        }
        let mut stack = [0u32; STACK_SIZE];
        let mut top = 0usize;
        let mut node = root;
        loop {
            if node.count > 0 {
                for i in node.first..node.first + node.count {
                    if let Some(t) = hit(i, t_max) {
                        t_max = t;
                    }
                }
            } else {
                let (a, b) = (node.first as usize, node.first as usize + 1);
                let ta = self.nodes[a].bounds.hit(q, t_max);
                let tb = self.nodes[b].bounds.hit(q, t_max);
                match (ta, tb) {
                    (Some(ta), Some(tb)) => {
                        let (near, far) = if ta <= tb { (a, b) } else { (b, a) };
                        stack[top] = far as u32;
                        top += 1;
                        node = &self.nodes[near];
                        continue;
                    }
                    (Some(_), None) => {
                        node = &self.nodes[a];
                        continue;
                    }
                    (None, Some(_)) => {
                        node = &self.nodes[b];
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next node that the (possibly shortened) ray still reaches.
            loop {
                if top == 0 {
                    return t_max;
                }
                top -= 1;
                let candidate = &self.nodes[stack[top] as usize];
                if candidate.bounds.hit(q, t_max).is_some() {
                    node = candidate;
                    break;
                }
            }
        }
    }

    /// Visits every primitive whose leaf the segment (0, t_max) reaches, in no particular
    /// order, until `visit` returns false.
    #[inline]
    pub fn visit(&self, q: &RayQuery, t_max: f32, mut visit: impl FnMut(u32) -> bool) {
        let mut stack = [0u32; STACK_SIZE];
        let mut top = 0usize;
        if self.nodes.is_empty() {
            return;
        }
        stack[0] = 0;
        top += 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if node.bounds.hit(q, t_max).is_none() {
                continue;
            }
            if node.count > 0 {
                for i in node.first..node.first + node.count {
                    if !visit(i) {
                        return;
                    }
                }
            } else {
                stack[top] = node.first;
                stack[top + 1] = node.first + 1;
                top += 2;
            }
        }
    }

    /// The depth of the deepest leaf (a stack of this size suffices for traversal).
    pub fn depth(&self) -> usize {
        fn depth_of(nodes: &[BvhNode], i: usize) -> usize {
            let n = &nodes[i];
            if n.count > 0 {
                1
            } else {
                1 + depth_of(nodes, n.first as usize).max(depth_of(nodes, n.first as usize + 1))
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            depth_of(&self.nodes, 0)
        }
    }
}

/// Moves the items for which `left` holds to the front; returns how many there are.
fn partition(items: &mut [BuildItem], left: impl Fn(&BuildItem) -> bool) -> usize {
    let mut i = 0;
    for j in 0..items.len() {
        if left(&items[j]) {
            items.swap(i, j);
            i += 1;
        }
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Ray, Sphere};
    use glam::Vec3;

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
        let mut rng = 12345u32;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 17;
            rng ^= rng << 5;
            rng as f32 / u32::MAX as f32
        };
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
