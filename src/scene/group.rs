//! Groups: named frames that objects, lights and other groups are placed in, so that what
//! a group holds follows its transform (a moon placed in its planet's group orbits with it).

use super::placement::ObjectPlacement;
use glam::DAffine3;

/// A `[[groups]]` entry: a frame placed in its parent's (or the world's).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneGroup {
    /// The name entries give as their `group`.
    pub name: String,
    /// The group it is placed in (an index into `Scene::groups`); None for the world.
    pub parent: Option<usize>,
    /// Its `translate`, `rotate` and `scale`, in its parent's frame.
    pub placement: ObjectPlacement,
    /// The lights placed in it (indices into `Scene::lights`), not those of its subgroups.
    pub lights: Vec<usize>,
}

/// The map from group `group`'s frame (of `groups`) to the world's: its placement, then its
/// parent's, and so on out to the world; the identity for None.
pub fn group_frame(groups: &[SceneGroup], group: Option<usize>) -> DAffine3 {
    let mut frame = DAffine3::IDENTITY;
    let mut at = group;
    // The loader refuses loops; the bound keeps a hand-made scene from looping.
    for _ in 0..=groups.len() {
        let Some(g) = at.and_then(|g| groups.get(g)) else {
            break;
        };
        frame = g.placement.affine() * frame;
        at = g.parent;
    }
    frame
}
