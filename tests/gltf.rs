//! glTF 2.0 scenes as mesh entries, on files the tests write (`.gltf` with a `.bin` or a
//! data URI, and `.glb`): a node tree's transforms give the same image as the same
//! triangles placed by hand, materials map as the docs say, lights arrive where their
//! nodes put them with the documented intensity, what prism does not read is named, and
//! every malformed file is refused with a message (never a panic).

mod common;

use common::Dir as TempDir;
use common::gltf::{base64, cube, geometry, glb};
use glam::{DVec3, Vec3};
use prism::appearance::{LightKind, Relief, Texture};
use prism::scene::{Scene, ShapeDesc};
use prism::scene_file::{LoadedScene, load_scene_file};
use serde_json::{Value, json};
use std::f64::consts::FRAC_1_SQRT_2;

/// The cube's document: a root node turned and moved, its child scaled holding the mesh,
/// the buffer at `uri` (None: the GLB's chunk), and `extra` merged in.
fn cube_document(byte_length: usize, uri: Option<&str>, extra: Value) -> Value {
    let (_, views, accessors) = geometry(&cube().0, &cube().1);
    let mut buffer = json!({ "byteLength": byte_length });
    if let Some(uri) = uri {
        buffer["uri"] = json!(uri);
    }
    let s = (0.5f64).sqrt();
    let mut doc = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [
            { "name": "arm", "translation": [1.0, 0.5, -1.0], "rotation": [0.0, s, 0.0, s],
              "children": [1] },
            { "name": "box", "scale": [2.0, 1.0, 1.0], "translation": [0.5, 0.0, 0.0], "mesh": 0 }
        ],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [buffer],
        "bufferViews": views,
        "accessors": accessors
    });
    if let (Value::Object(d), Value::Object(e)) = (&mut doc, extra) {
        d.extend(e);
    }
    doc
}

const CAMERA: &str = "[camera]\neye = [0, 3, 8]\nlook_at = [0.5, 0.5, -1]\nfov = 40\n\
                      [render]\nambient = [1, 1, 1]\nbackground = [0, 0, 0]\n\
                      [materials.flat]\ncolor = [1, 0.5, 0.2]\nambient = 1\ndiffuse = 0\nspecular = 0\n";

fn load(dir: &TempDir, text: &str) -> LoadedScene {
    let path = dir.write("scene.toml", text);
    load_scene_file(&path).result.unwrap()
}

fn image(scene: &Scene) -> image::RgbImage {
    let mut settings = prism::render::RenderSettings::new(160, 120, 1);
    settings.layout = prism::sampler::SampleLayout::Grid;
    common::render_scene(scene, settings)
}

fn differing(a: &image::RgbImage, b: &image::RgbImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
}

/// The node tree's transforms (a turn of 90° about y and a move, then a scale and a move)
/// place the triangles where the same cube written as an OBJ and placed by the same
/// transforms by hand lands: as `.gltf` with a `.bin`, with a data URI, and as `.glb`.
#[test]
fn a_node_tree_places_its_mesh_as_the_same_transforms_by_hand() {
    let dir = TempDir::new();
    let (p, t) = cube();
    let (bytes, ..) = geometry(&p, &t);
    std::fs::write(dir.path("cube.bin"), &bytes).unwrap();
    let doc = cube_document(bytes.len(), Some("cube.bin"), json!({}));
    dir.write("cube.gltf", &doc.to_string());
    let uri = format!("data:application/octet-stream;base64,{}", base64(&bytes));
    let doc = cube_document(bytes.len(), Some(&uri), json!({}));
    dir.write("inline.gltf", &doc.to_string());
    let doc = cube_document(bytes.len(), None, json!({}));
    std::fs::write(dir.path("cube.glb"), glb(&doc, &bytes)).unwrap();
    let mut obj = String::new();
    for v in &p {
        obj += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in t.chunks(3) {
        obj += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    dir.write("cube.obj", &obj);
    // By hand: the child's scale and move, then the parent's turn and move, as two
    // groups (prism's groups compose as glTF's nodes do).
    let by_hand = load(
        &dir,
        &format!(
            "{CAMERA}[[groups]]\nname = \"arm\"\nrotate = [0, 90, 0]\ntranslate = [1, 0.5, -1]\n\
             [[meshes]]\npath = \"cube.obj\"\ngroup = \"arm\"\nscale = [2, 1, 1]\n\
             translate = [0.5, 0, 0]\nmaterial = \"flat\"\nsmooth = false\n"
        ),
    );
    let reference = image(&by_hand.scene);
    let lit = reference.pixels().filter(|p| p.0 != [0, 0, 0]).count();
    assert!(lit > 300, "{lit} pixels show the cube");
    for file in ["cube.gltf", "inline.gltf", "cube.glb"] {
        let loaded = load(
            &dir,
            &format!(
                "{CAMERA}[[meshes]]\npath = \"{file}\"\nmaterial = \"flat\"\nsmooth = false\n"
            ),
        );
        assert_eq!(loaded.scene.objects.len(), 1);
        assert_eq!(loaded.scene.objects[0].name, "meshes 0");
        let n = differing(&image(&loaded.scene), &reference);
        assert!(
            n <= 8,
            "{file}: {n} pixels differ from the cube placed by hand"
        );
        assert!(loaded.unread().is_empty(), "{:?}", loaded.unread());
    }
    // A mirroring node keeps the faces facing out (a cube's outside seen, lit).
    let mut doc = cube_document(bytes.len(), None, json!({}));
    doc["nodes"][1]["scale"] = json!([-2.0, 1.0, 1.0]);
    std::fs::write(dir.path("mirror.glb"), glb(&doc, &bytes)).unwrap();
    let loaded = load(
        &dir,
        &format!("{CAMERA}[[meshes]]\npath = \"mirror.glb\"\nmaterial = \"flat\"\n"),
    );
    let ShapeDesc::Mesh { mesh, .. } = &loaded.scene.objects[0].shape else {
        panic!()
    };
    let centre: Vec3 = mesh
        .positions()
        .iter()
        .map(|p| Vec3::from(*p))
        .sum::<Vec3>()
        / 8.0;
    for i in 0..mesh.triangle_count() as u32 {
        let [a, b, c] = mesh.corners(i).map(Vec3::from);
        let outward = (b - a).cross(c - a).dot(a - centre);
        assert!(outward > 0.0, "triangle {i} faces in");
    }
}

/// A tiny PNG, `w` × `h`, of one colour.
fn png(w: u32, h: u32, rgb: [u8; 3]) -> Vec<u8> {
    let img = image::RgbImage::from_pixel(w, h, image::Rgb(rgb));
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

/// Four cubes side by side, each of one material: base colour; metal; glass with an index;
/// emissive with a normal map; and a base colour texture from the GLB's own bytes.
#[test]
fn materials_map_as_documented() {
    let dir = TempDir::new();
    let (p, t) = cube();
    let (mut bytes, views, accessors) = geometry(&p, &t);
    let picture = png(4, 2, [200, 100, 50]);
    let picture_offset = bytes.len();
    bytes.extend(&picture);
    let mut views = views.as_array().unwrap().clone();
    views.push(json!({ "buffer": 0, "byteOffset": picture_offset, "byteLength": picture.len() }));
    let normal_uri = format!(
        "data:image/png;base64,{}",
        base64(&png(2, 2, [128, 128, 255]))
    );
    let nodes: Vec<Value> = (0..5)
        .map(|i| json!({ "name": format!("cube{i}"), "translation": [i as f64 * 1.5, 0.0, 0.0], "mesh": i }))
        .collect();
    let meshes: Vec<Value> = (0..5)
        .map(|i| json!({ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1, "material": i }] }))
        .collect();
    let doc = json!({
        "asset": { "version": "2.0" },
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_texture_transform"],
        "scenes": [{ "nodes": [0, 1, 2, 3, 4] }],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [
            { "name": "paint", "pbrMetallicRoughness": { "baseColorFactor": [0.8, 0.2, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5 } },
            { "name": "gold", "pbrMetallicRoughness": { "baseColorFactor": [1.0, 0.77, 0.34, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.2 } },
            { "name": "glass", "pbrMetallicRoughness": { "metallicFactor": 0.0, "roughnessFactor": 0.0 },
              "extensions": { "KHR_materials_transmission": { "transmissionFactor": 1.0 }, "KHR_materials_ior": { "ior": 1.33 } } },
            { "name": "lamp", "emissiveFactor": [1.0, 0.5, 0.25], "normalTexture": { "index": 1, "scale": 0.5 },
              "occlusionTexture": { "index": 1 } },
            { "name": "picture", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }
        ],
        "textures": [{ "source": 0 }, { "source": 1 }],
        "images": [{ "bufferView": 2, "mimeType": "image/png" }, { "uri": normal_uri }],
        "buffers": [{ "byteLength": bytes.len() }],
        "bufferViews": views,
        "accessors": accessors
    });
    std::fs::write(dir.path("materials.glb"), glb(&doc, &bytes)).unwrap();
    let loaded = load(
        &dir,
        &format!("{CAMERA}[[meshes]]\nname = \"set\"\npath = \"materials.glb\"\n"),
    );
    let m: Vec<_> = loaded.scene.objects.iter().map(|o| &o.material).collect();
    let names: Vec<&str> = loaded
        .scene
        .objects
        .iter()
        .map(|o| o.name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "set/cube0",
            "set/cube1",
            "set/cube2",
            "set/cube3",
            "set/cube4"
        ]
    );
    assert_eq!(m[0].texture, Texture::Solid(Vec3::new(0.8, 0.2, 0.1)));
    assert_eq!(
        (m[0].diffuse, m[0].conductor, m[0].reflectivity),
        (1.0, None, 0.0)
    );
    assert!((m[0].shininess - 30.0).abs() < 1e-3, "{}", m[0].shininess);
    assert_eq!(m[1].conductor, Some(Vec3::new(1.0, 0.77, 0.34)));
    assert_eq!(
        (m[1].reflectivity, m[1].roughness, m[1].diffuse),
        (1.0, 0.2, 0.0)
    );
    assert_eq!(
        (m[2].eta, m[2].fresnel, m[2].transparency),
        (Some(1.33), true, 1.0)
    );
    assert_eq!(m[3].emission, Vec3::new(1.0, 0.5, 0.25));
    let Some(Relief::NormalMap { strength, .. }) = &m[3].relief else {
        panic!("{:?}", m[3].relief)
    };
    assert_eq!(*strength, 0.5);
    let Texture::Image { image, .. } = &m[4].texture else {
        panic!("{:?}", m[4].texture)
    };
    assert_eq!((image.width, image.height), (4, 2));
    let unread = loaded.unread().join("\n");
    for word in ["KHR_texture_transform", "occlusionTexture"] {
        assert!(unread.contains(word), "{word} in {unread}");
    }
    assert!(unread.starts_with("meshes[0]: "), "{unread}");
    // The entry's own material overrides every part's.
    let plain = load(
        &dir,
        &format!("{CAMERA}[[meshes]]\npath = \"materials.glb\"\nmaterial = \"flat\"\n"),
    );
    assert!(
        plain
            .scene
            .objects
            .iter()
            .all(|o| o.material.ambient == 1.0)
    );
}

/// `KHR_lights_punctual`: a point, a spot and a directional light arrive where their nodes
/// and the entry's placement put them, their candela as prism's intensity by the documented
/// rule; and a white floor under the point light is as bright as that rule says.
#[test]
fn punctual_lights_arrive_placed_and_scaled() {
    let dir = TempDir::new();
    // A floor: a 20 × 20 square at y = 0, facing up.
    let p = vec![
        [-10.0, 0.0, -10.0],
        [10.0, 0.0, -10.0],
        [10.0, 0.0, 10.0],
        [-10.0, 0.0, 10.0],
    ];
    let t = vec![0u16, 2, 1, 0, 3, 2];
    let (bytes, views, accessors) = geometry(&p, &t);
    let candela = 683.0 * std::f64::consts::PI * 4.0;
    let doc = json!({
        "asset": { "version": "2.0" },
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "point", "intensity": candela, "color": [1.0, 1.0, 1.0] },
            { "type": "spot", "intensity": candela, "spot": { "innerConeAngle": 0.2, "outerConeAngle": 0.4 } },
            { "type": "directional", "intensity": 683.0 * std::f64::consts::PI }
        ] } },
        "scenes": [{ "nodes": [0, 1, 2, 3] }],
        "nodes": [
            { "mesh": 0 },
            { "translation": [0.0, 2.0, 0.0], "extensions": { "KHR_lights_punctual": { "light": 0 } } },
            { "translation": [3.0, 4.0, 0.0], "rotation": [-FRAC_1_SQRT_2, 0.0, 0.0, FRAC_1_SQRT_2],
              "extensions": { "KHR_lights_punctual": { "light": 1 } } },
            { "extensions": { "KHR_lights_punctual": { "light": 2 } } }
        ],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "byteLength": bytes.len() }],
        "bufferViews": views,
        "accessors": accessors
    });
    std::fs::write(dir.path("lights.glb"), glb(&doc, &bytes)).unwrap();
    let text = "[camera]\neye = [0, 5, 6]\nlook_at = [0, 0, 0]\nfov = 40\n\
                [render]\nambient = [0, 0, 0]\nbackground = [0, 0, 0]\n\
                [materials.white]\ncolor = [1, 1, 1]\nambient = 0\ndiffuse = 1\nspecular = 0\n\
                [[meshes]]\npath = \"lights.glb\"\nmaterial = \"white\"\ntranslate = [0, 0, -1]\n";
    let loaded = load(&dir, text);
    let scene = &loaded.scene;
    assert_eq!(scene.lights.len(), 3);
    let world = |v: Vec3| scene.origin + v.as_dvec3();
    let LightKind::Point { position, falloff } = scene.lights[0].kind else {
        panic!()
    };
    assert!((world(position) - DVec3::new(0.0, 2.0, -1.0)).length() < 1e-5);
    let prism::appearance::Falloff::InverseSquare { intensity } = falloff else {
        panic!()
    };
    assert!((intensity - 4.0).abs() < 1e-4, "{intensity}");
    let LightKind::Spot { position, cone, .. } = scene.lights[1].kind else {
        panic!()
    };
    assert!((world(position) - DVec3::new(3.0, 4.0, -1.0)).length() < 1e-5);
    // Its node turns −z to −y: it shines straight down.
    assert!(
        (cone.direction - Vec3::NEG_Y).length() < 1e-5,
        "{}",
        cone.direction
    );
    assert!((cone.angle - 0.4f32.to_degrees()).abs() < 1e-3);
    assert!((cone.softness - 0.5).abs() < 1e-5);
    assert_eq!(scene.lights[2].color, Vec3::ONE);
    // Under the point light alone, the floor below it: intensity / d² = 4 / 2² = 1.
    let mut only_point = scene.clone();
    only_point.lights.truncate(1);
    let below = common::colour_along(&only_point, Vec3::new(0.0, 1.0, -1.0), Vec3::NEG_Y);
    assert!((below - Vec3::ONE).abs().max_element() < 1e-3, "{below}");
}

/// lamp.glb: the cube (node "box"), and a point light 3 above it (node "bulb").
fn write_lamp(dir: &TempDir) {
    let (positions, indices) = cube();
    let (bytes, views, accessors) = geometry(&positions, &indices);
    let doc = json!({
        "asset": { "version": "2.0" },
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "point", "intensity": 100.0 }
        ] } },
        "scenes": [{ "nodes": [0, 1] }],
        "nodes": [
            { "name": "box", "mesh": 0 },
            { "name": "bulb", "translation": [0.0, 3.0, 0.0],
              "extensions": { "KHR_lights_punctual": { "light": 0 } } }
        ],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "byteLength": bytes.len() }],
        "bufferViews": views,
        "accessors": accessors
    });
    std::fs::write(dir.path("lamp.glb"), glb(&doc, &bytes)).unwrap();
}

/// The point light's place in the world.
fn lamp_position(scene: &Scene) -> DVec3 {
    match scene.lights[0].kind {
        LightKind::Point { position, .. } => scene.origin + position.as_dvec3(),
        ref other => panic!("{other:?}"),
    }
}

/// A glTF scene's lights move with their entry at once, as a load of the file with the
/// new placement puts them, whether the entry or a group it is in is placed anew; an edit
/// of a light's colour stays.
#[test]
fn a_gltf_scenes_lights_move_with_its_entry() {
    let dir = TempDir::new();
    write_lamp(&dir);
    let entry = |translate: &str, group_turn: &str| {
        format!(
            "{CAMERA}[[groups]]\nname = \"table\"\nrotate = [0, {group_turn}, 0]\n\
             [[meshes]]\npath = \"lamp.glb\"\ngroup = \"table\"\ntranslate = {translate}\n"
        )
    };
    let position = lamp_position;
    let loaded = load(&dir, &entry("[0, 0, 0]", "0"));
    let mut scene = loaded.scene.clone();
    assert!((position(&scene) - DVec3::new(0.0, 3.0, 0.0)).length() < 1e-5);
    let moved = prism::scene::ObjectPlacement {
        translate: DVec3::new(2.0, 0.0, -1.0),
        ..prism::scene::ObjectPlacement::IDENTITY
    };
    loaded.place_object(&mut scene, 0, moved).unwrap();
    // Saved, the entry's move is written, and the light that followed it is no lost edit.
    let saved = prism::scene_file::saved_text(&loaded, &scene, &scene.camera).unwrap();
    assert!(saved.skipped.is_empty(), "{:?}", saved.skipped);
    assert!(
        saved.text.contains("translate = [2.0, 0.0, -1.0]"),
        "{}",
        saved.text
    );
    // A colour edit of the file's light cannot be written, and the save says so.
    scene.lights[0].color = Vec3::new(1.0, 0.5, 0.25);
    let saved = prism::scene_file::saved_text(&loaded, &scene, &scene.camera).unwrap();
    assert_eq!(saved.skipped.len(), 1, "{:?}", saved.skipped);
    assert!(
        saved.skipped[0].starts_with("light 0"),
        "{:?}",
        saved.skipped
    );
    loaded.place_object(&mut scene, 0, moved).unwrap();
    let by_file = load(&dir, &entry("[2, 0, -1]", "0"));
    assert!((position(&scene) - DVec3::new(2.0, 3.0, -1.0)).length() < 1e-5);
    assert!((position(&scene) - position(&by_file.scene)).length() < 1e-9);
    assert_eq!(scene.lights[0].color, Vec3::new(1.0, 0.5, 0.25));
    // The group turned a quarter about y: (2, 3, −1) goes to (−1, 3, −2).
    let turned = prism::scene::ObjectPlacement {
        rotate: Vec3::new(0.0, 90.0, 0.0),
        ..prism::scene::ObjectPlacement::IDENTITY
    };
    loaded.place_group(&mut scene, 0, turned).unwrap();
    let by_file = load(&dir, &entry("[2, 0, -1]", "90"));
    assert!((position(&scene) - DVec3::new(-1.0, 3.0, -2.0)).length() < 1e-5);
    assert!((position(&scene) - position(&by_file.scene)).length() < 1e-9);
    assert_eq!(scene.lights[0].color, Vec3::new(1.0, 0.5, 0.25));
}

/// An animation's frames read a glTF file once: with the file gone after the first frame,
/// the next frames still place its triangles and lights where their keys say.
#[test]
fn an_animation_reads_a_gltf_file_once() {
    let dir = TempDir::new();
    write_lamp(&dir);
    let text = format!(
        "{CAMERA}[[meshes]]\nname = \"lamp\"\npath = \"lamp.glb\"\n\
         [animation]\nframes = 3\n\
         [[animation.track]]\ntarget = \"lamp\"\nfield = \"translate\"\ninterpolation = \"linear\"\n\
         keys = [{{ frame = 0, value = [0, 0, 0] }}, {{ frame = 2, value = [4, 0, 0] }}]\n"
    );
    let path = dir.write("scene.toml", &text);
    let frames = prism::scene_file::SceneFrames::load(&path).unwrap();
    let first = frames.frame(0).unwrap();
    std::fs::remove_file(dir.path("lamp.glb")).unwrap();
    let last = frames.frame(2).unwrap();
    assert_eq!(last.objects.len(), first.objects.len());
    let light_x = |scene: &Scene| lamp_position(scene).x;
    assert!((light_x(&first) - 0.0).abs() < 1e-6);
    assert!((light_x(&last) - 4.0).abs() < 1e-6);
    // Without the cache, the file is read again, and it is gone.
    assert!(load_scene_file(&path).result.is_err());
}

/// An entry's `nodes` pose a glTF file's nodes anew, by name or as `nodes[i]`: each part
/// of the pose given replaces that part of the node's own transform, the others kept, and
/// what the node holds (triangles, a light) follows.
/// Two entries of one file posed apart each get their own pose. A pose of a node the file
/// lacks, or on an OBJ file, or with a bad value, is refused at its entry.
#[test]
fn nodes_are_posed_by_the_entry() {
    let dir = TempDir::new();
    write_lamp(&dir);
    let text = format!(
        "{CAMERA}[[meshes]]\npath = \"lamp.glb\"\n\
         [meshes.nodes.bulb]\ntranslate = [1, 5, 0]\n\
         [meshes.nodes.\"nodes[0]\"]\nscale = 2\nrotate = [0, 45, 0]\n\
         [[meshes]]\npath = \"lamp.glb\"\n[meshes.nodes.bulb]\nrotate = [0, 90, 0]\n"
    );
    let loaded = load(&dir, &text);
    let scene = &loaded.scene;
    assert!((lamp_position(scene) - DVec3::new(1.0, 5.0, 0.0)).length() < 1e-5);
    // The second entry's light, only turned, keeps the file's place.
    let LightKind::Point { position, .. } = scene.lights[1].kind else {
        panic!()
    };
    assert!((scene.origin + position.as_dvec3() - DVec3::new(0.0, 3.0, 0.0)).length() < 1e-5);
    let extent = |i: usize| match &scene.objects[i].shape {
        ShapeDesc::Mesh { mesh, .. } => {
            let b = mesh.bounds();
            (b.max.x - b.min.x, b.max.y - b.min.y)
        }
        other => panic!("{other:?}"),
    };
    // The posed cube: twice the size, turned 45° about y (its width across x is 2√2).
    let (wide, tall) = extent(0);
    assert!(
        (wide - 2.0 * std::f32::consts::SQRT_2).abs() < 1e-4,
        "{wide}"
    );
    assert!((tall - 2.0).abs() < 1e-5, "{tall}");
    assert_eq!(extent(1), (1.0, 1.0));

    let refused = |text: String| {
        let path = dir.write("bad.toml", &text);
        load_scene_file(&path).result.unwrap_err().to_string()
    };
    let e = refused(format!(
        "{CAMERA}[[meshes]]\npath = \"lamp.glb\"\n[meshes.nodes.blub]\ntranslate = [1, 0, 0]\n"
    ));
    assert!(e.contains("no node named \"blub\""), "{e}");
    assert!(e.contains("did you mean \"bulb\""), "{e}");
    assert!(e.contains("bad.toml:"), "{e}");
    let obj = "o cube\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    dir.write("tri.obj", obj);
    let e = refused(format!(
        "{CAMERA}[[meshes]]\npath = \"tri.obj\"\n[meshes.nodes.bulb]\nscale = 2\n"
    ));
    assert!(e.contains("an OBJ file has none"), "{e}");
    let e = refused(format!(
        "{CAMERA}[[meshes]]\npath = \"lamp.glb\"\n[meshes.nodes.bulb]\nscale = 0\n"
    ));
    assert!(e.contains("node \"bulb\"") && e.contains("`scale`"), "{e}");
    let e = refused(format!(
        "{CAMERA}[[meshes]]\npath = \"lamp.glb\"\n[meshes.nodes.bulb]\nmove = 2\n"
    ));
    assert!(e.contains("move"), "{e}");
}

/// A pose by a name two nodes share is refused, as it could mean either; `nodes[i]` poses
/// one of them alone.
#[test]
fn a_shared_node_name_is_posed_by_index() {
    let dir = TempDir::new();
    let (positions, indices) = cube();
    let (bytes, views, accessors) = geometry(&positions, &indices);
    let doc = json!({
        "asset": { "version": "2.0" },
        "scenes": [{ "nodes": [0, 1] }],
        "nodes": [
            { "name": "twin", "mesh": 0 },
            { "name": "twin", "mesh": 0, "translation": [2.0, 0.0, 0.0] }
        ],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "byteLength": bytes.len() }],
        "bufferViews": views,
        "accessors": accessors
    });
    std::fs::write(dir.path("twins.glb"), glb(&doc, &bytes)).unwrap();
    let entry = |pose: &str| format!("{CAMERA}[[meshes]]\npath = \"twins.glb\"\n{pose}");
    let path = dir.write("shared.toml", &entry("[meshes.nodes.twin]\nscale = 2\n"));
    let e = load_scene_file(&path).result.unwrap_err().to_string();
    assert!(e.contains("names 2 nodes") && e.contains("nodes[i]"), "{e}");
    let loaded = load(
        &dir,
        &entry("[meshes.nodes.\"nodes[1]\"]\ntranslate = [0, 0, 5]\n"),
    );
    let centres: Vec<glam::Vec3> = loaded
        .scene
        .objects
        .iter()
        .map(|o| match &o.shape {
            ShapeDesc::Mesh { mesh, .. } => mesh.bounds().centroid(),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(centres.len(), 2);
    assert!((centres[0] - Vec3::ZERO).length() < 1e-6, "{centres:?}");
    assert!(
        (centres[1] - Vec3::new(0.0, 0.0, 5.0)).length() < 1e-6,
        "{centres:?}"
    );
}

/// Every malformed file is refused with the entry and the file named, and what is wrong.
#[test]
fn malformed_files_are_refused_with_a_message() {
    let dir = TempDir::new();
    let (p, t) = cube();
    let (bytes, ..) = geometry(&p, &t);
    let good = cube_document(bytes.len(), None, json!({}));
    let whole = glb(&good, &bytes);
    let mut cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("truncated", whole[..whole.len() - 40].to_vec(), ""),
        ("not json", b"{ \"asset\": ".to_vec(), ""),
        ("empty", Vec::new(), ""),
    ];
    let mut edit = |name: &'static str, change: &dyn Fn(&mut Value), want: &'static str| {
        let mut doc = good.clone();
        change(&mut doc);
        cases.push((name, glb(&doc, &bytes), want));
    };
    edit(
        "accessor past its view",
        &|d| d["accessors"][0]["count"] = json!(9),
        "run past",
    );
    edit(
        "view past its buffer",
        &|d| d["bufferViews"][1]["byteLength"] = json!(400),
        "past the end",
    );
    edit(
        "a loop",
        &|d| d["nodes"][1]["children"] = json!([0]),
        "within itself",
    );
    edit(
        "no such node",
        &|d| d["nodes"][0]["children"] = json!([7]),
        "",
    );
    edit(
        "required extension",
        &|d| d["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]),
        "extension",
    );
    edit(
        "sparse",
        &|d| {
            d["accessors"][1]["sparse"] = json!({ "count": 1,
        "indices": { "bufferView": 1, "componentType": 5123 }, "values": { "bufferView": 1 } })
        },
        "sparse",
    );
    edit(
        "bad factor",
        &|d| d["materials"] = json!([{ "pbrMetallicRoughness": { "metallicFactor": 2.0 } }]),
        "",
    );
    edit(
        "no scene nodes",
        &|d| d["scenes"] = json!([{ "nodes": [] }]),
        "no triangles",
    );
    edit(
        "external missing",
        &|d| d["buffers"][0]["uri"] = json!("missing.bin"),
        "missing.bin",
    );
    edit(
        "escape",
        &|d| d["buffers"][0]["uri"] = json!("/etc/passwd"),
        "relative",
    );
    // A GLB whose header gives a length shorter than itself (the crate would take 12 from it).
    let mut short = whole.clone();
    short[8..12].copy_from_slice(&3u32.to_le_bytes());
    cases.push(("header length", short, "cut short"));
    // An index past the vertices: the cube's last index made 200.
    let mut far = bytes.clone();
    let n = far.len();
    far[n - 2..].copy_from_slice(&200u16.to_le_bytes());
    cases.push(("index past the vertices", glb(&good, &far), "index 200"));
    // A node named with a control character: the message shows it escaped.
    let mut named = good.clone();
    named["nodes"][1]["name"] = json!("bo\u{7f}x\nline");
    cases.push(("control characters", glb(&named, &far), "bo\\u{7f}x\\nline"));
    for (name, file, want) in cases {
        std::fs::write(dir.path("bad.glb"), file).unwrap();
        let path = dir.write(
            "scene.toml",
            &format!("{CAMERA}[[meshes]]\nname = \"x\"\npath = \"bad.glb\"\n"),
        );
        let e = match load_scene_file(&path).result {
            Ok(_) => panic!("{name}: loaded"),
            Err(e) => e.to_string(),
        };
        println!("{name}: {e}");
        assert!(!e.chars().any(char::is_control), "{name}: {e:?}");
        assert!(
            e.contains("meshes[0]") && e.contains("bad.glb"),
            "{name}: {e}"
        );
        assert!(e.contains(want), "{name}: {want:?} in {e}");
    }
}

/// Thousands of damaged copies of a good GLB (bytes overwritten, cut short, lengths and
/// counts changed at random, deterministically): each loads or is refused, and none panics
/// or hangs.
#[test]
fn damaged_files_never_panic() {
    let (p, t) = cube();
    let (bytes, ..) = geometry(&p, &t);
    let good = glb(&cube_document(bytes.len(), None, json!({})), &bytes);
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let scene = format!("{CAMERA}[[meshes]]\npath = \"x.glb\"\n");
    // Whether the scene loads with `file` as its glTF file (else it is refused).
    let loads = |file: &[u8]| {
        let files = [("x.glb", file)];
        prism::scene_file::parse_scene_with(
            &scene,
            std::path::Path::new("scene.toml"),
            prism::scene_file::Assets::Embedded(&files),
        )
        .is_ok()
    };
    let (mut loaded, mut refused) = (0, 0);
    for _ in 0..3000 {
        let mut file = good.clone();
        for _ in 0..1 + next() % 4 {
            let at = (next() as usize) % file.len();
            match next() % 3 {
                0 => file[at] = next() as u8,
                1 => file[at] = [0, 0xff, b'9', b'-'][(next() % 4) as usize],
                _ => file.truncate(at.max(1)),
            }
        }
        match loads(&file) {
            true => loaded += 1,
            false => refused += 1,
        }
    }
    // The document's numbers set to hostile values, the file otherwise well formed.
    let pointers = [
        "/accessors/0/count",
        "/accessors/0/byteOffset",
        "/accessors/1/count",
        "/accessors/1/componentType",
        "/bufferViews/0/byteLength",
        "/bufferViews/0/byteOffset",
        "/bufferViews/1/byteStride",
        "/buffers/0/byteLength",
        "/meshes/0/primitives/0/indices",
        "/meshes/0/primitives/0/attributes/POSITION",
        "/meshes/0/primitives/0/mode",
        "/nodes/0/children/0",
        "/nodes/1/mesh",
        "/scenes/0/nodes/0",
        "/scene",
    ];
    let hostile = [
        0i64,
        1,
        2,
        3,
        4,
        7,
        255,
        5121,
        5123,
        5125,
        5126,
        65535,
        1 << 31,
        -1,
    ];
    let good_doc = cube_document(bytes.len(), None, json!({}));
    for _ in 0..3000 {
        let mut doc = good_doc.clone();
        for _ in 0..1 + next() % 3 {
            let at = pointers[(next() as usize) % pointers.len()];
            let value = hostile[(next() as usize) % hostile.len()];
            if let Some(v) = doc.pointer_mut(at) {
                *v = json!(value);
            }
        }
        let file = glb(&doc, &bytes);
        match loads(&file) {
            true => loaded += 1,
            false => refused += 1,
        }
    }
    println!("{loaded} loaded, {refused} refused");
    assert!(loaded > 100 && refused > 1000);
}

/// A glTF camera chosen by the entry's `camera` (by name or index) views the scene: its
/// node's place, −z and +y, through the entry's placement, and its vertical field of view,
/// as the same camera written in `[camera]` by hand; a name it lacks is refused with the
/// names it has, two entries cannot both choose, and one that does not choose is told.
#[test]
fn a_gltf_camera_can_be_chosen() {
    let dir = TempDir::new();
    let (p, t) = cube();
    let (bytes, ..) = geometry(&p, &t);
    // Its node 3 up and 6 back from the origin, pitched down by atan(3/6).
    let pitch = -(0.5f64).atan();
    let (s, c) = ((pitch / 2.0).sin(), (pitch / 2.0).cos());
    let doc = cube_document(
        bytes.len(),
        None,
        json!({
            "cameras": [
                { "name": "wide", "type": "perspective", "perspective": { "yfov": 1.0, "znear": 0.1 } },
                { "name": "view", "type": "perspective", "perspective": { "yfov": 0.6, "znear": 0.1 } }
            ]
        }),
    );
    let mut doc = doc;
    doc["nodes"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "name": "eye", "camera": 1, "translation": [0.0, 3.0, 6.0], "rotation": [s, 0.0, 0.0, c] }));
    doc["scenes"][0]["nodes"] = json!([0, 2]);
    std::fs::write(dir.path("camera.glb"), glb(&doc, &bytes)).unwrap();
    let entry = |choice: &str| {
        format!(
            "[camera]\neye = [5, 5, 5]\nlook_at = [0, 0, 0]\nfov = 50\n\
             [[meshes]]\npath = \"camera.glb\"\ntranslate = [1, 0, 0]\n{choice}"
        )
    };
    let by_hand = load(
        &dir,
        &format!(
            "[camera]\neye = [1, 3, 6]\ndirection = [0, -3, -6]\nfov = {}\n\
             [[meshes]]\npath = \"camera.glb\"\ntranslate = [1, 0, 0]\ncamera = \"view\"\n",
            0.6f32.to_degrees()
        ),
    );
    for choice in ["camera = \"view\"\n", "camera = 1\n"] {
        let chosen = load(&dir, &entry(choice));
        let (a, b) = (&chosen.scene, &by_hand.scene);
        let eye = |s: &Scene| s.origin + s.camera.eye.as_dvec3();
        assert!(
            (eye(a) - DVec3::new(1.0, 3.0, 6.0)).length() < 1e-5,
            "{}",
            eye(a)
        );
        assert!((a.camera.yaw - b.camera.yaw).abs() < 1e-3, "{choice}");
        assert!((a.camera.pitch - (-(0.5f32).atan().to_degrees())).abs() < 1e-3);
        assert!((a.camera.vfov - 0.6f32.to_degrees()).abs() < 1e-4);
        assert!(chosen.unread().is_empty(), "{:?}", chosen.unread());
    }
    let e = load_scene_file(&dir.write("scene.toml", &entry("camera = \"veiw\"\n")))
        .result
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("did you mean \"view\"") && e.contains("(it has \"view\" (1))"),
        "{e}"
    );
    let twice = format!(
        "{}[[meshes]]\npath = \"camera.glb\"\ncamera = 1\n",
        entry("camera = 1\n")
    );
    let e = load_scene_file(&dir.write("scene.toml", &twice))
        .result
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("meshes[1]") && e.contains("chose the camera already"),
        "{e}"
    );
    let unchosen = load(&dir, &entry(""));
    assert!(
        unchosen.unread().join(" ").contains("camera"),
        "{:?}",
        unchosen.unread()
    );
    assert_eq!(unchosen.scene.camera.vfov, 50.0);
}
