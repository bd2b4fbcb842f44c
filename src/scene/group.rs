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

/// The groups from `group` out to the world (of `groups`): it, its parent, and so on. The
/// walk stops before a group it has met (the loader refuses loops; a hand-made scene might
/// have one) or an index past `groups`.
pub fn group_chain(groups: &[SceneGroup], group: Option<usize>) -> Vec<usize> {
    let mut chain = Vec::new();
    let mut at = group;
    while let Some(g) = at {
        if chain.contains(&g) || g >= groups.len() {
            break;
        }
        chain.push(g);
        at = groups[g].parent;
    }
    chain
}

/// The map from group `group`'s frame (of `groups`) to the world's: its placement, then its
/// parent's, and so on out to the world; the identity for None.
pub fn group_frame(groups: &[SceneGroup], group: Option<usize>) -> DAffine3 {
    group_chain(groups, group)
        .into_iter()
        .fold(DAffine3::IDENTITY, |frame, g| {
            groups[g].placement.affine() * frame
        })
}
