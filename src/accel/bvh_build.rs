//! The binned surface area heuristic build (Wald 2007) of a binary hierarchy, which
//! `bvh.rs` then collapses into four-wide nodes for traversal.
//!
//! Each node makes two passes over its primitives: the bins of all three axes at once, and
//! the partition, which also gathers each side's boxes and centroids. The two halves of a
//! large split are built on two threads without sharing anything, and the tree is laid
//! out after, so it is the same whichever thread builds what.

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

const BINS: usize = 12;
/// Cost of a box test relative to a primitive test, for the SAH.
const TRAVERSAL_COST: f32 = 1.0;

/// How a leaf's primitives are tested, for the SAH: `group` at a time, each group counted
/// as one test (a mesh's four triangles in SIMD lanes), and at most `max` in one leaf.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LeafCost {
    pub group: usize,
    pub max: usize,
}

impl LeafCost {
    /// One primitive at a time: the scene's objects.
    pub const SINGLE: LeafCost = LeafCost { group: 1, max: 8 };

    /// What testing `n` primitives costs, in primitive tests.
    #[inline(always)]
    fn of(self, n: usize) -> f32 {
        // The widths used, spelled out so that each divides by a constant: the sweep in
        // `best_split` asks this twice per candidate split, and a division by a width
        // known only at run time takes tens of cycles.
        match self.group {
            1 => n as f32,
            4 => n.div_ceil(4) as f32,
            group => n.div_ceil(group) as f32,
        }
    }
}
/// Leaves deeper than this are not split further, however large: it bounds the traversal
/// stack (bvh.rs), and 2^32 leaves are more than any scene has.
pub const MAX_DEPTH: usize = 32;
/// Subtrees of fewer primitives are built on the thread that split them: below this, the
/// cost of handing work to another thread outweighs the work.
const PARALLEL_MIN: usize = 8192;

/// A primitive's box in SIMD lanes (the same values as its `Aabb`, so the tree is the same
/// as one built from the boxes themselves). Its index travels in an array of its own, so
/// the passes that only read boxes stream a third less memory.
struct BuildItem {
    min: Vec3A,
    max: Vec3A,
}

impl BuildItem {
    #[inline(always)]
    fn centroid(&self) -> Vec3A {
        (self.min + self.max) * 0.5
    }
}

/// A box in SIMD lanes while it is grown.
#[derive(Clone, Copy)]
struct Bounds {
    min: Vec3A,
    max: Vec3A,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    #[inline(always)]
    fn union(self, it: &BuildItem) -> Bounds {
        Bounds {
            min: self.min.min(it.min),
            max: self.max.max(it.max),
        }
    }

    #[inline(always)]
    fn merge(self, other: Bounds) -> Bounds {
        Bounds {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    #[inline(always)]
    fn grow(self, p: Vec3A) -> Bounds {
        Bounds {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    fn aabb(self) -> Aabb {
        Aabb {
            min: self.min.into(),
            max: self.max.into(),
        }
    }
}

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
        let mut nodes = Vec::with_capacity(1 + tree.len_below());
        nodes.push(UNUSED);
        nodes[0] = tree.place(&mut nodes);
        // The items are in stored order now, side by side in memory.
        (BinaryBvh { nodes }, order, Coincident::of(&items))
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
        if n < PARALLEL_MIN {
            let mut below = Vec::with_capacity(2 * n - 2);
            let root = build_serial(items, order, around, at, leaf_cost, &mut below);
            return Subtree::Serial { root, below };
        }
        let Some((mid, left_around, right_around)) =
            split(items, order, around, at.depth, leaf_cost)
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
/// a child pair, then the left child's descendants, then the right child's.
fn build_serial(
    items: &mut [BuildItem],
    order: &mut [u32],
    around: Around,
    at: Place,
    leaf_cost: LeafCost,
    below: &mut Vec<BinaryNode>,
) -> BinaryNode {
    let n = items.len();
    let Some((mid, left_around, right_around)) = split(items, order, around, at.depth, leaf_cost)
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
        below,
    );
    below[pair + 1] = build_serial(
        right_items,
        right_order,
        right_around,
        at.right_of(mid),
        leaf_cost,
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
) -> Option<(usize, Around, Around)> {
    let n = items.len();
    // A leaf at the depth limit, however large, keeps traversal within its fixed stack.
    if depth >= MAX_DEPTH || n <= 1 {
        return None;
    }
    let (bounds, centroid_bounds) = (around.boxes.aabb(), around.centroids.aabb());
    let extent = centroid_bounds.max - centroid_bounds.min;
    match best_split(items, &bounds, &centroid_bounds, leaf_cost) {
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

/// Every axis's bins: the box around the items in each, and how many.
struct Bins {
    bounds: [[Bounds; BINS]; 3],
    count: [[usize; BINS]; 3],
}

impl Bins {
    const EMPTY: Bins = Bins {
        bounds: [[Bounds::EMPTY; BINS]; 3],
        count: [[0; BINS]; 3],
    };

    /// The bins of `items` on every axis, in one pass; bin b of an axis holds the items
    /// whose centroid c has `(c - low) * scale` in [b, b + 1) (the last bin also those
    /// beyond). With `two_sets`, items take turns between two sets of bins, merged after:
    /// neighbouring items often fall in one bin, and each would otherwise wait for the one
    /// before it to be stored. A box's union and a count's sum do not depend on the order,
    /// so the bins are the same either way.
    fn of(items: &[BuildItem], low: Vec3A, scale: Vec3A, two_sets: bool) -> Bins {
        let bin = |bins: &mut Bins, it: &BuildItem| {
            let b = bin_index((it.centroid() - low) * scale);
            for axis in 0..3 {
                let b = b[axis] as usize;
                bins.bounds[axis][b] = bins.bounds[axis][b].union(it);
                bins.count[axis][b] += 1;
            }
        };
        let mut all = Bins::EMPTY;
        if !two_sets {
            items.iter().for_each(|it| bin(&mut all, it));
            return all;
        }
        let mut odd = Bins::EMPTY;
        let pairs = items.chunks_exact(2);
        if let [last] = pairs.remainder() {
            bin(&mut all, last);
        }
        for pair in pairs {
            bin(&mut all, &pair[0]);
            bin(&mut odd, &pair[1]);
        }
        all.absorb(&odd);
        all
    }

    fn absorb(&mut self, other: &Bins) {
        for axis in 0..3 {
            for b in 0..BINS {
                self.bounds[axis][b] = self.bounds[axis][b].merge(other.bounds[axis][b]);
                self.count[axis][b] += other.count[axis][b];
            }
        }
    }
}

/// Each axis's bin for x = (c − low) · scale: `min(x as u32, BINS − 1)`, where x is never
/// negative, and NaN (0 · ∞ on an extent so thin that its scale overflows) is bin 0. The
/// lanes are clamped to [0, BINS − 1] first (`max` gives 0 for NaN), so that truncating
/// all three at once gives exactly what the saturating conversion would.
#[inline(always)]
fn bin_index(x: Vec3A) -> [u32; 3] {
    let clamped = x.max(Vec3A::ZERO).min(Vec3A::splat((BINS - 1) as f32));
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{__m128, __m128i, _mm_cvttps_epi32};
        // SAFETY: SSE2 is part of the x86-64 baseline; the lanes are in [0, BINS − 1].
        let lanes: [u32; 4] = unsafe {
            std::mem::transmute::<__m128i, [u32; 4]>(_mm_cvttps_epi32(__m128::from(clamped)))
        };
        [lanes[0], lanes[1], lanes[2]]
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        clamped.as_uvec3().to_array()
    }
}

/// Nodes of at least this many items are binned into two sets of bins (`Bins::of`);
/// below it, clearing and merging a second set costs more than it saves.
const TWO_BIN_SETS_MIN: usize = 64;

/// The cheapest split by the SAH among every axis's bin boundaries, as (cost, axis, the
/// first bin on the right); None when all centroids coincide.
fn best_split(
    items: &[BuildItem],
    bounds: &Aabb,
    centroid_bounds: &Aabb,
    leaf: LeafCost,
) -> Option<(f32, usize, usize)> {
    let extent = centroid_bounds.max - centroid_bounds.min;
    let extent_a = Vec3A::from(extent);
    let scale = Vec3A::select(
        extent_a.cmpgt(Vec3A::ZERO),
        Vec3A::splat(BINS as f32) / extent_a,
        Vec3A::ZERO,
    );
    let low = Vec3A::from(centroid_bounds.min);
    let Bins {
        bounds: bins,
        count: bin_count,
    } = Bins::of(items, low, scale, items.len() >= TWO_BIN_SETS_MIN);
    let mut best: Option<(f32, usize, usize)> = None;
    let parent_area = bounds.half_area().max(f32::MIN_POSITIVE);
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let (bins, counts) = (&bins[axis], &bin_count[axis]);
        // Only boundaries just past a non-empty bin can be best: past an empty one, both
        // sides hold what they held one boundary before, at the same cost, and the first
        // of equal costs wins. A small node has few non-empty bins, so this is most of
        // the work saved where most nodes are.
        let mut full = [0usize; BINS];
        let mut k = 0;
        // Without a branch: whether a bin is empty is as good as random.
        for (b, &count) in counts.iter().enumerate() {
            full[k] = b;
            k += (count > 0) as usize;
        }
        // Sweep from the right to know the cost of every right-hand side.
        let mut right_area = [0.0f32; BINS];
        let mut right_count = [0usize; BINS];
        let (mut acc, mut cnt) = (Bounds::EMPTY, 0);
        for j in (1..k).rev() {
            acc = acc.merge(bins[full[j]]);
            cnt += counts[full[j]];
            right_area[j] = acc.aabb().half_area();
            right_count[j] = cnt;
        }
        let (mut acc, mut cnt) = (Bounds::EMPTY, 0);
        for j in 1..k {
            acc = acc.merge(bins[full[j - 1]]);
            cnt += counts[full[j - 1]];
            let cost = TRAVERSAL_COST
                + (acc.aabb().half_area() * leaf.of(cnt) + right_area[j] * leaf.of(right_count[j]))
                    / parent_area;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, full[j - 1] + 1));
            }
        }
    }
    best
}

/// Whether an item at `x` = (c − min) · scale along the split axis (never negative) falls
/// in a bin below `split` (< BINS): whether `min(x as usize, BINS − 1) < split`, which is
/// `x < split`, and true for x = NaN (0 · ∞ on an extent so thin that its scale overflows),
/// whose bin is 0. Compared without converting x, once per item per level.
#[inline(always)]
fn below_split(x: f32, split: usize) -> bool {
    x < split as f32 || x.is_nan()
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
    use glam::Vec3;

    /// Boxes along a diagonal, some coinciding, of varied sizes.
    fn boxes(n: usize) -> Vec<Aabb> {
        (0..n)
            .map(|i| {
                let c = Vec3::new(
                    (i % 97) as f32,
                    (i % 13) as f32 * 0.5,
                    (i / 7) as f32 * 0.25,
                );
                let r = Vec3::splat(0.1 + (i % 5) as f32 * 0.05);
                Aabb {
                    min: c - r,
                    max: c + r,
                }
            })
            .collect()
    }

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

    /// Places along an axis, in bins, that the binning meets and the hard ones: each bin
    /// boundary and its neighbouring floats, tiny and huge values, infinity and NaN.
    fn places_to_bin() -> Vec<f32> {
        let mut xs = vec![0.0, f32::MIN_POSITIVE, 1e-30, f32::INFINITY, f32::NAN, 1e30];
        for k in 0..=BINS + 1 {
            let at = k as f32;
            xs.extend([at, at.next_down(), at.next_up(), at + 0.5]);
        }
        xs
    }

    /// The split test compares without converting, and agrees with the bin index the
    /// binning computed, at and around every boundary and at the odd values.
    #[test]
    fn the_split_test_agrees_with_the_bins() {
        let bin = |x: f32| (x as usize).min(BINS - 1);
        for x in places_to_bin() {
            for split in 1..BINS {
                assert_eq!(
                    below_split(x, split),
                    bin(x) < split,
                    "x = {x}, split {split}"
                );
            }
        }
    }

    /// The three lanes' bins at once are the saturating conversion's, lane by lane.
    #[test]
    fn bin_indices_are_the_saturating_conversions() {
        let reference = |x: f32| (x as u32).min(BINS as u32 - 1);
        let xs = places_to_bin();
        for &x in &xs {
            for &y in &xs {
                let z = xs[(x as usize + 3) % xs.len()];
                let got = bin_index(Vec3A::new(x, y, z));
                assert_eq!(
                    got,
                    [reference(x), reference(y), reference(z)],
                    "{x} {y} {z}"
                );
            }
        }
        let got = bin_index(Vec3A::new(f32::NAN, f32::INFINITY, 11.5));
        assert_eq!(got, [0, BINS as u32 - 1, BINS as u32 - 1]);
    }

    /// Two sets of bins merged hold what one set holds, bit for bit, for odd and even
    /// numbers of items.
    #[test]
    fn two_sets_of_bins_hold_what_one_holds() {
        for n in [1, 2, 63, 64, 65, 1000, 1001] {
            let items: Vec<BuildItem> = boxes(n)
                .iter()
                .map(|b| BuildItem {
                    min: b.min.into(),
                    max: b.max.into(),
                })
                .collect();
            let around = Around::of(&items).centroids;
            let extent = around.max - around.min;
            let scale = Vec3A::splat(BINS as f32) / extent.max(Vec3A::splat(1e-6));
            let one = Bins::of(&items, around.min, scale, false);
            let two = Bins::of(&items, around.min, scale, true);
            assert_eq!(one.count, two.count, "n = {n}");
            for axis in 0..3 {
                for b in 0..BINS {
                    let (p, q) = (one.bounds[axis][b], two.bounds[axis][b]);
                    assert_eq!(
                        (p.min.to_array(), p.max.to_array()),
                        (q.min.to_array(), q.max.to_array()),
                        "n = {n}, axis {axis}, bin {b}"
                    );
                }
            }
            assert_eq!(one.count.iter().flatten().sum::<usize>(), 3 * n);
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
