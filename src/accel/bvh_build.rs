//! The binned surface area heuristic build (Wald 2007) of a binary hierarchy, which
//! `bvh.rs` then collapses into eight-wide nodes for traversal.
//!
//! Each node makes two passes over its primitives: the bins of all three axes at once
//! (`bvh_bins.rs`, which also chooses the split), and the partition, which also gathers
//! each side's boxes and centroids. The two halves of a large split are built on two
//! threads without sharing anything, and the tree is laid out after, so it is the same
//! whichever thread builds what.

use super::bvh_bins::{
    BINS, BinSets, Bounds, BuildItem, LeafCost, TRAVERSAL_COST, below_split, best_split,
};
use crate::geometry::Aabb;
use glam::Vec3A;

/// Interior nodes have `count == 0` and their children at `first` and `first + 1`; leaves
/// hold primitives `first .. first + count` of the reordered primitive array.
#[derive(Clone, Copy, Debug)]
pub struct BinaryNode {
    pub bounds: Aabb,
    pub first: u32,
    pub count: u32,
}

/// A binary tree in one array; the root is node 0. Slots no node needed (a subtree that
/// ends in leaves of several primitives uses fewer than it owns) are left empty and
/// unreachable.
#[derive(Clone, Debug, Default)]
pub struct BinaryBvh {
    pub nodes: Vec<BinaryNode>,
}

/// Leaves deeper than this are not split further, however large: it bounds the traversal
/// stack (bvh.rs), and 2^32 leaves are more than any scene has.
pub const MAX_DEPTH: usize = 32;
/// Subtrees of fewer primitives are built on the thread that split them: below this, the
/// cost of handing work to another thread outweighs the work.
const PARALLEL_MIN: usize = 8192;

/// A node slot before its node is written.
const UNUSED: BinaryNode = BinaryNode {
    bounds: Aabb::EMPTY,
    first: 0,
    count: 0,
};

/// The largest group of primitives whose boxes share one centre.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Coincident {
    /// How many.
    pub count: u32,
    /// The first of them, in stored order.
    pub first: u32,
}

impl Coincident {
    /// The largest group among `items` in the order the build stored them. Primitives of
    /// one centre fall on one side of every split, so they are stored side by side: the
    /// longest run of one centre is the largest group.
    fn of(items: &[BuildItem]) -> Coincident {
        let mut best = Coincident::default();
        let mut start = 0;
        for k in 1..=items.len() {
            if k == items.len() || items[k].centroid() != items[start].centroid() {
                if (k - start) as u32 > best.count {
                    best = Coincident {
                        count: (k - start) as u32,
                        first: start as u32,
                    };
                }
                start = k;
            }
        }
        best
    }
}

impl BinaryBvh {
    /// Builds over primitives with the given bounds; returns the tree, the order in which
    /// the primitives must be stored (leaf ranges index into that order) and their largest
    /// group of one centre.
    pub fn build(bounds: &[Aabb], leaf: LeafCost) -> (BinaryBvh, Vec<u32>, Coincident) {
        use rayon::prelude::*;
        let mut items: Vec<BuildItem> = bounds
            .par_iter()
            .map(|b| BuildItem {
                min: b.min.into(),
                max: b.max.into(),
            })
            .collect();
        let mut order: Vec<u32> = (0..bounds.len() as u32).into_par_iter().collect();
        if items.is_empty() {
            return (BinaryBvh::default(), Vec::new(), Coincident::default());
        }
        let around = Around::of_many(&items);
        let at = Place {
            offset: 0,
            depth: 0,
        };
        let tree = Subtree::build(&mut items, &mut order, around, at, leaf);
        let (nodes, coincident) = rayon::join(
            || {
                let mut nodes = Vec::with_capacity(1 + tree.len_below());
                nodes.push(UNUSED);
                nodes[0] = tree.place(&mut nodes);
                nodes
            },
            // The items are in stored order now, side by side in memory.
            || Coincident::of(&items),
        );
        (BinaryBvh { nodes }, order, coincident)
    }
}

/// The box around some items and the box around their centroids.
#[derive(Clone, Copy)]
struct Around {
    boxes: Bounds,
    centroids: Bounds,
}

impl Around {
    const EMPTY: Around = Around {
        boxes: Bounds::EMPTY,
        centroids: Bounds::EMPTY,
    };

    #[inline(always)]
    fn add(self, it: &BuildItem, centroid: Vec3A) -> Around {
        Around {
            boxes: self.boxes.union(it),
            centroids: self.centroids.grow(centroid),
        }
    }

    fn of(items: &[BuildItem]) -> Around {
        items
            .iter()
            .fold(Around::EMPTY, |a, it| a.add(it, it.centroid()))
    }

    fn merge(self, other: Around) -> Around {
        Around {
            boxes: self.boxes.merge(other.boxes),
            centroids: self.centroids.merge(other.centroids),
        }
    }

    /// `of` for many items, in pieces on several threads, merged in order. The same boxes
    /// as `of` bit for bit: of equal bounds such as 0 and −0, a lane's minimum and maximum
    /// keep the later, and merging pieces in order keeps the same one.
    fn of_many(items: &[BuildItem]) -> Around {
        use rayon::prelude::*;
        items
            .par_chunks(PARALLEL_MIN)
            .map(Around::of)
            .reduce(|| Around::EMPTY, Around::merge)
    }
}

/// Where a node's subtree goes: its primitives are `offset ..` of the final order, and it
/// lies `depth` below the root.
#[derive(Clone, Copy)]
struct Place {
    offset: usize,
    depth: usize,
}

impl Place {
    fn right_of(self, mid: usize) -> Place {
        Place {
            offset: self.offset + mid,
            depth: self.depth + 1,
        }
    }

    fn left(self) -> Place {
        Place {
            offset: self.offset,
            depth: self.depth + 1,
        }
    }
}

/// A subtree as it is built: the large nodes split on the thread that reaches them, each
/// half built on whichever thread takes it, and below `PARALLEL_MIN` primitives a subtree
/// built on one thread into a list of its own. `place` then lays the whole tree out in one
/// array in depth-first order, so only the nodes the tree has are ever written (a layout
/// reserved in advance would hold 2m − 1 slots for m primitives, most of them never used),
/// and the array is the same whichever thread built what.
enum Subtree {
    /// Built on one thread: its root, and the nodes below it, whose interior nodes'
    /// `first` indexes `below`.
    Serial {
        root: BinaryNode,
        below: Vec<BinaryNode>,
    },
    /// Split here, its halves built in parallel.
    Split {
        bounds: Aabb,
        halves: Box<(Subtree, Subtree)>,
    },
}

impl Subtree {
    /// The subtree over `items` (`around` is their boxes' box and their centroids').
    fn build(
        items: &mut [BuildItem],
        order: &mut [u32],
        around: Around,
        at: Place,
        leaf_cost: LeafCost,
    ) -> Subtree {
        let n = items.len();
        let mut bins = BinSets::new();
        if n < PARALLEL_MIN {
            let mut below = Vec::with_capacity(2 * n - 2);
            let root = build_serial(items, order, around, at, leaf_cost, &mut bins, &mut below);
            return Subtree::Serial { root, below };
        }
        let Some((mid, left_around, right_around)) =
            split(items, order, around, at.depth, leaf_cost, &mut bins)
        else {
            return Subtree::Serial {
                root: leaf_over(around, at, n),
                below: Vec::new(),
            };
        };
        let (left_items, right_items) = items.split_at_mut(mid);
        let (left_order, right_order) = order.split_at_mut(mid);
        let halves = rayon::join(
            || Subtree::build(left_items, left_order, left_around, at.left(), leaf_cost),
            || {
                let at = at.right_of(mid);
                Subtree::build(right_items, right_order, right_around, at, leaf_cost)
            },
        );
        Subtree::Split {
            bounds: around.boxes.aabb(),
            halves: Box::new(halves),
        }
    }

    /// How many nodes lie below the root.
    fn len_below(&self) -> usize {
        match self {
            Subtree::Serial { below, .. } => below.len(),
            Subtree::Split { halves, .. } => 2 + halves.0.len_below() + halves.1.len_below(),
        }
    }

    /// Appends the nodes below the root to `out`, a child pair before the left child's
    /// descendants and those before the right child's; returns the root.
    fn place(&self, out: &mut Vec<BinaryNode>) -> BinaryNode {
        match self {
            Subtree::Serial { root, below } => {
                let base = out.len() as u32;
                let moved = |n: &BinaryNode| BinaryNode {
                    first: if n.count == 0 {
                        n.first + base
                    } else {
                        n.first
                    },
                    ..*n
                };
                out.extend(below.iter().map(moved));
                moved(root)
            }
            Subtree::Split { bounds, halves } => {
                let pair = out.len();
                out.extend([UNUSED; 2]);
                out[pair] = halves.0.place(out);
                out[pair + 1] = halves.1.place(out);
                BinaryNode {
                    bounds: *bounds,
                    first: pair as u32,
                    count: 0,
                }
            }
        }
    }
}

/// The leaf over `n` items at `at`.
fn leaf_over(around: Around, at: Place, n: usize) -> BinaryNode {
    BinaryNode {
        bounds: around.boxes.aabb(),
        first: at.offset as u32,
        count: n as u32,
    }
}

/// The node over `items`, built on this thread, with its descendants appended to `below`:
/// a child pair, then the left child's descendants, then the right child's. `bins` is
/// this thread's space for binning, used by one node after another.
fn build_serial(
    items: &mut [BuildItem],
    order: &mut [u32],
    around: Around,
    at: Place,
    leaf_cost: LeafCost,
    bins: &mut BinSets,
    below: &mut Vec<BinaryNode>,
) -> BinaryNode {
    let n = items.len();
    let Some((mid, left_around, right_around)) =
        split(items, order, around, at.depth, leaf_cost, bins)
    else {
        return leaf_over(around, at, n);
    };
    let (left_items, right_items) = items.split_at_mut(mid);
    let (left_order, right_order) = order.split_at_mut(mid);
    let pair = below.len();
    below.extend([UNUSED; 2]);
    below[pair] = build_serial(
        left_items,
        left_order,
        left_around,
        at.left(),
        leaf_cost,
        bins,
        below,
    );
    below[pair + 1] = build_serial(
        right_items,
        right_order,
        right_around,
        at.right_of(mid),
        leaf_cost,
        bins,
        below,
    );
    BinaryNode {
        bounds: around.boxes.aabb(),
        first: pair as u32,
        count: 0,
    }
}

/// Splits the node over `items` (`around` is their boxes' box and their centroids'), at
/// `depth` below the root, by moving the left side's items to the front: how many they
/// are, and what each side is around. None where the node stays a leaf.
fn split(
    items: &mut [BuildItem],
    order: &mut [u32],
    around: Around,
    depth: usize,
    leaf_cost: LeafCost,
    bins: &mut BinSets,
) -> Option<(usize, Around, Around)> {
    let n = items.len();
    // A leaf at the depth limit, however large, keeps traversal within its fixed stack.
    if depth >= MAX_DEPTH || n <= 1 {
        return None;
    }
    // Every split costs at least a box test: a leaf that costs no more is kept unlooked-at.
    if n <= leaf_cost.max && leaf_cost.of(n) <= TRAVERSAL_COST {
        return None;
    }
    let (bounds, centroid_bounds) = (around.boxes.aabb(), around.centroids.aabb());
    let extent = centroid_bounds.max - centroid_bounds.min;
    match best_split(items, &bounds, &centroid_bounds, leaf_cost, bins) {
        Some((cost, axis, split)) if cost < leaf_cost.of(n) || n > leaf_cost.max => {
            let scale = BINS as f32 / extent[axis];
            let min = centroid_bounds.min[axis];
            Some(partition(items, order, |c| {
                below_split((c[axis] - min) * scale, split)
            }))
        }
        Some(_) => None,
        // All centroids coincide: split in the middle if the leaf would be too large.
        None if n > leaf_cost.max => {
            let mid = n / 2;
            Some((mid, Around::of(&items[..mid]), Around::of(&items[mid..])))
        }
        None => None,
    }
}

/// Moves the items whose centroid `left` accepts to the front; returns how many there
/// are, and what each side's items are around (gathered here, in the pass that moves them,
/// rather than in a pass of their own).
fn partition(
    items: &mut [BuildItem],
    order: &mut [u32],
    left: impl Fn(Vec3A) -> bool,
) -> (usize, Around, Around) {
    let (mut l, mut r) = (Around::EMPTY, Around::EMPTY);
    let mut i = 0;
    for j in 0..items.len() {
        let c = items[j].centroid();
        if left(c) {
            l = l.add(&items[j], c);
            items.swap(i, j);
            order.swap(i, j);
            i += 1;
        } else {
            r = r.add(&items[j], c);
        }
    }
    (i, l, r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::bvh_bins::test_boxes as boxes;

    /// Every primitive is in exactly one leaf, every leaf's box holds its primitives' and
    /// every interior node's box its children's; returns how many nodes it visited.
    fn check(
        bounds: &[Aabb],
        bvh: &BinaryBvh,
        order: &[u32],
        node: usize,
        seen: &mut [bool],
    ) -> usize {
        let n = bvh.nodes[node];
        if n.count > 0 {
            for &p in &order[n.first as usize..(n.first + n.count) as usize] {
                assert!(!seen[p as usize], "primitive {p} twice");
                seen[p as usize] = true;
                let b = bounds[p as usize];
                assert!(n.bounds.min.cmple(b.min).all() && n.bounds.max.cmpge(b.max).all());
            }
            1
        } else {
            let mut visited = 1;
            for child in [n.first as usize, n.first as usize + 1] {
                let c = bvh.nodes[child].bounds;
                assert!(n.bounds.min.cmple(c.min).all() && n.bounds.max.cmpge(c.max).all());
                visited += check(bounds, bvh, order, child, seen);
            }
            visited
        }
    }

    #[test]
    fn every_primitive_lands_in_one_leaf_serial_and_parallel() {
        // Below and far above the size at which subtrees go to other threads.
        for n in [1, 2, 9, 100, 3 * PARALLEL_MIN] {
            let bounds = boxes(n);
            let (bvh, order, _) = BinaryBvh::build(&bounds, LeafCost::SINGLE);
            assert_eq!(order.len(), n);
            let mut seen = vec![false; n];
            let visited = check(&bounds, &bvh, &order, 0, &mut seen);
            assert!(seen.iter().all(|&s| s), "n = {n}");
            // The tree holds no slot that no node uses (each visited once: a tree).
            assert_eq!(visited, bvh.nodes.len(), "n = {n}");
        }
    }

    /// The root's boxes found in pieces on several threads are those of one pass, bit for
    /// bit, also where the extremes tie between 0 and −0 (which compare equal).
    #[test]
    fn bounds_in_pieces_are_those_of_one_pass() {
        let bits = |b: Bounds| {
            (
                b.min.to_array().map(f32::to_bits),
                b.max.to_array().map(f32::to_bits),
            )
        };
        for n in [1, 5, PARALLEL_MIN + 1, 3 * PARALLEL_MIN + 7] {
            for last_negative in [false, true] {
                let items: Vec<BuildItem> = (0..n)
                    .map(|i| {
                        // Every item touches 0 on each side; the signs of those zeros vary.
                        let negative = (i * 7919 % 13 < 6) != (last_negative && i == n - 1);
                        let zero = if negative { -0.0 } else { 0.0 };
                        let far = 1.0 + (i % 11) as f32;
                        BuildItem {
                            min: Vec3A::new(zero, -far, zero),
                            max: Vec3A::new(far, zero, zero),
                        }
                    })
                    .collect();
                let (one, many) = (Around::of(&items), Around::of_many(&items));
                assert_eq!(bits(one.boxes), bits(many.boxes), "n = {n}");
                assert_eq!(bits(one.centroids), bits(many.centroids), "n = {n}");
            }
        }
    }

    #[test]
    fn the_tree_does_not_depend_on_the_threads() {
        let bounds = boxes(4 * PARALLEL_MIN);
        let (a, order_a, coincident_a) = BinaryBvh::build(&bounds, LeafCost::SINGLE);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let (b, order_b, coincident_b) =
            pool.install(|| BinaryBvh::build(&bounds, LeafCost::SINGLE));
        assert_eq!(order_a, order_b);
        assert_eq!(coincident_a, coincident_b);
        assert_eq!(a.nodes.len(), b.nodes.len());
        for (x, y) in a.nodes.iter().zip(&b.nodes) {
            assert_eq!((x.bounds, x.first, x.count), (y.bounds, y.first, y.count));
        }
    }
}
