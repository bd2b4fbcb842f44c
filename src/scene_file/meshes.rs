//! `[[meshes]]`: triangle meshes read from OBJ files, with their MTL materials mapped onto
//! prism's. A file placed by many entries is read and built once (instancing).

use super::assets::{beside, read_text_file};
use super::entry_def::placement_fields;
use super::error::SceneError;
use super::gltf_file::{is_gltf, too_many_triangles};
use super::gltf_scene::{GltfCamera, GltfFile, GltfLight, NodePose, NodeRef};
use super::mtl::{MtlMaterial, parse_mtl};
use super::obj::{LineError, parse_obj};
use super::placement::Placement;
use super::read_cache::ReadMesh;
use super::textures::{BudgetError, Images};
use super::validator::{Item, P3, V3, Validator};
use crate::appearance::{Material, Relief, Texture, UvTransform};
use crate::geometry::{Aabb, Mesh, Transform};
use crate::limits;
use crate::messages::{did_you_mean, quoted, shown_within};
use crate::scene::ObjectPlacement;
use glam::{DVec3, Vec3};
use serde::Deserialize;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeshDef {
    pub(super) name: Option<String>,
    pub(super) path: String,
    pub(super) material: Option<String>,
    pub(super) smooth: Option<bool>,
    /// A glTF file's camera to view the scene through: its name or its index.
    pub(super) camera: Option<toml::Value>,
    pub(super) shadow: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
    /// A glTF file's nodes posed anew, by name (or `nodes[i]`).
    pub(super) nodes: Option<BTreeMap<String, toml::Spanned<NodeDef>>>,
}

/// A glTF node's transform in its parent's frame, in place of the file's.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct NodeDef {
    translate: Option<P3>,
    rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    scale: Option<toml::Value>,
}

impl MeshDef {
    /// Gives the node its pose at `key` (of `nodes`) names the parts `parts` of `pose`
    /// (translate, rotate, scale), in place of those it had; `span` locates a new pose.
    pub(super) fn set_node_pose(
        &mut self,
        key: &str,
        pose: &ObjectPlacement,
        [translate, rotate, scale]: [bool; 3],
        span: std::ops::Range<usize>,
    ) {
        let nodes = self.nodes.get_or_insert_with(BTreeMap::new);
        let def = nodes.entry(key.to_string()).or_insert_with(|| {
            toml::Spanned::new(
                span,
                NodeDef {
                    translate: None,
                    rotate: None,
                    scale: None,
                },
            )
        });
        let (t, r, s) = placement_fields(pose);
        let def = def.get_mut();
        if translate {
            def.translate = t;
        }
        if rotate {
            def.rotate = r;
        }
        if scale {
            def.scale = s;
        }
    }
}

/// The mesh files one scene reads, each once.
#[derive(Default)]
pub(super) struct MeshFiles {
    /// By the file's path, whether it was asked for smooth, and a glTF file's node poses.
    loaded: HashMap<(PathBuf, bool, Vec<NodePose>), LoadedFile>,
    /// Triangles in all the files read so far.
    triangles: usize,
}

/// A mesh file, read.
struct LoadedFile {
    /// One per material it uses.
    parts: Vec<LoadedPart>,
    /// Its `mtllib` names and their lines.
    libraries: Vec<(String, usize)>,
    /// Each part's material from the libraries, once an entry without a material of its
    /// own has asked for them (a glTF file's, read with it).
    materials: Option<Vec<Material>>,
    /// A glTF file's lights, in its own frame.
    lights: Vec<GltfLight>,
    /// A glTF file's perspective cameras, in its own frame.
    cameras: Vec<GltfCamera>,
    /// What the file holds that prism does not read, in words.
    unread: Vec<String>,
    /// A glTF file as read, to walk again when the viewer poses its nodes anew.
    gltf: Option<Arc<GltfFile>>,
}

/// One material's part of a mesh file.
struct LoadedPart {
    /// The material name the file uses for it.
    name: Option<String>,
    /// The line that starts the part.
    line: usize,
    mesh: Arc<Mesh>,
}

/// What a mesh entry makes: its objects, and a glTF file's lights and what it holds that
/// prism does not read.
pub(super) struct MeshEntry<'f> {
    pub(super) objects: Vec<MeshObject>,
    /// A glTF file as read (its parts are `objects`, in order).
    pub(super) gltf: Option<&'f Arc<GltfFile>>,
    pub(super) lights: &'f [GltfLight],
    pub(super) cameras: &'f [GltfCamera],
    pub(super) unread: &'f [String],
}

/// One object a mesh entry makes.
pub(super) struct MeshObject {
    /// The material name of its part, when the file has more than one.
    pub(super) part: Option<String>,
    pub(super) mesh: Arc<Mesh>,
    pub(super) material: Material,
}

/// How far an MTL height map's white stands above its black per unit of `-bm`, as a
/// share of the mesh file's size (the diagonal of the box around its positions).
pub const MTL_BUMP_SHARE: f32 = 0.005;

/// The diagonal of the box around every position of a mesh file's parts.
fn file_size(file: &LoadedFile) -> f32 {
    let mut bounds = Aabb::EMPTY;
    for part in &file.parts {
        bounds = bounds.union(part.mesh.bounds());
    }
    if bounds.is_empty() {
        0.0
    } else {
        (bounds.max - bounds.min).length()
    }
}

/// Whether a picture's mean colour is a tangent-space normal map's: the red and green of
/// normals tilted every way about a blue of mostly straight out.
fn looks_like_normal_map(mean: Vec3) -> bool {
    (mean.x - 0.5).abs() < 0.15 && (mean.y - 0.5).abs() < 0.15 && mean.z > 0.7
}

/// A problem at a line of mesh or material file `path`, read for table `at`.
fn asset_error(path: &Path, at: &Item, e: LineError) -> SceneError {
    SceneError::Asset {
        path: path.to_path_buf(),
        line: e.line,
        message: format!("{} (read by {})", e.message, at.name),
    }
}

impl Validator<'_> {
    /// The objects mesh entry `d` makes: one per material its OBJ file uses, or one per
    /// primitive of its glTF file. `material` is the entry's own, when it gives one (an
    /// OBJ's libraries are then not read).
    pub(super) fn mesh_objects<'f>(
        &self,
        at: &Item,
        d: &MeshDef,
        material: Option<&Material>,
        files: &'f mut MeshFiles,
        images: &mut Images,
    ) -> Result<MeshEntry<'f>, SceneError> {
        let smooth = d.smooth.unwrap_or(true);
        let poses = self.node_poses(at, d)?;
        let key = (self.locate(&d.path), smooth, poses.clone());
        if !files.loaded.contains_key(&key) {
            let file = if is_gltf(&d.path) {
                self.gltf_mesh(at, &d.path, smooth, files.triangles, images, &poses)?
            } else {
                self.read_mesh(at, &d.path, smooth, files.triangles)?
            };
            files.triangles += file
                .parts
                .iter()
                .map(|p| p.mesh.triangle_count())
                .sum::<usize>();
            files.loaded.insert(key.clone(), file);
        }
        let file = files.loaded.get_mut(&key).expect("just loaded");
        if material.is_none() && file.materials.is_none() {
            file.materials = Some(self.file_materials(at, &d.path, file, images)?);
        }
        let several = file.parts.len() > 1;
        let objects = file
            .parts
            .iter()
            .enumerate()
            .map(|(i, p)| MeshObject {
                part: several.then(|| p.name.clone().unwrap_or_else(|| "default".into())),
                mesh: p.mesh.clone(),
                material: match (material, &file.materials) {
                    (Some(m), _) => m.clone(),
                    (None, Some(materials)) => materials[i].clone(),
                    (None, None) => unreachable!("materials read above"),
                },
            })
            .collect();
        Ok(MeshEntry {
            objects,
            gltf: file.gltf.as_ref(),
            lights: &file.lights,
            cameras: &file.cameras,
            unread: &file.unread,
        })
    }

    /// From the meshes' space to the scene's under `placement`: the placed meshes must lie
    /// within `MAX_COORDINATE` of the camera, like every shape.
    pub(super) fn mesh_transform<'m>(
        &self,
        at: &Item,
        meshes: impl IntoIterator<Item = &'m Mesh>,
        placement: &Placement,
    ) -> Result<Transform, SceneError> {
        for mesh in meshes {
            for p in mesh.bounds().corners() {
                let p = p.as_dvec3();
                let placed = DVec3::from(placement.point(p.to_array().into())) - self.origin;
                if !(placed.is_finite() && placed.abs().max_element() <= limits::MAX_COORDINATE) {
                    return Err(self.field_error(
                        at,
                        "path",
                        format!(
                            "the mesh, placed, reaches {:?}, more than {:e} from the camera",
                            placed.to_array(),
                            limits::MAX_COORDINATE
                        ),
                    ));
                }
            }
        }
        placement
            .model(self.origin)
            .ok_or_else(|| self.field_error(at, "scale", "the placement cannot be inverted"))
    }

    /// Entry `d`'s poses for its glTF file's nodes, checked (none for an OBJ file, which
    /// has no nodes).
    pub(super) fn node_poses(&self, at: &Item, d: &MeshDef) -> Result<Vec<NodePose>, SceneError> {
        let Some(nodes) = &d.nodes else {
            return Ok(Vec::new());
        };
        if !is_gltf(&d.path) {
            return Err(self.field_error(
                at,
                "nodes",
                "`nodes` poses a glTF file's nodes; an OBJ file has none",
            ));
        }
        nodes
            .iter()
            .map(|(node, def)| {
                let name = format!("{} node {}", at.name, quoted(node));
                let item = Item {
                    span: def.span(),
                    name: &name,
                };
                let def = def.get_ref();
                let placement =
                    self.own_placement(&item, (def.translate, def.rotate, def.scale.as_ref()))?;
                Ok(NodePose {
                    node: NodeRef::parse(node),
                    translate: def.translate.map(|_| placement.translate),
                    rotate: def.rotate.map(|_| placement.rotate),
                    scale: def.scale.as_ref().map(|_| placement.scale),
                })
            })
            .collect()
    }

    /// Refuses a pose of `poses` that names no node of glTF file `path` (whose `document`
    /// a walk with them read), or several: `posed_nodes` counts those each one named.
    pub(super) fn check_poses(
        &self,
        at: &Item,
        path: &Path,
        poses: &[NodePose],
        posed_nodes: &[usize],
        document: &gltf::Document,
    ) -> Result<(), SceneError> {
        for (pose, &met) in poses.iter().zip(posed_nodes) {
            let problem = match met {
                1 => continue,
                0 => format!(
                    "glTF file {} has no node named {} in its scene{}",
                    quoted(&path.display().to_string()),
                    quoted(&pose.node.to_string()),
                    did_you_mean(
                        &pose.node.to_string(),
                        document.nodes().filter_map(|n| n.name())
                    )
                ),
                n => format!(
                    "{} names {n} nodes of glTF file {}; name one as `nodes[i]`, its index \
                     in the file",
                    quoted(&pose.node.to_string()),
                    quoted(&path.display().to_string())
                ),
            };
            return Err(self.field_error(at, "nodes", problem));
        }
        Ok(())
    }

    /// Reads glTF file `rel` (the scene's meshes hold `triangles` already) with its nodes
    /// posed by `poses`: its primitives as parts, with their materials mapped.
    fn gltf_mesh(
        &self,
        at: &Item,
        rel: &str,
        smooth: bool,
        triangles: usize,
        images: &mut Images,
        poses: &[NodePose],
    ) -> Result<LoadedFile, SceneError> {
        let path = self.locate(rel);
        // The reasons may quote the file's own text (its names, the parser's excerpts).
        let fail = |e: String| {
            self.field_error(
                at,
                "path",
                format!(
                    "glTF file {}: {}",
                    quoted(&path.display().to_string()),
                    shown_within(&e, 1000)
                ),
            )
        };
        // An animation's frames read the file once (its triangles still count against
        // what the scene may hold with the frame's other meshes).
        let key = (path.clone(), smooth, poses.to_vec());
        let file = match self.assets.cache().and_then(|cache| cache.gltf(&key)) {
            Some(file) => {
                let total: usize = file
                    .walk
                    .parts
                    .iter()
                    .map(|p| p.mesh.triangle_count())
                    .sum();
                if total > limits::MAX_SCENE_TRIANGLES.saturating_sub(triangles) {
                    return Err(fail(too_many_triangles()));
                }
                file
            }
            None => {
                let file = Arc::new(
                    self.read_gltf(rel, smooth, triangles, poses)
                        .map_err(fail)?,
                );
                if let Some(cache) = self.assets.cache() {
                    cache.keep_gltf(key, file.clone());
                }
                file
            }
        };
        self.check_poses(at, &path, poses, &file.walk.posed_nodes, &file.document)?;
        let mut unread = file.unread.clone();
        let mut materials = self
            .gltf_materials(rel, &file, images, &mut unread)
            .map_err(fail)?;
        // glTF's default material: white, rough, not metal.
        let default = materials.len();
        materials.push(Material {
            texture: Texture::Solid(Vec3::ONE),
            specular: 0.0,
            ..Material::default()
        });
        let (parts, materials) = file
            .walk
            .parts
            .iter()
            .map(|p| {
                let part = LoadedPart {
                    name: Some(p.name.clone()),
                    line: 0,
                    mesh: p.mesh.clone(),
                };
                (part, materials[p.material.unwrap_or(default)].clone())
            })
            .unzip();
        Ok(LoadedFile {
            parts,
            libraries: Vec::new(),
            materials: Some(materials),
            lights: file.walk.lights.clone(),
            cameras: file.walk.cameras.clone(),
            unread: unread.iter().map(|u| shown_within(u, 300)).collect(),
            gltf: Some(file),
        })
    }

    /// Reads and parses mesh file `rel`; the scene's meshes hold `triangles` already.
    fn read_mesh(
        &self,
        at: &Item,
        rel: &str,
        smooth: bool,
        triangles: usize,
    ) -> Result<LoadedFile, SceneError> {
        let path = self.locate(rel);
        let budget = limits::MAX_SCENE_TRIANGLES.saturating_sub(triangles);
        let key = (path.clone(), smooth);
        let cached = self.assets.cache().and_then(|cache| cache.mesh(&key));
        // Read before: taken as it is, unless it no longer fits (then read again, for
        // the parser's message).
        if let Some(read) = cached
            && read
                .parts
                .iter()
                .map(|p| p.2.triangle_count())
                .sum::<usize>()
                <= budget
        {
            return Ok(LoadedFile {
                parts: read
                    .parts
                    .into_iter()
                    .map(|(name, line, mesh)| LoadedPart { name, line, mesh })
                    .collect(),
                libraries: read.libraries,
                materials: None,
                lights: Vec::new(),
                cameras: Vec::new(),
                unread: Vec::new(),
                gltf: None,
            });
        }
        let text = self.read_asset_text(rel).map_err(|e| {
            self.field_error(
                at,
                "path",
                format!(
                    "cannot read mesh {}: {e}",
                    quoted(&path.display().to_string())
                ),
            )
        })?;
        let obj = parse_obj(&text, budget, smooth).map_err(|e| asset_error(&path, at, e))?;
        let file = LoadedFile {
            parts: obj
                .parts
                .into_iter()
                .map(|p| LoadedPart {
                    name: p.material,
                    line: p.line,
                    mesh: Arc::new(p.mesh),
                })
                .collect(),
            libraries: obj.libraries,
            materials: None,
            lights: Vec::new(),
            cameras: Vec::new(),
            unread: Vec::new(),
            gltf: None,
        };
        if let Some(cache) = self.assets.cache() {
            let read = ReadMesh {
                parts: file
                    .parts
                    .iter()
                    .map(|p| (p.name.clone(), p.line, p.mesh.clone()))
                    .collect(),
                libraries: file.libraries.clone(),
            };
            cache.keep_mesh(key, read);
        }
        Ok(file)
    }

    /// Each part's material, from the libraries of `file` (read from `rel`); a part with no
    /// `usemtl` gets the default.
    fn file_materials(
        &self,
        at: &Item,
        rel: &str,
        file: &LoadedFile,
        images: &mut Images,
    ) -> Result<Vec<Material>, SceneError> {
        let path = self.locate(rel);
        let mut library: HashMap<String, Material> = HashMap::new();
        if file.parts.iter().any(|p| p.name.is_some()) {
            for (name, line) in &file.libraries {
                let mtl_rel = beside(rel, name);
                let mtl_path = self.locate(&mtl_rel);
                let mtl_text = self
                    .read_asset_text(&mtl_rel)
                    .map_err(|e| SceneError::Asset {
                        path: path.clone(),
                        line: *line,
                        message: format!(
                            "cannot read material library {}: {e} (read by {}; give the entry a \
                         `material` to do without it)",
                            quoted(&mtl_path.display().to_string()),
                            at.name
                        ),
                    })?;
                let materials = parse_mtl(&mtl_text).map_err(|e| asset_error(&mtl_path, at, e))?;
                // Every image of the library is counted from its header before any is
                // decoded, so the budget refuses before memory is spent.
                for m in &materials {
                    let maps = [
                        ("map_Kd", m.map_kd.as_ref()),
                        ("map_Bump", m.bump.as_ref().map(|b| &b.0)),
                        ("norm", m.norm.as_ref().map(|n| &n.0)),
                    ];
                    for (key, name) in maps {
                        if let Some(name) = name
                            && let Err(BudgetError::Exceeded(message)) =
                                images.count(self, &beside(&mtl_rel, name))
                        {
                            let line = m
                                .lines
                                .get(key)
                                .or(m.lines.get("bump"))
                                .copied()
                                .unwrap_or(m.line);
                            return Err(asset_error(&mtl_path, at, LineError { line, message }));
                        }
                    }
                }
                let size = file_size(file);
                for m in materials {
                    let material = self
                        .mtl_material(&m, &mtl_rel, size, images)
                        .map_err(|e| asset_error(&mtl_path, at, e))?;
                    // The first library to define a name wins, as in other readers.
                    library.entry(m.name.clone()).or_insert(material);
                }
            }
        }
        file.parts
            .iter()
            .map(|part| match &part.name {
                None => Ok(Material::default()),
                Some(name) => library.get(name).cloned().ok_or_else(|| SceneError::Asset {
                    path: path.clone(),
                    line: part.line,
                    message: format!(
                        "no material library of the file defines {} (read by {}; give the \
                         entry a `material` to do without it)",
                        quoted(name),
                        at.name
                    ),
                }),
            })
            .collect()
    }

    /// The text of asset `rel`: at most `MAX_MESH_FILE_BYTES`, UTF-8.
    fn read_asset_text(&self, rel: &str) -> Result<String, String> {
        match self.assets.embedded(rel) {
            Some(bytes) => {
                let bytes = bytes.map_err(|e| e.to_string())?;
                String::from_utf8(bytes.to_vec()).map_err(|_| "it is not UTF-8 text".into())
            }
            None => read_text_file(&self.locate(rel), limits::MAX_MESH_FILE_BYTES, "mesh file")
                .map_err(|e| match e {
                    SceneError::Read { reason, .. } => reason,
                    other => other.to_string(),
                }),
        }
    }

    /// Prism's material for an MTL one, each value held to the scene file's limits; `size`
    /// is the diagonal of the box around the mesh file's positions (MTL's bump heights
    /// have no unit: prism measures them against it).
    fn mtl_material(
        &self,
        m: &MtlMaterial,
        mtl_rel: &str,
        size: f32,
        images: &mut Images,
    ) -> Result<Material, LineError> {
        let at = |key: &'static str| m.lines.get(key).copied().unwrap_or(m.line);
        let fail = |key: &'static str, message: String| LineError {
            line: at(key),
            message: format!("material {}: {message}", quoted(&m.name)),
        };
        let color =
            |key: &'static str, v: Option<[f32; 3]>, hi: f32| -> Result<Option<Vec3>, LineError> {
                match v {
                    None => Ok(None),
                    Some(c) if c.iter().all(|x| (0.0..=hi).contains(x)) => Ok(Some(Vec3::from(c))),
                    Some(c) => Err(fail(
                        key,
                        format!("`{key}` must lie in [0, {hi}] on every channel, got {c:?}"),
                    )),
                }
            };
        let mean = |c: Vec3| (c.x + c.y + c.z) / 3.0;
        let d = Material::default();
        let kd = color("Kd", m.kd, *limits::REFLECTANCE.end())?;
        let ka = color("Ka", m.ka, *limits::REFLECTANCE.end())?;
        let ks = color("Ks", m.ks, *limits::REFLECTANCE.end())?;
        let ke = color("Ke", m.ke, limits::MAX_RADIANCE)?;
        let texture = match &m.map_kd {
            Some(name) => {
                let rel = beside(mtl_rel, name);
                let image = images.load(self, &rel).map_err(|e| fail("map_Kd", e))?;
                Texture::Image {
                    image,
                    uv: UvTransform::IDENTITY,
                }
            }
            None => Texture::Solid(kd.unwrap_or(Vec3::splat(0.8))),
        };
        let in_range = |key: &'static str, v: f32, lo: f32, hi: f32| {
            if (lo..=hi).contains(&v) {
                Ok(v)
            } else {
                Err(fail(
                    key,
                    format!("`{key}` must lie in [{lo}, {hi}], got {v}"),
                ))
            }
        };
        let transparency = match m.transparency {
            Some(t) => in_range(
                if m.lines.contains_key("Tr") {
                    "Tr"
                } else {
                    "d"
                },
                t,
                0.0,
                1.0,
            )?,
            None => 0.0,
        };
        // illum 3 to 7 ask for ray-traced reflection; 4, 6, 7 and 9 for refraction.
        let illum = m.illum.unwrap_or(2);
        let reflects = (3..=7).contains(&illum);
        let refracts = matches!(illum, 4 | 6 | 7 | 9);
        let eta = match m.ni {
            Some(ni) if refracts => Some(in_range(
                "Ni",
                ni,
                *limits::ETA.start(),
                *limits::ETA.end(),
            )?),
            _ => None,
        };
        let relief = self.mtl_relief(m, mtl_rel, size, images)?;
        let specular = ks
            .map(mean)
            .unwrap_or(if illum >= 2 { d.specular } else { 0.0 });
        Ok(Material {
            texture,
            ambient: ka.map(mean).unwrap_or(d.ambient),
            diffuse: d.diffuse,
            specular: if illum >= 2 { specular } else { 0.0 },
            shininess: match m.ns {
                Some(ns) => in_range("Ns", ns, 0.0, limits::MAX_SHININESS)?,
                None => d.shininess,
            },
            reflectivity: if reflects { specular.min(1.0) } else { 0.0 },
            transparency,
            eta,
            emission: ke.unwrap_or(Vec3::ZERO),
            relief,
            ..d
        })
    }

    /// An MTL material's relief. `norm` is a normal map; `map_Bump` (or `bump`) is one too
    /// when its picture reads as one (bluish, as Blender writes its normal maps there), and
    /// otherwise a height map raising white `-bm` × `MTL_BUMP_SHARE` of `size` above black.
    /// `-bm` is a normal map's strength.
    fn mtl_relief(
        &self,
        m: &MtlMaterial,
        mtl_rel: &str,
        size: f32,
        images: &mut Images,
    ) -> Result<Option<Relief>, LineError> {
        let (key, (name, multiplier)) = match (&m.norm, &m.bump) {
            (Some(norm), _) => ("norm", norm),
            (None, Some(bump)) => (
                if m.lines.contains_key("bump") {
                    "bump"
                } else {
                    "map_Bump"
                },
                bump,
            ),
            (None, None) => return Ok(None),
        };
        let line = m.lines.get(key).copied().unwrap_or(m.line);
        let fail = |message: String| LineError {
            line,
            message: format!("material {}: {message}", quoted(&m.name)),
        };
        let image = images.load(self, &beside(mtl_rel, name)).map_err(&fail)?;
        let normal_map = key == "norm" || looks_like_normal_map(image.mean());
        let map = Texture::Image {
            image,
            uv: UvTransform::IDENTITY,
        };
        let (relief, field, value, range) = if normal_map {
            let relief = Relief::NormalMap {
                map,
                strength: *multiplier,
            };
            (relief, "strength", *multiplier, limits::NORMAL_STRENGTH)
        } else {
            let depth = multiplier * MTL_BUMP_SHARE * size;
            let relief = Relief::Bump { height: map, depth };
            (relief, "depth", depth, limits::BUMP_DEPTH)
        };
        if !range.contains(&value) {
            return Err(fail(format!(
                "`{key}`'s `-bm` gives a {field} of {value}, outside [{}, {}]",
                range.start(),
                range.end()
            )));
        }
        Ok(Some(relief))
    }
}
