//! A glTF file as read (gltf_file.rs reads it): its primitives placed in the file's frame,
//! its lights and cameras, and the document and buffers its materials come from; and the
//! poses an entry gives its nodes, which key a reading. Apart from the reader, so that the
//! read cache can keep one without depending on how it is read.

use crate::geometry::Mesh;
use crate::messages::shortest;
use crate::scene::ObjectPlacement;
use glam::{DMat3, DMat4, DQuat, DVec3, EulerRot, Vec3};
use std::sync::Arc;

/// A glTF file read: the document (for its materials), its buffers (for the images they
/// hold), and its scene walked with the entry's poses.
#[derive(Debug)]
pub(super) struct GltfFile {
    pub(super) document: gltf::Document,
    pub(super) buffers: Vec<Vec<u8>>,
    pub(super) walk: GltfWalk,
    /// What the file has that prism does not read, in words (the walk's too).
    pub(super) unread: Vec<String>,
}

/// What a walk of a glTF file's scene finds, its nodes posed by an entry's poses.
#[derive(Debug)]
pub(super) struct GltfWalk {
    /// Each primitive of each mesh node, in the file's frame.
    pub(super) parts: Vec<GltfPart>,
    /// Each node met, parents first.
    pub(super) nodes: Vec<GltfNode>,
    pub(super) lights: Vec<GltfLight>,
    pub(super) cameras: Vec<GltfCamera>,
    /// What it met that prism does not read, in words.
    pub(super) unread: Vec<String>,
    /// For each pose, how many nodes it named.
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
    /// Its node (an index into `GltfFile::nodes`).
    pub(super) node: usize,
    pub(super) mesh: Arc<Mesh>,
    /// Its material's index; None for glTF's default material.
    pub(super) material: Option<usize>,
}

/// A node of the file's scene, as the walk met it.
#[derive(Clone, Debug)]
pub(super) struct GltfNode {
    /// Its index in the file's `nodes`.
    pub(super) index: usize,
    /// Its name as messages show it, or `nodes[i]`.
    pub(super) name: String,
    /// The node above it (an index into `GltfFile::nodes`); None at the top of the scene.
    pub(super) parent: Option<usize>,
    /// Its transform in its parent's frame as a `translate`, `rotate` and `scale` would
    /// write it (with the parts an entry's pose gives); None where it cannot be placed on
    /// its own: a shear or a mirror no such values can write, or a node the walk met more
    /// than once (posing it would move it everywhere it is met).
    pub(super) placement: Option<ObjectPlacement>,
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
    /// The turns about x, then y, then z, in degrees, as a `rotate` gives them.
    pub(super) rotate: Option<Vec3>,
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
            self.rotate.map(|r| r.as_dvec3().to_array().to_vec()),
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
}

/// A node's transform in its parent's frame: the file's (`decomposed` into translation,
/// rotation (x, y, z, w) and scale) with the parts its pose gives, if it has one, put in.
pub(super) fn node_local(
    pose: Option<&NodePose>,
    decomposed: ([f32; 3], [f32; 4], [f32; 3]),
) -> DMat4 {
    let file = NodeParts::of(decomposed);
    let turn = match pose.and_then(|p| p.rotate) {
        Some(rotate) => ObjectPlacement {
            rotate,
            ..ObjectPlacement::IDENTITY
        }
        .rotation(),
        None => DMat3::from_quat(file.rotation),
    };
    let scale = pose.and_then(|p| p.scale).unwrap_or(file.scale);
    let translation = pose.and_then(|p| p.translate).unwrap_or(file.translation);
    let linear = turn * DMat3::from_diagonal(scale);
    DMat4::from(glam::DAffine3::from_mat3_translation(linear, translation))
}

/// A node's transform as `translate`, `rotate` and `scale` would write it: the parts its
/// pose gives, if it has one, and the file's (`decomposed`) for the rest, the turn as the
/// turns about x, then y, then z that make it.
pub(super) fn node_placement(
    pose: Option<&NodePose>,
    (translation, rotation, scale): ([f32; 3], [f32; 4], [f32; 3]),
) -> ObjectPlacement {
    // The file's f32s as a saved pose would write them (0.6, not 0.6000000238418579).
    let written = |v: [f32; 3]| DVec3::from_array(v.map(shortest));
    let turn = DQuat::from_array(rotation.map(f64::from)).normalize();
    ObjectPlacement {
        translate: pose
            .and_then(|p| p.translate)
            .unwrap_or_else(|| written(translation)),
        rotate: pose
            .and_then(|p| p.rotate)
            .unwrap_or_else(|| rotate_of(turn)),
        scale: pose.and_then(|p| p.scale).unwrap_or_else(|| written(scale)),
    }
}

/// A node's transform as the file gives it (decomposed), in f64.
struct NodeParts {
    translation: DVec3,
    /// Of unit length.
    rotation: DQuat,
    scale: DVec3,
}

impl NodeParts {
    fn of((translation, rotation, scale): ([f32; 3], [f32; 4], [f32; 3])) -> NodeParts {
        let wide = |v: [f32; 3]| DVec3::from_array(v.map(f64::from));
        NodeParts {
            translation: wide(translation),
            rotation: DQuat::from_array(rotation.map(f64::from)).normalize(),
            scale: wide(scale),
        }
    }
}

/// The turns about x, then y, then z (degrees, as `rotate` writes them) that make
/// `rotation`.
pub(super) fn rotate_of(rotation: DQuat) -> Vec3 {
    // Turning about x, then y, then z (about the fixed axes) is Rz·Ry·Rx: glam's intrinsic
    // Z-Y-X order.
    let (z, y, x) = rotation.to_euler(EulerRot::ZYX);
    // No turn is written 0, not -0.
    DVec3::new(x.to_degrees(), y.to_degrees(), z.to_degrees()).as_vec3() + Vec3::ZERO
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

    #[test]
    fn a_turn_is_written_as_the_turns_that_make_it() {
        for (axis, angle) in [
            (DVec3::X, 0.3),
            (DVec3::new(1.0, 2.0, -0.5).normalize(), 2.5),
            (DVec3::new(-0.2, 0.1, 1.0).normalize(), -1.2),
            (DVec3::Y, std::f64::consts::FRAC_PI_2),
        ] {
            let q = DQuat::from_axis_angle(axis, angle);
            let written = ObjectPlacement {
                rotate: rotate_of(q),
                ..ObjectPlacement::IDENTITY
            };
            let error = (written.rotation() - DMat3::from_quat(q))
                .abs()
                .to_cols_array();
            // The degrees are f32.
            assert!(error.iter().all(|e| *e < 1e-6), "{axis} {angle}: {error:?}");
        }
    }
}
