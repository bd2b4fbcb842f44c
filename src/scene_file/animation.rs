//! Animation: an `[animation]` table of frames and tracks, each track a field of one table
//! of the scene file (the camera's `eye`, an object's `rotate`, a light's `intensity`, a
//! material's `color`) given at keyframes and interpolated between them.
//!
//! A frame is made by writing each track's value at that frame into a copy of the scene
//! file's parse tree (the text is parsed once, frames.rs) and validating the result as any
//! scene file is, so an animated value obeys every bound the file's own values do, and a
//! frame that breaks one is refused with its number.
//! Positions and numbers follow a Catmull-Rom spline through the keys (its tangents scaled
//! by the keys' spacing in frames, so uneven keys keep an even speed); a `rotate` turns
//! along the shortest arc between keys (quaternion slerp); `linear` and `step` do what
//! they say (a linear `rotate` spins through every degree between its keys: a turntable).

use super::error::{SceneError, line_column, syntax_error};
use super::kinds::object_kinds;
use super::parse_tree::ParsedText;
use crate::limits;
use glam::{DQuat, EulerRot};
use serde::Deserialize;
use std::path::Path;
use std::sync::Arc;
use toml::Spanned;
use toml_edit::{DocumentMut, Item, TableLike, Value};

/// The names of the object kinds' tables (kinds.rs).
macro_rules! table_names {
    ($($table:ident: $def:ty, $($how:ident)+;)*) => {
        [$(stringify!($table)),*]
    };
}

/// The tables of the scene file that hold objects, each an array of tables, in the file's
/// order (kinds.rs).
pub const OBJECT_TABLES: &[&str] = &object_kinds!(table_names);

/// The tables whose entries a track may name by their `name`: the objects' and `groups`.
fn named_tables() -> impl Iterator<Item = &'static str> {
    OBJECT_TABLES.iter().copied().chain(["groups"])
}

/// How a track moves between its keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// Catmull-Rom through the keys; the shortest arc for a `rotate`.
    Smooth,
    /// Straight lines between keys (for a `rotate`, every angle in between).
    Linear,
    /// Each key's value holds until the next.
    Step,
}

/// One keyframe: a value at a frame (a number, or a list of numbers).
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    /// The frame it is at (may lie between or beyond the frames rendered).
    pub frame: f64,
    /// Its value's numbers.
    pub value: Vec<f64>,
}

/// One field of one table, keyed.
#[derive(Clone, Debug, PartialEq)]
pub struct Track {
    /// The table: `camera`, `render`, `fog`, `lights[i]`, `materials.NAME`, an object's
    /// or a group's name, or `TABLE[i]` (`spheres[2]`, `groups[0]`).
    pub target: String,
    /// The field of that table.
    pub field: String,
    /// How it moves between keys.
    pub interpolation: Interpolation,
    /// The keys, in increasing frame order.
    pub keys: Vec<Key>,
    /// Whether the value is a single number (else a list).
    scalar: bool,
    /// `target` as a table and index where it names an object (see `canonical`).
    place: String,
}

/// A scene's animation.
#[derive(Clone, Debug)]
pub struct Animation {
    /// Frames 0 to `frames − 1` are rendered.
    pub frames: u32,
    /// Frames a second, for a video made of the frames.
    pub fps: f64,
    /// The tracks.
    pub tracks: Vec<Track>,
    /// The scene file as written but for the tracks' keys, parsed once for every frame.
    written: Arc<ParsedText>,
}

#[derive(Deserialize)]
struct WithAnimation {
    animation: Option<Spanned<AnimationDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AnimationDef {
    frames: i64,
    fps: Option<f64>,
    #[serde(default)]
    track: Vec<Spanned<TrackDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TrackDef {
    target: Spanned<String>,
    field: String,
    interpolation: Option<String>,
    keys: Vec<Spanned<KeyDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct KeyDef {
    frame: f64,
    value: toml::Value,
}

impl Animation {
    /// The animation of the scene text `source` (named `path` in messages); None when it
    /// has no `[animation]` table, or does not parse as TOML (which the scene loader
    /// reports).
    pub fn parse(source: &str, path: &Path) -> Result<Option<Self>, SceneError> {
        let Ok(file) = toml::from_str::<WithAnimation>(source) else {
            // Either not TOML, or an `[animation]` of the wrong shape: parse it alone for
            // the message, or leave a syntax error to the scene loader.
            return match toml::from_str::<toml::Table>(source) {
                Ok(table) if table.contains_key("animation") => {
                    let e = toml::from_str::<WithAnimation>(source)
                        .err()
                        .expect("it failed");
                    Err(syntax_error(source, path, e.span(), e.message()))
                }
                _ => Ok(None),
            };
        };
        let Some(def) = file.animation else {
            return Ok(None);
        };
        let Ok(document) = source.parse::<DocumentMut>() else {
            return Ok(None);
        };
        let at =
            |span: std::ops::Range<usize>, item: String, message: String| SceneError::Invalid {
                path: path.to_path_buf(),
                line: line_column(source, span.start).0,
                item,
                message,
            };
        let span = def.span();
        let def = def.into_inner();
        if !(1..=limits::MAX_FRAMES as i64).contains(&def.frames) {
            return Err(at(
                span,
                "animation".into(),
                format!(
                    "`frames` must be 1 to {}, got {}",
                    limits::MAX_FRAMES,
                    def.frames
                ),
            ));
        }
        let fps = def.fps.unwrap_or(24.0);
        if !(fps.is_finite() && fps > 0.0 && fps <= 1000.0) {
            return Err(at(
                span,
                "animation".into(),
                format!(
                    "`fps` must be a number above 0, at most 1000, got {}",
                    crate::messages::number64(fps)
                ),
            ));
        }
        let mut document = document;
        let keys: usize = def.track.iter().map(|t| t.get_ref().keys.len()).sum();
        if keys > limits::MAX_KEYS {
            return Err(at(
                span,
                "animation".into(),
                format!(
                    "at most {} keys in all, over every track; got {keys}",
                    limits::MAX_KEYS
                ),
            ));
        }
        // The frames' text needs no keys (the tracks hold them now): each frame then
        // copies and reads the scene's tree, not its animation.
        without_keys(&mut document);
        // One copy to look targets up in (the lookup borrows the document mutably).
        let mut lookup = document.clone();
        let mut tracks: Vec<Track> = Vec::new();
        for (i, track) in def.track.into_iter().enumerate() {
            let span = track.span();
            let item = format!("animation.track[{i}]");
            let track = track.into_inner();
            let target_span = track.target.span();
            let fail = |message: String| at(span.clone(), item.clone(), message);
            let fail_at = |(place, message): (Option<std::ops::Range<usize>>, String)| {
                at(place.unwrap_or(span.clone()), item.clone(), message)
            };
            let parsed = Track::from_def(track).map_err(fail_at)?;
            let place = canonical(&document, &parsed.target);
            if let Some(other) = tracks
                .iter()
                .find(|t| t.place == place && t.field == parsed.field)
            {
                return Err(fail(format!(
                    "{}.{} already has a track; give each field one track",
                    other.target, other.field
                )));
            }
            // The target must exist now, so a typo is caught at load, not at some frame.
            target_table(&mut lookup, &parsed.target)
                .map_err(|message| at(target_span.clone(), item.clone(), message))?;
            let mut parsed = parsed;
            parsed.place = place;
            tracks.push(parsed);
        }
        Ok(Some(Animation {
            frames: def.frames as u32,
            fps,
            tracks,
            written: Arc::new(ParsedText::parse(document.to_string(), path)?),
        }))
    }

    /// The scene file's text as written, but for the tracks' keys (emptied, their lines
    /// kept): what validating the file as written reads, and every frame's text.
    pub fn written_source(&self) -> &str {
        self.written.text()
    }

    /// The parsed text of `written_source`.
    pub(super) fn written(&self) -> &ParsedText {
        &self.written
    }
}

impl Track {
    /// The track `def` describes, or what is wrong with it and where (a key's span; None
    /// for the track as a whole).
    fn from_def(def: TrackDef) -> Result<Self, (Option<std::ops::Range<usize>>, String)> {
        let whole = |message: String| (None, message);
        let interpolation = match def.interpolation.as_deref() {
            None | Some("smooth") => Interpolation::Smooth,
            Some("linear") => Interpolation::Linear,
            Some("step") => Interpolation::Step,
            Some(other) => {
                return Err(whole(format!(
                    "`interpolation` must be \"smooth\" (the default), \"linear\" or \
                     \"step\", got {}",
                    crate::messages::quoted(other)
                )));
            }
        };
        if def.field.is_empty() || def.field.contains(['.', '[', ']']) {
            return Err(whole(format!(
                "`field` names one field of the target's table (such as \"eye\" or \
                 \"rotate\"), got {}",
                crate::messages::quoted(&def.field)
            )));
        }
        if def.keys.is_empty() {
            return Err(whole("a track needs at least one key".into()));
        }
        let mut keys: Vec<Key> = Vec::with_capacity(def.keys.len());
        let mut scalar = None;
        for (k, key) in def.keys.into_iter().enumerate() {
            let place = Some(key.span());
            let fail = |message: String| Err((place.clone(), message));
            let key = key.into_inner();
            if !(key.frame.is_finite() && (0.0..=limits::MAX_FRAMES as f64).contains(&key.frame)) {
                return fail(format!(
                    "keys[{k}]: `frame` must be a number from 0 to {}, got {}",
                    limits::MAX_FRAMES,
                    crate::messages::number64(key.frame)
                ));
            }
            if let Some(before) = keys.last()
                && key.frame <= before.frame
            {
                return fail(format!(
                    "keys[{k}]: frame {} does not come after the key before it (frame {}): \
                     keys go in increasing frame order",
                    key.frame, before.frame
                ));
            }
            let Some((is_scalar, value)) = numbers(&key.value) else {
                return fail(format!(
                    "keys[{k}]: `value` must be a number or a list of numbers"
                ));
            };
            if value
                .iter()
                .any(|v| !v.is_finite() || v.abs() > limits::MAX_COORDINATE)
            {
                return fail(format!(
                    "keys[{k}]: `value` must hold finite numbers of at most {:e} in size, got \
                     {value:?}",
                    limits::MAX_COORDINATE
                ));
            }
            match scalar {
                None => scalar = Some((is_scalar, value.len())),
                Some(shape) if shape != (is_scalar, value.len()) => {
                    return fail(format!(
                        "keys[{k}]: `value` has another shape than the first key's (a \
                         number, or a list of as many numbers)"
                    ));
                }
                _ => {}
            }
            keys.push(Key {
                frame: key.frame,
                value,
            });
        }
        Ok(Track {
            target: def.target.into_inner(),
            field: def.field,
            interpolation,
            keys,
            scalar: scalar.expect("one key at least").0,
            place: String::new(),
        })
    }

    /// Whether the track turns its target: a `rotate` of three angles, interpolated along
    /// the shortest arc when smooth.
    fn is_rotation(&self) -> bool {
        self.field == "rotate" && !self.scalar && self.keys[0].value.len() == 3
    }

    /// The value at `frame` as TOML text: a number, or an array of numbers, each written
    /// so that it reads back as the same f64.
    pub(super) fn toml_at(&self, frame: u32) -> String {
        let number = |x: f64| {
            if x.is_nan() {
                "nan".to_string()
            } else {
                format!("{x:?}")
            }
        };
        let numbers = self.value_at(frame as f64);
        if self.scalar {
            number(numbers[0])
        } else {
            let items: Vec<String> = numbers.into_iter().map(number).collect();
            format!("[{}]", items.join(", "))
        }
    }

    /// The table the track writes, as `camera`, `materials.NAME` or `spheres[2]` (an
    /// object's name made its table and index, which no track can change).
    pub(super) fn place(&self) -> &str {
        &self.place
    }

    /// The value at `frame`: a key's own value at its frame, the first key's before it and
    /// the last key's after.
    pub fn value_at(&self, frame: f64) -> Vec<f64> {
        let keys = &self.keys;
        // The key at or before `frame`.
        let i = keys.partition_point(|k| k.frame <= frame);
        if i == 0 {
            return keys[0].value.clone();
        }
        let k1 = &keys[i - 1];
        if i == keys.len() || k1.frame == frame {
            return k1.value.clone();
        }
        let k2 = &keys[i];
        let u = (frame - k1.frame) / (k2.frame - k1.frame);
        match self.interpolation {
            Interpolation::Step => k1.value.clone(),
            Interpolation::Linear => lerp(&k1.value, &k2.value, u),
            Interpolation::Smooth if self.is_rotation() => {
                let (a, b) = (rotation(&k1.value), rotation(&k2.value));
                let (z, y, x) = a.slerp(b, u).to_euler(EulerRot::ZYX);
                vec![x.to_degrees(), y.to_degrees(), z.to_degrees()]
            }
            Interpolation::Smooth => {
                let before = (i >= 2).then(|| &keys[i - 2]);
                let after = keys.get(i + 1);
                catmull_rom(before, k1, k2, after, frame)
            }
        }
    }
}

/// The numbers of a TOML value: (whether it was a single number, the numbers).
fn numbers(value: &toml::Value) -> Option<(bool, Vec<f64>)> {
    let one = |v: &toml::Value| match v {
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::Float(f) => Some(*f),
        _ => None,
    };
    match value {
        toml::Value::Array(items) if !items.is_empty() && items.len() <= 16 => {
            Some((false, items.iter().map(one).collect::<Option<_>>()?))
        }
        other => Some((true, vec![one(other)?])),
    }
}

/// POV-Ray's `rotate [x, y, z]` (degrees; about x, then y, then z) as a quaternion.
fn rotation(degrees: &[f64]) -> DQuat {
    let [x, y, z] = [degrees[0], degrees[1], degrees[2]].map(f64::to_radians);
    DQuat::from_euler(EulerRot::ZYX, z, y, x)
}

fn lerp(a: &[f64], b: &[f64], u: f64) -> Vec<f64> {
    a.iter().zip(b).map(|(a, b)| a + (b - a) * u).collect()
}

/// The Catmull-Rom spline through k1 and k2 at `frame`, its tangents from the neighbouring
/// keys (each per frame, so keys spaced unevenly keep the speed even); at the first or last
/// key the tangent is the segment's own slope.
fn catmull_rom(
    before: Option<&Key>,
    k1: &Key,
    k2: &Key,
    after: Option<&Key>,
    frame: f64,
) -> Vec<f64> {
    let h = k2.frame - k1.frame;
    let u = (frame - k1.frame) / h;
    let (u2, u3) = (u * u, u * u * u);
    let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
    let h10 = u3 - 2.0 * u2 + u;
    let h01 = -2.0 * u3 + 3.0 * u2;
    let h11 = u3 - u2;
    (0..k1.value.len())
        .map(|c| {
            let slope = (k2.value[c] - k1.value[c]) / h;
            let m1 = before.map_or(slope, |k0| {
                (k2.value[c] - k0.value[c]) / (k2.frame - k0.frame)
            });
            let m2 = after.map_or(slope, |k3| {
                (k3.value[c] - k1.value[c]) / (k3.frame - k1.frame)
            });
            h00 * k1.value[c] + h10 * h * m1 + h01 * k2.value[c] + h11 * h * m2
        })
        .collect()
}

/// The table `target` names in the document, for editing.
fn target_table<'d>(
    document: &'d mut DocumentMut,
    target: &str,
) -> Result<&'d mut dyn TableLike, String> {
    let missing = |what: String| format!("`target` {}: {what}", crate::messages::quoted(target));
    let root = document.as_table_mut();
    if let Some(name) = target.strip_prefix("materials.") {
        let known: Vec<String> = root
            .get("materials")
            .and_then(Item::as_table_like)
            .map(|m| m.iter().map(|(k, _)| k.to_string()).collect())
            .unwrap_or_default();
        return root
            .get_mut("materials")
            .and_then(Item::as_table_like_mut)
            .and_then(|m| m.get_mut(name))
            .and_then(Item::as_table_like_mut)
            .ok_or_else(|| {
                missing(format!(
                    "no material named {}{}",
                    crate::messages::quoted(name),
                    crate::messages::did_you_mean(name, known.iter().map(String::as_str))
                ))
            });
    }
    if let Some((table, index)) = target.strip_suffix(']').and_then(|t| t.split_once('[')) {
        let index: usize = index
            .parse()
            .map_err(|_| missing("the index in [..] is not a whole number".into()))?;
        if table != "lights" && !named_tables().any(|t| t == table) {
            return Err(missing(format!(
                "an indexed target is lights[i], groups[i] or an object table's entry, such \
                 as spheres[0]; there is no table {}",
                crate::messages::quoted(table)
            )));
        }
        let count = entries(root.get(table)).len();
        return entry_mut(root.get_mut(table), index).ok_or_else(|| {
            let entries = if count == 1 { "entry" } else { "entries" };
            missing(format!("{table} has {count} {entries}, counted from 0"))
        });
    }
    if matches!(target, "camera" | "render" | "fog") {
        return root
            .get_mut(target)
            .and_then(Item::as_table_like_mut)
            .ok_or_else(|| missing(format!("the file has no [{target}] table")));
    }
    // An object's or a group's name: the one entry with `name = target`.
    let mut found = None;
    for table in named_tables() {
        for (i, entry) in entries(root.get(table)).into_iter().enumerate() {
            if entry.get("name").and_then(Item::as_str) == Some(target) {
                if let Some((other, j)) = found {
                    return Err(missing(format!(
                        "two entries have this name ({other}[{j}] and {table}[{i}]); name \
                         one by its table and index"
                    )));
                }
                found = Some((table, i));
            }
        }
    }
    let Some((table, i)) = found else {
        let names: Vec<String> = named_tables()
            .flat_map(|table| entries(root.get(table)))
            .filter_map(|entry| entry.get("name").and_then(Item::as_str).map(str::to_string))
            .collect();
        let hint = crate::messages::did_you_mean(target, names.iter().map(String::as_str));
        return Err(missing(format!(
            "no such table, object or group: a target is camera, render, fog, lights[i], \
             materials.NAME, an object's or a group's name, or its table and index \
             (spheres[0], groups[1]){hint}"
        )));
    };
    Ok(entry_mut(root.get_mut(table), i).expect("it was just found"))
}

/// `target` in a form that does not depend on any value a track may change: an object's
/// name becomes its table and index (a track may key another track's target's `name`).
fn canonical(document: &DocumentMut, target: &str) -> String {
    for table in named_tables() {
        for (i, entry) in entries(document.as_table().get(table))
            .into_iter()
            .enumerate()
        {
            if entry.get("name").and_then(Item::as_str) == Some(target) {
                return format!("{table}[{i}]");
            }
        }
    }
    target.to_string()
}

/// The entries of an array of tables (`[[spheres]]`) or an array of inline tables.
/// Empties every track's list of keys written as an array in `document`, keeping the
/// lines it took (as blank lines), so that every later line keeps its number for messages.
fn without_keys(document: &mut DocumentMut) {
    let Some(animation) = document
        .get_mut("animation")
        .and_then(|a| a.as_table_like_mut())
    else {
        return;
    };
    let Some(tracks) = animation.get_mut("track") else {
        return;
    };
    let count = entries(Some(tracks)).len();
    for i in 0..count {
        let Some(track) = entry_mut(Some(tracks), i) else {
            continue;
        };
        if let Some(keys) = track.get_mut("keys")
            && keys.is_array()
        {
            let lines = keys.to_string().matches('\n').count();
            let mut empty = Value::Array(toml_edit::Array::new());
            empty.decor_mut().set_prefix(" ");
            empty.decor_mut().set_suffix("\n".repeat(lines));
            *keys = Item::Value(empty);
        }
    }
}

fn entries(item: Option<&Item>) -> Vec<&dyn TableLike> {
    match item {
        Some(Item::ArrayOfTables(tables)) => tables.iter().map(|t| t as &dyn TableLike).collect(),
        Some(Item::Value(Value::Array(values))) => values
            .iter()
            .filter_map(|v| v.as_inline_table().map(|t| t as &dyn TableLike))
            .collect(),
        _ => Vec::new(),
    }
}

fn entry_mut(item: Option<&mut Item>, index: usize) -> Option<&mut dyn TableLike> {
    match item? {
        Item::ArrayOfTables(tables) => tables.get_mut(index).map(|t| t as &mut dyn TableLike),
        Item::Value(Value::Array(values)) => values
            .get_mut(index)?
            .as_inline_table_mut()
            .map(|t| t as &mut dyn TableLike),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_file::SceneFrames;
    use glam::DVec3;

    fn track(field: &str, interpolation: Interpolation, keys: &[(f64, &[f64])]) -> Track {
        Track {
            target: "camera".into(),
            field: field.into(),
            interpolation,
            scalar: keys[0].1.len() == 1 && field != "rotate",
            place: "camera".into(),
            keys: keys
                .iter()
                .map(|(frame, value)| Key {
                    frame: *frame,
                    value: value.to_vec(),
                })
                .collect(),
        }
    }

    #[test]
    fn smooth_tracks_pass_through_their_keys_and_keep_their_slope() {
        let t = track(
            "eye",
            Interpolation::Smooth,
            &[
                (0.0, &[0.0]),
                (10.0, &[4.0]),
                (30.0, &[0.0]),
                (40.0, &[1.0]),
            ],
        );
        for k in &t.keys {
            assert_eq!(t.value_at(k.frame), k.value, "exact at a key");
        }
        assert_eq!(t.value_at(-5.0), vec![0.0], "held before the first key");
        assert_eq!(t.value_at(99.0), vec![1.0], "and after the last");
        // C¹ at an inner key: the slope just before it equals the slope just after.
        let slope = |f: f64| (t.value_at(f + 1e-4)[0] - t.value_at(f - 1e-4)[0]) / 2e-4;
        let (left, right) = (
            (t.value_at(10.0)[0] - t.value_at(10.0 - 1e-5)[0]) / 1e-5,
            (t.value_at(10.0 + 1e-5)[0] - t.value_at(10.0)[0]) / 1e-5,
        );
        assert!((left - right).abs() < 1e-3, "{left} {right}");
        // The tangent at key 1 is the chord from key 0 to key 2, per frame: (0 − 0) / 30.
        assert!(slope(10.0).abs() < 1e-3, "{}", slope(10.0));
        // Keys on a line, however unevenly spaced, give that line.
        let line = track(
            "eye",
            Interpolation::Smooth,
            &[(0.0, &[1.0, 0.0]), (1.0, &[3.0, 0.0]), (7.0, &[15.0, 0.0])],
        );
        for f in [0.25, 0.5, 2.0, 4.5, 6.9] {
            let v = line.value_at(f);
            assert!((v[0] - (1.0 + 2.0 * f)).abs() < 1e-9, "{f}: {v:?}");
        }
    }

    #[test]
    fn linear_and_step_tracks() {
        let keys: &[(f64, &[f64])] = &[(0.0, &[0.0, 10.0]), (4.0, &[8.0, 10.0])];
        assert_eq!(
            track("eye", Interpolation::Linear, keys).value_at(1.0),
            vec![2.0, 10.0]
        );
        assert_eq!(
            track("eye", Interpolation::Step, keys).value_at(3.9),
            vec![0.0, 10.0]
        );
        assert_eq!(
            track("eye", Interpolation::Step, keys).value_at(4.0),
            vec![8.0, 10.0]
        );
    }

    /// Where a rotation of `degrees` (POV-Ray's convention) takes `v`.
    fn turn(degrees: &[f64], v: DVec3) -> DVec3 {
        rotation(degrees) * v
    }

    #[test]
    fn rotations_take_the_shortest_arc_or_spin_when_linear() {
        // POV-Ray's convention: +90 about y turns +x into −z.
        assert!((turn(&[0.0, 90.0, 0.0], DVec3::X) - DVec3::NEG_Z).length() < 1e-12);
        let smooth = track(
            "rotate",
            Interpolation::Smooth,
            &[(0.0, &[0.0, 10.0, 0.0]), (2.0, &[0.0, 350.0, 0.0])],
        );
        // From 10° to 350° the short way passes 0°, not 180°.
        let mid = smooth.value_at(1.0);
        assert!((turn(&mid, DVec3::X) - DVec3::X).length() < 1e-9, "{mid:?}");
        let quarter = track(
            "rotate",
            Interpolation::Smooth,
            &[(0.0, &[0.0, 0.0, 0.0]), (1.0, &[90.0, 0.0, 90.0])],
        );
        // Slerp turns at an even rate: halfway is half the angle of the whole turn.
        let whole = rotation(&[90.0, 0.0, 90.0]);
        let half = rotation(&quarter.value_at(0.5));
        assert!(
            (half.angle_between(DQuat::IDENTITY) - whole.angle_between(DQuat::IDENTITY) / 2.0)
                .abs()
                < 1e-9
        );
        assert!((half * half).abs_diff_eq(whole, 1e-9) || (half * half).abs_diff_eq(-whole, 1e-9));
        // A linear rotate spins through every angle between its keys: a turntable.
        let spin = track(
            "rotate",
            Interpolation::Linear,
            &[(0.0, &[0.0, 0.0, 0.0]), (4.0, &[0.0, 360.0, 0.0])],
        );
        assert_eq!(spin.value_at(2.0), vec![0.0, 180.0, 0.0]);
    }

    const SCENE: &str = r#"# A scene with an animation.
[camera]
eye = [0, 1, 8]    # the eye
look_at = [0, 1, 0]
fov = 40

[materials.red]
color = [0.8, 0.1, 0.1]

[[spheres]]
name = "ball"
center = [0, 1, 0]
radius = 1
material = "red"

[[lights]]
position = [5, 5, 5]

[animation]
frames = 10
fps = 5

[[animation.track]]
target = "camera"
field = "eye"
keys = [{ frame = 0, value = [0, 1, 8] }, { frame = 9, value = [8, 1, 0] }]

[[animation.track]]
target = "ball"
field = "rotate"
interpolation = "linear"
keys = [{ frame = 0, value = [0, 0, 0] }, { frame = 10, value = [0, 360, 0] }]

[[animation.track]]
target = "materials.red"
field = "color"
keys = [{ frame = 0, value = [0.8, 0.1, 0.1] }, { frame = 9, value = [0.1, 0.1, 0.8] }]
"#;

    #[test]
    fn a_frame_is_the_file_with_the_tracks_values_written_in() {
        let a = Animation::parse(SCENE, Path::new("a.toml"))
            .unwrap()
            .unwrap();
        assert_eq!((a.frames, a.fps, a.tracks.len()), (10, 5.0, 3));
        let still = SCENE
            .replace("eye = [0, 1, 8]", "eye = [8, 1, 0]")
            .replace("color = [0.8, 0.1, 0.1]", "color = [0.1, 0.1, 0.8]")
            .replace(
                "material = \"red\"",
                "material = \"red\"\nrotate = [0, 324, 0]",
            );
        let still = &still[..still.find("[animation]").unwrap()];
        let dir = Path::new(".");
        let assets = crate::scene_file::Assets::Folder(dir);
        let framed = a.scene_at(9, Path::new("a.toml"), assets).unwrap();
        let expected = crate::scene_file::parse_scene(still, Path::new("b.toml"), dir).unwrap();
        assert_eq!(framed, expected);
        // The loader takes an animated file at its first frame.
        let first = crate::scene_file::parse_scene(SCENE, Path::new("a.toml"), dir).unwrap();
        assert_eq!(
            first.camera.eye,
            glam::Vec3::ZERO,
            "positions are relative to the eye"
        );
    }

    #[test]
    fn a_file_loads_at_any_frame_clamped_to_its_last() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.toml");
        std::fs::write(&path, SCENE).unwrap();
        let frames = SceneFrames::load(&path).unwrap();
        let at = |n| {
            crate::scene_file::load_scene_file_at(&path, n)
                .result
                .unwrap()
        };
        assert_eq!(at(0).scene, frames.frame(0).unwrap());
        let six = at(6);
        assert_eq!((six.frame, six.scene), (6, frames.frame(6).unwrap()));
        let past = at(99);
        assert_eq!((past.frame, past.scene), (9, frames.frame(9).unwrap()));
        assert_eq!(past.animation.as_ref().map(|a| a.frames), Some(10));
        // A still file has only frame 0.
        let still = dir.path().join("b.toml");
        std::fs::write(&still, &SCENE[..SCENE.find("[animation]").unwrap()]).unwrap();
        let loaded = crate::scene_file::load_scene_file_at(&still, 5)
            .result
            .unwrap();
        assert_eq!(loaded.frame, 0);
        assert!(loaded.animation.is_none());
    }

    /// An animation's frames read its meshes and images once: with the files gone after
    /// the load, every frame still validates, and equals a fresh load of that frame.
    #[test]
    fn frames_read_their_files_once() {
        let dir = tempfile::tempdir().unwrap();
        let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        std::fs::write(dir.path().join("t.obj"), obj).unwrap();
        let image = image::RgbImage::from_pixel(4, 2, image::Rgb([200, 100, 50]));
        image.save(dir.path().join("t.png")).unwrap();
        let scene = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\
                     [textures.t]\ntype = \"image\"\npath = \"t.png\"\n\
                     [materials.m]\ntexture = \"t\"\n\
                     [[meshes]]\nname = \"m\"\npath = \"t.obj\"\nmaterial = \"m\"\n\
                     [animation]\nframes = 4\n[[animation.track]]\ntarget = \"m\"\n\
                     field = \"rotate\"\n\
                     keys = [{ frame = 0, value = [0, 0, 0] }, { frame = 3, value = [0, 90, 0] }]\n";
        let path = dir.path().join("a.toml");
        std::fs::write(&path, scene).unwrap();
        let fresh: Vec<_> = (0..4)
            .map(|f| {
                crate::scene_file::load_scene_file_at(&path, f)
                    .result
                    .unwrap()
                    .scene
            })
            .collect();
        let frames = SceneFrames::load(&path).unwrap();
        std::fs::remove_file(dir.path().join("t.obj")).unwrap();
        std::fs::remove_file(dir.path().join("t.png")).unwrap();
        for (f, scene) in fresh.iter().enumerate() {
            assert_eq!(&frames.frame(f as u32).unwrap(), scene, "frame {f}");
        }
        assert_ne!(fresh[0], fresh[3], "the frames differ");
    }

    /// Lines keep their numbers though the frames' text drops the keys: a bad value after
    /// an animation whose keys span many lines is reported at its own line.
    #[test]
    fn lines_after_the_keys_keep_their_numbers() {
        let text = format!(
            "{SCENE}\n[[animation.track]]\ntarget = \"ball\"\nfield = \"radius\"\nkeys = [\n\
             {{ frame = 0, value = 1 }},\n{{ frame = 5, value = 2 }},\n]\n\n\
             [[spheres]]\ncenter = [0, 0, 0]\nradius = -1\n"
        );
        let line = text.lines().position(|l| l == "radius = -1").unwrap() + 1;
        let e = crate::scene_file::parse_scene(&text, Path::new("a.toml"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&format!("a.toml:{line}: ")),
            "line {line}: {e}"
        );
        // The text the frames are made from keeps every line where it was.
        let a = Animation::parse(&text, Path::new("a.toml"))
            .unwrap()
            .unwrap();
        let written = a.written_source();
        assert_eq!(written.lines().count(), text.lines().count());
        assert_eq!(
            written.lines().position(|l| l == "radius = -1"),
            Some(line - 1)
        );
        assert!(
            !written.contains("value = 2"),
            "the keys are gone: {written}"
        );
    }

    /// A value a track overwrites is still checked as the file has it (the eye here).
    #[test]
    fn a_field_a_track_overwrites_is_checked_as_written() {
        let text = SCENE.replace("eye = [0, 1, 8]    # the eye", "eye = [nan, 1, 8]");
        assert_ne!(text, SCENE);
        let e = crate::scene_file::parse_scene(&text, Path::new("a.toml"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("a.toml:3: ") && e.contains("eye"), "{e}");
    }

    fn refusal(edit: (&str, &str)) -> String {
        let text = SCENE.replace(edit.0, edit.1);
        assert_ne!(text, SCENE, "the edit applies");
        match Animation::parse(&text, Path::new("a.toml")) {
            Err(e) => e.to_string(),
            Ok(_) => {
                match crate::scene_file::parse_scene(&text, Path::new("a.toml"), Path::new(".")) {
                    Err(e) => e.to_string(),
                    Ok(_) => panic!("accepted: {}", edit.1),
                }
            }
        }
    }

    #[test]
    fn bad_tracks_are_refused_with_their_line() {
        for (edit, needles) in [
            (
                ("target = \"ball\"", "target = \"bal\""),
                &["a.toml:29", "\"bal\"", "no such"][..],
            ),
            (
                ("target = \"materials.red\"", "target = \"materials.blue\""),
                &["no material named \"blue\""],
            ),
            (
                ("target = \"ball\"", "target = \"spheres[3]\""),
                &["spheres has 1 entry"],
            ),
            (
                (
                    "frame = 9, value = [8, 1, 0]",
                    "frame = 0, value = [8, 1, 0]",
                ),
                &["increasing frame order"],
            ),
            (("value = [8, 1, 0]", "value = [8, 1]"), &["another shape"]),
            (
                ("interpolation = \"linear\"", "interpolation = \"cubic\""),
                &["\"cubic\""],
            ),
            (("frames = 10", "frames = 0"), &["`frames` must be 1 to"]),
            (("fps = 5", "fps = -5"), &["`fps`"]),
            (
                (
                    "target = \"ball\"\nfield = \"rotate\"",
                    "target = \"camera\"\nfield = \"eye\"",
                ),
                &["camera.eye already has a track"],
            ),
            (
                ("field = \"eye\"", "field = \"eye\"\nspeed = 2"),
                &["unknown field `speed`"],
            ),
        ] {
            let e = refusal(edit);
            for n in needles {
                assert!(e.contains(n), "{edit:?}: expected {n:?} in {e}");
            }
        }
        // A track that keys another's target's name neither loses that target nor panics:
        // the frame is refused, since a name is text.
        let renamed = SCENE.replace(
            "[[animation.track]]\ntarget = \"ball\"",
            "[[animation.track]]\ntarget = \"ball\"\nfield = \"name\"\nkeys = [{ frame = 0, value = 1 }]\n\n[[animation.track]]\ntarget = \"ball\"",
        );
        assert_ne!(renamed, SCENE);
        let a = Animation::parse(&renamed, Path::new("a.toml"))
            .unwrap()
            .unwrap();
        let e = a.scene_at(
            3,
            Path::new("a.toml"),
            crate::scene_file::Assets::Folder(Path::new(".")),
        );
        assert!(e.unwrap_err().to_string().starts_with("frame 3: "));

        // A value out of bounds at some frame is refused there, with the frame and the field.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.toml");
        std::fs::write(
            &path,
            SCENE.replace("value = [0.1, 0.1, 0.8]", "value = [0.1, 0.1, 1.8]"),
        )
        .unwrap();
        let frames = SceneFrames::load(&path).unwrap();
        assert!(frames.frame(4).is_ok(), "still within bounds");
        let e = frames.frame(9).unwrap_err().to_string();
        assert!(
            e.contains("frame 9: ") && e.contains("a.toml:8") && e.contains("color"),
            "{e}"
        );
    }
}
