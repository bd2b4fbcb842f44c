//! Constructive solid geometry: solids combined by union, intersection, difference and
//! merge, as POV-Ray combines them. A hit on a member's surface is a hit on the solid when
//! the member's surface is part of the solid's there, which depends only on whether the
//! point lies inside the other members (POV-Ray's method): no interval lists, no
//! allocation per ray, at most the members' own intersection work plus point tests.

use super::csg_members::{BoxFinder, MIN_MEMBERS_FOR_HIERARCHY, MemberFinder};
use super::instance::{Instance, Model};
use crate::geometry::{
    Aabb, Disc, HitDetail, RayQuery, Shape, ShapeHit, ShapePart, SurfacePoint, UvFrame,
};
use glam::Vec3A;

/// How a CSG node combines its members (a closed set).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsgOperation {
    /// Everything inside any member; every member's whole surface shows (inner ones too),
    /// except inside another combination, where a union is a merge.
    Union,
    /// Only what is inside every member.
    Intersection,
    /// The first member minus the rest.
    Difference,
    /// A union without the surfaces inside other members (for glass).
    Merge,
}

impl CsgOperation {
    /// The operations' names in the scene file, in the order above.
    pub const NAMES: [&'static str; 4] = ["union", "intersection", "difference", "merge"];

    /// Its name in the scene file.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The operation named `name`.
    pub fn named(name: &str) -> Option<CsgOperation> {
        Some(match name {
            "union" => CsgOperation::Union,
            "intersection" => CsgOperation::Intersection,
            "difference" => CsgOperation::Difference,
            "merge" => CsgOperation::Merge,
            _ => return None,
        })
    }
}

/// A closed solid at the bottom of a CSG tree.
#[derive(Clone, Debug)]
pub enum CsgLeaf {
    /// A closed shape in the scene's space.
    Shape(Shape),
    /// A closed shape placed by a transform.
    Instance(Box<Instance>),
    /// The half of space behind a plane (its normal points out of it), traced as a disc
    /// far wider than the scene, as planes are.
    HalfSpace(Disc),
}

impl CsgLeaf {
    #[inline]
    fn intersect_after(&self, q: &RayQuery, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match self {
            CsgLeaf::Shape(shape) => shape.intersect_after(q, t_min, t_max),
            CsgLeaf::Instance(instance) => instance.intersect_after(q, t_min, t_max),
            CsgLeaf::HalfSpace(disc) => {
                disc.intersect_after(&q.ray, t_min, t_max)
                    .map(|t| ShapeHit {
                        t,
                        detail: HitDetail::Disc,
                    })
            }
        }
    }

    /// Whether scene point `p` lies inside.
    #[inline]
    fn contains(&self, p: Vec3A) -> bool {
        match self {
            CsgLeaf::Shape(shape) => shape.contains(p),
            CsgLeaf::Instance(instance) => instance.contains(p),
            CsgLeaf::HalfSpace(disc) => {
                (p - Vec3A::from(disc.center)).dot(disc.normal.into()) < 0.0
            }
        }
    }

    /// The shape whose parts a hit names.
    fn shape(&self) -> Shape {
        match self {
            CsgLeaf::Shape(shape) => *shape,
            CsgLeaf::Instance(instance) => match &**instance.model() {
                Model::Shape(shape) => *shape,
                Model::Mesh { .. } => unreachable!("a CSG member is a closed shape"),
            },
            CsgLeaf::HalfSpace(disc) => Shape::Disc(*disc),
        }
    }

    fn bounds(&self) -> Aabb {
        match self {
            CsgLeaf::Shape(shape) => shape.bounds(),
            CsgLeaf::Instance(instance) => instance.bounds(),
            CsgLeaf::HalfSpace(disc) => disc.bounds(),
        }
    }
}

/// A node of a CSG tree: a member, or members combined.
#[derive(Clone, Debug)]
pub enum CsgNode {
    /// Leaf `index` (leaves are numbered in the tree's order).
    Leaf(u32),
    /// Members combined by an operation.
    Combine {
        /// How.
        operation: CsgOperation,
        /// The members, each a subtree.
        members: Vec<CsgNode>,
        /// The leaves under it, as they are numbered in the tree's order (kept, so that a
        /// hit finds its member without walking the tree).
        leaves: std::ops::Range<u32>,
        /// For many members, which may hold a point (set by `Csg::new`).
        finder: Option<Box<MemberFinder>>,
    },
}

impl CsgNode {
    /// Members combined by `operation`, their leaves numbered in the tree's order.
    pub fn combine(operation: CsgOperation, members: Vec<CsgNode>) -> CsgNode {
        let first = members.first().map_or(0, |m| m.leaves().start);
        let last = members.last().map_or(0, |m| m.leaves().end);
        CsgNode::Combine {
            operation,
            members,
            leaves: first..last,
            finder: None,
        }
    }

    /// The leaves under it.
    fn leaves(&self) -> std::ops::Range<u32> {
        match self {
            CsgNode::Leaf(i) => *i..*i + 1,
            CsgNode::Combine { leaves, .. } => leaves.clone(),
        }
    }
}

/// The most hits a ray may have on one member (a torus has four): a bound on the work
/// per member, whatever rounding does.
const MAX_HITS_PER_LEAF: u32 = 8;

/// A CSG solid: its tree, its leaves, and which leaves' surfaces face into the solid's
/// outside the other way (those subtracted an odd number of times).
#[derive(Clone, Debug)]
pub struct Csg {
    root: CsgNode,
    leaves: Vec<CsgLeaf>,
    /// Whether each leaf's outward normal points into the solid (its normal is turned).
    turned: Vec<bool>,
    /// The material each leaf's surface takes, as the appearance numbers them.
    materials: Vec<u32>,
    bounds: Aabb,
    /// For many leaves, which a ray may meet.
    leaf_finder: Option<BoxFinder>,
}

impl Csg {
    /// The solid of tree `root` over `leaves` (numbered in the tree's order), each leaf's
    /// surface of the material `materials` gives it. With `hierarchies`, a solid of many
    /// members finds those a ray or a point comes near through hierarchies over their boxes
    /// (csg_members.rs); without, it asks every one (the same image, for comparisons).
    ///
    /// # Panics
    /// If there is not one material per leaf.
    pub fn new(
        mut root: CsgNode,
        leaves: Vec<CsgLeaf>,
        materials: Vec<u32>,
        hierarchies: bool,
    ) -> Self {
        assert_eq!(materials.len(), leaves.len(), "one material per leaf");
        let mut turned = vec![false; leaves.len()];
        mark_turned(&root, false, &mut turned);
        let bounds = node_bounds(&root, &leaves);
        let mut leaf_finder = None;
        if hierarchies {
            add_finders(&mut root, &leaves);
            if leaves.len() >= MIN_MEMBERS_FOR_HIERARCHY {
                let boxes: Vec<Aabb> = leaves.iter().map(CsgLeaf::bounds).collect();
                leaf_finder = Some(BoxFinder::new(&boxes));
            }
        }
        Self {
            root,
            leaves,
            turned,
            materials,
            bounds,
            leaf_finder,
        }
    }

    /// The material of the member `hit` is on.
    #[inline]
    pub fn material_slot(&self, hit: &ShapeHit) -> u32 {
        match hit.detail {
            HitDetail::Csg { leaf, .. } => self.materials[leaf as usize],
            detail => unreachable!("hit {detail:?} is not on a CSG solid"),
        }
    }

    /// The box around the solid.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Whether `p` lies inside the subtree `node`.
    fn contains(&self, node: &CsgNode, p: Vec3A) -> bool {
        match node {
            CsgNode::Leaf(i) => self.leaves[*i as usize].contains(p),
            CsgNode::Combine {
                operation,
                members,
                finder,
                ..
            } => match operation {
                CsgOperation::Union | CsgOperation::Merge => {
                    self.any_holding(members, finder, p, |_| true)
                }
                CsgOperation::Intersection => members.iter().all(|m| self.contains(m, p)),
                CsgOperation::Difference => {
                    self.contains(&members[0], p)
                        && !self.any_holding(members, finder, p, |m| m > 0)
                }
            },
        }
    }

    /// Whether `p` lies inside one of `members` that `asked` picks (by its index), found
    /// by `finder` where the combination has one.
    #[inline]
    fn any_holding(
        &self,
        members: &[CsgNode],
        finder: &Option<Box<MemberFinder>>,
        p: Vec3A,
        asked: impl Fn(usize) -> bool,
    ) -> bool {
        let holds = |m: usize| asked(m) && self.contains(&members[m], p);
        match finder {
            Some(finder) => finder.any(p, holds),
            None => (0..members.len()).any(holds),
        }
    }

    /// Whether point `p`, on leaf `leaf`'s surface, is on the surface of subtree `node`
    /// (which holds the leaf). Only the root shows a union's inner surfaces: below it, a
    /// union bounds a solid as a merge does (a member's surface inside another member of a
    /// subtracted union is in the hole, not on its wall).
    fn on_surface(&self, node: &CsgNode, leaf: u32, p: Vec3A) -> bool {
        self.on_surface_below(node, leaf, p, true)
    }

    fn on_surface_below(&self, node: &CsgNode, leaf: u32, p: Vec3A, root: bool) -> bool {
        let CsgNode::Combine {
            operation,
            members,
            finder,
            ..
        } = node
        else {
            return true;
        };
        // Members hold their leaves in order: the one holding `leaf` is found by halving.
        let own = members.partition_point(|m| m.leaves().end <= leaf);
        if !members.get(own).is_some_and(|m| m.leaves().contains(&leaf)) {
            return false;
        }
        if !self.on_surface_below(&members[own], leaf, p, false) {
            return false;
        }
        let other = |m: usize| m != own;
        match operation {
            CsgOperation::Union if root => true,
            CsgOperation::Union | CsgOperation::Merge => {
                !self.any_holding(members, finder, p, other)
            }
            CsgOperation::Intersection => members
                .iter()
                .enumerate()
                .all(|(m, member)| m == own || self.contains(member, p)),
            CsgOperation::Difference if own == 0 => !self.any_holding(members, finder, p, other),
            CsgOperation::Difference => {
                self.contains(&members[0], p)
                    && !self.any_holding(members, finder, p, |m| m > 0 && m != own)
            }
        }
    }

    /// Leaf `leaf`'s hits along `q` in (t_min, t_max), nearest first, that lie on the
    /// solid's surface: `visit` is given each, and stops the walk by returning false.
    #[inline]
    fn leaf_hits(
        &self,
        leaf: usize,
        q: &RayQuery,
        t_min: f32,
        t_max: f32,
        mut visit: impl FnMut(ShapeHit) -> bool,
    ) {
        let mut t = t_min;
        for _ in 0..MAX_HITS_PER_LEAF {
            let Some(hit) = self.leaves[leaf].intersect_after(q, t, t_max) else {
                return;
            };
            if self.on_surface(&self.root, leaf as u32, q.ray.at(hit.t)) && !visit(hit) {
                return;
            }
            t = hit.t;
        }
    }

    /// The nearest hit on the solid with t in (t_min, t_max); of hits at one distance, the
    /// one on the lowest-numbered leaf.
    pub fn intersect_after(&self, q: &RayQuery, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let mut nearest: Option<(usize, ShapeHit)> = None;
        let mut try_leaf = |leaf: usize| {
            // A leaf numbered below the nearest's may meet the ray at the same distance.
            let limit = match nearest {
                None => t_max,
                Some((at, hit)) if leaf < at => hit.t.next_up(),
                Some((_, hit)) => hit.t,
            };
            self.leaf_hits(leaf, q, t_min, limit, |hit| {
                let hit = ShapeHit {
                    t: hit.t,
                    detail: HitDetail::Csg {
                        leaf: leaf as u16,
                        part: ShapePart::of(hit.detail),
                    },
                };
                nearest = Some((leaf, hit));
                false
            });
            nearest.map(|(_, hit)| hit.t)
        };
        match &self.leaf_finder {
            Some(finder) => {
                finder
                    .bvh()
                    .closest(q, t_max, |i, _| try_leaf(finder.index(i)));
            }
            None => (0..self.leaves.len()).for_each(|leaf| {
                try_leaf(leaf);
            }),
        }
        nearest.map(|(_, hit)| hit)
    }

    /// How many times the segment (0, t_max) crosses the solid's surface.
    pub fn crossings(&self, q: &RayQuery, t_max: f32) -> u32 {
        let mut count = 0;
        let mut count_leaf = |leaf: usize| {
            self.leaf_hits(leaf, q, 0.0, t_max, |_| {
                count += 1;
                true
            });
            true
        };
        match &self.leaf_finder {
            Some(finder) => finder
                .bvh()
                .visit(q, t_max, |i| count_leaf(finder.index(i))),
            None => (0..self.leaves.len()).for_each(|leaf| {
                count_leaf(leaf);
            }),
        }
        count
    }

    /// The member's own hit that `hit` names.
    #[inline]
    fn leaf_hit(&self, hit: &ShapeHit) -> (usize, ShapeHit) {
        let HitDetail::Csg { leaf, part } = hit.detail else {
            unreachable!("hit {:?} is not on a CSG solid", hit.detail);
        };
        let leaf = leaf as usize;
        let detail = part.detail(&self.leaves[leaf].shape());
        (leaf, ShapeHit { t: hit.t, detail })
    }

    /// The surface point of `hit` along `q`: its member's, the normal turned out of the
    /// solid where the member is subtracted.
    pub fn surface(&self, q: &RayQuery, hit: &ShapeHit) -> SurfacePoint {
        let (leaf, own) = self.leaf_hit(hit);
        let surface = match &self.leaves[leaf] {
            CsgLeaf::Shape(shape) => shape.surface(q, &own),
            CsgLeaf::Instance(instance) => instance.surface(q, &own),
            CsgLeaf::HalfSpace(disc) => Shape::Disc(*disc).surface(q, &own),
        };
        self.turned_for(leaf, &surface)
    }

    /// The texture coordinates of `hit`, its member's.
    pub fn uv(&self, q: &RayQuery, surface: &SurfacePoint, hit: &ShapeHit) -> (f32, f32) {
        let (leaf, own) = self.leaf_hit(hit);
        match &self.leaves[leaf] {
            CsgLeaf::Shape(shape) => shape.uv(&self.turned_for(leaf, surface), &own),
            CsgLeaf::Instance(instance) => instance.uv(q, &own),
            CsgLeaf::HalfSpace(disc) => Shape::Disc(*disc).uv(surface, &own),
        }
    }

    /// The texture coordinates of `hit` and their tangents, its member's.
    pub fn uv_frame(&self, q: &RayQuery, surface: &SurfacePoint, hit: &ShapeHit) -> UvFrame {
        let (leaf, own) = self.leaf_hit(hit);
        match &self.leaves[leaf] {
            CsgLeaf::Shape(shape) => shape.uv_frame(&self.turned_for(leaf, surface), &own),
            CsgLeaf::Instance(instance) => instance.uv_frame(q, &own),
            CsgLeaf::HalfSpace(disc) => Shape::Disc(*disc).uv_frame(surface, &own),
        }
    }

    /// `surface` with its normals turned where leaf `leaf`'s are: from the member's own to
    /// the solid's, and back (a sphere's map reads its own).
    fn turned_for(&self, leaf: usize, surface: &SurfacePoint) -> SurfacePoint {
        let mut own = *surface;
        if self.turned[leaf] {
            own.normal = -own.normal;
            own.shading = -own.shading;
        }
        own
    }
}

/// Marks the leaves under `node` whose normals are turned: those under an odd number of
/// subtracted members (`turned` says whether `node` itself is).
fn mark_turned(node: &CsgNode, turned: bool, out: &mut [bool]) {
    match node {
        CsgNode::Leaf(i) => out[*i as usize] = turned,
        CsgNode::Combine {
            operation, members, ..
        } => {
            for (k, m) in members.iter().enumerate() {
                let subtracted = *operation == CsgOperation::Difference && k > 0;
                mark_turned(m, turned != subtracted, out);
            }
        }
    }
}

/// The box around subtree `node`: an intersection lies within every member's box, a
/// difference within its first member's.
fn node_bounds(node: &CsgNode, leaves: &[CsgLeaf]) -> Aabb {
    combined_box(node, &|i| Some(leaves[i as usize].bounds())).unwrap_or(Aabb::EMPTY)
}

/// The box subtree `node`'s leaves' boxes (`leaf_box`; None for one without a bound) make
/// as its operations combine them; None when it has no bound.
fn combined_box(node: &CsgNode, leaf_box: &impl Fn(u32) -> Option<Aabb>) -> Option<Aabb> {
    match node {
        CsgNode::Leaf(i) => leaf_box(*i),
        CsgNode::Combine {
            operation, members, ..
        } => {
            let mut boxes = members.iter().map(|m| combined_box(m, leaf_box));
            match operation {
                CsgOperation::Union | CsgOperation::Merge => {
                    boxes.try_fold(Aabb::EMPTY, |a, b| Some(a.union(b?)))
                }
                CsgOperation::Intersection => boxes.flatten().reduce(|a, b| Aabb {
                    min: a.min.max(b.min),
                    max: a.max.min(b.max),
                }),
                CsgOperation::Difference => boxes.next().flatten(),
            }
        }
    }
}

/// Gives every combination of many members under `node` its member finder.
fn add_finders(node: &mut CsgNode, leaves: &[CsgLeaf]) {
    if let CsgNode::Combine {
        members, finder, ..
    } = node
    {
        if members.len() >= MIN_MEMBERS_FOR_HIERARCHY {
            let insides: Vec<Option<Aabb>> =
                members.iter().map(|m| inside_bounds(m, leaves)).collect();
            *finder = Some(Box::new(MemberFinder::new(&insides)));
        }
        for m in members {
            add_finders(m, leaves);
        }
    }
}

/// The box the inside of subtree `node` lies in; None where it has no bound (a half-space
/// is the inside of a plane, which its disc's box does not hold).
fn inside_bounds(node: &CsgNode, leaves: &[CsgLeaf]) -> Option<Aabb> {
    combined_box(node, &|i| match &leaves[i as usize] {
        CsgLeaf::HalfSpace(_) => None,
        leaf => Some(leaf.bounds()),
    })
}
