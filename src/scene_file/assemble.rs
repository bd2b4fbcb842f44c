//! The whole file: its tables read in order (camera, render, groups, lights, textures,
//! materials, objects), each by its subject's reader, into one `Scene`, and the images it names
//! counted against one texel budget before any is decoded.

use super::camera::CameraDef;
use super::entry_def::EntryDef;
use super::entry_def::entry_label;
use super::error::SceneError;
use super::gltf_nodes::{GltfOrigin, node_groups};
use super::groups::GroupDef;
use super::kinds::object_kinds;
use super::lights::LightDef;
use super::materials::MaterialDef;
use super::meshes::MeshFiles;
use super::placement::Placement;
use super::render_table::{FogDef, RenderDef};

use super::textures::{BudgetError, Images, TextureDef};
use super::validator::{Item, Validator};
use crate::appearance::Material;
use crate::messages::{did_you_mean, quoted};
use crate::scene::{Scene, SceneObject, ShapeDesc};
use serde::Deserialize;
use std::collections::{BTreeMap, HashMap};
use std::ops::Range;
use std::sync::Arc;
use toml::Spanned;

/// The entry of a scene file that made an object.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectOrigin {
    /// The array of tables it is in: "spheres", "boxes", "meshes", ….
    pub table: &'static str,
    /// Its index in that array.
    pub index: usize,
    /// The name of the `[materials]` entry it uses; None for the default material or for
    /// a mesh part whose material comes from the mesh's own MTL file.
    pub material: Option<String>,
    /// What the entry's file (a glTF scene) holds that prism does not read, in words.
    pub unread: Vec<String>,
    /// For a glTF entry's parts, what they share: the file, its lights and its nodes, which
    /// placing the entry or a node anew places anew.
    pub(super) gltf: Option<Arc<GltfOrigin>>,
}

/// The whole file as parsed: the scene-wide tables, then one array of tables per kind of
/// object entry (kinds.rs).
macro_rules! scene_file {
    ($($table:ident: $def:ty, $($how:ident)+;)*) => {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        pub(super) struct SceneFile {
            pub(super) camera: Spanned<CameraDef>,
            pub(super) render: Option<Spanned<RenderDef>>,
            pub(super) fog: Option<Spanned<FogDef>>,
            #[serde(default)]
            pub(super) groups: Vec<Spanned<GroupDef>>,
            #[serde(default)]
            pub(super) lights: Vec<Spanned<LightDef>>,
            #[serde(default)]
            pub(super) textures: BTreeMap<String, Spanned<TextureDef>>,
            #[serde(default)]
            pub(super) materials: BTreeMap<String, Spanned<MaterialDef>>,
            $(
                #[serde(default)]
                pub(super) $table: Vec<Spanned<$def>>,
            )*
            /// Read by animation.rs; a still frame's validation passes over it.
            #[allow(dead_code)]
            pub(super) animation: Option<serde::de::IgnoredAny>,
        }
    };
}
object_kinds!(scene_file);

impl Validator<'_> {
    pub(super) fn scene(&self, file: SceneFile) -> Result<(Scene, Vec<ObjectOrigin>), SceneError> {
        let camera = self.camera(&file.camera)?;
        let (render, ambient) = self.render(file.render.as_ref())?;
        // Lights and objects name the groups they are placed in.
        let mut groups = self.groups(&file.groups)?;
        let _ = self.groups.set(groups.clone());
        let mut lights = Vec::with_capacity(file.lights.len());
        for (i, l) in file.lights.iter().enumerate() {
            let name = format!("lights[{i}]");
            let at = Item {
                span: l.span(),
                name: &name,
            };
            let (light, group) = self.light(&at, l.get_ref())?;
            if let Some(g) = group {
                groups[g].lights.push(i);
            }
            lights.push(light);
        }
        let fog = self.fog(file.fog.as_ref())?;
        let mut images = Images::default();
        self.check_texel_budget(&file.textures, file.render.as_ref(), &mut images)?;
        let background = self.background(file.render.as_ref(), &mut images)?;
        let textures = file
            .textures
            .iter()
            .map(|(name, t)| Ok((name.clone(), self.texture(name, t, &mut images)?)))
            .collect::<Result<HashMap<_, _>, SceneError>>()?;
        let materials = file
            .materials
            .iter()
            .map(|(name, m)| Ok((name.clone(), self.material(name, m, &textures)?)))
            .collect::<Result<HashMap<_, _>, SceneError>>()?;
        // CSG members name materials too.
        let _ = self.materials.set(materials.clone());

        let mut objects = Vec::new();
        let mut origins = Vec::new();
        let mut add = |kind: &'static str,
                       i: usize,
                       span: Range<usize>,
                       d: &dyn EntryDef,
                       shape: &dyn Fn(&Item, &Placement) -> Result<ShapeDesc, SceneError>|
         -> Result<(), SceneError> {
            let label = entry_label(kind, i, d.name());
            let at = Item { span, name: &label };
            let material = match d.material() {
                None => Material::default(),
                Some(m) => materials.get(m).cloned().ok_or_else(|| {
                    self.field_error(
                        &at,
                        "material",
                        format!(
                            "no material named {} (see [materials]){}",
                            quoted(m),
                            did_you_mean(m, materials.keys().map(String::as_str))
                        ),
                    )
                })?,
            };
            let placement = self.placement(&at, d)?;
            let shape = shape(&at, &placement)?;
            objects.push(SceneObject {
                name: d
                    .name()
                    .map_or_else(|| format!("{kind} {i}"), str::to_string),
                shape,
                material,
                casts_shadow: d.shadow().unwrap_or(true),
                placement: placement.written(),
                group: placement.group(),
                node: None,
            });
            origins.push(ObjectOrigin {
                table: kind,
                index: i,
                material: d.material().map(str::to_string),
                unread: Vec::new(),
                gltf: None,
            });
            Ok(())
        };
        // Every shape entry, kind by kind; meshes, which make an object per part, after.
        macro_rules! shape_entries {
            ($($table:ident: $def:ty, $($how:ident)+;)*) => {
                $(shape_entry!($table $($how)+);)*
            };
        }
        macro_rules! shape_entry {
            ($table:ident shape $read:ident) => {
                for (i, item) in file.$table.iter().enumerate() {
                    let d = item.get_ref();
                    add(stringify!($table), i, item.span(), d, &|at, p| {
                        self.$read(at, d, p)
                    })?;
                }
            };
            ($table:ident mesh) => {};
        }
        object_kinds!(shape_entries);
        let mut mesh_files = MeshFiles::default();
        // A glTF file's camera that a mesh entry chose to view the scene through.
        let mut chosen_camera = None;
        for (i, m) in file.meshes.iter().enumerate() {
            let d = m.get_ref();
            let label = entry_label("meshes", i, d.name());
            let at = Item {
                span: m.span(),
                name: &label,
            };
            let material = match &d.material {
                None => None,
                Some(name) => Some(materials.get(name).ok_or_else(|| {
                    self.field_error(
                        &at,
                        "material",
                        format!(
                            "no material named {} (see [materials]){}",
                            quoted(name),
                            did_you_mean(name, materials.keys().map(String::as_str))
                        ),
                    )
                })?),
            };
            let placement = self.placement(&at, d)?;
            let entry = self.mesh_objects(&at, d, material, &mut mesh_files, &mut images)?;
            let mut file_lights = Vec::new();
            for light in entry.lights {
                file_lights.push((lights.len(), light.clone()));
                lights.push(self.gltf_light(&at, light, &placement)?);
            }
            // A glTF file's nodes become groups its parts hang from.
            let keys = d.nodes.iter().flat_map(|n| n.keys());
            let (node_groups, nodes, part_nodes) = match entry.gltf {
                Some(file) => node_groups(file, keys, groups.len()),
                None => (Vec::new(), Vec::new(), Vec::new()),
            };
            groups.extend(node_groups);
            // Shared by the entry's parts.
            let gltf = entry.gltf.map(|file| {
                Arc::new(GltfOrigin {
                    file: file.clone(),
                    lights: file_lights,
                    nodes,
                    last_walk: Default::default(),
                })
            });
            let mut unread = entry.unread.to_vec();
            match &d.camera {
                Some(_) if !super::gltf_file::is_gltf(&d.path) => {
                    return Err(self.field_error(
                        &at,
                        "camera",
                        "`camera` chooses a glTF file's camera; an OBJ file has none",
                    ));
                }
                Some(choice) => {
                    if chosen_camera.is_some() {
                        return Err(self.field_error(
                            &at,
                            "camera",
                            "another mesh entry chose the camera already",
                        ));
                    }
                    let view = self.gltf_view(&at, entry.cameras, choice)?;
                    chosen_camera = Some(self.gltf_camera(&at, view, &placement, &camera)?);
                }
                None if !entry.cameras.is_empty() => unread.push(format!(
                    "its {} camera(s) (the entry's `camera` chooses one; [camera] is used)",
                    entry.cameras.len()
                )),
                None => {}
            }
            let parts = entry.objects;
            let transform =
                self.mesh_transform(&at, parts.iter().map(|p| p.mesh.as_ref()), &placement)?;
            let name = d.name.clone().unwrap_or_else(|| format!("meshes {i}"));
            for (p, part) in parts.into_iter().enumerate() {
                objects.push(SceneObject {
                    name: match &part.part {
                        Some(p) => format!("{name}/{p}"),
                        None => name.clone(),
                    },
                    shape: ShapeDesc::Mesh {
                        mesh: part.mesh,
                        transform,
                    },
                    material: part.material,
                    casts_shadow: d.shadow.unwrap_or(true),
                    placement: placement.written(),
                    group: placement.group(),
                    node: part_nodes.get(p).copied().flatten(),
                });
                origins.push(ObjectOrigin {
                    table: "meshes",
                    index: i,
                    material: d.material.clone(),
                    unread: unread.clone(),
                    gltf: gltf.clone(),
                });
            }
        }
        let scene = Scene {
            origin: self.origin,
            camera: chosen_camera.unwrap_or(camera),
            render,
            background,
            ambient,
            lights,
            fog,
            objects,
            groups,
        };
        Ok((scene, origins))
    }

    /// Counts the images of `[textures]` and the background against the scene's texel
    /// budget from their headers, before any is decoded, refusing the one that passes it
    /// with its field. (A file that cannot be read is reported when it is loaded.)
    pub(super) fn check_texel_budget(
        &self,
        textures: &BTreeMap<String, Spanned<TextureDef>>,
        render: Option<&Spanned<RenderDef>>,
        budget: &mut Images,
    ) -> Result<(), SceneError> {
        // Every image the scene names: (where, the field, the path).
        let mut images: Vec<(String, Range<usize>, &str, &str)> = textures
            .iter()
            .filter_map(|(name, t)| {
                let label = format!("textures.{}", crate::messages::shown(name));
                match (&t.get_ref().path, t.get_ref().kind.as_str()) {
                    (Some(rel), "image") => Some((label, t.span(), "path", rel.as_str())),
                    _ => None,
                }
            })
            .collect();
        if let Some(r) = render
            && let Some(toml::Value::Table(t)) = &r.get_ref().background
            && let Some(toml::Value::String(rel)) = t.get("image")
        {
            images.push(("render".into(), r.span(), "background", rel.as_str()));
        }
        for (label, span, field, rel) in images {
            if let Err(BudgetError::Exceeded(message)) = budget.count(self, rel) {
                let at = Item { span, name: &label };
                return Err(self.field_error(&at, field, message));
            }
        }
        Ok(())
    }
}
