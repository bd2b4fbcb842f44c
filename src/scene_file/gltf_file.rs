//! glTF 2.0 files (`.gltf` with its buffers, or one `.glb`) as a mesh entry's parts: the
//! default scene's node tree walked, each mesh primitive's triangles placed by its node's
//! transform, and each `KHR_lights_punctual` light where its node puts it. The `gltf` crate
//! parses and checks the document's references; prism reads every buffer itself, through the
//! scene's bounded file access, and checks every accessor's bytes and every index before it
//! reads one, so a malformed or truncated file is refused with a message, never a panic.

use super::assets::{beside, read_file};
use super::gltf_scene::{
    GltfCamera, GltfFile, GltfLight, GltfLightKind, GltfNode, GltfPart, GltfWalk, NodePose,
    node_local, node_placement,
};
use super::validator::Validator;
use crate::geometry::Mesh;
use crate::limits;
use crate::messages::{quoted, shown};
use glam::{DMat3, DMat4, DVec3, Vec2, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use std::path::Path;
use std::sync::Arc;

/// The most nodes a walk of a glTF scene visits (a node listed as a child many times is
/// visited each time).
pub const MAX_GLTF_NODE_VISITS: usize = 1 << 20;

/// How deep a glTF node tree may be.
pub const MAX_GLTF_DEPTH: usize = 256;

/// A problem with a glTF file, in words (the reader names the file and the entry).
type Refusal = String;

/// Why a glTF file's triangles are refused: too many with the scene's other meshes.
pub(super) fn too_many_triangles() -> Refusal {
    format!(
        "its triangles take the scene's meshes past the {} they may have together",
        limits::MAX_SCENE_TRIANGLES
    )
}

/// Whether `rel` names a glTF file (by its extension).
pub(super) fn is_gltf(rel: &str) -> bool {
    let ext = Path::new(rel)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    matches!(ext.as_deref(), Some("gltf" | "glb"))
}

/// The bytes of a `data:` URI (base64 only), or None when `uri` is not one.
pub(super) fn data_uri(uri: &str) -> Option<Result<Vec<u8>, Refusal>> {
    let rest = uri.strip_prefix("data:")?;
    let Some((header, data)) = rest.split_once(',') else {
        return Some(Err("a data URI without a comma".into()));
    };
    if !header.ends_with(";base64") {
        return Some(Err("a data URI that is not base64".into()));
    }
    Some(base64(data))
}

/// Decodes base64 text (the standard alphabet, padding optional).
fn base64(text: &str) -> Result<Vec<u8>, Refusal> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        } as u32)
    };
    let text = text.trim_end_matches('=').as_bytes();
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 3);
    for chunk in text.chunks(4) {
        if chunk.len() == 1 {
            return Err("base64 data of a wrong length".into());
        }
        let mut bits = 0u32;
        for (i, &c) in chunk.iter().enumerate() {
            let v = value(c).ok_or("base64 data with a character outside its alphabet")?;
            bits |= v << (18 - 6 * i);
        }
        let bytes = bits.to_be_bytes();
        out.extend_from_slice(&bytes[1..chunk.len()]);
    }
    Ok(out)
}

/// A relative URI's path: percent-escapes decoded; refused when it names another scheme
/// or an absolute path (only files beside the glTF file are read).
pub(super) fn relative_uri(uri: &str) -> Result<String, Refusal> {
    if uri.contains("://") || uri.starts_with('/') || uri.starts_with('\\') {
        return Err(format!(
            "{} is not a path relative to the glTF file (prism reads only files beside it)",
            quoted(uri)
        ));
    }
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = uri
                .get(i + 1..i + 3)
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("{}: a bad percent escape", quoted(uri)))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("{}: not UTF-8 once decoded", quoted(uri)))
}

/// A glTF file's document and binary chunk, its references checked (the `gltf` crate's
/// checks, after one of prism's that keeps them from indexing past an array).
fn parse_gltf(bytes: &[u8]) -> Result<gltf::Gltf, Refusal> {
    use gltf::json::mesh::Semantic;
    use gltf::json::validation::Checked;
    // The crate takes 12 from a GLB's declared length unchecked.
    if let Some(header) = bytes.strip_prefix(b"glTF") {
        let declared = header
            .get(4..8)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
        if declared.is_none_or(|n| n < 12) {
            return Err("a GLB file whose header is cut short or gives it no length".into());
        }
    }
    let unchecked = gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| e.to_string())?;
    let json = unchecked.document.as_json();
    for (i, mesh) in json.meshes.iter().enumerate() {
        for (j, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(a) = primitive
                .attributes
                .get(&Checked::Valid(Semantic::Positions))
                && a.value() >= json.accessors.len()
            {
                return Err(format!(
                    "meshes[{i}].primitives[{j}]: POSITION names accessors[{}], which the file \
                     does not have",
                    a.value()
                ));
            }
        }
    }
    let document =
        gltf::Document::from_json(unchecked.document.into_json()).map_err(|e| e.to_string())?;
    Ok(gltf::Gltf {
        document,
        blob: unchecked.blob,
    })
}

/// The bytes an accessor covers, after checking that they lie within its buffer view and
/// the view within its buffer: (the bytes from its first element, the stride).
fn accessor_bytes<'b>(
    accessor: &gltf::Accessor,
    buffers: &'b [Vec<u8>],
) -> Result<(&'b [u8], usize), Refusal> {
    let name = format!("accessors[{}]", accessor.index());
    if accessor.sparse().is_some() {
        return Err(format!("{name} is sparse, which prism does not read"));
    }
    let view = accessor
        .view()
        .ok_or_else(|| format!("{name} has no buffer view"))?;
    let buffer = &buffers[view.buffer().index()];
    let view_end = view
        .offset()
        .checked_add(view.length())
        .filter(|&end| end <= buffer.len())
        .ok_or_else(|| {
            format!(
                "bufferViews[{}] runs past the end of its buffer ({} bytes)",
                view.index(),
                buffer.len()
            )
        })?;
    let element = accessor.size();
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "{name}: a stride of {stride} bytes is shorter than its elements ({element})"
        ));
    }
    let count = accessor.count();
    if count == 0 {
        return Ok((&[], stride));
    }
    let end = view
        .offset()
        .checked_add(accessor.offset())
        .and_then(|start| Some((start, (count - 1).checked_mul(stride)?)))
        .and_then(|(start, span)| Some((start, span.checked_add(element)?.checked_add(start)?)))
        .filter(|&(_, end)| end <= view_end)
        .ok_or_else(|| {
            format!(
                "{name}: {count} elements run past the end of bufferViews[{}]",
                view.index()
            )
        })?;
    Ok((&buffer[end.0..end.1], stride))
}

/// The `count` elements of `n` components each, as f32 (floats, or normalised integers
/// where `normalised_ok`).
fn read_floats(
    accessor: &gltf::Accessor,
    buffers: &[Vec<u8>],
    dims: Dimensions,
    normalised_ok: bool,
) -> Result<Vec<f32>, Refusal> {
    let name = format!("accessors[{}]", accessor.index());
    if accessor.dimensions() != dims {
        return Err(format!(
            "{name} holds {:?} where {dims:?} is needed",
            accessor.dimensions()
        ));
    }
    let n = dims.multiplicity();
    let (bytes, stride) = accessor_bytes(accessor, buffers)?;
    let (size, read): (usize, fn(&[u8]) -> f32) = match accessor.data_type() {
        DataType::F32 => (4, |b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        DataType::U8 if normalised_ok && accessor.normalized() => (1, |b| b[0] as f32 / 255.0),
        DataType::U16 if normalised_ok && accessor.normalized() => {
            (2, |b| u16::from_le_bytes([b[0], b[1]]) as f32 / 65535.0)
        }
        other => return Err(format!("{name} holds {other:?} components, not floats")),
    };
    let mut out = Vec::with_capacity(accessor.count() * n);
    for i in 0..accessor.count() {
        let at = &bytes[i * stride..];
        for c in 0..n {
            out.push(read(&at[c * size..]));
        }
    }
    Ok(out)
}

/// An index accessor's values.
fn read_indices(accessor: &gltf::Accessor, buffers: &[Vec<u8>]) -> Result<Vec<u32>, Refusal> {
    let name = format!("accessors[{}]", accessor.index());
    if accessor.dimensions() != Dimensions::Scalar {
        return Err(format!("{name}: indices must be scalars"));
    }
    let (bytes, stride) = accessor_bytes(accessor, buffers)?;
    let read: fn(&[u8]) -> u32 = match accessor.data_type() {
        DataType::U8 => |b| b[0] as u32,
        DataType::U16 => |b| u16::from_le_bytes([b[0], b[1]]) as u32,
        DataType::U32 => |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        other => return Err(format!("{name}: indices of {other:?} components")),
    };
    Ok((0..accessor.count())
        .map(|i| read(&bytes[i * stride..]))
        .collect())
}

/// A primitive's corners as triangles (lists, strips and fans); None for points and lines.
fn triangles_of(mode: Mode, corners: &[u32]) -> Option<Vec<[u32; 3]>> {
    Some(match mode {
        Mode::Triangles => corners
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
        // Every other strip triangle is wound the other way round; swapping keeps them all.
        Mode::TriangleStrip => (0..corners.len().saturating_sub(2))
            .map(|i| {
                let [a, b, c] = [corners[i], corners[i + 1], corners[i + 2]];
                if i % 2 == 0 { [a, b, c] } else { [b, a, c] }
            })
            .collect(),
        Mode::TriangleFan => (1..corners.len().saturating_sub(1))
            .map(|i| [corners[0], corners[i], corners[i + 1]])
            .collect(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => return None,
    })
}

impl Validator<'_> {
    /// Reads glTF file `rel` (the scene's meshes hold `triangles` already).
    pub(super) fn read_gltf(
        &self,
        rel: &str,
        smooth: bool,
        triangles: usize,
        poses: &[NodePose],
    ) -> Result<GltfFile, Refusal> {
        let bytes = self.read_gltf_bytes(rel)?;
        let gltf = parse_gltf(&bytes)?;
        let mut unread = Vec::new();
        if let Some(ext) = gltf.extensions_required().next() {
            return Err(format!(
                "it requires extension {}, which prism does not read",
                shown(ext)
            ));
        }
        const READ: [&str; 4] = [
            "KHR_lights_punctual",
            "KHR_materials_transmission",
            "KHR_materials_ior",
            "KHR_materials_emissive_strength",
        ];
        for ext in gltf.extensions_used() {
            if !READ.contains(&ext) {
                unread.push(format!("extension {}", shown(ext)));
            }
        }
        let buffers = self.gltf_buffers(rel, &gltf)?;
        let walk = walk_gltf(
            &gltf.document,
            &buffers,
            smooth,
            limits::MAX_SCENE_TRIANGLES.saturating_sub(triangles),
            poses,
        )?;
        unread.extend(walk.unread.iter().cloned());
        let document = &gltf.document;
        if document.animations().next().is_some() {
            unread.push("animations (the first frame's pose is not applied either)".into());
        }
        if document.skins().next().is_some() {
            unread.push("skins".into());
        }
        if walk.parts.is_empty() {
            return Err("its scene holds no triangles".into());
        }
        Ok(GltfFile {
            document: gltf.document,
            buffers,
            walk,
            unread,
        })
    }

    /// The bytes of asset `rel`, at most `MAX_MESH_FILE_BYTES`.
    pub(super) fn read_gltf_bytes(&self, rel: &str) -> Result<Vec<u8>, Refusal> {
        match self.assets.embedded(rel) {
            Some(bytes) => bytes.map(<[u8]>::to_vec).map_err(|e| e.to_string()),
            None => read_file(&self.locate(rel), limits::MAX_MESH_FILE_BYTES, "glTF file").map_err(
                |e| match e {
                    super::error::SceneError::Read { reason, .. } => reason,
                    other => other.to_string(),
                },
            ),
        }
    }

    /// Every buffer of `gltf` (read from `rel`): the GLB's binary chunk, a data URI, or a
    /// file beside it; each at least as long as the document says.
    fn gltf_buffers(&self, rel: &str, gltf: &gltf::Gltf) -> Result<Vec<Vec<u8>>, Refusal> {
        let mut buffers = Vec::new();
        for buffer in gltf.buffers() {
            let name = format!("buffers[{}]", buffer.index());
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => gltf
                    .blob
                    .clone()
                    .ok_or_else(|| format!("{name} is the binary chunk, which the file lacks"))?,
                gltf::buffer::Source::Uri(uri) => match data_uri(uri) {
                    Some(data) => data.map_err(|e| format!("{name}: {e}"))?,
                    None => {
                        let path = beside(rel, &relative_uri(uri)?);
                        self.read_gltf_bytes(&path)
                            .map_err(|e| format!("{name} ({}): {e}", quoted(&path)))?
                    }
                },
            };
            if data.len() < buffer.length() {
                return Err(format!(
                    "{name} holds {} bytes where the file says {} (truncated?)",
                    data.len(),
                    buffer.length()
                ));
            }
            buffers.push(data);
        }
        Ok(buffers)
    }
}

/// Walks the default scene (else the first) of the glTF file whose document is `document`
/// and buffers `buffers`, each node posed by the pose in `poses` that names it: its mesh
/// primitives (at most `budget` triangles together) placed in the file's frame, read
/// `smooth` or not, with its nodes, lights and cameras.
pub(super) fn walk_gltf(
    document: &gltf::Document,
    buffers: &[Vec<u8>],
    smooth: bool,
    budget: usize,
    poses: &[NodePose],
) -> Result<GltfWalk, Refusal> {
    let scene = match document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        Some(scene) => scene,
        None => return Err("it has no scene to show".into()),
    };
    let mut unread = Vec::new();
    let mut walk = NodeWalk {
        json: document.as_json(),
        cameras: Vec::new(),
        buffers,
        smooth,
        budget,
        visits: 0,
        parts: Vec::new(),
        nodes: Vec::new(),
        lights: Vec::new(),
        unread: &mut unread,
        poses,
        posed: vec![Vec::new(); poses.len()],
    };
    let mut path = Vec::new();
    for node in scene.nodes() {
        walk.node(&node, None, DMat4::IDENTITY, &mut path)?;
    }
    let (parts, mut nodes, lights, cameras) = (walk.parts, walk.nodes, walk.lights, walk.cameras);
    let posed_nodes = walk.posed.iter().map(Vec::len).collect();
    // A node met more than once cannot be placed on its own.
    let mut met = std::collections::HashMap::<usize, usize>::new();
    for n in &nodes {
        *met.entry(n.index).or_default() += 1;
    }
    for n in &mut nodes {
        if met[&n.index] > 1 {
            n.placement = None;
        }
    }
    Ok(GltfWalk {
        parts,
        nodes,
        lights,
        cameras,
        unread,
        posed_nodes,
    })
}

/// A walk of a glTF scene's node tree.
struct NodeWalk<'a> {
    json: &'a gltf::json::Root,
    cameras: Vec<GltfCamera>,
    buffers: &'a [Vec<u8>],
    smooth: bool,
    /// Triangles the scene may still take.
    budget: usize,
    visits: usize,
    parts: Vec<GltfPart>,
    nodes: Vec<GltfNode>,
    lights: Vec<GltfLight>,
    unread: &'a mut Vec<String>,
    /// The entry's poses for nodes, and the nodes each one met.
    poses: &'a [NodePose],
    posed: Vec<Vec<usize>>,
}

impl NodeWalk<'_> {
    /// Node `node` and its children, under `above` (the node above it, an index into
    /// `nodes`) whose frame `parent` maps to the file's; `path` holds the nodes above it, to
    /// refuse a node within itself.
    fn node(
        &mut self,
        node: &gltf::Node,
        above: Option<usize>,
        parent: DMat4,
        path: &mut Vec<usize>,
    ) -> Result<(), Refusal> {
        // Shown as messages show names: control characters escaped, long ones cut.
        let name = node
            .name()
            .map_or_else(|| format!("nodes[{}]", node.index()), shown);
        if path.contains(&node.index()) {
            return Err(format!(
                "{name} lies within itself (the node tree has a loop)"
            ));
        }
        if path.len() >= MAX_GLTF_DEPTH {
            return Err(format!("its node tree is more than {MAX_GLTF_DEPTH} deep"));
        }
        self.visits += 1;
        if self.visits > MAX_GLTF_NODE_VISITS {
            return Err(format!(
                "its scene places more than {MAX_GLTF_NODE_VISITS} nodes"
            ));
        }
        let transform = node.transform();
        let decomposed = transform.clone().decomposed();
        // The pose that names it (the last, if several do).
        let mut pose = None;
        for (p, met) in self.poses.iter().zip(&mut self.posed) {
            if p.node.names(node) {
                pose = Some(p);
                if !met.contains(&node.index()) {
                    met.push(node.index());
                }
            }
        }
        // A matrix is taken as it is unless a pose replaces some of its parts; parts are
        // composed by the one rule a pose's parts are (the turn taken of unit length).
        let (local, sheared) = match transform {
            gltf::scene::Transform::Matrix { matrix } if pose.is_none() => {
                let matrix = DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from)));
                let parts = node_local(None, decomposed);
                let size = matrix.abs().to_cols_array().into_iter().fold(1.0, f64::max);
                let apart = (parts - matrix).abs().to_cols_array();
                (matrix, apart.iter().any(|d| *d > 1e-6 * size))
            }
            _ => (node_local(pose, decomposed), false),
        };
        let frame = parent * local;
        if !frame.is_finite() {
            return Err(format!("{name}'s transform is not finite"));
        }
        // A node whose transform a `translate`, `rotate` and `scale` cannot write (a shear,
        // a mirror) is not placed on its own.
        let placement = node_placement(pose, decomposed);
        let writable = !sheared && placement.scale.min_element() > 0.0;
        let this = self.nodes.len();
        self.nodes.push(GltfNode {
            index: node.index(),
            name: name.clone(),
            parent: above,
            placement: writable.then_some(placement),
        });
        if let Some(mesh) = node.mesh() {
            let several = mesh.primitives().len() > 1;
            for primitive in mesh.primitives() {
                let part = if several {
                    format!("{name}/{}", primitive.index())
                } else {
                    name.clone()
                };
                self.primitive(&primitive, &part, this, frame)?;
            }
        }
        if let Some(light) = node.light() {
            use gltf::khr_lights_punctual::Kind;
            let kind = match light.kind() {
                Kind::Point => GltfLightKind::Point,
                Kind::Spot {
                    inner_cone_angle,
                    outer_cone_angle,
                } => GltfLightKind::Spot {
                    inner: inner_cone_angle,
                    outer: outer_cone_angle,
                },
                Kind::Directional => GltfLightKind::Directional,
            };
            if light.range().is_some() {
                self.unread.push(format!("{name}'s light's range"));
            }
            self.lights.push(GltfLight {
                kind,
                color: Vec3::from(light.color()),
                intensity: light.intensity(),
                position: frame.transform_point3(DVec3::ZERO),
                direction: frame.transform_vector3(DVec3::NEG_Z),
            });
        }
        if let Some(camera) = node.camera() {
            use gltf::json::camera::Type;
            use gltf::json::validation::Checked;
            // Read from the document itself: a camera's type and its projection may
            // disagree in a malformed file.
            let json = &self.json.cameras[camera.index()];
            match (&json.type_, &json.perspective) {
                (Checked::Valid(Type::Perspective), Some(p)) => self.cameras.push(GltfCamera {
                    name: camera.name().or(node.name()).map(str::to_string),
                    index: camera.index(),
                    eye: frame.transform_point3(DVec3::ZERO),
                    direction: frame.transform_vector3(DVec3::NEG_Z),
                    up: frame.transform_vector3(DVec3::Y),
                    yfov: p.yfov,
                }),
                _ => self
                    .unread
                    .push(format!("{name}'s camera (not a perspective one)")),
            }
        }
        path.push(node.index());
        for child in node.children() {
            self.node(&child, Some(this), frame, path)?;
        }
        path.pop();
        Ok(())
    }

    /// A mesh primitive's triangles, placed by `frame`.
    fn primitive(
        &mut self,
        primitive: &gltf::Primitive,
        name: &str,
        node: usize,
        frame: DMat4,
    ) -> Result<(), Refusal> {
        let at = |e: Refusal| format!("{name}: {e}");
        let Some(positions) = primitive.get(&gltf::Semantic::Positions) else {
            return Err(at("a primitive without positions".into()));
        };
        // No more corners than the triangles the scene may still take can use: a file's
        // small integers are not widened into more memory than that.
        let most = self.budget.saturating_mul(3).saturating_add(2);
        let too_many = too_many_triangles;
        if positions.count() > most || primitive.indices().is_some_and(|i| i.count() > most) {
            return Err(too_many());
        }
        let positions =
            read_floats(&positions, self.buffers, Dimensions::Vec3, false).map_err(at)?;
        let count = positions.len() / 3;
        let corners: Vec<u32> = match primitive.indices() {
            Some(indices) => read_indices(&indices, self.buffers).map_err(at)?,
            None => (0..count as u32).collect(),
        };
        if let Some(bad) = corners.iter().find(|&&i| i as usize >= count) {
            return Err(at(format!("index {bad} is past its {count} vertices")));
        }
        let Some(triangles) = triangles_of(primitive.mode(), &corners) else {
            self.unread.push(format!(
                "{name}: {:?} (only triangles are drawn)",
                primitive.mode()
            ));
            return Ok(());
        };
        if triangles.len() > self.budget {
            return Err(too_many());
        }
        let normals = match primitive.get(&gltf::Semantic::Normals) {
            Some(n) => read_floats(&n, self.buffers, Dimensions::Vec3, false).map_err(at)?,
            None => Vec::new(),
        };
        let uvs = match primitive.get(&gltf::Semantic::TexCoords(0)) {
            Some(t) => read_floats(&t, self.buffers, Dimensions::Vec2, true).map_err(at)?,
            None => Vec::new(),
        };
        if normals.len() / 3 != count && !normals.is_empty()
            || uvs.len() / 2 != count && !uvs.is_empty()
        {
            return Err(at("its attributes have different counts".into()));
        }
        // Baked into the file's frame: a mirroring transform turns the winding round so
        // that the faces keep facing out.
        let linear = DMat3::from_mat4(frame);
        let normal_map = linear.inverse().transpose();
        let mirrored = linear.determinant() < 0.0;
        let placed: Vec<Vec3> = positions
            .chunks_exact(3)
            .map(|p| {
                frame
                    .transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
                    .as_vec3()
            })
            .collect();
        let normals: Vec<Vec3> = normals
            .chunks_exact(3)
            .map(|n| (normal_map * DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64)).as_vec3())
            .collect();
        // glTF's v runs down the picture from its top, as prism's image v does.
        let uvs: Vec<Vec2> = uvs.chunks_exact(2).map(|t| Vec2::new(t[0], t[1])).collect();
        let triangles: Vec<[u32; 3]> = triangles
            .into_iter()
            .map(|[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
            .collect();
        let taken = triangles.len();
        let mesh = match Mesh::new(placed, normals, uvs, triangles) {
            Ok(mesh) => mesh,
            Err(e) => {
                self.unread.push(format!("{name}: {e}"));
                return Ok(());
            }
        };
        // Smooth: the file's normals, or where it has none, the faces' averaged.
        let mesh = if self.smooth {
            mesh.smooth()
        } else {
            mesh.faceted()
        };
        self.budget -= taken;
        self.parts.push(GltfPart {
            name: name.to_string(),
            node,
            mesh: Arc::new(mesh),
            material: primitive.material().index(),
        });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_every_length_and_refuses_bad_text() {
        assert_eq!(base64("").unwrap(), b"");
        assert_eq!(base64("TQ==").unwrap(), b"M");
        assert_eq!(base64("TWE=").unwrap(), b"Ma");
        assert_eq!(base64("TWFu").unwrap(), b"Man");
        assert_eq!(base64("TWFuIGlz").unwrap(), b"Man is");
        assert_eq!(base64("+/8A").unwrap(), [0xfb, 0xff, 0x00]);
        assert!(base64("TWFu!").is_err());
        assert!(base64("TWFuI").is_err());
    }

    #[test]
    fn uris_are_files_beside_or_data() {
        assert_eq!(relative_uri("a%20b.bin").unwrap(), "a b.bin");
        assert!(relative_uri("http://example.com/a.bin").is_err());
        assert!(relative_uri("/etc/passwd").is_err());
        assert!(relative_uri("a%zz").is_err());
        assert_eq!(
            data_uri("data:application/octet-stream;base64,TWFu")
                .unwrap()
                .unwrap(),
            b"Man"
        );
        assert!(data_uri("data:text/plain,hello").unwrap().is_err());
        assert!(data_uri("a.bin").is_none());
    }

    #[test]
    fn strips_and_fans_become_triangles_facing_alike() {
        let strip = triangles_of(Mode::TriangleStrip, &[0, 1, 2, 3]).unwrap();
        assert_eq!(strip, [[0, 1, 2], [2, 1, 3]]);
        let fan = triangles_of(Mode::TriangleFan, &[0, 1, 2, 3]).unwrap();
        assert_eq!(fan, [[0, 1, 2], [0, 2, 3]]);
        assert!(triangles_of(Mode::Lines, &[0, 1]).is_none());
    }
}
