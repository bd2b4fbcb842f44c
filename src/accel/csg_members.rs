//! Hierarchies inside a CSG solid, so that its cost grows with the members a ray or a
//! point comes near rather than with all of them: one over the leaves' boxes for rays, and
//! one per combination of many members over the boxes their insides lie in, for asking
//! whether a point lies inside any of them. Each finds exactly what a walk of every leaf or
//! member finds (the ray's hits are taken nearest first, a tie to the lower-numbered leaf,
//! as the walk in order takes them), so the image is the same with or without them.

use super::bvh::Bvh;
use crate::geometry::Aabb;
use glam::{Vec3, Vec3A};

/// Below this many, a list is as quick as a hierarchy.
pub const MIN_MEMBERS_FOR_HIERARCHY: usize = 8;

/// A hierarchy over boxes, and the index each stored primitive stands for.
#[derive(Clone, Debug)]
pub struct BoxFinder {
    bvh: Bvh,
    order: Vec<u32>,
}

impl BoxFinder {
    /// The hierarchy over `boxes`.
    pub fn new(boxes: &[Aabb]) -> Self {
        let (bvh, order) = Bvh::build(boxes);
        Self { bvh, order }
    }

    /// The tree, whose primitives are `index(i)`.
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The box index stored primitive `i` stands for.
    #[inline]
    pub fn index(&self, i: u32) -> usize {
        self.order[i as usize] as usize
    }
}

/// Which members of a combination may hold a point: those whose insides lie in a box,
/// found by a hierarchy over the boxes padded against the members' own rounding, and those
/// whose insides have no bound (a half-space among them), always asked.
#[derive(Clone, Debug)]
pub struct MemberFinder {
    bounded: BoxFinder,
    unbounded: Vec<u32>,
}

impl MemberFinder {
    /// The finder over members whose insides lie in `insides` (None: unbounded).
    pub fn new(insides: &[Option<Aabb>]) -> Self {
        let mut boxes = Vec::new();
        let mut indices = Vec::new();
        let mut unbounded = Vec::new();
        for (m, inside) in insides.iter().enumerate() {
            match inside {
                Some(b) if !b.is_empty() => {
                    boxes.push(padded(*b));
                    indices.push(m as u32);
                }
                // An empty inside holds no point: never asked.
                Some(_) => {}
                None => unbounded.push(m as u32),
            }
        }
        let mut bounded = BoxFinder::new(&boxes);
        for o in &mut bounded.order {
            *o = indices[*o as usize];
        }
        Self { bounded, unbounded }
    }

    /// Whether `holds(m)` is true for some member `m` whose inside may hold `p`.
    #[inline]
    pub fn any(&self, p: Vec3A, mut holds: impl FnMut(usize) -> bool) -> bool {
        self.unbounded.iter().any(|&m| holds(m as usize))
            || self
                .bounded
                .bvh
                .any_containing(p, |i| holds(self.bounded.index(i)))
    }
}

/// `b` grown on every side by more than a member's inside test can stray beyond its box by
/// rounding: a part of its size and of its distance from the origin.
fn padded(b: Aabb) -> Aabb {
    let size = (b.max - b.min).max_element();
    let far = b.min.abs().max(b.max.abs()).max_element();
    let pad = Vec3::splat(1e-4 * size + 1e-5 * far + f32::MIN_POSITIVE);
    Aabb {
        min: b.min - pad,
        max: b.max + pad,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_is_asked_of_every_member_that_may_hold_it_and_no_other() {
        let cube = |x: f32| {
            Some(Aabb {
                min: Vec3::new(x, 0.0, 0.0),
                max: Vec3::new(x + 1.0, 1.0, 1.0),
            })
        };
        let mut insides: Vec<Option<Aabb>> = (0..20).map(|i| cube(2.0 * i as f32)).collect();
        insides.push(None);
        insides.push(Some(Aabb::EMPTY));
        let finder = MemberFinder::new(&insides);
        for (x, expected) in [(0.5, vec![0, 20]), (4.0, vec![2, 20]), (1.5, vec![20])] {
            let mut asked = Vec::new();
            let p = Vec3A::new(x, 0.5, 0.5);
            assert!(!finder.any(p, |m| {
                asked.push(m);
                false
            }));
            asked.sort();
            assert_eq!(asked, expected, "at x = {x}");
            // It stops at the first member that holds the point.
            assert!(finder.any(p, |m| m == expected[0]));
        }
    }
}
