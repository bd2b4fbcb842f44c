//! The validator every table's reader uses: where a problem is (the file, the line of the
//! field, the entry's name), and the checks values of any table share (finite numbers,
//! lengths, ranges, points, positions relative to the camera, colours, counts).

use super::assets::Assets;
use super::error::SceneError;
use super::error::line_column;
use super::fixed_array::Fixed;
use super::spans::FieldSpans;
use crate::appearance::Material;
use crate::limits;
use crate::messages::{outside_color_range, outside_length, outside_range};
use glam::Vec3;
use std::ops::Range;
use std::path::PathBuf;

pub(super) type V3 = Fixed<f32, 3>;
/// Positions are read in f64 and stored relative to the scene origin (see `Scene`).
pub(super) type P3 = Fixed<f64, 3>;

pub(super) struct Validator<'a> {
    pub(super) path: PathBuf,
    pub(super) source: &'a str,
    /// Where every key and value lies in `source`.
    pub(super) spans: FieldSpans<'a>,
    pub(super) assets: Assets<'a>,
    /// The camera's eye, in f64: positions are stored relative to it.
    pub(super) origin: glam::DVec3,
    /// The files the scene names that have been looked for, in order (from a folder only).
    pub(super) reads: std::cell::RefCell<Vec<PathBuf>>,
    /// The file's `[materials]`, once read: what CSG members name. (Unset when an entry is
    /// placed again for an edit, which keeps its members' materials.)
    pub(super) materials: std::cell::OnceCell<std::collections::HashMap<String, Material>>,
    /// The file's `[[groups]]`, once read (an edit's placements in them): what entries'
    /// `group` names.
    pub(super) groups: std::cell::OnceCell<Vec<crate::scene::SceneGroup>>,
}

/// Where a problem is: the span of the table it is in, and how to name that table.
pub(super) struct Item<'s> {
    pub(super) span: Range<usize>,
    pub(super) name: &'s str,
}

impl Validator<'_> {
    /// An error in table `at`, pointing at the line of `field` (or of the element
    /// `field[i]` names) when the table has it, else at the table.
    pub(super) fn field_error(
        &self,
        at: &Item,
        field: &str,
        message: impl Into<String>,
    ) -> SceneError {
        match self.spans.field(at.span.start, field) {
            Some(span) => {
                let at = Item {
                    span,
                    name: at.name,
                };
                self.error(&at, message)
            }
            None => self.error(at, message),
        }
    }

    pub(super) fn error(&self, at: &Item, message: impl Into<String>) -> SceneError {
        let (line, _) = line_column(self.source, at.span.start);
        SceneError::Invalid {
            path: self.path.clone(),
            line,
            item: at.name.to_string(),
            message: message.into(),
        }
    }

    pub(super) fn number(&self, at: &Item, field: &str, v: f32) -> Result<f32, SceneError> {
        self.in_range(at, field, v, f32::NEG_INFINITY, f32::INFINITY)
    }

    /// A radius, height or pattern size: positive, and within the lengths the tracer's
    /// squares and products keep finite (limits.rs).
    pub(super) fn length(&self, at: &Item, field: &str, v: f32) -> Result<f32, SceneError> {
        match outside_length(field, v) {
            Some(message) => Err(self.field_error(at, field, message)),
            None => Ok(v),
        }
    }

    pub(super) fn in_range(
        &self,
        at: &Item,
        field: &str,
        v: f32,
        lo: f32,
        hi: f32,
    ) -> Result<f32, SceneError> {
        match outside_range(field, v, &(lo..=hi)) {
            Some(message) => Err(self.field_error(at, field, message)),
            None => Ok(v),
        }
    }

    pub(super) fn point(&self, at: &Item, field: &str, v: V3) -> Result<Vec3, SceneError> {
        if v.iter().all(|c| c.is_finite()) {
            Ok(Vec3::from(v))
        } else {
            Err(self.field_error(
                at,
                field,
                format!("`{field}` must hold finite numbers, got {v:?}"),
            ))
        }
    }

    /// A position, relative to the scene origin (the camera), within `MAX_COORDINATE` of it.
    pub(super) fn position(&self, at: &Item, field: &str, v: P3) -> Result<Vec3, SceneError> {
        let relative = glam::DVec3::from(v) - self.origin;
        if relative.is_finite() && relative.abs().max_element() <= limits::MAX_COORDINATE {
            Ok(relative.as_vec3())
        } else {
            Err(self.field_error(
                at,
                field,
                format!(
                    "`{field}` must hold finite numbers within {:e} of the camera on every \
                     axis, got {v:?}",
                    limits::MAX_COORDINATE
                ),
            ))
        }
    }

    /// A colour whose channels lie in [0, hi]; `why` says why hi is the bound.
    pub(super) fn color_up_to(
        &self,
        at: &Item,
        field: &str,
        v: V3,
        hi: f32,
        why: &str,
    ) -> Result<Vec3, SceneError> {
        match outside_color_range(field, v.0, hi, why) {
            Some(message) => Err(self.field_error(at, field, message)),
            None => Ok(Vec3::from(v)),
        }
    }

    /// A surface's colour: the fraction of light it reflects, per channel.
    pub(super) fn reflectance(&self, at: &Item, field: &str, v: V3) -> Result<Vec3, SceneError> {
        let hi = *limits::REFLECTANCE.end();
        self.color_up_to(at, field, v, hi, limits::REFLECTANCE_BOUND)
    }

    /// A light's colour, the background, the ambient light: brighter than white is allowed.
    pub(super) fn radiance(&self, at: &Item, field: &str, v: V3) -> Result<Vec3, SceneError> {
        self.color_up_to(at, field, v, limits::MAX_RADIANCE, limits::RADIANCE_BOUND)
    }

    pub(super) fn count(
        &self,
        at: &Item,
        field: &str,
        v: i64,
        lo: i64,
        hi: i64,
    ) -> Result<u32, SceneError> {
        if (lo..=hi).contains(&v) {
            Ok(v as u32)
        } else {
            Err(self.field_error(
                at,
                field,
                format!("`{field}` must lie in {lo}..={hi}, got {v}"),
            ))
        }
    }

    /// Where asset `rel` is, noted as read.
    pub(super) fn locate(&self, rel: &str) -> PathBuf {
        let path = self.assets.locate(rel);
        if self.assets.on_disk() {
            self.reads.borrow_mut().push(path.clone());
        }
        path
    }
}
