//! The binned surface area heuristic build (Wald 2007) of a binary hierarchy, which
//! `bvh.rs` then collapses into four-wide nodes for traversal.

use crate::geometry::Aabb;

/// Interior nodes have `count == 0` and their children at `first` and `first + 1`; leaves
/// hold primitives `first .. first + count` of the reordered primitive array.
#[derive(Clone, Copy, Debug)]
pub struct BinaryNode {
    pub bounds: Aabb,
    pub first: u32,
    pub count: u32,
}

/// A binary tree in one array; the root is node 0.
#[derive(Clone, Debug, Default)]
pub struct BinaryBvh {
    pub nodes: Vec<BinaryNode>,
}

const BINS: usize = 12;
const MAX_LEAF: usize = 8;
/// Cost of a box test relative to a primitive test, for the SAH.
const TRAVERSAL_COST: f32 = 1.0;
/// Leaves deeper than this are not split further, however large: it bounds the traversal
/// stack (bvh.rs), and 2^32 leaves are more than any scene has.
pub const MAX_DEPTH: usize = 32;

struct BuildItem {
    bounds: Aabb,
    centroid: glam::Vec3,
    index: u32,
}

impl BinaryBvh {
    /// Builds over primitives with the given bounds; returns the tree and the order in
    /// which the primitives must be stored (leaf ranges index into that order).
    pub fn build(bounds: &[Aabb]) -> (BinaryBvh, Vec<u32>) {
        let mut items: Vec<BuildItem> = bounds
            .iter()
            .enumerate()
            .map(|(i, b)| BuildItem {
                bounds: *b,
                centroid: b.centroid(),
                index: i as u32,
            })
            .collect();
        let mut bvh = BinaryBvh {
            nodes: Vec::with_capacity(2 * bounds.len().max(1)),
        };
        if items.is_empty() {
            return (bvh, Vec::new());
        }
        let root_bounds = items.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
        bvh.nodes.push(BinaryNode {
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
            self.nodes.push(BinaryNode {
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
