//! Groups: entries placed in a group's frame against POV-Ray's nested `union`s with the
//! same transforms (flat colours, then lit by a light inside a group), a group's transform
//! composed with its members' as arithmetic says, a moon orbiting an orbiting planet
//! frame by frame, edits of a group in the viewer's terms (placed again, refused, undone,
//! saved), and every bad table refused at its line.

mod common;

use common::povray::{compare, povray_available, povray_render, prism_render};
use glam::{DMat3, DVec3, Vec3};
use prism::appearance::LightKind;
use prism::scene::{EditError, ObjectPlacement, Scene, ShapeDesc};
use prism::scene_file::{Animation, Assets, LoadedScene, parse_loaded, parse_scene, saved_text};
use std::path::Path;

const W: u32 = 320;
const H: u32 = 240;

/// The groups, as prism's file writes them: a group turned and scaled, a group in it
/// scaled unevenly and turned, and a group in that one.
const GROUPS: &str = "\
[[groups]]
name = \"outer\"
scale = 1.1
rotate = [0, 30, 0]
translate = [0.5, 0, -0.5]

[[groups]]
name = \"inner\"
group = \"outer\"
scale = [1, 1.5, 0.8]
rotate = [20, 0, 10]
translate = [1.5, 0.8, 0]

[[groups]]
name = \"leaf\"
group = \"inner\"
rotate = [0, 0, 45]
translate = [-0.6, 0.9, 0.3]
";

/// The members, prism's way and POV-Ray's: which group each is in, and both texts.
const MEMBERS: [(&str, &str, &str); 6] = [
    (
        "outer",
        "[[spheres]]\ncenter = [-2.2, 0.5, 0]\nradius = 0.6\ntranslate = [0, 0.3, 0]\nmaterial = \"red\"\n",
        "sphere { <-2.2, 0.5, 0>, 0.6 translate <0, 0.3, 0> pigment { rgb <1, 0, 0> } finish { F } }",
    ),
    (
        "inner",
        "[[boxes]]\nmin = [-0.4, -0.4, -0.4]\nmax = [0.4, 0.4, 0.4]\nrotate = [0, 20, 0]\nmaterial = \"green\"\n",
        "box { -0.4, 0.4 rotate <0, 20, 0> pigment { rgb <0, 1, 0> } finish { F } }",
    ),
    (
        "inner",
        "[[tori]]\ncenter = [0, -0.9, 0]\nmajor_radius = 0.6\nminor_radius = 0.15\nmaterial = \"yellow\"\n",
        "torus { 0.6, 0.15 translate <0, -0.9, 0> pigment { rgb <1, 1, 0> } finish { F } }",
    ),
    (
        "leaf",
        "[[cylinders]]\nbase = [0, -0.4, 0]\nradius = 0.2\nheight = 0.8\nscale = [1, 1, 2]\nmaterial = \"blue\"\n",
        "cylinder { <0, -0.4, 0>, <0, 0.4, 0>, 0.2 scale <1, 1, 2> pigment { rgb <0, 0, 1> } finish { F } }",
    ),
    (
        "outer",
        "[[csg]]\noperation = \"difference\"\nmaterial = \"cyan\"\ntranslate = [-0.6, -0.2, 1.2]\n\
         [[csg.members]]\ntype = \"box\"\nmin = [-0.5, -0.5, -0.5]\nmax = [0.5, 0.5, 0.5]\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [0.3, 0.3, 0.3]\nradius = 0.5\n",
        "difference { box { -0.5, 0.5 } sphere { <0.3, 0.3, 0.3>, 0.5 } \
         pigment { rgb <0, 1, 1> } finish { F } translate <-0.6, -0.2, 1.2> }",
    ),
    (
        "leaf",
        "[[triangles]]\nvertices = [[0.3, 0, 0], [1.1, 0, 0], [0.3, 0.7, 0.2]]\nmaterial = \"magenta\"\n",
        "triangle { <0.3, 0, 0>, <1.1, 0, 0>, <0.3, 0.7, 0.2> pigment { rgb <1, 0, 1> } finish { F } }",
    ),
];

const COLOURS: [(&str, [u8; 3]); 6] = [
    ("red", [255, 0, 0]),
    ("green", [0, 255, 0]),
    ("yellow", [255, 255, 0]),
    ("blue", [0, 0, 255]),
    ("cyan", [0, 255, 255]),
    ("magenta", [255, 0, 255]),
];

/// prism's scene: `head`, the groups, a light placed in group `inner` when `light` is
/// given, each material `finish` over its colour, and the members in their groups.
fn prism_scene(head: &str, finish: &str, light: Option<&str>) -> String {
    let mut s = format!(
        "[camera]\neye = [0, 3, 8]\nlook_at = [0, 1, 0]\nfov = 40\n\n{head}\n{GROUPS}\n\
         [materials.gray]\ncolor = [0.5, 0.5, 0.5]\n{finish}\n\
         [[planes]]\npoint = [0, -1.2, 0]\nnormal = [0, 1, 0]\nmaterial = \"gray\"\n"
    );
    if let Some(at) = light {
        s += &format!("[[lights]]\ngroup = \"inner\"\nposition = {at}\n");
    }
    for (name, rgb) in COLOURS {
        let c = rgb.map(|v| v as f32 / 255.0);
        s += &format!("[materials.{name}]\ncolor = {c:?}\n{finish}\n");
    }
    for (group, toml, _) in MEMBERS {
        // The group's name goes in the entry's own table (before any [[csg.members]]).
        let (first, rest) = toml.split_once('\n').unwrap();
        s += &format!("{first}\ngroup = \"{group}\"\n{rest}\n");
    }
    s
}

/// POV-Ray's scene: the same members in nested unions with the groups' transforms, a
/// light in union `inner` at `light` when given.
fn povray_scene(finish: &str, light: Option<&str>) -> String {
    let aspect = W as f64 / H as f64;
    let members = |group: &str| {
        MEMBERS
            .iter()
            .filter(|(g, ..)| *g == group)
            .map(|(.., pov)| format!("{pov}\n"))
            .collect::<String>()
    };
    let lamp = light.map_or(String::new(), |at| {
        format!(
            "light_source {{ <{}> color rgb 1 }}\n",
            &at[1..at.len() - 1]
        )
    });
    format!(
        "#version 3.7;\nglobal_settings {{ assumed_gamma 1.0 ambient_light 1 }}\n\
         camera {{ perspective location <0, 3, 8> look_at <0, 1, 0> right -x * {aspect} up y \
         angle 2 * degrees(atan(tan(radians(20)) * {aspect})) }}\n\
         background {{ rgb 0 }}\n#declare F = finish {{ {finish} }};\n\
         plane {{ y, -1.2 pigment {{ rgb 0.5 }} finish {{ F }} }}\n\
         union {{\n{}\
           union {{\n{}{lamp}\
             union {{\n{} rotate <0, 0, 45> translate <-0.6, 0.9, 0.3> }}\n\
             scale <1, 1.5, 0.8> rotate <20, 0, 10> translate <1.5, 0.8, 0> }}\n\
           scale 1.1 rotate <0, 30, 0> translate <0.5, 0, -0.5> }}\n",
        members("outer"),
        members("inner"),
        members("leaf"),
    )
}

/// Flat colours: every member, in its group's frame, covers the pixels POV-Ray's nested
/// unions with the same transforms cover.
#[test]
fn groups_place_their_members_as_povrays_unions_do() {
    if !povray_available() {
        return;
    }
    let reference = povray_render(&povray_scene("ambient 1 diffuse 0 specular 0", None), W, H);
    let ours = prism_render(
        &prism_scene(
            "[render]\nbackground = [0, 0, 0]\nambient = [1, 1, 1]\n",
            "ambient = 1\ndiffuse = 0\nspecular = 0\n",
            None,
        ),
        W,
        H,
        None,
    );
    for (name, colour) in COLOURS {
        let n = ours.pixels().filter(|p| p.0 == colour).count();
        assert!(n > 150, "{name}: {n} pixels");
    }
    let (far, _) = compare(&ours, &reference, 1);
    assert!(far <= 10, "{far} of {} pixels differ from POV-Ray's", W * H);
}

/// Lit by a light placed in a group: the light moves with its group as POV-Ray's
/// `light_source` in a `union` does (diffuse shading and shadows); the same light left in
/// the world's frame does not match.
#[test]
fn a_light_in_a_group_lights_as_povrays() {
    if !povray_available() {
        return;
    }
    let light = "[0.5, 2.5, 2.5]";
    let reference = povray_render(
        &povray_scene("ambient 0.2 diffuse 0.8 specular 0", Some(light)),
        W,
        H,
    );
    let head = "[render]\nbackground = [0, 0, 0]\nambient = [1, 1, 1]\n";
    let finish = "ambient = 0.2\ndiffuse = 0.8\nspecular = 0\n";
    let ours = prism_render(&prism_scene(head, finish, Some(light)), W, H, None);
    let (far, mean) = compare(&ours, &reference, 2);
    println!("lit: {far} pixels beyond 2 levels, mean {mean:.3}");
    assert!(
        far <= 20 && mean < 0.05,
        "{far} pixels beyond 2 levels, mean {mean:.3}"
    );
    // The light where the file writes it, unmoved by its group: clearly another image.
    let unmoved = prism_scene(head, finish, Some(light))
        .replace("[[lights]]\ngroup = \"inner\"\n", "[[lights]]\n");
    let (far_unmoved, _) = compare(&prism_render(&unmoved, W, H, None), &reference, 2);
    assert!(
        far_unmoved > 50 * far.max(20),
        "{far_unmoved} against {far}"
    );
}

fn load(text: &str) -> Scene {
    parse_scene(text, Path::new("groups.toml"), Path::new(".")).unwrap()
}

fn loaded(text: &str) -> LoadedScene {
    parse_loaded(
        text,
        Path::new("groups.toml"),
        Assets::Folder(Path::new(".")),
    )
    .unwrap()
}

const CAMERA: &str = "[camera]\neye = [0, 0, 10]\nlook_at = [0, 0, 0]\nfov = 40\n";

/// A sphere's world centre (relative to the camera, as the scene stores it) and radius,
/// whether it kept its own parameters or went under a transform.
fn sphere_at(shape: &ShapeDesc) -> (Vec3, f32) {
    match shape {
        ShapeDesc::Sphere { center, radius } => (*center, *radius),
        ShapeDesc::Transformed { shape, transform } => {
            let ShapeDesc::Sphere { center, radius } = **shape else {
                panic!("not a sphere: {shape:?}")
            };
            let m = transform.to_scene();
            (
                m.transform_point3(center),
                radius * m.matrix3.x_axis.length(),
            )
        }
        other => panic!("not a sphere: {other:?}"),
    }
}

/// The turn `rotate` (degrees about x, then y, then z) as a matrix, computed here apart
/// from prism's own.
fn turn(deg: [f64; 3]) -> DMat3 {
    let [x, y, z] = deg.map(f64::to_radians);
    DMat3::from_rotation_z(z) * DMat3::from_rotation_y(y) * DMat3::from_rotation_x(x)
}

/// A sphere two groups deep lands where the groups' maps, applied in turn, put its centre;
/// its radius scales by the groups' even scales; its solid texture turns with them; and a
/// group of a move alone gives bit for bit the shape of the sum of the moves written by hand.
#[test]
fn a_groups_transform_composes_with_its_members() {
    let scene = load(&format!(
        "{CAMERA}\
         [[groups]]\nname = \"a\"\nscale = 2\nrotate = [0, 90, 0]\ntranslate = [1, 0, 0]\n\
         [[groups]]\nname = \"b\"\ngroup = \"a\"\nrotate = [0, 0, 90]\ntranslate = [0, 1, 0]\n\
         [[spheres]]\nname = \"s\"\ngroup = \"b\"\ncenter = [1, 0, 0]\nradius = 0.25\ntranslate = [0, 0, 0.5]\n\
         [[spheres]]\nname = \"moved\"\ngroup = \"c\"\ncenter = [0.1, 0.2, 0.3]\nradius = 0.5\ntranslate = [2, 0, 0]\n\
         [[spheres]]\nname = \"by hand\"\ncenter = [0.1, 0.2, 0.3]\nradius = 0.5\ntranslate = [3, -1, 0]\n\
         [[groups]]\nname = \"c\"\ntranslate = [1, -1, 0]\n"
    ));
    let p = |deg: [f64; 3], s: f64, t: [f64; 3], v: DVec3| turn(deg) * (v * s) + DVec3::from(t);
    let local = DVec3::new(1.0, 0.0, 0.5);
    let in_a = p([0.0, 0.0, 90.0], 1.0, [0.0, 1.0, 0.0], local);
    let world = p([0.0, 90.0, 0.0], 2.0, [1.0, 0.0, 0.0], in_a);
    let (center, radius) = sphere_at(&scene.objects[0].shape);
    let center = scene.origin + center.as_dvec3();
    assert!((center - world).length() < 1e-5, "{center} against {world}");
    assert!((radius - 0.5).abs() < 1e-6, "{radius}");
    // Its textures turn and scale with both groups.
    let linear = scene.object_linear(0);
    let want = turn([0.0, 90.0, 0.0]) * 2.0 * turn([0.0, 0.0, 90.0]);
    assert!(
        (linear - want)
            .abs()
            .to_cols_array()
            .iter()
            .all(|d| *d < 1e-12)
    );
    // A group declared after its member still places it; a move composes exactly.
    assert_eq!(scene.objects[1].shape, scene.objects[2].shape);
    assert_eq!(scene.objects[1].group, Some(2));
    assert_eq!(scene.objects[2].group, None);
}

/// A moon in a group turning inside a planet's group turning about the sun, keyed by an
/// animation: at every frame the moon is where the two turns put it.
#[test]
fn a_moon_orbits_an_orbiting_planet() {
    let text = format!(
        "{CAMERA}\
         [[groups]]\nname = \"planet-orbit\"\n\
         [[groups]]\nname = \"planet\"\ngroup = \"planet-orbit\"\ntranslate = [6, 0, 0]\n\
         [[groups]]\nname = \"moon-orbit\"\ngroup = \"planet\"\n\
         [[spheres]]\nname = \"planet\"\ngroup = \"planet\"\ncenter = [0, 0, 0]\nradius = 1\n\
         [[spheres]]\nname = \"moon\"\ngroup = \"moon-orbit\"\ncenter = [2, 0, 0]\nradius = 0.25\n\
         [animation]\nframes = 12\n\
         [[animation.track]]\ntarget = \"planet-orbit\"\nfield = \"rotate\"\ninterpolation = \"linear\"\n\
         keys = [{{ frame = 0, value = [0, 0, 0] }}, {{ frame = 12, value = [0, 360, 0] }}]\n\
         [[animation.track]]\ntarget = \"groups[2]\"\nfield = \"rotate\"\ninterpolation = \"linear\"\n\
         keys = [{{ frame = 0, value = [0, 0, 0] }}, {{ frame = 12, value = [0, 1440, 0] }}]\n"
    );
    let path = Path::new("orbits.toml");
    let animation = Animation::parse(&text, path).unwrap().unwrap();
    let mut moon_paths = Vec::new();
    for frame in 0..12u32 {
        let scene = animation
            .scene_at(frame, path, Assets::Folder(Path::new(".")))
            .unwrap();
        let theta = 30.0 * frame as f64;
        let planet = turn([0.0, theta, 0.0]) * DVec3::new(6.0, 0.0, 0.0);
        let moon = turn([0.0, theta, 0.0])
            * (DVec3::new(6.0, 0.0, 0.0) + turn([0.0, 4.0 * theta, 0.0]) * DVec3::X * 2.0);
        for (i, want) in [(0, planet), (1, moon)] {
            let (c, _) = sphere_at(&scene.objects[i].shape);
            let c = scene.origin + c.as_dvec3();
            assert!(
                (c - want).length() < 1e-4,
                "frame {frame}, {i}: {c} against {want}"
            );
        }
        moon_paths.push(moon);
    }
    // The moon is not merely carried: it leaves the planet's circle.
    assert!(moon_paths.iter().any(|m| (m.length() - 6.0).abs() > 1.5));
}

/// Lights in a group follow it: a point light's position, a spotlight's axis and a
/// rectangle's edges, and a sphere light's radius with an even scale.
#[test]
fn lights_follow_their_group() {
    let scene = load(&format!(
        "{CAMERA}\
         [[groups]]\nname = \"g\"\nscale = 2\nrotate = [0, 0, 90]\ntranslate = [1, 2, 3]\n\
         [[lights]]\ngroup = \"g\"\nposition = [1, 0, 0]\n\
         [[lights]]\ngroup = \"g\"\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [1, 0, 0]\nangle = 20\n\
         [[lights]]\ngroup = \"g\"\ntype = \"area\"\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\nedge_v = [0, 0, 1]\n\
         [[lights]]\ngroup = \"g\"\ntype = \"sphere\"\nposition = [0, 0, 0]\nradius = 0.5\n"
    ));
    let world = |v: Vec3| (scene.origin + v.as_dvec3()).as_vec3();
    let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-5;
    let LightKind::Point { position, .. } = scene.lights[0].kind else {
        panic!()
    };
    assert!(
        close(world(position), Vec3::new(1.0, 4.0, 3.0)),
        "{position}"
    );
    let LightKind::Spot { cone, .. } = scene.lights[1].kind else {
        panic!()
    };
    assert!(close(cone.direction, Vec3::Y), "{}", cone.direction);
    let LightKind::Area { shape, .. } = scene.lights[2].kind else {
        panic!()
    };
    let prism::appearance::AreaShape::Rectangle { edge_u, edge_v, .. } = shape else {
        panic!()
    };
    assert!(close(edge_u, Vec3::new(0.0, 2.0, 0.0)) && close(edge_v, Vec3::new(0.0, 0.0, 2.0)));
    let LightKind::Area { shape, .. } = scene.lights[3].kind else {
        panic!()
    };
    let prism::appearance::AreaShape::Sphere { radius, .. } = shape else {
        panic!()
    };
    assert!((radius - 1.0).abs() < 1e-6, "{radius}");
    assert_eq!(scene.groups[0].lights, vec![0, 1, 2, 3]);
}

const EDITED: &str = "\
[camera]
eye = [0, 0, 10]
look_at = [0, 0, 0]
fov = 40

[[groups]]
name = \"arm\"
translate = [1, 0, 0]

[[groups]]
name = \"hand\"
group = \"arm\"
translate = [0, 1, 0]

[[lights]]
group = \"hand\"
position = [0, 0, 1]

[[spheres]]
name = \"ball\"
group = \"hand\"
center = [0, 0, 0]
radius = 0.5

[[spheres]]
name = \"apart\"
center = [-3, 0, 0]
radius = 0.5
";

/// A group placed anew moves what is in it, its subgroups' included, and nothing else,
/// exactly as the file with the new values would; a placement the file would refuse is
/// refused naming the group, leaving the scene as it was; and the edit saves into the
/// group's entry, the file then loading as the scene shown.
#[test]
fn editing_a_group_places_its_members_again_and_saves() {
    let loaded = loaded(EDITED);
    let mut scene = loaded.scene.clone();
    let new = ObjectPlacement {
        translate: DVec3::new(2.0, 0.0, 0.0),
        rotate: Vec3::new(0.0, 0.0, 90.0),
        scale: DVec3::ONE,
    };
    loaded.place_group(&mut scene, 0, new).unwrap();
    let by_file = load(&EDITED.replacen(
        "translate = [1, 0, 0]",
        "translate = [2, 0, 0]\nrotate = [0, 0, 90]",
        1,
    ));
    assert_eq!(scene.objects, by_file.objects);
    assert_eq!(scene.lights, by_file.lights);
    assert_eq!(scene.groups, by_file.groups);
    // The ball went from (1, 1, 0) to (2 − 1, 0, 0); the other sphere stayed.
    let (c, _) = sphere_at(&scene.objects[0].shape);
    assert!(((scene.origin + c.as_dvec3()) - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-5);
    assert_eq!(scene.objects[1], loaded.scene.objects[1]);

    // An edit of the light's colour stays when its group moves again.
    scene.lights[0].color = Vec3::new(0.2, 0.4, 0.6);
    let again = ObjectPlacement {
        translate: DVec3::new(0.0, 0.0, 1.0),
        ..ObjectPlacement::IDENTITY
    };
    loaded.place_group(&mut scene, 1, again).unwrap();
    assert_eq!(scene.lights[0].color, Vec3::new(0.2, 0.4, 0.6));
    let LightKind::Point { position, .. } = scene.lights[0].kind else {
        panic!()
    };
    // In `hand` (now at (0, 0, 1) in `arm`, which turns 90° about z and moves by (2, 0, 0)).
    let want = DVec3::new(2.0, 0.0, 2.0);
    assert!(((scene.origin + position.as_dvec3()) - want).length() < 1e-5);

    // Refused as the file would refuse it; the scene unchanged.
    let before = scene.clone();
    let bad = ObjectPlacement {
        scale: DVec3::new(0.0, 1.0, 1.0),
        ..ObjectPlacement::IDENTITY
    };
    let e = loaded.place_group(&mut scene, 0, bad).unwrap_err();
    let EditError::Placement { item, message } = &e else {
        panic!("{e:?}")
    };
    assert!(item.contains("groups[0]") && item.contains("arm"), "{e}");
    assert!(message.contains("scale"), "{e}");
    assert_eq!(scene, before);
    assert!(matches!(
        loaded.place_group(&mut scene, 7, new),
        Err(EditError::NoSuchGroup(7))
    ));

    // Saved: the groups' entries get the new values, the light its colour but not a place
    // (its group says where it is), and the file loads as the scene shown.
    let saved = saved_text(&loaded, &scene, &scene.camera).unwrap();
    assert!(saved.skipped.is_empty(), "{:?}", saved.skipped);
    let back = load(&saved.text);
    assert_eq!(back.groups, scene.groups);
    assert_eq!(back.objects, scene.objects);
    assert_eq!(back.lights, scene.lights, "{}", saved.text);
    assert!(
        saved.text.contains("position = [0, 0, 1]"),
        "{}",
        saved.text
    );
}

/// An object in a group placed anew by its own values lands in its group's frame.
#[test]
fn editing_an_object_in_a_group_keeps_it_in_the_group() {
    let loaded = loaded(EDITED);
    let mut scene = loaded.scene.clone();
    let p = ObjectPlacement {
        translate: DVec3::new(0.0, 0.0, 2.0),
        ..ObjectPlacement::IDENTITY
    };
    loaded.place_object(&mut scene, 0, p).unwrap();
    let (c, _) = sphere_at(&scene.objects[0].shape);
    let want = DVec3::new(1.0, 1.0, 2.0);
    assert!(((scene.origin + c.as_dvec3()) - want).length() < 1e-5);
    assert_eq!(scene.objects[0].placement, p);
    assert_eq!(scene.objects[0].group, Some(1));
}

/// A scene whose members are grouped renders the same image at every scale, as any does:
/// the groups' frames hold no precision the stress suite can see.
#[test]
fn grouped_scenes_render_the_same_at_every_scale() {
    let scene = load(&prism_scene(
        "[render]\nbackground = [0.2, 0.2, 0.3]\nambient = [0.3, 0.3, 0.3]\n",
        "ambient = 1\ndiffuse = 0.8\nspecular = 0.3\n",
        Some("[0.5, 2.5, 2.5]"),
    ));
    let image = |scene: &Scene| {
        let mut settings = prism::render::RenderSettings::new(160, 120, 1);
        settings.layout = prism::sampler::SampleLayout::Grid;
        common::render_scene(scene, settings)
    };
    let base = image(&scene);
    for (scale, offset) in [
        (1e-3f32, DVec3::ZERO),
        (1e3, DVec3::ZERO),
        (1.0, DVec3::splat(1e5)),
    ] {
        let other = image(&scene.transformed(scale, offset));
        let (far, _) = compare(&base, &other, 2);
        assert!(
            far <= 8,
            "scale {scale}, offset {offset}: {far} pixels differ"
        );
    }
}

/// Every bad group table, and every bad use of one, refused with its line and entry.
#[test]
fn every_bad_group_is_refused_with_its_line() {
    let cases: [(&str, &str, &[&str]); 9] = [
        (
            "[[groups]]\nname = \"a\"\n[[spheres]]\ngroup = \"b\"\ncenter = [0, 0, 0]\nradius = 1\n",
            "line 4",
            &["no group named \"b\"", "spheres[0]"],
        ),
        (
            "[[groups]]\nname = \"planet\"\n[[spheres]]\ngroup = \"plnet\"\ncenter = [0, 0, 0]\nradius = 1\n",
            "line 4",
            &["did you mean \"planet\"?"],
        ),
        (
            "[[groups]]\nname = \"a\"\n[[groups]]\nname = \"a\"\n",
            "line 4",
            &["groups[1]", "has this name already"],
        ),
        (
            "[[groups]]\nname = \"a\"\ngroup = \"b\"\n[[groups]]\nname = \"b\"\ngroup = \"a\"\n",
            "line 3",
            &["groups[0]", "within itself"],
        ),
        ("[[groups]]\nname = \" \"\n", "line 2", &["not blank"]),
        (
            "[[groups]]\nname = \"a\"\ncolour = [1, 0, 0]\n",
            "line 3",
            &["colour"],
        ),
        (
            "[[groups]]\nname = \"a\"\nscale = [1, -1, 1]\n",
            "line 3",
            &["groups[0]", "scale"],
        ),
        (
            "[[groups]]\nname = \"a\"\nscale = [1, 2, 1]\n\
             [[lights]]\ntype = \"sphere\"\ngroup = \"a\"\nposition = [0, 0, 0]\nradius = 0.5\n",
            "line 6",
            &["lights[0]", "unevenly"],
        ),
        (
            "[[groups]]\nname = \"a\"\n[[csg]]\noperation = \"union\"\n\
             [[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\ngroup = \"a\"\n\
             [[csg.members]]\ntype = \"sphere\"\ncenter = [1, 0, 0]\nradius = 1\n",
            "line 9",
            &["give the whole a group"],
        ),
    ];
    for (body, line, words) in cases {
        let text = format!("{CAMERA}{body}");
        let body_lines = CAMERA.lines().count();
        let e = parse_scene(&text, Path::new("g.toml"), Path::new("."))
            .unwrap_err()
            .to_string();
        let want: usize = line[5..].parse::<usize>().unwrap() + body_lines;
        assert!(e.contains(&format!("g.toml:{want}:")), "{body}: {e}");
        for w in words {
            assert!(e.contains(w), "{body}: {e}");
        }
    }
    // Nesting deeper than the limit: refused at the deepest group.
    let mut deep = String::from(CAMERA);
    for i in 0..=prism::limits::MAX_GROUP_DEPTH {
        deep += &format!("[[groups]]\nname = \"g{i}\"\n");
        if i > 0 {
            deep += &format!("group = \"g{}\"\n", i - 1);
        }
    }
    let e = parse_scene(&deep, Path::new("g.toml"), Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(e.contains("nest at most 32 deep"), "{e}");
}
