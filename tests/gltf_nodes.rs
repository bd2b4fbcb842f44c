//! A glTF scene's nodes as groups the viewer places: which nodes become groups and what
//! hangs from them, placing one as a load of the file with that pose (`[meshes.nodes]`)
//! would, with everything under it and the entry's other edits following, refusals that
//! leave the scene unchanged, and the save that writes the pose.

mod common;

use common::Dir as TempDir;
use common::gltf::{cube, geometry, glb};
use glam::{DVec3, Vec3};
use prism::appearance::LightKind;
use prism::scene::{GroupKind, ObjectPlacement, Scene};
use prism::scene_file::{LoadedScene, load_scene_file, saved_text};
use serde_json::{Value, json};

const CAMERA: &str = "[camera]\neye = [0, 3, 8]\nlook_at = [0.5, 0.5, -1]\nfov = 40\n";

/// A file whose root node `arm` is turned and moved and holds `box` (scaled and moved,
/// the cube) and `bulb` (a point light above), with `extra` nodes appended (numbered from
/// 3), of which `roots` are in the scene.
fn write_arm(dir: &TempDir, extra: &[Value], roots: &[usize]) {
    let (positions, indices) = cube();
    let (bytes, views, accessors) = geometry(&positions, &indices);
    let s = 0.5f64.sqrt();
    let mut nodes = vec![
        json!({ "name": "arm", "translation": [1.0, 0.5, -1.0], "rotation": [0.0, s, 0.0, s],
                "children": [1, 2] }),
        json!({ "name": "box", "scale": [2.0, 1.0, 1.0], "translation": [0.5, 0.0, 0.0],
                "mesh": 0 }),
        json!({ "name": "bulb", "translation": [0.0, 2.0, 0.0],
                "extensions": { "KHR_lights_punctual": { "light": 0 } } }),
    ];
    nodes.extend(extra.iter().cloned());
    let roots: Vec<usize> = std::iter::once(0).chain(roots.iter().copied()).collect();
    let doc = json!({
        "asset": { "version": "2.0" },
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "point", "intensity": 100.0 }
        ] } },
        "scenes": [{ "nodes": roots }],
        "nodes": nodes,
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "byteLength": bytes.len() }],
        "bufferViews": views,
        "accessors": accessors
    });
    std::fs::write(dir.path("arm.glb"), glb(&doc, &bytes)).unwrap();
}

fn load(dir: &TempDir, text: &str) -> LoadedScene {
    let path = dir.write("scene.toml", text);
    load_scene_file(&path).result.unwrap()
}

/// The group named `name`.
fn group(scene: &Scene, name: &str) -> usize {
    scene
        .groups
        .iter()
        .position(|g| g.name == name)
        .unwrap_or_else(|| panic!("no group {name}: {:?}", scene.groups))
}

fn light_position(scene: &Scene, i: usize) -> DVec3 {
    match scene.lights[i].kind {
        LightKind::Point { position, .. } => scene.origin + position.as_dvec3(),
        ref other => panic!("{other:?}"),
    }
}

/// The parts of two scenes are the same triangles placed the same way, their lights are
/// the same, and their groups are placed alike.
fn assert_same(a: &Scene, b: &Scene) {
    assert_eq!(a.objects, b.objects);
    assert_eq!(a.lights, b.lights);
    assert_eq!(a.groups, b.groups);
}

/// Each node that holds triangles and whose transform a placement can write becomes a
/// group, in its parent node's frame; the parts hang from their node. A node that holds no
/// triangles (the bulb), one met twice (the leaf), one with a shear and one that mirrors
/// are not groups: what they hold hangs from the nearest group above, or from none.
#[test]
fn nodes_that_hold_triangles_become_groups() {
    let dir = TempDir::new();
    let shear = [
        1.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];
    write_arm(
        &dir,
        &[
            json!({ "name": "sheared", "matrix": shear, "children": [4] }),
            json!({ "name": "inner", "translation": [0.0, 0.0, 3.0], "mesh": 0 }),
            json!({ "name": "mirror", "scale": [-1.0, 1.0, 1.0], "mesh": 0 }),
            json!({ "name": "twice", "children": [7, 7] }),
            json!({ "name": "leaf", "mesh": 0, "translation": [0.0, 4.0, 0.0] }),
        ],
        &[3, 5, 6],
    );
    let loaded = load(&dir, &format!("{CAMERA}[[meshes]]\npath = \"arm.glb\"\n"));
    let scene = &loaded.scene;
    let names: Vec<&str> = scene.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["arm", "box", "inner", "twice"]);
    assert!(scene.groups.iter().all(|g| g.kind == GroupKind::FileNode));
    let (arm, boxed, inner) = (
        group(scene, "arm"),
        group(scene, "box"),
        group(scene, "inner"),
    );
    assert_eq!(scene.groups[arm].parent, None);
    assert_eq!(scene.groups[boxed].parent, Some(arm));
    // Under a shear, which is no group: at the top of the file's frame.
    assert_eq!(scene.groups[inner].parent, None);
    let p = scene.groups[arm].placement;
    assert_eq!(p.translate, DVec3::new(1.0, 0.5, -1.0));
    assert!(
        (p.rotate - Vec3::new(0.0, 90.0, 0.0)).length() < 1e-4,
        "{p:?}"
    );
    assert_eq!(p.scale, DVec3::ONE);
    let p = scene.groups[boxed].placement;
    assert_eq!(
        (p.translate, p.rotate),
        (DVec3::new(0.5, 0.0, 0.0), Vec3::ZERO)
    );
    assert_eq!(p.scale, DVec3::new(2.0, 1.0, 1.0));
    // box, inner, mirror, and the leaf twice.
    let nodes: Vec<Option<usize>> = scene.objects.iter().map(|o| o.node).collect();
    let twice = group(scene, "twice");
    assert_eq!(
        nodes,
        [Some(boxed), Some(inner), None, Some(twice), Some(twice)]
    );
    assert!(scene.objects.iter().all(|o| o.group.is_none()));
}

/// Placing a node anew gives the scene a load of the file with that pose gives: the
/// triangles under it, the light under it and the node's group, bit for bit. The entry
/// moved afterwards keeps the pose; the node placed back is the scene as loaded; and the
/// save writes the pose, which loads as the scene shown.
#[test]
fn a_node_placed_anew_is_the_file_with_that_pose() {
    let dir = TempDir::new();
    write_arm(&dir, &[], &[]);
    let entry = |pose: &str, translate: &str| {
        format!(
            "{CAMERA}# the arm\n[[meshes]]\npath = \"arm.glb\"\ntranslate = {translate}\n{pose}"
        )
    };
    let loaded = load(&dir, &entry("", "[0, 0, 0]"));
    let mut scene = loaded.scene.clone();
    let arm = group(&scene, "arm");
    let posed = ObjectPlacement {
        translate: DVec3::new(-2.0, 1.0, 0.5),
        ..scene.groups[arm].placement
    };
    loaded.place_group(&mut scene, arm, posed).unwrap();
    let by_file = load(
        &dir,
        &entry(
            "[meshes.nodes.arm]\ntranslate = [-2, 1, 0.5]\n",
            "[0, 0, 0]",
        ),
    );
    assert_same(&scene, &by_file.scene);
    // The bulb hangs below the arm, 2 up in its frame: the arm's move carries it.
    assert!((light_position(&scene, 0) - DVec3::new(-2.0, 3.0, 0.5)).length() < 1e-6);

    // A turn too: the whole `rotate` is the pose's, its other parts still the file's.
    let turned = ObjectPlacement {
        rotate: Vec3::new(0.0, 30.0, 10.0),
        ..scene.groups[arm].placement
    };
    loaded.place_group(&mut scene, arm, turned).unwrap();
    let pose = "[meshes.nodes.arm]\ntranslate = [-2, 1, 0.5]\nrotate = [0, 30, 10]\n";
    assert_same(&scene, &load(&dir, &entry(pose, "[0, 0, 0]")).scene);

    // The entry moved keeps its nodes' poses.
    let moved = ObjectPlacement {
        translate: DVec3::new(0.0, 0.0, -3.0),
        ..ObjectPlacement::IDENTITY
    };
    loaded.place_object(&mut scene, 0, moved).unwrap();
    assert_same(&scene, &load(&dir, &entry(pose, "[0, 0, -3]")).scene);

    // Saved: the pose and the move are written, and the file loads as the scene shown.
    let saved = saved_text(&loaded, &scene, &scene.camera).unwrap();
    assert!(saved.skipped.is_empty(), "{:?}", saved.skipped);
    assert!(saved.text.contains("[meshes.nodes.arm]"), "{}", saved.text);
    assert!(saved.text.contains("# the arm"), "{}", saved.text);
    assert_same(&scene, &load(&dir, &saved.text).scene);

    // Placed back, the node is as the file has it again.
    let back = loaded.scene.groups[arm].placement;
    loaded.place_group(&mut scene, arm, back).unwrap();
    loaded
        .place_object(&mut scene, 0, ObjectPlacement::IDENTITY)
        .unwrap();
    assert_same(&scene, &loaded.scene);
}

/// A child node placed anew moves what it holds and nothing else; a pose the file gives
/// already (by index) is where the save writes, in a file whose entries are inline tables;
/// and a node of an entry in a `[[groups]]` group follows both.
#[test]
fn a_child_node_an_existing_pose_and_a_group() {
    let dir = TempDir::new();
    write_arm(&dir, &[], &[]);
    let text = |pose: &str, turn: &str| {
        format!(
            "groups = [{{ name = \"table\", rotate = [0, {turn}, 0] }}]\n\
             meshes = [{{ path = \"arm.glb\", group = \"table\", nodes = {{ {pose} }} }}]\n\
             {CAMERA}"
        )
    };
    let loaded = load(&dir, &text("\"nodes[1]\" = { scale = 3 }", "0"));
    let mut scene = loaded.scene.clone();
    let boxed = group(&scene, "box");
    let table = group(&scene, "table");
    assert_eq!(scene.groups[table].kind, GroupKind::Entry);
    assert_eq!(scene.groups[boxed].placement.scale, DVec3::splat(3.0));
    let light_before = light_position(&scene, 0);
    let lifted = ObjectPlacement {
        translate: DVec3::new(0.5, 2.0, 0.0),
        ..scene.groups[boxed].placement
    };
    loaded.place_group(&mut scene, boxed, lifted).unwrap();
    let pose = "\"nodes[1]\" = { scale = 3, translate = [0.5, 2, 0] }";
    assert_same(&scene, &load(&dir, &text(pose, "0")).scene);
    // The bulb is the arm's, not the box's.
    assert_eq!(light_position(&scene, 0), light_before);
    let turned = ObjectPlacement {
        rotate: Vec3::new(0.0, 90.0, 0.0),
        ..ObjectPlacement::IDENTITY
    };
    loaded.place_group(&mut scene, table, turned).unwrap();
    assert_same(&scene, &load(&dir, &text(pose, "90")).scene);
    let saved = saved_text(&loaded, &scene, &scene.camera).unwrap();
    assert!(saved.skipped.is_empty(), "{:?}", saved.skipped);
    assert!(!saved.text.contains("nodes.box"), "{}", saved.text);
    assert_same(&scene, &load(&dir, &saved.text).scene);
}

/// A node's placement that the file's rules refuse (a zero scale, a move past the
/// coordinates allowed) is refused with the node and the field named, the scene unchanged.
#[test]
fn a_refused_node_placement_leaves_the_scene() {
    let dir = TempDir::new();
    write_arm(&dir, &[], &[]);
    let loaded = load(&dir, &format!("{CAMERA}[[meshes]]\npath = \"arm.glb\"\n"));
    let mut scene = loaded.scene.clone();
    let arm = group(&scene, "arm");
    let flat = ObjectPlacement {
        scale: DVec3::new(1.0, 0.0, 1.0),
        ..scene.groups[arm].placement
    };
    let e = loaded
        .place_group(&mut scene, arm, flat)
        .unwrap_err()
        .to_string();
    assert!(e.contains("node \"arm\"") && e.contains("`scale`"), "{e}");
    let far = ObjectPlacement {
        translate: DVec3::new(2e12, 0.0, 0.0),
        ..scene.groups[arm].placement
    };
    let e = loaded
        .place_group(&mut scene, arm, far)
        .unwrap_err()
        .to_string();
    assert!(e.contains("translate"), "{e}");
    assert_same(&scene, &loaded.scene);
}
