//! The viewer's transform edits (`LoadedScene::place_object`): an object's `translate`, `rotate`
//! and `scale` set from outside the file give exactly the shapes the file with those values
//! gives, are refused where the file would be, and save back to a file that loads as the
//! scene shown.

use glam::{DVec3, Vec3};
use prism::scene::ShapeDesc;
use prism::scene::{EditError, ObjectPlacement};
use prism::scene_file::{LoadedScene, load_scene_file, saved_text};
use std::path::PathBuf;

/// A square pyramid with two materials: a mesh entry of two parts.
const PYRAMID_OBJ: &str = "\
mtllib pyramid.mtl
v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
v 0 1.5 0
usemtl stone
f 1 2 5
f 2 3 5
f 3 4 5
f 4 1 5
usemtl base
f 1 4 3
f 1 3 2
";

const PYRAMID_MTL: &str = "newmtl stone\nKd 0.7 0.6 0.5\nnewmtl base\nKd 0.2 0.2 0.2\n";

/// One entry of every kind, each written without a placement and then with `placements[i]`
/// (its lines appended to entry i).
const ENTRIES: [&str; 12] = [
    "[[spheres]]\nname = \"ball\"\ncenter = [1, 0.5, -2]\nradius = 0.75\n",
    "[[cylinders]]\nbase = [-2, -1, -3]\nradius = 0.5\nheight = 2\n",
    "[[polygons]]\nvertices = [[0, -1, -6], [2, -1, -6], [2, 1, -6.5], [0, 1, -6.5]]\n",
    "[[triangles]]\nvertices = [[-3, 2, -5], [-1, 2, -5], [-2, 3, -5.5]]\n",
    "[[tetrahedra]]\nvertices = [[3, -1, -4], [4, -1, -4], [3.5, -1, -5], [3.5, 0.5, -4.5]]\n",
    "[[boxes]]\nmin = [-1, -1, -8]\nmax = [0.5, 0, -7]\n",
    "[[discs]]\ncenter = [0, 2, -6]\nnormal = [0, 0, 1]\nradius = 0.6\n",
    "[[planes]]\npoint = [0, -1.5, 0]\nnormal = [0, 1, 0]\n",
    "[[cones]]\nbase = [2, -1, -7]\nradius = 0.5\ntop_radius = 0.1\nheight = 1.5\n",
    "[[tori]]\ncenter = [-2, 0, -6]\nmajor_radius = 0.8\nminor_radius = 0.2\n",
    "[[meshes]]\nname = \"pyramid\"\npath = \"pyramid.obj\"\n",
    "[[capsules]]\nbase = [-3.5, 1, -7]\nradius = 0.3\nheight = 1\n",
];

const HEADER: &str = "\
# Every kind of entry, for the placement edits.
[camera]
eye = [0.25, 1, 6]
look_at = [0, 0, -4]
fov = 50

[[lights]]
position = [4, 6, 4]
";

/// The scene text with `placements[i]` written into entry i where given.
fn text(placements: &[Option<ObjectPlacement>]) -> String {
    let mut t = HEADER.to_string();
    for (i, entry) in ENTRIES.iter().enumerate() {
        t.push('\n');
        t.push_str(entry);
        if let Some(Some(p)) = placements.get(i) {
            let [tx, ty, tz] = p.translate.to_array();
            let [rx, ry, rz] = p.rotate.to_array();
            let [sx, sy, sz] = p.scale.to_array();
            t.push_str(&format!(
                "translate = [{tx:?}, {ty:?}, {tz:?}]\nrotate = [{rx:?}, {ry:?}, {rz:?}]\n\
                 scale = [{sx:?}, {sy:?}, {sz:?}]\n"
            ));
        }
    }
    t
}

struct Files {
    _dir: tempfile::TempDir,
    dir: PathBuf,
}

impl Files {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("pyramid.obj"), PYRAMID_OBJ).unwrap();
        std::fs::write(dir.path().join("pyramid.mtl"), PYRAMID_MTL).unwrap();
        Files {
            dir: dir.path().to_path_buf(),
            _dir: dir,
        }
    }

    fn load(&self, name: &str, text: &str) -> LoadedScene {
        let path = self.dir.join(name);
        std::fs::write(&path, text).unwrap();
        match load_scene_file(&path).result {
            Ok(loaded) => loaded,
            Err(e) => panic!("{e}\n{text}"),
        }
    }
}

fn placement(translate: [f64; 3], rotate: [f32; 3], scale: [f64; 3]) -> ObjectPlacement {
    ObjectPlacement {
        translate: DVec3::from(translate),
        rotate: Vec3::from(rotate),
        scale: DVec3::from(scale),
    }
}

/// The objects entry `entry` of ENTRIES makes (the mesh makes two: one per material).
fn objects_of(loaded: &LoadedScene, entry: usize) -> Vec<usize> {
    let table = ENTRIES[entry]
        .trim_start_matches("[[")
        .split("]]")
        .next()
        .unwrap();
    (0..loaded.origins.len())
        .filter(|&i| loaded.origins[i].table == table)
        .collect()
}

#[test]
fn the_file_s_placement_is_what_the_objects_show() {
    let files = Files::new();
    let loaded = files.load("plain.toml", &text(&[]));
    assert_eq!(loaded.scene.objects.len(), ENTRIES.len() + 1);
    for o in &loaded.scene.objects {
        assert_eq!(o.placement, ObjectPlacement::IDENTITY, "{}", o.name);
    }
    let p = placement([1.5, -0.25, 3.0], [10.0, 20.0, 30.0], [2.0, 2.0, 0.5]);
    let placed = files.load("placed.toml", &text(&vec![Some(p); ENTRIES.len()]));
    for o in &placed.scene.objects {
        assert_eq!(o.placement, p, "{}", o.name);
    }
    // A single number scales every axis alike.
    let one = files.load("one.toml", &format!("{HEADER}\n{}scale = 3\n", ENTRIES[0]));
    assert_eq!(one.scene.objects[0].placement.scale, DVec3::splat(3.0));
}

/// Each kind, placed in each way its shape's own parameters can or cannot say (a move, an
/// even scale, a turn, an uneven scale, all together), equals the file with those values,
/// bit for bit, and no other object changes.
#[test]
fn every_kind_placed_by_an_edit_equals_the_file_with_those_values() {
    let files = Files::new();
    let loaded = files.load("scene.toml", &text(&[]));
    let placements = [
        placement([0.5, -1.0, 2.0], [0.0; 3], [1.0; 3]),
        placement([0.0; 3], [0.0; 3], [1.5; 3]),
        placement([0.0; 3], [0.0, 90.0, 0.0], [1.0; 3]),
        placement([0.0; 3], [0.0; 3], [2.0, 1.0, 2.0]),
        placement([-0.75, 0.25, 1e-3], [30.0, -45.0, 370.0], [0.5, 1.25, 2.0]),
        ObjectPlacement::IDENTITY,
    ];
    for entry in 0..ENTRIES.len() {
        for p in placements {
            let mut edited = loaded.scene.clone();
            let objects = objects_of(&loaded, entry);
            loaded.place_object(&mut edited, objects[0], p).unwrap();
            let mut wanted = vec![None; ENTRIES.len()];
            wanted[entry] = Some(p);
            let file = files.load("expected.toml", &text(&wanted));
            for i in 0..edited.objects.len() {
                let (got, want) = (&edited.objects[i], &file.scene.objects[i]);
                assert_eq!(got.shape, want.shape, "entry {entry}, object {i}, {p:?}");
                assert_eq!(got.placement, want.placement, "entry {entry}, object {i}");
            }
        }
    }
}

#[test]
fn a_placement_the_file_refuses_is_refused_naming_the_entry() {
    let files = Files::new();
    let loaded = files.load("scene.toml", &text(&[]));
    let cases: [(usize, ObjectPlacement, &str); 4] = [
        (
            0,
            placement([0.0; 3], [0.0; 3], [0.0; 3]),
            "`scale` must be greater than zero",
        ),
        (
            0,
            placement([1e30, 0.0, 0.0], [0.0; 3], [1.0; 3]),
            "`translate`",
        ),
        (
            1,
            placement([0.0; 3], [0.0; 3], [f64::NAN, 1.0, 1.0]),
            "`scale`",
        ),
        (
            objects_of(&loaded, 10)[0],
            placement([1e12, 0.0, 0.0], [0.0; 3], [1e6; 3]),
            "the mesh, placed",
        ),
    ];
    for (object, p, says) in cases {
        let mut edited = loaded.scene.clone();
        let e = loaded.place_object(&mut edited, object, p).unwrap_err();
        let EditError::Placement { item, message } = &e else {
            panic!("{e:?}")
        };
        let entry = &loaded.origins[object];
        assert!(
            item.starts_with(&format!("{}[{}]", entry.table, entry.index)),
            "{e}"
        );
        assert!(message.contains(says), "{e}");
        assert_eq!(edited, loaded.scene, "a refused edit changes nothing");
    }
    let mut edited = loaded.scene.clone();
    assert_eq!(
        loaded.place_object(&mut edited, 99, ObjectPlacement::IDENTITY),
        Err(EditError::NoSuchObject(99))
    );
}

/// A mesh entry's parts are placed together; saved, every placement edit reads back as the
/// scene shown, the file's comments kept and untouched fields as they were.
#[test]
fn placements_save_back_and_load_as_the_scene_shown() {
    let files = Files::new();
    let loaded = files.load("scene.toml", &text(&[]));
    let mesh = objects_of(&loaded, 10);
    assert_eq!(mesh.len(), 2, "the pyramid has two materials");
    let mut edited = loaded.scene.clone();
    loaded
        .place_object(
            &mut edited,
            mesh[1],
            placement([0.0, 0.5, -1.0], [0.0, 45.0, 0.0], [1.5; 3]),
        )
        .unwrap();
    assert_eq!(
        edited.objects[mesh[0]].placement,
        edited.objects[mesh[1]].placement
    );
    let transform = |i: usize| match &edited.objects[i].shape {
        ShapeDesc::Mesh { transform, .. } => *transform,
        other => panic!("{other:?}"),
    };
    assert_eq!(transform(mesh[0]), transform(mesh[1]));
    loaded
        .place_object(
            &mut edited,
            0,
            placement([0.0; 3], [0.0; 3], [1.0, 2.0, 1.0]),
        )
        .unwrap();
    loaded
        .place_object(
            &mut edited,
            5,
            placement([0.25, 0.0, 0.0], [0.0, 0.0, 15.0], [1.0; 3]),
        )
        .unwrap();
    let saved = saved_text(&loaded, &edited, &edited.camera).unwrap();
    assert!(saved.skipped.is_empty(), "{:?}", saved.skipped);
    for line in [
        "# Every kind of entry",
        "scale = 1.5",
        "scale = [1.0, 2.0, 1.0]",
        "rotate = [0.0, 0.0, 15.0]",
    ] {
        assert!(saved.text.contains(line), "{line} not in\n{}", saved.text);
    }
    // Only changed fields are written: the box's scale stays unwritten.
    let boxes = saved.text.split("[[boxes]]").nth(1).unwrap();
    let boxes = boxes.split("[[").next().unwrap();
    assert!(!boxes.contains("scale"), "{boxes}");
    let back = files.load("scene.toml", &saved.text);
    assert_eq!(back.scene.objects, edited.objects, "{}", saved.text);
}

/// At a frame of an animation, the placement shown is the frame's, and placing the object
/// there starts from it.
#[test]
fn an_animated_placement_is_edited_at_its_frame() {
    let files = Files::new();
    let animated = format!(
        "{}\n[animation]\nframes = 11\n[[animation.track]]\ntarget = \"ball\"\n\
         field = \"translate\"\ninterpolation = \"linear\"\n\
         keys = [{{ frame = 0, value = [0, 0, 0] }}, {{ frame = 10, value = [2, 0, 0] }}]\n",
        text(&[])
    );
    let path = files.dir.join("animated.toml");
    std::fs::write(&path, &animated).unwrap();
    let loaded = prism::scene_file::load_scene_file_at(&path, 5)
        .result
        .unwrap();
    let ball = &loaded.scene.objects[0];
    assert_eq!(ball.placement.translate, DVec3::new(1.0, 0.0, 0.0));
    let mut edited = loaded.scene.clone();
    loaded.place_object(&mut edited, 0, ball.placement).unwrap();
    assert_eq!(
        edited, loaded.scene,
        "the frame's own placement changes nothing"
    );
    let turned = ObjectPlacement {
        rotate: Vec3::new(0.0, 0.0, 90.0),
        ..ball.placement
    };
    loaded.place_object(&mut edited, 0, turned).unwrap();
    let still = files.load("still.toml", &text(&[Some(turned)]));
    assert_eq!(edited.objects[0].shape, still.scene.objects[0].shape);
}
