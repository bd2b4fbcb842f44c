//! A scene edited in the viewer, written back into the text of the file it came from. Only
//! the values that changed are rewritten; every other line, comment and blank keeps its
//! place (`toml_edit` keeps the file's layout).

use super::camera_table::camera_table;
use super::load::LoadedScene;
use crate::appearance::{
    Background, Falloff, Fog, FogKind, Light, LightKind, Material, Relief, Texture,
};
use crate::camera::Camera;
use crate::messages::shortest;
use crate::scene::{GroupKind, ObjectPlacement, Scene, ShapeDesc};
use glam::{DVec3, Vec3};
use std::collections::{BTreeMap, HashMap};
use thiserror::Error;
use toml_edit::{Array, DocumentMut, Item, Table, TableLike, Value};

/// Why the edited scene cannot be written into its file's text.
#[derive(Debug, Error, PartialEq)]
pub enum SaveError {
    /// The text no longer parses (it was read as a valid scene, so this is a bug).
    #[error("the scene file's text cannot be edited: {0}")]
    Parse(String),
    /// An entry the loader read is not where it was (a bug, or a file changed under us).
    #[error("the file has no {0} to write into")]
    Missing(String),
    /// The edited scene does not have the file's objects and lights.
    #[error("the scene shown no longer has the file's objects and lights; reload it first")]
    Mismatch,
}

/// The new text of a scene file, and the edits it could not hold.
#[derive(Debug)]
pub struct SavedText {
    /// The file's text with the edits in it.
    pub text: String,
    /// Edits the scene file cannot express, in words (a material taken from a mesh's MTL
    /// file, which prism does not write).
    pub skipped: Vec<String>,
}

/// The text of `loaded`'s file with `edited` (the loaded scene after edits) and `camera` in
/// it. The edited scene must have the loaded one's objects and lights in the same order.
pub fn saved_text(
    loaded: &LoadedScene,
    edited: &Scene,
    camera: &Camera,
) -> Result<SavedText, SaveError> {
    let mut doc: DocumentMut = loaded
        .source
        .parse()
        .map_err(|e: toml_edit::TomlError| SaveError::Parse(e.message().to_string()))?;
    let before = &loaded.scene;
    let same_parts = before.objects.len() == edited.objects.len()
        && before.lights.len() == edited.lights.len()
        && before.groups.len() == edited.groups.len()
        && before.objects.iter().zip(&edited.objects).all(|(a, b)| {
            // A placement edit may put a shape under a transform: the same kind still.
            let kind = |s: &ShapeDesc| match s {
                ShapeDesc::Transformed { shape, .. } => std::mem::discriminant(&**shape),
                other => std::mem::discriminant(other),
            };
            a.name == b.name && kind(&a.shape) == kind(&b.shape)
        });
    if !same_parts || loaded.origins.len() != before.objects.len() {
        return Err(SaveError::Mismatch);
    }
    let origin = before.origin;
    let mut skipped = Vec::new();
    if *camera != before.camera {
        write_camera(&mut doc, camera, origin)?;
        // The view is now the `[camera]` table's: no glTF camera chosen by a mesh entry
        // overrides it.
        if let Some(meshes) = doc.get_mut("meshes").and_then(Item::as_array_of_tables_mut) {
            for entry in meshes.iter_mut() {
                entry.remove("camera");
            }
        }
    }
    write_render(&mut doc, before, edited);
    if edited.fog != before.fog
        && let Some(fog) = &edited.fog
    {
        write_fog(&mut doc, fog)?;
    }
    // Lights past the file's own come from its glTF scenes, which prism does not write.
    let written_lights = match doc.get("lights") {
        Some(Item::ArrayOfTables(a)) => a.len(),
        Some(Item::Value(Value::Array(a))) => a.len(),
        _ => 0,
    };
    let moved_with_entries = file_lights_placed(loaded, edited);
    for (i, (was, now)) in before.lights.iter().zip(&edited.lights).enumerate() {
        if i >= written_lights {
            // Moved with its entry (which is written) and otherwise as the file has it.
            let followed = moved_with_entries.get(&i).map(|at| was.placed_as(at));
            if was != now && followed.as_ref() != Some(now) {
                skipped.push(format!(
                    "light {i}: it comes from a glTF file, which prism does not write"
                ));
            }
            continue;
        }
        // A light in a group moves only with its group, whose entry says where it is.
        let grouped = edited.groups.iter().any(|g| g.lights.contains(&i));
        let now = if grouped { &now.placed_as(was) } else { now };
        if was != now {
            let entry = array_entry(&mut doc, "lights", i)?;
            write_light(entry, was, now, origin);
        }
    }
    write_materials(&mut doc, loaded, edited, &mut skipped)?;
    write_placements(&mut doc, loaded, edited, &mut skipped)?;
    Ok(SavedText {
        text: doc.to_string(),
        skipped,
    })
}

/// The camera's fields replaced by the view as it is now (eye, yaw and pitch, the lens).
fn write_camera(doc: &mut DocumentMut, camera: &Camera, origin: DVec3) -> Result<(), SaveError> {
    let table: DocumentMut = camera_table(camera, origin)
        .parse()
        .map_err(|e: toml_edit::TomlError| SaveError::Parse(e.message().to_string()))?;
    let new = table["camera"]
        .as_table_like()
        .ok_or_else(|| SaveError::Missing("[camera] table".into()))?;
    let old = doc
        .get_mut("camera")
        .and_then(Item::as_table_like_mut)
        .ok_or_else(|| SaveError::Missing("[camera] table".into()))?;
    // The view is now given by yaw and pitch: the other ways of giving it go.
    for key in [
        "look_at",
        "direction",
        "yaw",
        "pitch",
        "up",
        "aperture",
        "focus_distance",
    ] {
        if new.get(key).is_none() {
            old.remove(key);
        }
    }
    for (key, item) in new.iter() {
        if let Some(v) = item.as_value() {
            set(old, key, v.clone());
        }
    }
    // Without a lens the table leaves the focus out; the loader's default is 1.
    if new.get("focus_distance").is_none() && camera.focus_distance != 1.0 {
        set(old, "focus_distance", number(camera.focus_distance));
    }
    Ok(())
}

/// Ambient light, background colour and depth, in `[render]` (made if the file has none).
fn write_render(doc: &mut DocumentMut, before: &Scene, edited: &Scene) {
    let mut changes: Vec<(&str, Value)> = Vec::new();
    if edited.ambient != before.ambient {
        changes.push(("ambient", vector(edited.ambient)));
    }
    if edited.background != before.background
        && let Background::Solid(c) = &edited.background
    {
        changes.push(("background", vector(*c)));
    }
    if edited.render.max_depth != before.render.max_depth {
        changes.push(("max_depth", Value::from(edited.render.max_depth as i64)));
    }
    if changes.is_empty() {
        return;
    }
    if doc.get("render").and_then(Item::as_table_like).is_none() {
        doc.insert("render", Item::Table(Table::new()));
    }
    let render = doc["render"]
        .as_table_like_mut()
        .expect("[render] was just made a table");
    for (key, v) in changes {
        set(render, key, v);
    }
}

fn write_fog(doc: &mut DocumentMut, fog: &Fog) -> Result<(), SaveError> {
    let t = doc
        .get_mut("fog")
        .and_then(Item::as_table_like_mut)
        .ok_or_else(|| SaveError::Missing("[fog] table".into()))?;
    set(t, "color", vector(fog.color));
    match fog.kind {
        FogKind::Exponential { density } => set(t, "density", number(density)),
        FogKind::Linear { start, end } => {
            set(t, "start", number(start));
            set(t, "end", number(end));
        }
    }
    Ok(())
}

/// Where `edited`'s entries now place the lights their glTF files bring, by the lights'
/// index in the scene.
fn file_lights_placed(loaded: &LoadedScene, edited: &Scene) -> HashMap<usize, Light> {
    // One object of each entry whose file brings lights.
    let mut entries = Vec::new();
    let mut objects = Vec::new();
    for (i, origin) in loaded.origins.iter().enumerate() {
        let brings_lights = origin.gltf.as_ref().is_some_and(|g| !g.lights.is_empty());
        if brings_lights && !entries.contains(&(origin.table, origin.index)) {
            entries.push((origin.table, origin.index));
            objects.extend(edited.objects.get(i).map(|o| (i, o.placement)));
        }
    }
    match loaded.placed_entries(edited, &objects, &[]) {
        Ok(Some(placed)) => placed.objects.into_iter().flat_map(|e| e.lights).collect(),
        _ => HashMap::new(),
    }
}

/// The fields of light `was` that differ in `now`, written into its `[[lights]]` entry.
fn write_light(entry: &mut dyn TableLike, was: &Light, now: &Light, origin: DVec3) {
    if now.color != was.color {
        set(entry, "color", vector(now.color));
    }
    let intensity = |l: &Light| match l.kind {
        LightKind::Point { falloff, .. }
        | LightKind::Spot { falloff, .. }
        | LightKind::Area { falloff, .. } => match falloff {
            Falloff::InverseSquare { intensity } => Some(intensity),
            Falloff::None => None,
        },
        LightKind::Directional { .. } => None,
    };
    if let Some(i) = intensity(now)
        && intensity(was) != Some(i)
    {
        set(entry, "intensity", number(i));
    }
    match (was.kind, now.kind) {
        (
            LightKind::Point { position: a, .. } | LightKind::Spot { position: a, .. },
            LightKind::Point { position: b, .. } | LightKind::Spot { position: b, .. },
        ) if a != b => set(entry, "position", point(b, origin)),
        _ => {}
    }
    if let (LightKind::Spot { cone: a, .. }, LightKind::Spot { cone: b, .. }) = (was.kind, now.kind)
        && a != b
    {
        set(entry, "angle", number(b.angle));
        set(entry, "softness", number(b.softness));
    }
    if let (LightKind::Spot { radius: a, .. }, LightKind::Spot { radius: b, .. }) =
        (was.kind, now.kind)
        && a != b
    {
        set(entry, "radius", number(b));
    }
    if let (LightKind::Area { shape: a, .. }, LightKind::Area { shape: b, .. }) =
        (was.kind, now.kind)
        && a != b
    {
        use crate::appearance::AreaShape;
        match b {
            AreaShape::Rectangle {
                corner,
                edge_u,
                edge_v,
            } => {
                set(entry, "corner", point(corner, origin));
                set(entry, "edge_u", vector(edge_u));
                set(entry, "edge_v", vector(edge_v));
            }
            AreaShape::Sphere { center, radius } => {
                set(entry, "position", point(center, origin));
                set(entry, "radius", number(radius));
            }
        }
    }
}

/// Material edits. An object's material is the `[materials]` entry it names, which other
/// objects may share: an entry is rewritten when every object naming it was edited alike,
/// and otherwise each object edited apart gets an entry of its own (a copy with the
/// changes) so that the others keep theirs.
fn write_materials(
    doc: &mut DocumentMut,
    loaded: &LoadedScene,
    edited: &Scene,
    skipped: &mut Vec<String>,
) -> Result<(), SaveError> {
    let before = &loaded.scene;
    // The objects naming each entry (None: objects without a `material`).
    let mut users: BTreeMap<Option<&str>, Vec<usize>> = BTreeMap::new();
    for (i, origin) in loaded.origins.iter().enumerate() {
        users.entry(origin.material.as_deref()).or_default().push(i);
    }
    let mut taken: Vec<String> = doc
        .get("materials")
        .and_then(Item::as_table_like)
        .map(|t| t.iter().map(|(k, _)| k.to_string()).collect())
        .unwrap_or_default();
    for (name, objects) in users {
        let changed: Vec<usize> = objects
            .iter()
            .copied()
            .filter(|&i| edited.objects[i].material != before.objects[i].material)
            .collect();
        let Some(&first) = changed.first() else {
            continue;
        };
        let original = &before.objects[first].material;
        let mesh_parts = name.is_none() && loaded.origins[first].table == "meshes";
        if mesh_parts {
            for &i in &changed {
                skipped.push(format!(
                    "{}: its material comes from the mesh's MTL file, which prism does not \
                     write; give the mesh a `material` to edit it",
                    edited.objects[i].name
                ));
            }
            continue;
        }
        let alike = changed.len() == objects.len()
            && changed
                .iter()
                .all(|&i| edited.objects[i].material == edited.objects[first].material);
        if let (true, Some(name)) = (alike, name) {
            let table = material_table(doc, name)?;
            write_material(
                table,
                original,
                &edited.objects[first].material,
                skipped,
                name,
            );
            continue;
        }
        for &i in &changed {
            let object = &edited.objects[i];
            let new_name = unique_name(&mut taken, name, &object.name);
            let mut table = match name {
                Some(name) => material_table(doc, name)?.clone_table(),
                None => Table::new(),
            };
            write_material(&mut table, original, &object.material, skipped, &new_name);
            if doc.get("materials").and_then(Item::as_table_like).is_none() {
                let mut materials = Table::new();
                materials.set_implicit(true);
                doc.insert("materials", Item::Table(materials));
            }
            let materials = doc["materials"]
                .as_table_like_mut()
                .expect("[materials] is a table");
            materials.insert(&new_name, Item::Table(table));
            let o = &loaded.origins[i];
            set(
                array_entry(doc, o.table, o.index)?,
                "material",
                Value::from(new_name.as_str()),
            );
        }
    }
    Ok(())
}

/// Objects and groups placed anew in the viewer: each entry's `translate`, `rotate` and
/// `scale` that changed are written. The parts of one mesh entry (one per MTL material)
/// move together or not at all.
fn write_placements(
    doc: &mut DocumentMut,
    loaded: &LoadedScene,
    edited: &Scene,
    skipped: &mut Vec<String>,
) -> Result<(), SaveError> {
    let before = &loaded.scene;
    let mut entries: BTreeMap<(&str, usize), Vec<usize>> = BTreeMap::new();
    for (i, o) in loaded.origins.iter().enumerate() {
        entries.entry((o.table, o.index)).or_default().push(i);
    }
    for ((table, index), objects) in entries {
        let was = before.objects[objects[0]].placement;
        let now = edited.objects[objects[0]].placement;
        if objects.iter().any(|&i| edited.objects[i].placement != now) {
            skipped.push(format!(
                "{table}[{index}]: its parts were placed apart, which one entry cannot say"
            ));
            continue;
        }
        if now == was {
            continue;
        }
        let entry = array_entry(doc, table, index)?;
        write_placement(entry, &was, &now);
    }
    for (i, (was, now)) in before.groups.iter().zip(&edited.groups).enumerate() {
        if was.placement == now.placement {
            continue;
        }
        match now.kind {
            GroupKind::Entry => {
                let entry = array_entry(doc, "groups", i)?;
                write_placement(entry, &was.placement, &now.placement);
            }
            GroupKind::FileNode => {
                let pose = node_pose_table(doc, loaded, i)?;
                write_placement(pose, &was.placement, &now.placement);
            }
        }
    }
    Ok(())
}

/// The pose (`[meshes.nodes."NAME"]`) of the glTF node that is group `group`, in its
/// entry; made, empty, if the entry has none.
fn node_pose_table<'d>(
    doc: &'d mut DocumentMut,
    loaded: &LoadedScene,
    group: usize,
) -> Result<&'d mut dyn TableLike, SaveError> {
    // A part of the entry hangs from the node or a node within it.
    let scene = &loaded.scene;
    let part = scene
        .objects
        .iter()
        .position(|o| o.node.is_some_and(|n| scene.group_within(n, group)));
    let node = part.and_then(|i| {
        let o = loaded.origins.get(i)?;
        let nodes = &o.gltf.as_ref()?.nodes;
        let at = nodes.binary_search_by_key(&group, |n| n.group).ok()?;
        Some((o.table, o.index, nodes[at].key.clone()))
    });
    let Some((table, index, key)) = node else {
        return Err(SaveError::Missing(format!("glTF node for group {group}")));
    };
    // An entry written as a `[[meshes]]` table takes `[meshes.nodes."NAME"]` tables; one
    // written inline takes inline tables.
    let tables = matches!(doc.get(table), Some(Item::ArrayOfTables(_)));
    let new = || {
        if tables {
            let mut t = Table::new();
            t.set_implicit(true);
            Item::Table(t)
        } else {
            Item::Value(Value::InlineTable(Default::default()))
        }
    };
    let missing = || SaveError::Missing(format!("{table}[{index}]'s nodes.{key} table"));
    let entry = array_entry(doc, table, index)?;
    let nodes = entry
        .entry("nodes")
        .or_insert_with(new)
        .as_table_like_mut()
        .ok_or_else(missing)?;
    nodes
        .entry(&key)
        .or_insert_with(new)
        .as_table_like_mut()
        .ok_or_else(missing)
}

/// The fields of an entry's placement that changed from `was` to `now`.
fn write_placement(entry: &mut dyn TableLike, was: &ObjectPlacement, now: &ObjectPlacement) {
    if now.translate != was.translate {
        set(entry, "translate", doubles(now.translate.to_array()));
    }
    if now.rotate != was.rotate {
        set(entry, "rotate", vector(now.rotate));
    }
    if now.scale != was.scale {
        let s = now.scale;
        let value = if s.x == s.y && s.y == s.z {
            Value::from(s.x)
        } else {
            doubles(s.to_array())
        };
        set(entry, "scale", value);
    }
}

/// Three f64s, as an array.
fn doubles(v: [f64; 3]) -> Value {
    Value::Array(v.into_iter().map(Value::from).collect::<Array>())
}

/// The `[materials.NAME]` entry, as a table to edit.
fn material_table<'d>(
    doc: &'d mut DocumentMut,
    name: &str,
) -> Result<&'d mut dyn TableLikeClone, SaveError> {
    doc.get_mut("materials")
        .and_then(Item::as_table_like_mut)
        .and_then(|t| t.get_mut(name))
        .and_then(as_clonable)
        .ok_or_else(|| SaveError::Missing(format!("[materials.{name}] table")))
}

/// A table (`[x]`) or an inline one (`{ … }`): each can be edited and copied into a table.
trait TableLikeClone: TableLike {
    fn clone_table(&self) -> Table;
}

impl TableLikeClone for Table {
    fn clone_table(&self) -> Table {
        let mut t = self.clone();
        t.decor_mut().clear();
        t
    }
}

impl TableLikeClone for toml_edit::InlineTable {
    fn clone_table(&self) -> Table {
        self.clone().into_table()
    }
}

fn as_clonable(item: &mut Item) -> Option<&mut dyn TableLikeClone> {
    match item {
        Item::Table(t) => Some(t),
        Item::Value(Value::InlineTable(t)) => Some(t),
        _ => None,
    }
}

/// A name for a new material entry that no other entry has: the shared one's name and the
/// object's, made of the characters a bare TOML key may hold.
fn unique_name(taken: &mut Vec<String>, shared: Option<&str>, object: &str) -> String {
    let clean: String = object
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let base = match shared {
        Some(s) => format!("{s}_{clean}"),
        None => clean,
    };
    let mut name = base.clone();
    let mut n = 2;
    while taken.contains(&name) {
        name = format!("{base}_{n}");
        n += 1;
    }
    taken.push(name.clone());
    name
}

/// The fields of `now` that differ from `was`, written into a material entry.
fn write_material(
    t: &mut dyn TableLikeClone,
    was: &Material,
    now: &Material,
    skipped: &mut Vec<String>,
    name: &str,
) {
    if now.texture != was.texture {
        match &now.texture {
            Texture::Solid(c) => {
                t.remove("texture");
                set(t, "color", vector(*c));
            }
            _ => skipped.push(format!("materials.{name}: a texture cannot be written")),
        }
    }
    let numbers = [
        ("ambient", was.ambient, now.ambient),
        ("diffuse", was.diffuse, now.diffuse),
        ("specular", was.specular, now.specular),
        ("shininess", was.shininess, now.shininess),
        ("reflectivity", was.reflectivity, now.reflectivity),
        ("transparency", was.transparency, now.transparency),
        ("roughness", was.roughness, now.roughness),
    ];
    for (key, a, b) in numbers {
        if a != b {
            set(t, key, number(b));
        }
    }
    if now.eta != was.eta {
        match now.eta {
            Some(eta) => set(t, "eta", number(eta)),
            None => {
                t.remove("eta");
            }
        }
    }
    if now.fresnel != was.fresnel {
        set(t, "fresnel", Value::from(now.fresnel));
    }
    if now.emission != was.emission {
        set(t, "emission", vector(now.emission));
    }
    if now.absorption != was.absorption {
        set(t, "absorption", vector(now.absorption));
    }
    if now.conductor != was.conductor {
        match now.conductor {
            Some(c) => set(t, "conductor", vector(c)),
            None => {
                t.remove("conductor");
            }
        }
    }
    // The panel changes a relief's depth or strength, never its picture or kind.
    match (&was.relief, &now.relief) {
        (Some(Relief::Bump { depth: a, .. }), Some(Relief::Bump { depth: b, .. })) if a != b => {
            set(t, "bump_depth", number(*b));
        }
        (
            Some(Relief::NormalMap { strength: a, .. }),
            Some(Relief::NormalMap { strength: b, .. }),
        ) if a != b => set(t, "normal_strength", number(*b)),
        (Some(Relief::Bump { .. }), Some(Relief::Bump { .. }))
        | (Some(Relief::NormalMap { .. }), Some(Relief::NormalMap { .. })) => {}
        (a, b) if a != b => skipped.push(format!("materials.{name}: a relief cannot be written")),
        _ => {}
    }
}

/// Entry `index` of the array of tables `key` (`[[key]]`, or `key = [{ … }]`).
fn array_entry<'d>(
    doc: &'d mut DocumentMut,
    key: &str,
    index: usize,
) -> Result<&'d mut dyn TableLike, SaveError> {
    let missing = || SaveError::Missing(format!("{key}[{index}]"));
    match doc.get_mut(key).ok_or_else(missing)? {
        Item::ArrayOfTables(a) => a
            .get_mut(index)
            .map(|t| t as &mut dyn TableLike)
            .ok_or_else(missing),
        Item::Value(Value::Array(a)) => match a.get_mut(index) {
            Some(Value::InlineTable(t)) => Ok(t),
            _ => Err(missing()),
        },
        _ => Err(missing()),
    }
}

/// Sets `key` to `v`, keeping the comment and spacing around a value it replaces, and the
/// value itself when it is the same number written another way (`1` for `1.0`).
fn set(t: &mut dyn TableLike, key: &str, mut v: Value) {
    if let Some(old) = t.get_mut(key).and_then(Item::as_value_mut) {
        if same_value(old, &v) {
            return;
        }
        *v.decor_mut() = old.decor().clone();
        *old = v;
    } else {
        t.insert(key, Item::Value(v));
    }
}

/// Whether two values are equal as the loader reads them: numbers by value, arrays element
/// by element.
fn same_value(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y.iter()).all(|(p, q)| same_value(p, q))
        }
        _ => match (as_number(a), as_number(b)) {
            (Some(x), Some(y)) => x == y,
            _ => a.to_string().trim() == b.to_string().trim(),
        },
    }
}

/// A number of the file, float or integer.
fn as_number(v: &Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

/// An f32 written with the fewest digits that read back as the same f32.
fn number(v: f32) -> Value {
    Value::from(shortest(v))
}

fn vector(v: Vec3) -> Value {
    Value::Array(v.to_array().into_iter().map(number).collect::<Array>())
}

/// A position relative to `origin`, in world coordinates, each with the fewest digits that
/// the loader reads back as the same relative f32.
fn point(p: Vec3, origin: DVec3) -> Value {
    let world = |rel: f32, o: f64| {
        let exact = o + rel as f64;
        (1..=17)
            .map(|digits| {
                format!("{exact:.*e}", digits - 1)
                    .parse::<f64>()
                    .unwrap_or(exact)
            })
            .find(|&w| (w - o) as f32 == rel)
            .unwrap_or(exact)
    };
    let xyz = [
        world(p.x, origin.x),
        world(p.y, origin.y),
        world(p.z, origin.z),
    ];
    Value::Array(xyz.into_iter().map(Value::from).collect::<Array>())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_file::load_scene_file;

    fn load(text: &str) -> (tempfile::TempDir, std::path::PathBuf, LoadedScene) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("scene.toml");
        std::fs::write(&path, text).unwrap();
        let loaded = load_scene_file(&path).result.unwrap();
        (dir, path, loaded)
    }

    const SCENE: &str = "\
# A test scene: the comments must survive a save.
[camera]
eye = [0.5, 1, 10]   # where we stand
look_at = [0, 0, 0]
fov = 40

[[lights]]
position = [10, 20, 5]  # the key light
color = [0.9, 0.9, 0.9]

# Shared by two spheres.
[materials.red]
color = [0.8, 0.1, 0.1]   # red
specular = 0.5

[materials.mirror]
reflectivity = 0.8

[[spheres]]
name = \"left\"
center = [-2, 0, 0]
radius = 1
material = \"red\"

[[spheres]]
name = \"right\"
center = [2, 0, 0]
radius = 1
material = \"red\"

[[boxes]]
min = [-1, -2, -1]
max = [1, -1, 1]
material = \"mirror\"
";

    /// Saving without edits gives back the same text, byte for byte.
    #[test]
    fn an_unedited_scene_saves_as_the_same_text() {
        let (_dir, _path, loaded) = load(SCENE);
        let saved = saved_text(&loaded, &loaded.scene, &loaded.scene.camera).unwrap();
        assert_eq!(saved.text, SCENE);
        assert!(saved.skipped.is_empty());
    }

    /// Edits of every kind go into the file, which loads as the edited scene; untouched
    /// lines and every comment stay as they were.
    #[test]
    fn edits_are_written_back_and_read_back_with_the_comments_kept() {
        let (_dir, path, loaded) = load(SCENE);
        let mut edited = loaded.scene.clone();
        // Both users of "red" alike: the shared entry changes.
        for i in [0, 1] {
            let mut m = edited.objects[i].material.clone();
            m.texture = Texture::Solid(Vec3::new(0.1, 0.7, 0.2));
            m.shininess = 42.5;
            edited.set_material(i, m).unwrap();
        }
        let mut mirror = edited.objects[2].material.clone();
        mirror.roughness = 0.3;
        edited.set_material(2, mirror).unwrap();
        let to = edited.lights[0].center().unwrap() + Vec3::new(1.0, -2.0, 0.25);
        edited
            .set_light_at(0, Vec3::new(2.0, 1.5, 1.0), Some(to))
            .unwrap();
        edited.set_ambient(Vec3::splat(0.3)).unwrap();
        edited
            .set_background_color(Vec3::new(0.0, 0.0, 0.2))
            .unwrap();
        edited.set_max_depth(7).unwrap();
        let mut camera = edited.camera;
        camera.yaw += 10.0;
        camera.pitch = 5.0;
        let saved = saved_text(&loaded, &edited, &camera).unwrap();
        for kept in [
            "# A test scene: the comments must survive a save.",
            "# where we stand",
            "# the key light",
            "# Shared by two spheres.",
            "color = [0.1, 0.7, 0.2]   # red",
            "specular = 0.5",
        ] {
            assert!(saved.text.contains(kept), "{kept:?} lost:\n{}", saved.text);
        }
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        assert_eq!(back, Scene { camera, ..edited }, "{}", saved.text);
    }

    /// A bump map's depth and a normal map's strength edited in the panel are written
    /// back (the pictures' names kept) and read back.
    #[test]
    fn relief_depth_and_strength_are_saved() {
        let text = "[camera]\neye = [0, 2, 8]\nlook_at = [0, 0, 0]\nfov = 40\n\n\
                    [textures.dents]\ntype = \"noise\"\n\n\
                    [materials.bumpy]\nbump = \"dents\" # hammered\nbump_depth = 0.1\n\n\
                    [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"bumpy\"\n";
        let (_dir, path, loaded) = load(text);
        let mut edited = loaded.scene.clone();
        let mut m = edited.objects[0].material.clone();
        let Some(Relief::Bump { depth, .. }) = &mut m.relief else {
            panic!("{:?}", m.relief);
        };
        *depth = 0.025;
        edited.set_material(0, m).unwrap();
        let saved = saved_text(&loaded, &edited, &loaded.scene.camera).unwrap();
        for written in ["bump_depth = 0.025", "bump = \"dents\" # hammered"] {
            assert!(saved.text.contains(written), "{written}:\n{}", saved.text);
        }
        assert!(saved.skipped.is_empty(), "{:?}", saved.skipped);
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        assert_eq!(back, edited, "{}", saved.text);

        let pictures = tempfile::tempdir().unwrap();
        let picture = pictures.path().join("n.png");
        image::RgbImage::from_pixel(2, 2, image::Rgb([128, 128, 255]))
            .save(&picture)
            .unwrap();
        let text = format!(
            "[camera]\neye = [0, 2, 8]\nlook_at = [0, 0, 0]\nfov = 40\n\n\
             [textures.n]\ntype = \"image\"\npath = {:?}\n\n\
             [materials.mapped]\nnormal_map = \"n\"\n\n\
             [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"mapped\"\n",
            picture.to_str().unwrap()
        );
        let (_dir, path, loaded) = load(&text);
        let mut edited = loaded.scene.clone();
        let mut m = edited.objects[0].material.clone();
        let Some(Relief::NormalMap { strength, .. }) = &mut m.relief else {
            panic!("{:?}", m.relief);
        };
        *strength = 2.5;
        edited.set_material(0, m).unwrap();
        let saved = saved_text(&loaded, &edited, &loaded.scene.camera).unwrap();
        assert!(
            saved.text.contains("normal_strength = 2.5"),
            "{}",
            saved.text
        );
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        assert_eq!(back, edited, "{}", saved.text);
    }

    /// A spotlight's cone and disc edited in the panel are written back and read back.
    #[test]
    fn a_spotlights_cone_and_disc_are_saved() {
        let text = "[camera]\neye = [0, 2, 8]\nlook_at = [0, 0, 0]\nfov = 40\n\n\
                    [[lights]]\ntype = \"spot\" # the lamp\nposition = [0, 6, 0]\n\
                    direction = [0, -1, 0]\nangle = 25\n\n\
                    [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n";
        let (_dir, path, loaded) = load(text);
        let mut edited = loaded.scene.clone();
        edited.set_spot(0, 35.0, 0.25).unwrap();
        edited.set_spot_radius(0, 0.5).unwrap();
        let saved = saved_text(&loaded, &edited, &loaded.scene.camera).unwrap();
        for written in [
            "angle = 35",
            "softness = 0.25",
            "radius = 0.5",
            "# the lamp",
        ] {
            assert!(saved.text.contains(written), "{written}:\n{}", saved.text);
        }
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        assert_eq!(back.lights, edited.lights);
        // Back to a point: radius 0 is written, and reads back as the point it is.
        edited.set_spot_radius(0, 0.0).unwrap();
        assert!(edited.set_spot_radius(0, -1.0).is_err());
        let saved = saved_text(&loaded, &edited, &loaded.scene.camera).unwrap();
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        assert_eq!(back.lights[0].position(), edited.lights[0].position());
        assert!(back.lights[0].position().is_some());
    }

    /// A camera moved away from the file's eye is saved in world coordinates: the scene
    /// read back has its origin at the new eye, and every object where it was.
    #[test]
    fn a_moved_camera_is_saved_in_world_coordinates() {
        let (_dir, path, loaded) = load(SCENE);
        let mut camera = loaded.scene.camera;
        camera.eye += Vec3::new(0.25, 0.0, -1.0);
        let saved = saved_text(&loaded, &loaded.scene, &camera).unwrap();
        assert!(!saved.text.contains("look_at"), "{}", saved.text);
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        let world = |s: &Scene, p: Vec3| s.origin + p.as_dvec3();
        let eye = world(&loaded.scene, camera.eye);
        assert!((world(&back, back.camera.eye) - eye).length() < 1e-6);
        assert_eq!(back.camera.yaw, camera.yaw);
        assert_eq!(back.camera.pitch, camera.pitch);
        let light = |s: &Scene| world(s, s.lights[0].center().unwrap());
        assert!((light(&back) - light(&loaded.scene)).length() < 1e-5);
    }

    /// One of two objects sharing a material edited: it gets an entry of its own and the
    /// other keeps the shared one.
    #[test]
    fn an_object_edited_apart_gets_its_own_material_entry() {
        let (_dir, path, loaded) = load(SCENE);
        let mut edited = loaded.scene.clone();
        let mut m = edited.objects[1].material.clone();
        m.reflectivity = 0.5;
        edited.set_material(1, m).unwrap();
        let saved = saved_text(&loaded, &edited, &loaded.scene.camera).unwrap();
        assert!(
            saved.text.contains("[materials.red_right]"),
            "{}",
            saved.text
        );
        assert!(saved.text.contains("material = \"red_right\""));
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        assert_eq!(back.objects[0].material, loaded.scene.objects[0].material);
        assert_eq!(back.objects[1].material, edited.objects[1].material);
        assert_eq!(back.objects[2].material, loaded.scene.objects[2].material);
    }

    /// An object without a material gets a new entry; inline tables are edited in place.
    #[test]
    fn default_materials_and_inline_tables_are_written() {
        let text = "lights = [{ position = [1, 2, 3] }]\n\
                    [camera]\neye = [0, 0, 5]\nfov = 40\n\
                    [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n";
        let (_dir, path, loaded) = load(text);
        let mut edited = loaded.scene.clone();
        let mut m = edited.objects[0].material.clone();
        m.diffuse = 0.25;
        edited.set_material(0, m).unwrap();
        edited.set_light_at(0, Vec3::splat(0.5), None).unwrap();
        let saved = saved_text(&loaded, &edited, &loaded.scene.camera).unwrap();
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        assert_eq!(back, edited, "{}", saved.text);
    }

    /// A moved object gets a `translate`, and reads back where it was moved to.
    #[test]
    fn moved_objects_are_saved_as_translations() {
        let (_dir, path, loaded) = load(SCENE);
        let mut edited = loaded.scene.clone();
        let moved = |edited: &Scene, loaded: &LoadedScene, i: usize, by: [f64; 3]| {
            let mut e = edited.clone();
            let mut p = e.objects[i].placement;
            p.translate += DVec3::from(by);
            loaded.place_object(&mut e, i, p).unwrap();
            e
        };
        edited = moved(&edited, &loaded, 0, [0.5, 0.0, -1.0]);
        edited = moved(&edited, &loaded, 2, [0.0, 2.0, 0.0]);
        edited = moved(&edited, &loaded, 2, [0.0, 0.25, 0.0]);
        let saved = saved_text(&loaded, &edited, &loaded.scene.camera).unwrap();
        assert!(
            saved.text.contains("translate = [0.5, 0.0, -1.0]"),
            "{}",
            saved.text
        );
        assert!(
            saved.text.contains("translate = [0.0, 2.25, 0.0]"),
            "{}",
            saved.text
        );
        std::fs::write(&path, &saved.text).unwrap();
        let back = load_scene_file(&path).result.unwrap().scene;
        for i in [0, 1, 2] {
            let (a, b) = (
                back.objects[i].shape.bounds(),
                edited.objects[i].shape.bounds(),
            );
            assert!((a.min - b.min).abs().max_element() < 1e-6, "{i}");
            assert!((a.max - b.max).abs().max_element() < 1e-6, "{i}");
        }
        // Saved again, the translation grows.
        let loaded = load_scene_file(&path).result.unwrap();
        let again = moved(&loaded.scene, &loaded, 0, [0.5, 0.0, 0.0]);
        let text = saved_text(&loaded, &again, &loaded.scene.camera)
            .unwrap()
            .text;
        assert!(text.contains("translate = [1.0, 0.0, -1.0]"), "{text}");
    }

    /// A light's position is written with the fewest digits that read back exactly.
    #[test]
    fn positions_read_back_as_the_same_f32() {
        for (p, o) in [
            (Vec3::new(0.1, -3.3, 1e-7), DVec3::ZERO),
            (Vec3::new(0.1, 2.0, -3.3), DVec3::new(1e3, -2.5, 7.25)),
        ] {
            let Value::Array(a) = point(p, o) else {
                panic!()
            };
            let back: Vec<f32> = a
                .iter()
                .zip([o.x, o.y, o.z])
                .map(|(v, o)| (v.as_float().unwrap() - o) as f32)
                .collect();
            assert_eq!(back, p.to_array().to_vec());
        }
    }
}
