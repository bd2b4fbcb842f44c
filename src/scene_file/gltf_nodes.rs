//! A glTF entry's nodes as groups the viewer places: each node that holds triangles and
//! whose transform a `translate`, `rotate` and `scale` can write becomes a group of kind
//! `FileNode`, its parts hang from it, and placing it writes the entry's pose for it
//! (`[meshes.nodes."NAME"]`), as the scene file would.

use super::error::SceneError;
use super::gltf_file::walk_gltf;
use super::gltf_scene::{GltfFile, GltfLight, GltfWalk, NodePose, NodeRef};
use super::meshes::MeshDef;
use super::validator::{Item, Validator};
use crate::limits;
use crate::messages::{quoted, shown_within};
use crate::scene::{GroupKind, ObjectPlacement, Scene, SceneGroup};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// What the objects of one glTF entry share: the file as read, with what placing the entry
/// or one of its nodes anew needs.
#[derive(Debug)]
pub(super) struct GltfOrigin {
    /// The file as the load read it (its document and buffers, to walk again), with the
    /// entry's poses it was read with.
    pub(super) file: Arc<GltfFile>,
    /// The lights it brings, each by its index in the scene's lights, as the file places
    /// them (in its frame).
    pub(super) lights: Vec<(usize, GltfLight)>,
    /// Its nodes that are groups, in the order of their groups.
    pub(super) nodes: Vec<FileNode>,
    /// The last walk of the file with other poses than the load's, and those poses: an
    /// entry moved after its nodes were posed anew is not walked again.
    pub(super) last_walk: Mutex<Option<(Vec<NodePose>, Arc<GltfWalk>)>>,
}

impl PartialEq for GltfOrigin {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.file, &other.file)
            && self.lights == other.lights
            && self.nodes == other.nodes
    }
}

/// A node of a glTF file that is a group.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct FileNode {
    /// The group (an index into the scene's groups).
    pub(super) group: usize,
    /// The node's index in the file's `nodes`.
    pub(super) index: usize,
    /// The key of the entry's `nodes` that poses it (`PoseKeys::of`).
    pub(super) key: String,
}

/// The groups that the nodes of `file` (read for an entry whose `nodes` keys are `keys`)
/// become, numbered from `first` in the scene's groups; the nodes that are groups; and the
/// node group each part of the file hangs from.
pub(super) fn node_groups<'k>(
    file: &GltfFile,
    keys: impl Iterator<Item = &'k String>,
    first: usize,
) -> (Vec<SceneGroup>, Vec<FileNode>, Vec<Option<usize>>) {
    let nodes = &file.walk.nodes;
    // Which nodes hold a part, themselves or below them (parents come before children).
    let mut holds = vec![false; nodes.len()];
    for part in &file.walk.parts {
        let mut at = Some(part.node);
        while let Some(n) = at.filter(|&n| !holds[n]) {
            holds[n] = true;
            at = nodes[n].parent;
        }
    }
    let keys = PoseKeys::new(file, keys);
    let mut group_of: Vec<Option<usize>> = vec![None; nodes.len()];
    let mut groups = Vec::new();
    let mut file_nodes = Vec::new();
    for (n, node) in nodes.iter().enumerate() {
        let above = node.parent.and_then(|p| group_of[p]);
        let Some(placement) = node.placement.filter(|_| holds[n]) else {
            // Its parts hang from the nearest node above that is a group.
            group_of[n] = above;
            continue;
        };
        let group = first + groups.len();
        group_of[n] = Some(group);
        groups.push(SceneGroup {
            name: node.name.clone(),
            parent: above,
            placement,
            lights: Vec::new(),
            kind: GroupKind::FileNode,
        });
        file_nodes.push(FileNode {
            group,
            index: node.index,
            key: keys.of(node.index),
        });
    }
    let parts = file.walk.parts.iter().map(|p| group_of[p.node]).collect();
    (groups, file_nodes, parts)
}

/// How an entry's `nodes` names each node of its file.
struct PoseKeys<'f> {
    /// The file's nodes, by index.
    nodes: Vec<gltf::Node<'f>>,
    /// How many of them have each name.
    names: HashMap<&'f str, usize>,
    /// The keys the entry gives, with the node each names.
    given: Vec<(NodeRef, String)>,
}

impl<'f> PoseKeys<'f> {
    fn new<'k>(file: &'f GltfFile, keys: impl Iterator<Item = &'k String>) -> Self {
        let nodes: Vec<gltf::Node> = file.document.nodes().collect();
        let mut names = HashMap::new();
        for name in nodes.iter().filter_map(|n| n.name()) {
            *names.entry(name).or_default() += 1;
        }
        let given = keys.map(|k| (NodeRef::parse(k), k.clone())).collect();
        Self {
            nodes,
            names,
            given,
        }
    }

    /// The key that poses node `index`: the one the entry gives, else the node's name
    /// where no other node has it, else `nodes[i]`.
    fn of(&self, index: usize) -> String {
        let by_index = NodeRef::Index(index);
        let Some(node) = self.nodes.get(index) else {
            return by_index.to_string();
        };
        if let Some((_, key)) = self.given.iter().find(|(r, _)| r.names(node)) {
            return key.clone();
        }
        match node.name() {
            Some(name)
                if self.names.get(name) == Some(&1)
                    && NodeRef::parse(name) == NodeRef::Name(name.to_string()) =>
            {
                name.to_string()
            }
            _ => by_index.to_string(),
        }
    }
}

impl GltfOrigin {
    /// The parts of each of its node groups' placements in `scene` that differ from
    /// `loaded` (the scene as loaded): the poses an edit gives, by key, with which of
    /// translate, rotate and scale it gives. Empty when no node was placed anew.
    pub(super) fn edited_poses(
        &self,
        loaded: &Scene,
        scene: &Scene,
    ) -> Vec<(&str, ObjectPlacement, [bool; 3])> {
        self.nodes
            .iter()
            .filter_map(|n| {
                let was = loaded.groups.get(n.group)?.placement;
                let now = scene.groups.get(n.group)?.placement;
                let parts = [
                    now.translate != was.translate,
                    now.rotate != was.rotate,
                    now.scale != was.scale,
                ];
                parts
                    .contains(&true)
                    .then_some((n.key.as_str(), now, parts))
            })
            .collect()
    }
}

impl Validator<'_> {
    /// Entry `d`'s glTF file, as the load read it (`origin`), walked again with the poses
    /// `d` now gives its nodes: the parts and lights a load with those poses would read.
    pub(super) fn posed_walk(
        &self,
        at: &Item,
        d: &MeshDef,
        origin: &GltfOrigin,
    ) -> Result<Arc<GltfWalk>, SceneError> {
        let poses = self.node_poses(at, d)?;
        let last = origin.last_walk.lock().ok().and_then(|last| last.clone());
        if let Some((_, walk)) = last.filter(|(p, _)| *p == poses) {
            return Ok(walk);
        }
        let path = self.locate(&d.path);
        let file = &origin.file;
        let smooth = d.smooth.unwrap_or(true);
        let budget = limits::MAX_SCENE_TRIANGLES;
        let walk =
            walk_gltf(&file.document, &file.buffers, smooth, budget, &poses).map_err(|e| {
                let file = quoted(&path.display().to_string());
                self.field_error(
                    at,
                    "nodes",
                    format!("glTF file {file}: {}", shown_within(&e, 1000)),
                )
            })?;
        self.check_poses(at, &path, &poses, &walk.posed_nodes, &file.document)?;
        let walk = Arc::new(walk);
        if let Ok(mut last) = origin.last_walk.lock() {
            *last = Some((poses, walk.clone()));
        }
        Ok(walk)
    }
}
