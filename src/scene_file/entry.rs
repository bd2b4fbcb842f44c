//! An object entry of the scene file (`[[spheres]]`, `[[meshes]]`, …): what every kind has
//! (a name, a material, a shadow switch, a placement), and an entry validated again under
//! another placement, as a load of the file with those values would validate it (the
//! viewer's transform edits).

use super::assemble::SceneFile;
use super::assets::Assets;
use super::entry_def::{EntryDef, entry_label, placement_fields};
use super::error::SceneError;
use super::kinds::object_kinds;
use super::load::{LoadedScene, read_tables};
use super::parse_tree::{Tree, parse_tree};
use super::spans::FieldSpans;
use super::validator::{Item, P3, V3, Validator};
use crate::appearance::Light;
use crate::scene::{EditError, ObjectPlacement, Scene, ShapeDesc};
use std::path::{Path, PathBuf};

/// The entry interface for every kind of object entry (kinds.rs).
macro_rules! entry_defs {
    ($($table:ident: $def:ty, $($how:ident)+;)*) => {$(
        impl EntryDef for $def {
            fn name(&self) -> Option<&str> {
                self.name.as_deref()
            }
            fn material(&self) -> Option<&str> {
                self.material.as_deref()
            }
            fn shadow(&self) -> Option<bool> {
                self.shadow
            }
            fn group(&self) -> Option<&str> {
                self.group.as_deref()
            }
            fn placement(&self) -> (Option<P3>, Option<V3>, Option<&toml::Value>) {
                (self.translate, self.rotate, self.scale.as_ref())
            }
            fn set_placement(&mut self, p: &ObjectPlacement) {
                (self.translate, self.rotate, self.scale) = placement_fields(p);
            }
        }
    )*};
}

object_kinds!(entry_defs);
// A combination nested in another is an entry of its own kind, with a placement.
entry_defs! { csg: super::csg::NestedCsgDef, shape csg; }

/// Object `object`'s entry placed anew: each object the entry makes (a mesh entry's every
/// part), by its index in the scene, with its shape.
pub(crate) struct PlacedEntry {
    /// The objects and their shapes under the new placement.
    pub(crate) shapes: Vec<(usize, ShapeDesc)>,
    /// The placement, as the entry now writes it.
    pub(crate) placement: ObjectPlacement,
    /// The lights the entry's file brings (a glTF scene's), placed anew with it, by their
    /// index in the scene.
    pub(crate) lights: Vec<(usize, Light)>,
}

/// Entries placed anew: objects' and lights'.
#[derive(Default)]
pub(crate) struct PlacedEntries {
    /// Each object entry placed anew.
    pub(crate) objects: Vec<PlacedEntry>,
    /// Each light placed anew in its group, by its index in the scene.
    pub(crate) lights: Vec<(usize, Light)>,
}

impl PlacedEntries {
    /// Puts the new shapes, placements and lights into `scene`. A light keeps what an edit
    /// may have changed of it other than where it is (its colour, intensity and cone).
    pub(crate) fn apply(self, scene: &mut Scene) {
        let entry_lights = self.objects.iter().flat_map(|e| e.lights.iter().cloned());
        let lights: Vec<(usize, Light)> = entry_lights.chain(self.lights).collect();
        for entry in self.objects {
            for (i, mut shape) in entry.shapes {
                let o = &mut scene.objects[i];
                // What its CSG members are made of stays (they name `[materials]` entries,
                // which placing the entry again does not read).
                shape.keep_member_materials(&o.shape);
                o.shape = shape;
                o.placement = entry.placement;
            }
        }
        for (i, light) in lights {
            if let Some(l) = scene.lights.get_mut(i) {
                *l = l.placed_as(&light);
            }
        }
    }
}

/// A placement refused by the file's rules, as an edit's error (`name` for a problem not
/// in one entry).
pub(crate) fn edit_error(e: SceneError, name: &str) -> EditError {
    match e {
        SceneError::Invalid { item, message, .. } => EditError::Placement { item, message },
        other => EditError::Placement {
            item: name.to_string(),
            message: other.to_string(),
        },
    }
}

impl LoadedScene {
    /// Places `scene`'s object `object` (an edit of this load's scene) by `placement` (its
    /// entry's `translate`, `rotate` and `scale`), as this load would with those values: the
    /// same shapes, checked by the same rules. A mesh entry's parts move together.
    pub fn place_object(
        &self,
        scene: &mut Scene,
        object: usize,
        placement: ObjectPlacement,
    ) -> Result<(), EditError> {
        if object >= scene.objects.len() {
            return Err(EditError::NoSuchObject(object));
        }
        let placed = self
            .placed_entries(scene, &[(object, placement)], &[])
            .map_err(|e| edit_error(e, &scene.objects[object].name))?
            .ok_or(EditError::NoSuchObject(object))?;
        placed.apply(scene);
        Ok(())
    }

    /// The shapes the entries of `objects` make when their `translate`, `rotate` and
    /// `scale` are the placements given, and the lights `lights` (indices) placed anew in
    /// their groups: exactly what a load of the file with these values, and with `scene`'s
    /// groups' placements, would make, checked by the same rules. `scene` is this load's
    /// scene, edited or not (a mesh's parts keep the meshes it holds; no file is read).
    /// None when the file no longer has an entry the scene came from.
    pub(crate) fn placed_entries(
        &self,
        scene: &Scene,
        objects: &[(usize, ObjectPlacement)],
        lights: &[usize],
    ) -> Result<Option<PlacedEntries>, SceneError> {
        // The file as this load validated it: an animated file's at its frame.
        match &self.animation {
            Some(animation) => animation.with_frame_tree(self.frame, |tree, source| {
                self.placed_in(tree, source, scene, objects, lights)
            }),
            None => match parse_tree(&self.source, Path::new("")) {
                Ok(tree) => self.placed_in(&tree, &self.source, scene, objects, lights),
                Err(_) => Ok(None),
            },
        }
    }

    /// `placed_entries` in the file whose parse tree is `tree` and text `source`.
    fn placed_in(
        &self,
        tree: &Tree,
        source: &str,
        scene: &Scene,
        objects: &[(usize, ObjectPlacement)],
        lights: &[usize],
    ) -> Result<Option<PlacedEntries>, SceneError> {
        let Ok(mut file) = read_tables(tree, source, Path::new("")) else {
            return Ok(None);
        };
        let v = Validator {
            path: PathBuf::new(),
            source,
            spans: FieldSpans::of(tree),
            assets: Assets::Embedded(&[]),
            origin: glam::DVec3::from(file.camera.get_ref().eye),
            reads: Default::default(),
            materials: Default::default(),
            groups: Default::default(),
        };
        // The groups as the scene has them now (an edit's placements in them), checked by
        // the file's rules.
        for (def, group) in file.groups.iter_mut().zip(&scene.groups) {
            def.get_mut().set_placement(&group.placement);
        }
        let _ = v.groups.set(v.groups(&file.groups)?);
        let mut placed = PlacedEntries::default();
        for &(object, placement) in objects {
            let Some(entry) = self.placed_object(&mut file, &v, scene, object, &placement)? else {
                return Ok(None);
            };
            placed.objects.push(entry);
        }
        for &light in lights {
            let Some(def) = file.lights.get(light) else {
                return Ok(None);
            };
            let label = format!("lights[{light}]");
            let at = Item {
                span: def.span(),
                name: &label,
            };
            let (placed_light, _) = v.light(&at, def.get_ref())?;
            placed.lights.push((light, placed_light));
        }
        Ok(Some(placed))
    }

    /// Object `object`'s entry of `file` placed by `placement`; None when the file has no
    /// such entry.
    fn placed_object(
        &self,
        file: &mut SceneFile,
        v: &Validator,
        scene: &Scene,
        object: usize,
        placement: &ObjectPlacement,
    ) -> Result<Option<PlacedEntry>, SceneError> {
        let Some(origin) = self.origins.get(object) else {
            return Ok(None);
        };
        let (table, index) = (origin.table, origin.index);
        // A glTF scene's lights, placed anew with its entry.
        let mut lights = Vec::new();
        // The entry with the new placement, its span and its label; None if the file has
        // no such entry.
        macro_rules! entry {
            ($list:expr) => {{
                let Some(item) = $list.get_mut(index) else {
                    return Ok(None);
                };
                let span = item.span();
                let d = item.get_mut();
                d.set_placement(placement);
                let label = entry_label(table, index, d.name());
                (&*d, span, label)
            }};
        }
        macro_rules! placed {
            ($list:expr, $read:ident) => {{
                let (d, span, label) = entry!($list);
                let at = Item { span, name: &label };
                let placed = v.placement(&at, d)?;
                (vec![(object, v.$read(&at, d, &placed)?)], placed.written())
            }};
        }
        // The entry's kind, by its table (kinds.rs).
        macro_rules! placed_entries {
            ($($table:ident: $def:ty, $($how:ident)+;)*) => {
                $(if table == stringify!($table) {
                    placed_entry!($table $($how)+)
                } else)* {
                    return Ok(None);
                }
            };
        }
        macro_rules! placed_entry {
            ($table:ident shape $read:ident) => {
                placed!(file.$table, $read)
            };
            ($table:ident mesh) => {{
                // The entry, with its glTF file's nodes posed as the scene's node groups
                // now place them.
                let gltf = origin.gltf.as_deref();
                let edited = gltf.map_or_else(Vec::new, |g| g.edited_poses(&self.scene, scene));
                let Some(item) = file.$table.get_mut(index) else {
                    return Ok(None);
                };
                let span = item.span();
                let d = item.get_mut();
                d.set_placement(placement);
                for (key, pose, parts) in &edited {
                    d.set_node_pose(key, pose, *parts, span.clone());
                }
                let d = &*d;
                let label = entry_label(table, index, d.name());
                let at = Item { span, name: &label };
                let placed = v.placement(&at, d)?;
                // Every part of the entry, with the mesh the load read (a glTF file's
                // nodes as the file poses them).
                let mut parts: Vec<(usize, std::sync::Arc<crate::geometry::Mesh>)> = self
                    .origins
                    .iter()
                    .enumerate()
                    .filter(|(_, o)| o.table == stringify!($table) && o.index == index)
                    .filter_map(|(j, _)| match &self.scene.objects.get(j)?.shape {
                        ShapeDesc::Mesh { mesh, .. } => Some((j, mesh.clone())),
                        _ => None,
                    })
                    .collect();
                // The file's lights in its own frame, as its nodes now place them.
                let mut file_lights: Vec<_> = gltf
                    .iter()
                    .flat_map(|g| g.lights.iter().map(|(_, l)| l.clone()))
                    .collect();
                if let Some(g) = gltf.filter(|_| !edited.is_empty()) {
                    let walk = v.posed_walk(&at, d, g)?;
                    if walk.parts.len() != parts.len() {
                        return Err(v.field_error(
                            &at,
                            "nodes",
                            "posed so, a part of the glTF file holds no triangle it can draw",
                        ));
                    }
                    for ((_, mesh), part) in parts.iter_mut().zip(&walk.parts) {
                        *mesh = part.mesh.clone();
                    }
                    file_lights = walk.lights.clone();
                }
                let transform =
                    v.mesh_transform(&at, parts.iter().map(|(_, m)| m.as_ref()), &placed)?;
                let shapes = parts
                    .into_iter()
                    .map(|(j, mesh)| (j, ShapeDesc::Mesh { mesh, transform }))
                    .collect();
                // A glTF scene's lights go where the entry's new placement puts them.
                let numbers = gltf.iter().flat_map(|g| g.lights.iter().map(|(i, _)| *i));
                for (light, read) in numbers.zip(&file_lights) {
                    lights.push((light, v.gltf_light(&at, read, &placed)?));
                }
                (shapes, placed.written())
            }};
        }
        let (shapes, written) = object_kinds!(placed_entries);
        Ok(Some(PlacedEntry {
            shapes,
            placement: written,
            lights,
        }))
    }
}
