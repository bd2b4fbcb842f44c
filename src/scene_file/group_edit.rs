//! A group placed anew (the viewer's transform rows on a group): every object and light
//! within it placed again, as a load of the file with the group's new values would place
//! them, or none, with the reason, when one of them breaks the file's rules. A glTF
//! file's node is placed as its entry's pose for the node (`nodes`) with those values.

use super::entry::edit_error;
use super::load::LoadedScene;
use crate::scene::{EditError, GroupKind, ObjectPlacement, Scene};

impl LoadedScene {
    /// Places `scene`'s group `group` by `placement` (its entry's `translate`, `rotate` and
    /// `scale`): the objects, lights and groups within it follow. The scene is unchanged
    /// when any of them would be refused.
    pub fn place_group(
        &self,
        scene: &mut Scene,
        group: usize,
        placement: ObjectPlacement,
    ) -> Result<(), EditError> {
        let Some(g) = scene.groups.get(group) else {
            return Err(EditError::NoSuchGroup(group));
        };
        let (name, kind) = (g.name.clone(), g.kind);
        let mut placed = scene.clone();
        placed.groups[group].placement = placement;
        let (objects, lights) = match kind {
            GroupKind::Entry => self.entries_within(scene, group),
            GroupKind::FileNode => {
                // The entry whose file holds the node: its parts and lights follow.
                let object = scene
                    .objects
                    .iter()
                    .position(|o| o.node.is_some_and(|n| scene.group_within(n, group)))
                    .ok_or(EditError::NoSuchGroup(group))?;
                (vec![(object, scene.objects[object].placement)], Vec::new())
            }
        };
        let entries = self
            .placed_entries(&placed, &objects, &lights)
            .map_err(|e| edit_error(e, &name))?
            .ok_or(EditError::NoSuchGroup(group))?;
        entries.apply(&mut placed);
        *scene = placed;
        Ok(())
    }

    /// The entries within `scene`'s group `group` (one object of each: a mesh entry places
    /// all its parts together), with their placements, and the lights placed in it or in
    /// a group within it.
    fn entries_within(
        &self,
        scene: &Scene,
        group: usize,
    ) -> (Vec<(usize, ObjectPlacement)>, Vec<usize>) {
        let mut entries = Vec::new();
        let mut objects = Vec::new();
        for (i, o) in scene.objects.iter().enumerate() {
            let within = o.group.is_some_and(|g| scene.group_within(g, group));
            let entry = self.origins.get(i).map(|o| (o.table, o.index));
            if within && !entries.contains(&entry) {
                entries.push(entry);
                objects.push((i, o.placement));
            }
        }
        let lights = (0..scene.groups.len())
            .filter(|&g| scene.group_within(g, group))
            .flat_map(|g| scene.groups[g].lights.iter().copied())
            .collect();
        (objects, lights)
    }
}
