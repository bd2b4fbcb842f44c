//! Which descendants of a binary tree's node become the lanes of its wide node (`bvh.rs`):
//! the choice that makes the wide nodes' total surface area least. A ray enters a node's box
//! with a probability in proportion to its area (the surface area heuristic), and a wide
//! node costs one box test whether it uses two lanes or eight, so this total is what the
//! tree's node tests cost an average ray. Filling each node greedily from the top, by
//! opening its largest child first, leaves the levels near the leaves in many nodes of two
//! or three lanes; this plan, by dynamic programming over lane budgets (as in Ylitie,
//! Karras and Laine 2017, "Efficient incoherent ray traversal on GPUs through compressed
//! wide BVHs"), puts such small subtrees in their parents' spare lanes where that saves
//! more than opening a larger child would.

use super::bvh_build::BinaryBvh;
use super::wide_node::WIDTH;

/// How a subtree takes up to k lanes of the wide node above it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Placement {
    /// One lane: the subtree's root (a leaf, or a wide node of its own).
    Whole,
    /// Its root is opened: its first child takes up to this many lanes, its second the rest.
    Opened(u8),
}

/// For every binary node and lane budget, the least cost and the placement that gives it.
/// An inner node's placement in a full budget of eight lanes is always `Opened`: it is how
/// the node, made a wide node of its own, shares its lanes between its children.
pub(super) struct CollapsePlan {
    /// `cost[n][k - 1]`: the least total area of the wide nodes that subtree `n` needs
    /// when it may take up to k lanes of its parent's node.
    cost: Vec<[f64; WIDTH]>,
    placement: Vec<[Placement; WIDTH]>,
}

impl CollapsePlan {
    /// The plan for `binary` (not empty).
    pub fn new(binary: &BinaryBvh) -> Self {
        let n = binary.nodes.len();
        let mut plan = CollapsePlan {
            cost: vec![[0.0; WIDTH]; n],
            placement: vec![[Placement::Whole; WIDTH]; n],
        };
        // Children before parents: the nodes reachable from the root, in reverse of a
        // walk that meets every node before its children.
        let mut order = Vec::with_capacity(n);
        let mut stack = vec![0usize];
        while let Some(node) = stack.pop() {
            order.push(node);
            let b = &binary.nodes[node];
            if b.count == 0 {
                stack.push(b.first as usize);
                stack.push(b.first as usize + 1);
            }
        }
        for &node in order.iter().rev() {
            plan.settle(binary, node);
        }
        plan
    }

    /// Fills in node `node`'s costs, its children's being known.
    fn settle(&mut self, binary: &BinaryBvh, node: usize) {
        let b = &binary.nodes[node];
        if b.count > 0 {
            return; // a leaf takes one lane and needs no node: cost 0, `Whole`, as made
        }
        let (first, second) = (b.first as usize, b.first as usize + 1);
        // Opened into up to `budget` lanes: the least split, and its cost (ties to the
        // first child's smaller share, so the plan is the same on every machine).
        let opened = |budget: usize| {
            let mut best = (f64::INFINITY, 1u8);
            for share in 1..budget {
                let c = self.cost[first][share - 1] + self.cost[second][budget - share - 1];
                if c < best.0 {
                    best = (c, share as u8);
                }
            }
            best
        };
        let (inside, split) = opened(WIDTH);
        let own = f64::from(b.bounds.half_area()) + inside;
        let mut cost = [own; WIDTH];
        let mut placement = [Placement::Whole; WIDTH];
        for budget in 2..WIDTH {
            let (c, share) = opened(budget);
            // Opening saves this node's own box test; on a tie, fewer nodes.
            if c <= own {
                cost[budget - 1] = c;
                placement[budget - 1] = Placement::Opened(share);
            }
        }
        // Eight lanes hold the node's own lanes as well as any subtree it could open into:
        // opened, whatever its area.
        cost[WIDTH - 1] = inside;
        placement[WIDTH - 1] = Placement::Opened(split);
        self.cost[node] = cost;
        self.placement[node] = placement;
    }

    /// The lanes of inner node `node` made a wide node, in order: its first child's
    /// descendants, then its second's.
    pub fn lanes_of_node(&self, binary: &BinaryBvh, node: usize, lanes: &mut Vec<usize>) {
        debug_assert_eq!(binary.nodes[node].count, 0, "a leaf is no wide node");
        self.lanes_within(binary, node, WIDTH, lanes);
    }

    /// The lanes that subtree `node` takes within `budget` lanes of its parent's node.
    fn lanes_within(&self, binary: &BinaryBvh, node: usize, budget: usize, lanes: &mut Vec<usize>) {
        match self.placement[node][budget - 1] {
            Placement::Whole => lanes.push(node),
            Placement::Opened(share) => {
                let first = binary.nodes[node].first as usize;
                let share = usize::from(share);
                self.lanes_within(binary, first, share, lanes);
                self.lanes_within(binary, first + 1, budget - share, lanes);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::bvh::{Bvh, Child};
    use super::super::bvh_bins::LeafCost;
    use super::*;
    use crate::geometry::Aabb;
    use glam::Vec3;

    /// The total area of a wide tree's nodes: what the plan makes least.
    fn wide_area(bvh: &Bvh) -> f64 {
        let root = bvh.bounds.map_or(0.0, |b| f64::from(b.half_area()));
        let inner: f64 = bvh
            .nodes
            .iter()
            .flat_map(|node| {
                (0..WIDTH).filter_map(move |lane| match node.child(lane) {
                    Child::Node(_) => Some(f64::from(node.bounds(lane).half_area())),
                    _ => None,
                })
            })
            .sum();
        root + inner
    }

    /// The greedy fill: each node opens its inner lane of largest area until it has eight.
    fn greedy_area(binary: &BinaryBvh, node: usize) -> f64 {
        let nodes = &binary.nodes;
        if nodes[node].count > 0 {
            return 0.0;
        }
        let mut lanes = vec![nodes[node].first as usize, nodes[node].first as usize + 1];
        while lanes.len() < WIDTH {
            let open = (0..lanes.len())
                .filter(|&l| nodes[lanes[l]].count == 0)
                .max_by(|&a, &b| {
                    let area = |l: usize| nodes[lanes[l]].bounds.half_area();
                    area(a).total_cmp(&area(b))
                });
            let Some(l) = open else { break };
            let first = nodes[lanes[l]].first as usize;
            lanes[l] = first;
            lanes.push(first + 1);
        }
        f64::from(nodes[node].bounds.half_area())
            + lanes.iter().map(|&l| greedy_area(binary, l)).sum::<f64>()
    }

    /// Every leaf of the binary tree is a lane of exactly one wide node, and no node has
    /// more than eight lanes or fewer than two (but a root that is a leaf).
    fn assert_holds_every_leaf_once(binary: &BinaryBvh, bvh: &Bvh) {
        let mut leaves: Vec<(u32, u32)> = binary
            .nodes
            .iter()
            .filter(|n| n.count > 0)
            .map(|n| (n.first, n.count))
            .collect();
        let mut lanes: Vec<(u32, u32)> = Vec::new();
        for node in &bvh.nodes {
            let used = (0..WIDTH)
                .filter(|&l| node.child(l) != Child::Empty)
                .count();
            assert!(used >= 2 || bvh.nodes.len() == 1, "{used} lanes");
            for lane in 0..WIDTH {
                if let Child::Leaf(r) = node.child(lane) {
                    lanes.push((r.start, r.end - r.start));
                }
            }
        }
        leaves.sort();
        lanes.sort();
        assert_eq!(lanes, leaves);
    }

    #[test]
    fn the_plan_never_costs_more_than_the_greedy_fill_and_keeps_every_leaf() {
        let mut seed = 5u32;
        let mut next = || {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            (seed >> 8) as f32 / (1 << 24) as f32
        };
        let mut better = 0;
        for (count, spread) in [(3, 1.0), (40, 10.0), (500, 30.0), (3000, 100.0)] {
            let bounds: Vec<Aabb> = (0..count)
                .map(|_| {
                    let c = Vec3::new(next(), next(), next() * 0.2) * spread;
                    let r = Vec3::new(next(), next(), next()) * 0.5 + Vec3::splat(0.05);
                    Aabb {
                        min: c - r,
                        max: c + r,
                    }
                })
                .collect();
            let (binary, _, coincident) = BinaryBvh::build(&bounds, LeafCost::SINGLE);
            let bvh = Bvh::collapsed(&binary, coincident);
            assert_holds_every_leaf_once(&binary, &bvh);
            let (planned, greedy) = (wide_area(&bvh), greedy_area(&binary, 0));
            let plan = CollapsePlan::new(&binary);
            let expected = f64::from(binary.nodes[0].bounds.half_area()) + plan.cost[0][WIDTH - 1];
            if binary.nodes[0].count == 0 {
                assert!(
                    (planned - expected).abs() <= 1e-9 * expected,
                    "{planned} {expected}"
                );
            }
            assert!(
                planned <= greedy * (1.0 + 1e-12),
                "{count}: {planned} > {greedy}"
            );
            better += (planned < greedy * (1.0 - 1e-6)) as u32;
        }
        assert!(
            better >= 1,
            "the plan should beat the greedy fill on a large tree"
        );
    }
}
