//! Edits: the panel's changes applied to the scene and sent to the render thread, each kept
//! in the history so that Ctrl+Z and Ctrl+Shift+Z undo and redo it.

use super::app::App;
use super::history::EditKey;
use super::panel;
use super::render_thread::Request;
use prism::scene::{EditError, Scene};
use prism::scene_file::LoadedScene;
use std::time::Instant;

impl App {
    /// Sends what the panel changed to the render thread, and does what it asked.
    pub(super) fn apply(&mut self, changes: panel::Changes) {
        let now = Instant::now();
        let mut edits = changes.edits;
        // The entries are validated again with these values, as a load of the file would be.
        if let Some((object, placement, field)) = changes.place {
            let key = EditKey(format!("object {object} {field}"));
            self.place(&mut edits, key, |loaded, scene| {
                loaded.place_object(scene, object, placement)
            });
        }
        if let Some((group, placement, field)) = changes.place_group {
            let key = EditKey(format!("group {group} {field}"));
            self.place(&mut edits, key, |loaded, scene| {
                loaded.place_group(scene, group, placement)
            });
        }
        let edited = !edits.is_empty();
        for (key, before) in edits {
            self.history.record(&before, key, now);
        }
        if edited {
            self.send_scene();
        }
        let Some(g) = &self.gfx else { return };
        if let Some(selection) = changes.select {
            g.render.send(Request::Select(selection));
        }
        if let Some(view) = changes.view {
            g.render.send(Request::View(view));
        }
        if let Some(on) = changes.denoise {
            g.render.send(Request::Denoise(on));
        }
        if changes.camera {
            self.send_camera(false);
        }
        if changes.settings {
            let (iw, ih) = g.image_size();
            let generation = g.render.send(Request::Settings(self.settings(iw, ih)));
            if let Some(t) = &mut self.timing {
                t.sent(generation, "settings");
            }
        }
        if changes.screenshot {
            self.screenshot();
        }
        if changes.save {
            self.save();
        }
        if let Some(path) = changes.save_as {
            self.save_as(path);
        }
        if let Some(path) = changes.open {
            self.open(path);
        }
        if changes.reload {
            self.reload();
        }
        if let Some(frame) = changes.frame {
            // The file is loaded again at the frame: unsaved edits are one undo away, as
            // for any reload.
            self.document.set_frame(frame);
            self.reload();
        }
        if changes.undo {
            self.undo();
        }
        if changes.redo {
            self.redo();
        }
    }

    /// The panel's scene to the render thread (which rebuilds only what changed).
    pub(super) fn send_scene(&mut self) {
        if let Some(g) = &self.gfx {
            let generation = g
                .render
                .send(Request::Scene(Box::new(self.panel.scene.clone())));
            if let Some(t) = &mut self.timing {
                t.sent(generation, "edit");
            }
        }
    }

    pub(super) fn undo(&mut self) {
        match self.history.undo(&self.panel.scene) {
            Some(scene) => {
                self.panel.set_scene(scene);
                self.send_scene();
                self.say("undid the last edit".into(), false);
            }
            None => self.say("nothing to undo".into(), false),
        }
    }

    pub(super) fn redo(&mut self) {
        match self.history.redo(&self.panel.scene) {
            Some(scene) => {
                self.panel.set_scene(scene);
                self.send_scene();
                self.say("redid the edit".into(), false);
            }
            None => self.say("nothing to redo".into(), false),
        }
    }

    /// Places entries anew by `place` (of the loaded file), noting the edit in `edits` as
    /// `key` when it changed the scene and showing why when it was refused.
    fn place(
        &mut self,
        edits: &mut Vec<(EditKey, Scene)>,
        key: EditKey,
        place: impl FnOnce(&LoadedScene, &mut Scene) -> Result<(), EditError>,
    ) {
        let Some(loaded) = &self.document.loaded else {
            return;
        };
        let before = self.panel.scene.clone();
        match place(loaded, &mut self.panel.scene) {
            Ok(()) if self.panel.scene != before => edits.push((key, before)),
            Ok(()) => {}
            Err(e) => self.panel.message = Some((e.to_string(), true)),
        }
    }
}
