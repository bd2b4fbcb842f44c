//! An object entry of the scene file (`[[spheres]]`, `[[meshes]]`, …): what every kind has
//! (a name, a material, a shadow switch, a placement), and an entry validated again under
//! another placement, as a load of the file with those values would validate it (the
//! viewer's transform edits).

use super::assets::Assets;
use super::entry_def::{EntryDef, entry_label};
use super::error::SceneError;
use super::fixed_array::Fixed;
use super::kinds::object_kinds;
use super::load::{LoadedScene, read_tables};
use super::parse_tree::{Tree, parse_tree};
use super::spans::FieldSpans;
use super::validator::{Item, P3, V3, Validator};
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
            fn placement(&self) -> (Option<P3>, Option<V3>, Option<&toml::Value>) {
                (self.translate, self.rotate, self.scale.as_ref())
            }
            fn set_placement(&mut self, p: &ObjectPlacement) {
                self.translate = Some(Fixed(p.translate.to_array()));
                self.rotate = Some(Fixed(p.rotate.to_array()));
                self.scale = Some(toml::Value::Array(
                    p.scale.to_array().map(toml::Value::Float).to_vec(),
                ));
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
            .placed_entry(scene, object, &placement)
            .map_err(|e| match e {
                SceneError::Invalid { item, message, .. } => EditError::Placement { item, message },
                other => EditError::Placement {
                    item: scene.objects[object].name.clone(),
                    message: other.to_string(),
                },
            })?
            .ok_or(EditError::NoSuchObject(object))?;
        for (i, mut shape) in placed.shapes {
            let o = &mut scene.objects[i];
            // What its CSG members are made of stays (they name `[materials]` entries,
            // which placing the entry again does not read).
            shape.keep_member_materials(&o.shape);
            o.shape = shape;
            o.placement = placed.placement;
        }
        Ok(())
    }

    /// The shapes object `object`'s entry makes when its `translate`, `rotate` and `scale`
    /// are `placement`'s: exactly those a load of the file with these values would make,
    /// checked by the same rules. `scene` is this load's scene, edited or not (a mesh's
    /// parts keep the meshes it holds; no file is read).
    pub(crate) fn placed_entry(
        &self,
        scene: &Scene,
        object: usize,
        placement: &ObjectPlacement,
    ) -> Result<Option<PlacedEntry>, SceneError> {
        // The file as this load validated it: an animated file's at its frame.
        match &self.animation {
            Some(animation) => animation.with_frame_tree(self.frame, |tree, source| {
                self.placed_in(tree, source, scene, object, placement)
            }),
            None => match parse_tree(&self.source, Path::new("")) {
                Ok(tree) => self.placed_in(&tree, &self.source, scene, object, placement),
                Err(_) => Ok(None),
            },
        }
    }

    /// `placed_entry` in the file whose parse tree is `tree` and text `source`.
    fn placed_in(
        &self,
        tree: &Tree,
        source: &str,
        scene: &Scene,
        object: usize,
        placement: &ObjectPlacement,
    ) -> Result<Option<PlacedEntry>, SceneError> {
        let Some(origin) = self.origins.get(object) else {
            return Ok(None);
        };
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
        };
        let (table, index) = (origin.table, origin.index);
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
                let (d, span, label) = entry!(file.$table);
                let at = Item { span, name: &label };
                let placed = v.placement(&at, d)?;
                // Every part of the entry, with the mesh it holds.
                let parts: Vec<(usize, std::sync::Arc<crate::geometry::Mesh>)> = self
                    .origins
                    .iter()
                    .enumerate()
                    .filter(|(_, o)| o.table == stringify!($table) && o.index == index)
                    .filter_map(|(j, _)| match &scene.objects.get(j)?.shape {
                        ShapeDesc::Mesh { mesh, .. } => Some((j, mesh.clone())),
                        _ => None,
                    })
                    .collect();
                let transform =
                    v.mesh_transform(&at, parts.iter().map(|(_, m)| m.as_ref()), &placed)?;
                let shapes = parts
                    .into_iter()
                    .map(|(j, mesh)| (j, ShapeDesc::Mesh { mesh, transform }))
                    .collect();
                (shapes, placed.written())
            }};
        }
        let (shapes, written) = object_kinds!(placed_entries);
        Ok(Some(PlacedEntry {
            shapes,
            placement: written,
        }))
    }
}
