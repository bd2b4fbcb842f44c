//! The rows several sections share: a colour with its picker, x/y/z fields, a position, a
//! scale factor shown as it is, a texture's kind.

use egui::DragValue;
use glam::{DVec3, Vec3};
use prism::appearance::Texture;
use prism::limits::MAX_COORDINATE;
use std::ops::RangeInclusive;

/// Three numbers for a colour (within `range` per channel) with, for a reflectance
/// (`picker`), egui's colour picker beside them; true when any changed.
pub(super) fn color_row(
    ui: &mut egui::Ui,
    label: &str,
    c: &mut Vec3,
    range: RangeInclusive<f32>,
    picker: bool,
) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        let mut changed = false;
        if picker {
            let mut rgb = c.to_array();
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                *c = Vec3::from_array(rgb)
                    .clamp(Vec3::splat(*range.start()), Vec3::splat(*range.end()));
                changed = true;
            }
        }
        for (v, name) in [(&mut c.x, "r "), (&mut c.y, "g "), (&mut c.z, "b ")] {
            let r = ui.add(
                DragValue::new(v)
                    .range(range.clone())
                    .speed(0.005)
                    .max_decimals(4)
                    .prefix(name),
            );
            changed |= r.changed();
        }
        changed
    })
    .inner
}

/// A scale factor as the panel shows it: three decimals, and tiny factors (which a typed 0
/// is clamped to) in exponent form rather than as "0.000".
pub(super) fn scale_text(v: f64) -> String {
    if v != 0.0 && v.abs() < 0.01 {
        format!("{v:.2e}")
    } else {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Three numbers named x, y and z, each styled by `style`; true when one changed.
pub(super) fn xyz<N: egui::emath::Numeric>(
    ui: &mut egui::Ui,
    values: [&mut N; 3],
    style: impl Fn(DragValue<'_>) -> DragValue<'_>,
) -> bool {
    let mut changed = false;
    for (v, name) in values.into_iter().zip(["x ", "y ", "z "]) {
        changed |= ui.add(style(DragValue::new(v)).prefix(name)).changed();
    }
    changed
}

/// A position in world coordinates; true when it changed.
pub(super) fn position_row(ui: &mut egui::Ui, label: &str, p: &mut DVec3) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        xyz(ui, [&mut p.x, &mut p.y, &mut p.z], |d| {
            d.range(-MAX_COORDINATE..=MAX_COORDINATE).speed(0.05)
        })
    })
    .inner
}

pub(super) fn texture_kind(t: &Texture) -> &'static str {
    match t {
        Texture::Solid(_) => "solid",
        Texture::Checker { .. } => "checker",
        Texture::Stripes { .. } => "stripes",
        Texture::Pattern(pattern) => pattern.kind.name(),
        Texture::Image { .. } => "image",
    }
}
