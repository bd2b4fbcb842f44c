//! A glTF file as read (gltf_file.rs reads it): its primitives placed in the file's frame,
//! its lights and cameras, and the document and buffers its materials come from. Apart from
//! the reader, so that the read cache can keep one without depending on how it is read.

use crate::geometry::Mesh;
use glam::{DVec3, Vec3};
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
