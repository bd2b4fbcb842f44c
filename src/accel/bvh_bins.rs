//! The binned surface area heuristic's bins (Wald 2007): the primitives' boxes as the
//! build bins them, every axis's bins of a node filled in one pass, and the cheapest split
//! among their boundaries. `bvh_build.rs` builds the tree from these choices.

use crate::geometry::Aabb;
use glam::Vec3A;

/// Bins per axis.
pub(super) const BINS: usize = 12;
/// Cost of a box test relative to a primitive test, for the SAH.
pub(super) const TRAVERSAL_COST: f32 = 1.0;

/// How a leaf's primitives are tested, for the SAH: `group` at a time, each group counted
/// as one test (a mesh's eight triangles in SIMD lanes), and at most `max` in one leaf.
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
    pub(super) fn of(self, n: usize) -> f32 {
        // The widths used, spelled out so that each divides by a constant: the sweep in
        // `best_split` asks this twice per candidate split, and a division by a width
        // known only at run time takes tens of cycles.
        match self.group {
            1 => n as f32,
            8 => n.div_ceil(8) as f32,
            group => n.div_ceil(group) as f32,
        }
    }
}

/// A primitive's box in SIMD lanes (the same values as its `Aabb`, so the tree is the same
/// as one built from the boxes themselves). Its index travels in an array of its own, so
/// the passes that only read boxes stream a third less memory.
pub(super) struct BuildItem {
    pub(super) min: Vec3A,
    pub(super) max: Vec3A,
}

impl BuildItem {
    #[inline(always)]
    pub(super) fn centroid(&self) -> Vec3A {
        (self.min + self.max) * 0.5
    }
}

/// A box in SIMD lanes while it is grown.
#[derive(Clone, Copy)]
pub(super) struct Bounds {
    pub(super) min: Vec3A,
    pub(super) max: Vec3A,
}

impl Bounds {
    pub(super) const EMPTY: Bounds = Bounds {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    #[inline(always)]
    pub(super) fn union(self, it: &BuildItem) -> Bounds {
        Bounds {
            min: self.min.min(it.min),
            max: self.max.max(it.max),
        }
    }

    #[inline(always)]
    pub(super) fn merge(self, other: Bounds) -> Bounds {
        Bounds {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    #[inline(always)]
    pub(super) fn grow(self, p: Vec3A) -> Bounds {
        Bounds {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    #[inline(always)]
    pub(super) fn aabb(self) -> Aabb {
        Aabb {
            min: self.min.into(),
            max: self.max.into(),
        }
    }
}

/// Every axis's bins: the box around the items in each, and how many (a node has fewer
/// than 2^32 items: the order is of `u32`).
struct Bins {
    bounds: [[Bounds; BINS]; 3],
    count: [[u32; BINS]; 3],
}

impl Bins {
    const EMPTY: Bins = Bins {
        bounds: [[Bounds::EMPTY; BINS]; 3],
        count: [[0; BINS]; 3],
    };

    fn clear(&mut self) {
        for axis in 0..3 {
            for b in 0..BINS {
                self.bounds[axis][b] = Bounds::EMPTY;
                self.count[axis][b] = 0;
            }
        }
    }

    #[inline(always)]
    fn add(&mut self, it: &BuildItem, low: Vec3A, scale: Vec3A) {
        let b = bin_index((it.centroid() - low) * scale);
        for axis in 0..3 {
            let b = b[axis] as usize;
            self.bounds[axis][b] = self.bounds[axis][b].union(it);
            self.count[axis][b] += 1;
        }
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

/// Two sets of bins, filled in place by one node after another on a thread: a set is over
/// a kilobyte, and making one afresh for every node (most of which hold a few items) and
/// moving it out cost more than binning the items did.
pub(super) struct BinSets {
    all: Bins,
    odd: Bins,
}

impl BinSets {
    #[inline]
    pub(super) fn new() -> BinSets {
        BinSets {
            all: Bins::EMPTY,
            odd: Bins::EMPTY,
        }
    }

    /// The bins of `items` on every axis, in one pass; bin b of an axis holds the items
    /// whose centroid c has `(c - low) * scale` in [b, b + 1) (the last bin also those
    /// beyond). With `two_sets`, items take turns between two sets of bins, merged after:
    /// neighbouring items often fall in one bin, and each would otherwise wait for the one
    /// before it to be stored. A box's union and a count's sum do not depend on the order,
    /// so the bins are the same either way.
    fn fill(&mut self, items: &[BuildItem], low: Vec3A, scale: Vec3A, two_sets: bool) -> &Bins {
        let BinSets { all, odd } = self;
        all.clear();
        if !two_sets {
            items.iter().for_each(|it| all.add(it, low, scale));
            return all;
        }
        odd.clear();
        let pairs = items.chunks_exact(2);
        if let [last] = pairs.remainder() {
            all.add(last, low, scale);
        }
        for pair in pairs {
            all.add(&pair[0], low, scale);
            odd.add(&pair[1], low, scale);
        }
        all.absorb(odd);
        all
    }

    /// `fill` for a node of many items: its bins in pieces on several threads, absorbed
    /// in order. The same counts and the same boxes' areas (a box's bounds may differ
    /// only between 0 and −0, which the areas do not see), so the same split.
    #[inline]
    fn fill_many(&mut self, items: &[BuildItem], low: Vec3A, scale: Vec3A) -> &Bins {
        use rayon::prelude::*;
        let pieces: Vec<Bins> = items
            .par_chunks(BINNING_PIECE)
            .map(|piece| {
                let mut sets = BinSets::new();
                sets.fill(piece, low, scale, true);
                sets.all
            })
            .collect();
        self.all.clear();
        for piece in &pieces {
            self.all.absorb(piece);
        }
        &self.all
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

/// Nodes of at least this many items are binned into two sets of bins (`BinSets::fill`);
/// below it, clearing and merging a second set costs more than it saves.
const TWO_BIN_SETS_MIN: usize = 64;
/// Nodes of at least this many items are binned in pieces on several threads: above the
/// first splits, one thread would otherwise bin them while the others wait.
const PARALLEL_BINNING_MIN: usize = 4 * BINNING_PIECE;
/// How many items of such a node one thread bins at a time.
const BINNING_PIECE: usize = 8192;

/// The cheapest split by the SAH among every axis's bin boundaries, as (cost, axis, the
/// first bin on the right); None when all centroids coincide.
// Inlined into the split (another file's code, which the compiler may otherwise build
// apart and call).
#[inline]
pub(super) fn best_split(
    items: &[BuildItem],
    bounds: &Aabb,
    centroid_bounds: &Aabb,
    leaf: LeafCost,
    bin_sets: &mut BinSets,
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
    } = if items.len() >= PARALLEL_BINNING_MIN {
        bin_sets.fill_many(items, low, scale)
    } else {
        bin_sets.fill(items, low, scale, items.len() >= TWO_BIN_SETS_MIN)
    };
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
            cnt += counts[full[j]] as usize;
            right_area[j] = acc.aabb().half_area();
            right_count[j] = cnt;
        }
        let (mut acc, mut cnt) = (Bounds::EMPTY, 0);
        for j in 1..k {
            acc = acc.merge(bins[full[j - 1]]);
            cnt += counts[full[j - 1]] as usize;
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
pub(super) fn below_split(x: f32, split: usize) -> bool {
    x < split as f32 || x.is_nan()
}

/// Boxes along a diagonal, some coinciding, of varied sizes: the primitives of this file's
/// tests and bvh_build.rs's.
#[cfg(test)]
pub(super) fn test_boxes(n: usize) -> Vec<Aabb> {
    (0..n)
        .map(|i| {
            let c = glam::Vec3::new(
                (i % 97) as f32,
                (i % 13) as f32 * 0.5,
                (i / 7) as f32 * 0.25,
            );
            let r = glam::Vec3::splat(0.1 + (i % 5) as f32 * 0.05);
            Aabb {
                min: c - r,
                max: c + r,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `test_boxes` as the build bins them.
    fn items(n: usize) -> Vec<BuildItem> {
        test_boxes(n)
            .iter()
            .map(|b| BuildItem {
                min: b.min.into(),
                max: b.max.into(),
            })
            .collect()
    }

    /// The box around the items' centroids, and the scale that spreads it over the bins.
    fn low_and_scale(items: &[BuildItem]) -> (Vec3A, Vec3A) {
        let around = items
            .iter()
            .fold(Bounds::EMPTY, |b, it| b.grow(it.centroid()));
        let extent = around.max - around.min;
        (
            around.min,
            Vec3A::splat(BINS as f32) / extent.max(Vec3A::splat(1e-6)),
        )
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
            let items = items(n);
            let (low, scale) = low_and_scale(&items);
            let (mut one, mut two) = (BinSets::new(), BinSets::new());
            let one = one.fill(&items, low, scale, false);
            let two = two.fill(&items, low, scale, true);
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
            assert_eq!(one.count.iter().flatten().sum::<u32>() as usize, 3 * n);
        }
    }

    /// A node's bins filled in pieces on several threads hold the counts one pass finds,
    /// and boxes equal to its (bit for bit but for the sign of a zero, which no area sees).
    #[test]
    fn bins_in_pieces_hold_what_one_pass_holds() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        for n in [PARALLEL_BINNING_MIN, 3 * PARALLEL_BINNING_MIN + 7] {
            let items = items(n);
            let (low, scale) = low_and_scale(&items);
            let mut one = BinSets::new();
            let one = one.fill(&items, low, scale, true);
            let mut many = BinSets::new();
            let many = pool.install(|| many.fill_many(&items, low, scale));
            assert_eq!(one.count, many.count, "n = {n}");
            for axis in 0..3 {
                for b in 0..BINS {
                    let (p, q) = (one.bounds[axis][b], many.bounds[axis][b]);
                    assert!(
                        p.min == q.min && p.max == q.max,
                        "n = {n}, axis {axis}, bin {b}"
                    );
                }
            }
        }
    }
}
