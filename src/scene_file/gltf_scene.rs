//! A glTF file as read (gltf_file.rs reads it): its primitives placed in the file's frame,
//! its lights and cameras, and the document and buffers its materials come from; and the
//! poses an entry gives its nodes, which key a reading. Apart from the reader, so that the
//! read cache can keep one without depending on how it is read.

use crate::geometry::Mesh;
use glam::{DMat3, DMat4, DVec3, Vec3};
use std::sync::Arc;

/// A glTF file read: its primitives placed, its lights and cameras, the document (for its materials) and
/// its buffers (for the images they hold).
#[derive(Debug)]
pub(super) struct GltfFile {
    pub(super) document: gltf::Document,
    pub(super) buffers: Vec<Vec<u8>>,
    /// Each primitive of each mesh node, in the file's frame.
    pub(super) parts: Vec<GltfPart>,
    /// Each light node's light, in the file's frame.
    pub(super) lights: Vec<GltfLight>,
    /// Each perspective camera node's view, in the file's frame.
    pub(super) cameras: Vec<GltfCamera>,
    /// What the file has that prism does not read, in words.
    pub(super) unread: Vec<String>,
    /// For each of the entry's node poses, how many nodes it named.
    pub(super) posed_nodes: Vec<usize>,
}

/// A perspective camera placed by its node (in the file's frame).
#[derive(Clone, Debug)]
pub(super) struct GltfCamera {
    /// The camera's name, else its node's, if either has one.
    pub(super) name: Option<String>,
    /// Its index in the file's `cameras`.
    pub(super) index: usize,
    pub(super) eye: DVec3,
    /// The node's −z.
    pub(super) direction: DVec3,
    /// The node's +y.
    pub(super) up: DVec3,
    /// The vertical field of view, in radians.
    pub(super) yfov: f32,
}

/// One mesh primitive, placed by its node.
#[derive(Debug)]
pub(super) struct GltfPart {
    /// Its node's name (or `nodes[i]`), and the primitive's number when the mesh has more.
    pub(super) name: String,
    pub(super) mesh: Arc<Mesh>,
    /// Its material's index; None for glTF's default material.
    pub(super) material: Option<usize>,
}

/// A `KHR_lights_punctual` light placed by its node (in the file's frame).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct GltfLight {
    pub(super) kind: GltfLightKind,
    pub(super) color: Vec3,
    /// Candela for a point or spot light, lux for a directional one.
    pub(super) intensity: f32,
    pub(super) position: DVec3,
    /// Where it shines (the node's −z).
    pub(super) direction: DVec3,
}

/// The kinds of `KHR_lights_punctual` light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum GltfLightKind {
    Point,
    /// A cone, its half-angles in radians.
    Spot {
        inner: f32,
        outer: f32,
    },
    Directional,
}

/// A node's pose as a mesh entry's `nodes` gives it: the node's name (or `nodes[i]`, its
/// index in the file), and the parts of its transform (in its parent's frame) given in
/// place of the file's; a part not given keeps the file's.
#[derive(Clone, Debug)]
pub(super) struct NodePose {
    pub(super) node: NodeRef,
    pub(super) translate: Option<DVec3>,
    /// The turn, as a `rotate` gives it.
    pub(super) rotation: Option<DMat3>,
    pub(super) scale: Option<DVec3>,
}

/// How a pose names its node: by the node's name, or by its index in the file (written
/// `nodes[i]`, as messages show a node without a name).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) enum NodeRef {
    Name(String),
    Index(usize),
}

impl NodeRef {
    /// The node `key` (a key of an entry's `nodes`) names.
    pub(super) fn parse(key: &str) -> NodeRef {
        key.strip_prefix("nodes[")
            .and_then(|rest| rest.strip_suffix(']'))
            .and_then(|digits| digits.parse().ok())
            .map_or_else(|| NodeRef::Name(key.to_string()), NodeRef::Index)
    }

    /// Whether it names `node`.
    pub(super) fn names(&self, node: &gltf::Node) -> bool {
        match self {
            NodeRef::Name(name) => node.name() == Some(name.as_str()),
            NodeRef::Index(i) => node.index() == *i,
        }
    }
}

impl std::fmt::Display for NodeRef {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            NodeRef::Name(name) => f.write_str(name),
            NodeRef::Index(i) => write!(f, "nodes[{i}]"),
        }
    }
}

impl NodePose {
    /// What tells two poses apart: the node and the values' bits (poses key the files
    /// read, so equal means the same reading).
    fn bits(&self) -> (&NodeRef, Vec<u64>) {
        let mut bits = Vec::new();
        for part in [
            self.translate.map(|v| v.to_array().to_vec()),
            self.rotation.map(|m| m.to_cols_array().to_vec()),
            self.scale.map(|v| v.to_array().to_vec()),
        ] {
            match part {
                Some(values) => bits.extend(values.into_iter().map(f64::to_bits)),
                // Apart from any value's bits: a part not given.
                None => bits.push(u64::MAX),
            }
        }
        (&self.node, bits)
    }

    /// The node's transform in its parent's frame: `translation`, `rotation` (x, y, z, w)
    /// and `scale` (the file's, decomposed) with the parts this pose gives put in.
    pub(super) fn local(
        &self,
        (translation, rotation, scale): ([f32; 3], [f32; 4], [f32; 3]),
    ) -> DMat4 {
        let file = |v: [f32; 3]| DVec3::from_array(v.map(f64::from));
        let turn = self.rotation.unwrap_or_else(|| {
            DMat3::from_quat(glam::DQuat::from_array(rotation.map(f64::from)).normalize())
        });
        let linear = turn * DMat3::from_diagonal(self.scale.unwrap_or_else(|| file(scale)));
        let translation = self.translate.unwrap_or_else(|| file(translation));
        DMat4::from(glam::DAffine3::from_mat3_translation(linear, translation))
    }
}

impl PartialEq for NodePose {
    fn eq(&self, other: &Self) -> bool {
        self.bits() == other.bits()
    }
}

impl Eq for NodePose {}

impl std::hash::Hash for NodePose {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.bits().hash(state);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pose_names_a_node_by_name_or_by_index() {
        assert_eq!(NodeRef::parse("nodes[3]"), NodeRef::Index(3));
        assert_eq!(NodeRef::parse("lamp"), NodeRef::Name("lamp".into()));
        for written in ["nodes[x]", "nodes[]", "nodes[-1]", "nodes[3", "my nodes[3]"] {
            assert_eq!(NodeRef::parse(written), NodeRef::Name(written.into()));
        }
        assert_eq!(NodeRef::Index(3).to_string(), "nodes[3]");
        assert_eq!(NodeRef::parse("lamp").to_string(), "lamp");
    }
}
