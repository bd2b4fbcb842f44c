//! Groups: named frames that objects, lights and other groups are placed in, so that what
//! a group holds follows its transform (a moon placed in its planet's group orbits with it);
//! and the nodes of a glTF scene an entry brings in, which the viewer places the same way.

use super::placement::ObjectPlacement;
use glam::DAffine3;

/// A frame placed in its parent's: a `[[groups]]` entry, or a node of a glTF file.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneGroup {
    /// The name entries give as their `group`; a file node's name in its file (or
    /// `nodes[i]`).
    pub name: String,
    /// The group it is placed in (an index into `Scene::groups`); None for the world, or
    /// for a file node at the top of its file's scene, the file's frame.
    pub parent: Option<usize>,
    /// Its `translate`, `rotate` and `scale`, in its parent's frame.
    pub placement: ObjectPlacement,
    /// The lights placed in it (indices into `Scene::lights`), not those of its subgroups.
    pub lights: Vec<usize>,
    /// What it is.
    pub kind: GroupKind,
}

/// The kinds of group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroupKind {
    /// A `[[groups]]` entry, in the world's frame or its parent group's. Objects name it as
    /// their `group`.
    Entry,
    /// A node of a glTF file a mesh entry brings in, in its parent node's frame or the
    /// file's (which the entry places). The entry's parts name it as their `node`; its
    /// lights move with it but are not listed in it.
    FileNode,
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
