//! The panel's objects: the list to pick from, and the selection's material (colour or
//! texture, Phong factors, mirror, glass, emission, relief) and place (translate, rotate, scale).

use super::widgets::{color_row, position_row, scale_text, texture_kind, xyz};
use super::{Changes, PanelState, SLIDERS};
use egui::{DragValue, RichText, Slider, SliderClamping};
use glam::DVec3;
use prism::appearance::{Relief, Texture};
use prism::limits::{MAX_PHONG_FACTOR, MAX_RADIANCE, MAX_SHININESS};
use prism::scene::{GroupKind, ObjectPlacement};

/// The depth of a material's bumps or the strength of its normal map, when it has one;
/// the field changed, if one was.
fn relief_row(ui: &mut egui::Ui, relief: &mut Option<Relief>) -> Option<&'static str> {
    let (value, range, name, field, hint) = match relief {
        Some(Relief::Bump { depth, .. }) => (
            depth,
            prism::limits::BUMP_DEPTH,
            "bump depth ",
            "bump_depth",
            "How far the bump map's white stands above its black, in scene units (0: flat)",
        ),
        Some(Relief::NormalMap { strength, .. }) => (
            strength,
            prism::limits::NORMAL_STRENGTH,
            "normal strength ",
            "normal_strength",
            "What the normal map's tilt is multiplied by (0: flat, 1: the picture's own)",
        ),
        None => return None,
    };
    // A hundredth of the value per pixel dragged, whatever the scene's scale.
    let speed = (*value as f64 * 0.01).max(1e-4);
    let r = ui
        .add(
            DragValue::new(value)
                .range(range)
                .speed(speed)
                .max_decimals(5)
                .prefix(name),
        )
        .on_hover_text(hint);
    r.changed().then_some(field)
}

impl PanelState {
    /// The list of objects, and the selected one's material.
    pub(super) fn objects(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        ui.label(RichText::new("Objects").strong());
        egui::ScrollArea::vertical()
            .id_salt("objects")
            .max_height(110.0)
            .show(ui, |ui| {
                for (i, o) in self.scene.objects.iter().enumerate() {
                    let picked = self.selected == Some(i);
                    if ui.selectable_label(picked, &o.name).clicked() {
                        let new = if picked { None } else { Some(i) };
                        self.selected = new;
                        changes.select = Some(new);
                    }
                }
            });
        let Some(i) = self.selected else {
            ui.small("Click an object in the image or the list to edit it.");
            return;
        };
        ui.label(RichText::new(format!("Selected: {}", self.scene.objects[i].name)).strong());
        // What the transform rows place: the object, or one of the groups it is in (for a
        // part of a glTF file, its nodes first, then its entry's groups).
        let object = &self.scene.objects[i];
        let mut chain = self.scene.group_chain(object.node);
        chain.extend(self.scene.group_chain(object.group));
        let mut target = self
            .placing_group
            .filter(|(object, g)| *object == i && chain.contains(g))
            .map(|(_, g)| g);
        if !chain.is_empty() {
            ui.horizontal_wrapped(|ui| {
                ui.label("place").on_hover_text(
                    "The transform rows edit the object's own placement, or that of a group \
                     it is in (innermost first): everything in the group follows. A glTF \
                     file's nodes come first; the object's own placement places its whole \
                     file",
                );
                ui.radio_value(&mut target, None, "object");
                for &g in &chain {
                    let group = &self.scene.groups[g];
                    let kind = match group.kind {
                        GroupKind::Entry => "group",
                        GroupKind::FileNode => "node",
                    };
                    ui.radio_value(&mut target, Some(g), format!("{kind} {}", group.name));
                }
            });
        }
        self.placing_group = target.map(|g| (i, g));
        let before = match target {
            Some(g) => self.scene.groups[g].placement,
            None => self.scene.objects[i].placement,
        };
        if let Some((p, field)) = self.placement_rows(ui, before) {
            match target {
                Some(g) => changes.place_group = Some((g, p, field)),
                None => changes.place = Some((i, p, field)),
            }
        }
        let mut m = self.scene.objects[i].material.clone();
        let before = m.clone();
        let mut field = "";
        match &mut m.texture {
            Texture::Solid(c) => {
                if color_row(ui, "colour", c, 0.0..=1.0, true) {
                    field = "color";
                }
            }
            other => {
                ui.label(format!("colour: {} texture", texture_kind(other)));
            }
        }
        let factors: [(&str, &mut f32, f32, f32); 4] = [
            ("ambient", &mut m.ambient, MAX_PHONG_FACTOR, 0.01),
            ("diffuse", &mut m.diffuse, MAX_PHONG_FACTOR, 0.01),
            ("specular", &mut m.specular, MAX_PHONG_FACTOR, 0.01),
            ("shininess", &mut m.shininess, MAX_SHININESS, 1.0),
        ];
        ui.horizontal_wrapped(|ui| {
            for (name, v, hi, speed) in factors {
                let r = ui.add(
                    DragValue::new(v)
                        .range(0.0..=hi)
                        .speed(speed)
                        .prefix(format!("{name} ")),
                );
                if r.changed() {
                    field = name;
                }
            }
        });
        for (name, v) in [
            ("reflectivity", &mut m.reflectivity),
            ("transparency", &mut m.transparency),
        ] {
            let r = ui.add(
                Slider::new(v, SLIDERS.transparency)
                    .clamping(SliderClamping::Always)
                    .text(name),
            );
            if r.changed() {
                field = name;
            }
        }
        let mut refracts = m.eta.is_some();
        let mut eta = m.eta.unwrap_or(1.5);
        ui.horizontal(|ui| {
            let c = ui.checkbox(&mut refracts, "");
            let r = ui.add_enabled(
                refracts,
                // The whole range a file may give, on a log scale centred on 1.
                Slider::new(&mut eta, SLIDERS.eta)
                    .logarithmic(true)
                    .clamping(SliderClamping::Always)
                    .max_decimals(4)
                    .text("eta"),
            );
            if c.changed() || r.changed() {
                field = "eta";
            }
        });
        m.eta = refracts.then_some(eta);
        if !refracts {
            m.fresnel = false;
        }
        let reflects = m.reflectivity > 0.0 || m.fresnel;
        let r = ui.add_enabled(
            reflects,
            Slider::new(&mut m.roughness, prism::limits::ROUGHNESS)
                .clamping(SliderClamping::Always)
                .text("roughness"),
        );
        if r.changed() {
            field = "roughness";
        }
        if !reflects {
            m.roughness = 0.0;
        }
        let glass = matches!(m.eta, Some(e) if e != 1.0) && m.conductor.is_none();
        let r = ui.add_enabled(glass, egui::Checkbox::new(&mut m.fresnel, "Fresnel glass"));
        if r.changed() {
            field = "fresnel";
        }
        if color_row(ui, "emission", &mut m.emission, 0.0..=MAX_RADIANCE, false) {
            field = "emission";
        }
        if let Some(f) = relief_row(ui, &mut m.relief) {
            field = f;
        }
        if m != before {
            self.edit(changes, format!("object {i} {field}"), |s| {
                s.set_material(i, m)
            });
        }
    }
    /// The `translate`, `rotate` and `scale` rows of an entry placed as `before` (an
    /// object's or a group's, in its own frame); the new placement and the field changed,
    /// if one was.
    fn placement_rows(
        &mut self,
        ui: &mut egui::Ui,
        before: ObjectPlacement,
    ) -> Option<(ObjectPlacement, &'static str)> {
        let mut p = before;
        position_row(ui, "translate", &mut p.translate);
        ui.horizontal(|ui| {
            ui.label("rotate °").on_hover_text(
                "The file's `rotate`: degrees about x, then y, then z, about the origin of \
                 the entry's frame (its group's, or the world's), after the scale and before \
                 the move",
            );
            let r = &mut p.rotate;
            // Any finite angle, as in the file: placing the entry refuses the rest.
            xyz(ui, [&mut r.x, &mut r.y, &mut r.z], |d| d.speed(0.5));
        });
        ui.horizontal(|ui| {
            ui.label("scale").on_hover_text(
                "The file's `scale`: about the origin of the entry's frame, before the turn \
                 and the move",
            );
            fn factor(d: DragValue<'_>) -> DragValue<'_> {
                d.range(prism::limits::SCALE)
                    .speed(0.01)
                    .custom_formatter(|v, _| scale_text(v))
            }
            let even = p.scale.x == p.scale.y && p.scale.y == p.scale.z;
            if even && !self.scale_per_axis {
                let mut k = p.scale.x;
                if ui.add(factor(DragValue::new(&mut k))).changed() {
                    p.scale = DVec3::splat(k);
                }
            } else {
                let s = &mut p.scale;
                xyz(ui, [&mut s.x, &mut s.y, &mut s.z], factor);
            }
            let mut per_axis = self.scale_per_axis || !even;
            if ui
                .add_enabled(even, egui::Checkbox::new(&mut per_axis, "per axis"))
                .changed()
            {
                self.scale_per_axis = per_axis;
            }
        });
        let field = if p.translate != before.translate {
            "translate"
        } else if p.rotate != before.rotate {
            "rotate"
        } else {
            "scale"
        };
        (p != before).then_some((p, field))
    }
}
