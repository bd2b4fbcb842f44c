//! Files a scene reads, kept decoded for the next validation of the same scene: each frame
//! of an animation is its file with the tracks' values written in, validated again, and its
//! meshes and images are the same files. Read once, they are shared by every frame.

use super::gltf_scene::{GltfFile, NodePose};
use crate::appearance::ImageTexture;
use crate::geometry::Mesh;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// One mesh file as read: its parts (the material name each uses, the line that starts it,
/// its triangles) and its `mtllib` names with their lines.
#[derive(Clone, Debug)]
pub(super) struct ReadMesh {
    pub(super) parts: Vec<(Option<String>, usize, Arc<Mesh>)>,
    pub(super) libraries: Vec<(String, usize)>,
}

/// A glTF file as an entry reads it: its path, whether smooth, and its nodes' poses.
pub(super) type GltfKey = (PathBuf, bool, Vec<NodePose>);

/// The meshes and images validations of one scene have read, by path.
#[derive(Debug, Default)]
pub struct ReadCache {
    /// By the file's path and whether it was read smooth.
    meshes: Mutex<HashMap<(PathBuf, bool), ReadMesh>>,
    /// glTF files, by path, whether read smooth, and the entry's node poses.
    gltf: Mutex<HashMap<GltfKey, Arc<GltfFile>>>,
    images: Mutex<HashMap<PathBuf, Arc<ImageTexture>>>,
}

impl ReadCache {
    /// Mesh file `key`, if read before.
    pub(super) fn mesh(&self, key: &(PathBuf, bool)) -> Option<ReadMesh> {
        self.meshes.lock().ok()?.get(key).cloned()
    }

    /// Keeps mesh file `key` as read.
    pub(super) fn keep_mesh(&self, key: (PathBuf, bool), mesh: ReadMesh) {
        if let Ok(mut meshes) = self.meshes.lock() {
            meshes.insert(key, mesh);
        }
    }

    /// glTF file `key`, if read before.
    pub(super) fn gltf(&self, key: &GltfKey) -> Option<Arc<GltfFile>> {
        self.gltf.lock().ok()?.get(key).cloned()
    }

    /// Keeps glTF file `key` as read.
    pub(super) fn keep_gltf(&self, key: GltfKey, file: Arc<GltfFile>) {
        if let Ok(mut files) = self.gltf.lock() {
            files.insert(key, file);
        }
    }

    /// Image `path`, if decoded before.
    pub(super) fn image(&self, path: &PathBuf) -> Option<Arc<ImageTexture>> {
        self.images.lock().ok()?.get(path).cloned()
    }

    /// Keeps image `path` as decoded.
    pub(super) fn keep_image(&self, path: PathBuf, image: Arc<ImageTexture>) {
        if let Ok(mut images) = self.images.lock() {
            images.insert(path, image);
        }
    }
}
