//! The panel's File section: the scene file's name and state, Save, Save as, Open (with the
//! recent files), Reload, Undo and Redo.

use super::{Changes, PanelState};
use egui::RichText;
use std::path::PathBuf;

impl PanelState {
    pub(super) fn file_section(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        ui.label(RichText::new("File").strong());
        let name = match &self.file.path {
            Some(p) => p.display().to_string(),
            None => prism::seed::NAME.to_string(),
        };
        let unsaved = if self.file.unsaved { " (edited)" } else { "" };
        ui.label(format!("{name}{unsaved}"));
        ui.horizontal(|ui| {
            let saveable = self.file.path.is_some() && self.file.error.is_none();
            if ui
                .add_enabled(saveable, egui::Button::new("Save"))
                .on_hover_text("Ctrl+S: write the edits and the camera into the file")
                .clicked()
            {
                changes.save = true;
            }
            if ui
                .add_enabled(self.file.can_undo, egui::Button::new("Undo"))
                .clicked()
            {
                changes.undo = true;
            }
            if ui
                .add_enabled(self.file.can_redo, egui::Button::new("Redo"))
                .clicked()
            {
                changes.redo = true;
            }
            if ui
                .add_enabled(self.file.path.is_some(), egui::Button::new("Reload"))
                .clicked()
            {
                changes.reload = true;
            }
        });
        if let Some((frames, fps)) = self.file.animation {
            ui.horizontal(|ui| {
                let last = frames - 1;
                let mut frame = self.file.frame.min(last);
                ui.label("frame");
                if ui
                    .add_enabled(frame > 0, egui::Button::new("<").small())
                    .on_hover_text("the frame before")
                    .clicked()
                {
                    frame -= 1;
                }
                ui.add(egui::DragValue::new(&mut frame).range(0..=last));
                if ui
                    .add_enabled(frame < last, egui::Button::new(">").small())
                    .on_hover_text("the next frame")
                    .clicked()
                {
                    frame += 1;
                }
                ui.label(format!("of 0–{last}, {fps} fps"));
                if frame != self.file.frame {
                    changes.frame = Some(frame);
                }
            });
        }
        ui.horizontal(|ui| {
            ui.add(
                egui::TextEdit::singleline(&mut self.path_entry)
                    .hint_text("path/to/scene.toml")
                    .desired_width(150.0),
            );
            let path = || PathBuf::from(self.path_entry.trim());
            let typed = !self.path_entry.trim().is_empty();
            if ui.add_enabled(typed, egui::Button::new("Open")).clicked() {
                changes.open = Some(path());
            }
            if ui
                .add_enabled(typed, egui::Button::new("Save as"))
                .clicked()
            {
                changes.save_as = Some(path());
            }
        });
        // Collapsed, so that the panel's layout does not shift with the list's length.
        egui::CollapsingHeader::new("Recent files (or drop a file on the window)")
            .default_open(false)
            .show(ui, |ui| {
                for p in self.file.recent.clone() {
                    if ui.small_button(p.display().to_string()).clicked() {
                        changes.open = Some(p);
                    }
                }
            });
    }
}
