//! CSG: combinations of solids against POV-Ray's `union`, `intersection`, `difference` and
//! `merge` (flat colours, one ray per pixel centre, then lit, then a glass lens refracting a
//! checker), the meaning of each operation at points along a ray, shadows and crossings,
//! the same image at every scale and far away, and every bad table refused at its line.

mod common;

use common::povray::{compare, povray_available, povray_render, prism_render};
use glam::{DVec3, Vec3};
use prism::render::RenderSettings;
use prism::scene::Scene;
use prism::scene_file::parse_scene;
use std::path::Path;

const W: u32 = 320;
const H: u32 = 240;

/// Each combination as prism's scene file and POV-Ray's scene language write it: turned,
/// scaled (unevenly too), members placed on their own, nested, and a plane as a half-space.
const COMBINATIONS: [(&str, &str); 5] = [
    (
        "[[csg]]\noperation = \"difference\"\nmaterial = \"red\"\nscale = [1.2, 0.8, 1]\n\
         rotate = [20, 35, 0]\ntranslate = [-2, 0.4, 0]\n\
         [[csg.members]]\ntype = \"box\"\nmin = [-0.8, -0.8, -0.8]\nmax = [0.8, 0.8, 0.8]\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0.5, 0.5]\nradius = 0.9\nmaterial = \"cyan\"\n",
        "difference { box { <-0.8, -0.8, -0.8>, <0.8, 0.8, 0.8> } \
         sphere { <0, 0.5, 0.5>, 0.9 pigment { rgb <0, 1, 1> } finish { F } } \
         pigment { rgb <1, 0, 0> } finish { F } scale <1.2, 0.8, 1> rotate <20, 35, 0> \
         translate <-2, 0.4, 0> }",
    ),
    (
        "[[csg]]\noperation = \"intersection\"\nmaterial = \"green\"\nrotate = [0, 30, 20]\n\
         translate = [1.9, 0.7, 0]\n\
         [[csg.members]]\ntype = \"cylinder\"\nbase = [0, -1, 0]\nradius = 0.6\nheight = 2\n\
         [[csg.members]]\ntype = \"cylinder\"\nbase = [0, -1, 0]\nradius = 0.6\nheight = 2\n\
         rotate = [90, 0, 0]\n",
        "intersection { cylinder { <0, -1, 0>, <0, 1, 0>, 0.6 } \
         cylinder { <0, -1, 0>, <0, 1, 0>, 0.6 rotate <90, 0, 0> } \
         pigment { rgb <0, 1, 0> } finish { F } rotate <0, 30, 20> translate <1.9, 0.7, 0> }",
    ),
    (
        "[[csg]]\noperation = \"merge\"\nmaterial = \"blue\"\nscale = 0.9\ntranslate = [0, 2.3, -1]\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [-0.45, 0, 0]\nradius = 0.6\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [0.45, 0, 0]\nradius = 0.6\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0.5, 0.2]\nradius = 0.5\n",
        "merge { sphere { <-0.45, 0, 0>, 0.6 } sphere { <0.45, 0, 0>, 0.6 } \
         sphere { <0, 0.5, 0.2>, 0.5 } pigment { rgb <0, 0, 1> } finish { F } scale 0.9 \
         translate <0, 2.3, -1> }",
    ),
    (
        "[[csg]]\noperation = \"difference\"\nmaterial = \"yellow\"\nscale = 0.7\n\
         rotate = [-20, 30, 0]\ntranslate = [0, -0.5, 1.6]\n\
         [[csg.members]]\ntype = \"csg\"\noperation = \"intersection\"\n\
         [[csg.members.members]]\ntype = \"box\"\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\n\
         [[csg.members.members]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1.35\n\
         [[csg.members]]\ntype = \"csg\"\noperation = \"union\"\n\
         [[csg.members.members]]\ntype = \"cylinder\"\nbase = [0, -1.5, 0]\nradius = 0.55\nheight = 3\n\
         [[csg.members.members]]\ntype = \"cylinder\"\nbase = [0, -1.5, 0]\nradius = 0.55\nheight = 3\n\
         rotate = [90, 0, 0]\n\
         [[csg.members.members]]\ntype = \"cylinder\"\nbase = [0, -1.5, 0]\nradius = 0.55\nheight = 3\n\
         rotate = [0, 0, 90]\n",
        "difference { intersection { box { -1, 1 } sphere { 0, 1.35 } } \
         union { cylinder { <0, -1.5, 0>, <0, 1.5, 0>, 0.55 } \
         cylinder { <0, -1.5, 0>, <0, 1.5, 0>, 0.55 rotate <90, 0, 0> } \
         cylinder { <0, -1.5, 0>, <0, 1.5, 0>, 0.55 rotate <0, 0, 90> } } \
         pigment { rgb <1, 1, 0> } finish { F } scale 0.7 rotate <-20, 30, 0> \
         translate <0, -0.5, 1.6> }",
    ),
    (
        "[[csg]]\noperation = \"intersection\"\nmaterial = \"magenta\"\ntranslate = [-3.2, 1.9, -1]\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.8\n\
         [[csg.members]]\ntype = \"plane\"\npoint = [0, 0.1, 0]\nnormal = [0.3, 1, 0.4]\n",
        "intersection { sphere { 0, 0.8 } plane { <0.3, 1, 0.4>, 0.1 / vlength(<0.3, 1, 0.4>) } \
         pigment { rgb <1, 0, 1> } finish { F } translate <-3.2, 1.9, -1> }",
    ),
];

const COLOURS: [(&str, [u8; 3]); 6] = [
    ("red", [255, 0, 0]),
    ("cyan", [0, 255, 255]),
    ("green", [0, 255, 0]),
    ("blue", [0, 0, 255]),
    ("yellow", [255, 255, 0]),
    ("magenta", [255, 0, 255]),
];

/// prism's scene of the combinations, each material `finish` (TOML fields) over its colour.
fn prism_scene(head: &str, finish: &str) -> String {
    let mut s = format!(
        "[camera]\neye = [0, 3, 8]\nlook_at = [0, 1, 0]\nfov = 40\n\n{head}\n\
         [materials.gray]\ncolor = [0.5, 0.5, 0.5]\n{finish}\n"
    );
    for (name, rgb) in COLOURS {
        let c = rgb.map(|v| v as f32 / 255.0);
        s += &format!("[materials.{name}]\ncolor = {c:?}\n{finish}\n");
    }
    for (toml, _) in COMBINATIONS {
        s += toml;
        s += "\n";
    }
    s
}

/// POV-Ray's scene of the combinations, under `head` (its lights) with finish `finish`.
fn povray_scene(head: &str, finish: &str) -> String {
    let aspect = W as f64 / H as f64;
    let mut s = format!(
        "#version 3.7;\nglobal_settings {{ assumed_gamma 1.0 ambient_light 1 }}\n\
         camera {{ perspective location <0, 3, 8> look_at <0, 1, 0> right -x * {aspect} up y \
         angle 2 * degrees(atan(tan(radians(20)) * {aspect})) }}\n\
         background {{ rgb 0 }}\n{head}\n#declare F = finish {{ {finish} }};\n"
    );
    for (_, pov) in COMBINATIONS {
        s += pov;
        s += "\n";
    }
    s
}

/// Flat colours (ambient light alone): what is hit where decides each pixel, and the
/// combinations must cover the same pixels as POV-Ray's.
#[test]
fn every_combination_draws_as_povray_draws_it() {
    if !povray_available() {
        return;
    }
    let reference = povray_render(&povray_scene("", "ambient 1 diffuse 0 specular 0"), W, H);
    let ours = prism_render(
        &prism_scene(
            "[render]\nbackground = [0, 0, 0]\nambient = [1, 1, 1]\n",
            "ambient = 1\ndiffuse = 0\nspecular = 0\n",
        ),
        W,
        H,
        None,
    );
    for (name, colour) in COLOURS {
        let n = ours.pixels().filter(|p| p.0 == colour).count();
        assert!(n > 300, "{name}: {n} pixels");
    }
    let (far, _) = compare(&ours, &reference, 1);
    assert!(far <= 10, "{far} of {} pixels differ from POV-Ray's", W * H);
}

/// Lit by a point light (diffuse, with shadows): the normals of every member's part of the
/// surface, subtracted ones turned inwards, shade as POV-Ray's.
#[test]
fn lit_combinations_shade_as_povrays() {
    if !povray_available() {
        return;
    }
    let reference = povray_render(
        &povray_scene(
            "light_source { <-3, 6, 8> color rgb 1 }",
            "ambient 0.2 diffuse 0.8 specular 0",
        ),
        W,
        H,
    );
    let ours = prism_render(
        &prism_scene(
            "[render]\nbackground = [0, 0, 0]\nambient = [1, 1, 1]\n\
             [[lights]]\nposition = [-3, 6, 8]\n",
            "ambient = 0.2\ndiffuse = 0.8\nspecular = 0\n",
        ),
        W,
        H,
        None,
    );
    let (far, mean) = compare(&ours, &reference, 2);
    println!("lit: {far} pixels beyond 2 levels, mean {mean:.3}");
    assert!(
        far <= 10 && mean < 0.05,
        "{far} pixels beyond 2 levels, mean {mean:.3}"
    );
}

/// A biconvex lens (the intersection of two spheres, eta 1.5) before a checker: light
/// bends into it and out as POV-Ray bends it; and a lens of another index does not match.
#[test]
fn a_csg_lens_refracts_as_povrays() {
    if !povray_available() {
        return;
    }
    let (w, h) = (200u32, 150u32);
    let aspect = w as f64 / h as f64;
    let pov = |ior: f32| {
        format!(
            "#version 3.7;\nglobal_settings {{ assumed_gamma 1.0 ambient_light 1 max_trace_level 8 }}\n\
             camera {{ perspective location <0, 0, 6> look_at <0, 0, 0> right -x * {aspect} up y \
             angle 2 * degrees(atan(tan(radians(20)) * {aspect})) }}\n\
             background {{ rgb 0 }}\n\
             plane {{ z, -3.25 pigment {{ checker rgb 0 rgb 1 scale 0.5 }} \
             finish {{ ambient 1 diffuse 0 specular 0 }} }}\n\
             intersection {{ sphere {{ <0, 0, -1.2>, 1.6 }} sphere {{ <0, 0, 1.2>, 1.6 }} \
             pigment {{ rgbt 1 }} finish {{ ambient 0 diffuse 0 specular 0 }} \
             interior {{ ior {ior} }} rotate <0, 25, 0> }}\n"
        )
    };
    let text = "[camera]\neye = [0, 0, 6]\nlook_at = [0, 0, 0]\nfov = 40\n\
                [render]\nbackground = [0, 0, 0]\nambient = [1, 1, 1]\nmax_depth = 8\n\
                [textures.checks]\ntype = \"checker\"\ncolors = [[1, 1, 1], [0, 0, 0]]\nsize = 0.5\naxes = \"xy\"\n\
                [materials.wall]\ntexture = \"checks\"\nambient = 1\ndiffuse = 0\nspecular = 0\n\
                [materials.glass]\ntransparency = 1\neta = 1.5\nambient = 0\ndiffuse = 0\nspecular = 0\n\
                [[planes]]\npoint = [0, 0, -3.25]\nnormal = [0, 0, 1]\nmaterial = \"wall\"\n\
                [[csg]]\noperation = \"intersection\"\nmaterial = \"glass\"\nrotate = [0, 25, 0]\n\
                [[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0, -1.2]\nradius = 1.6\n\
                [[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0, 1.2]\nradius = 1.6\n";
    let ours = prism_render(text, w, h, None);
    let (far, mean) = compare(&ours, &povray_render(&pov(1.5), w, h), 128);
    println!("lens: {far} pixels differ by half the range, mean {mean:.3}");
    assert!(
        far * 200 < (w * h) as usize && mean < 2.0,
        "{far} pixels differ, mean {mean:.3}"
    );
    let (far_other, _) = compare(&ours, &povray_render(&pov(1.3), w, h), 128);
    assert!(
        far_other > 5 * far.max(40),
        "eta 1.3 went unnoticed: {far_other} against {far}"
    );
}

fn load(text: &str) -> Scene {
    parse_scene(text, Path::new("csg.toml"), Path::new(".")).unwrap()
}

/// The colour seen along -z through (x, y) from z = 5 (ambient light only, so a hit shows
/// its flat colour and a miss black).
fn seen(scene: &Scene, x: f32, y: f32) -> Vec3 {
    common::colour_along(scene, Vec3::new(x, y, 5.0), -Vec3::Z)
}

/// Two unit spheres 1.2 apart on x, combined each way, seen along z at points in either
/// alone, in both, and in neither: each operation keeps what it should (a union and a
/// merge both, an intersection the lens between, a difference the first minus the second).
#[test]
fn each_operation_keeps_what_it_should() {
    let scene = |operation: &str| {
        load(&format!(
            "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\
             [render]\nambient = [1, 1, 1]\nbackground = [0, 0, 0]\n\
             [materials.white]\ncolor = [1, 1, 1]\nambient = 1\ndiffuse = 0\nspecular = 0\n\
             [[csg]]\noperation = \"{operation}\"\nmaterial = \"white\"\n\
             [[csg.members]]\ntype = \"sphere\"\ncenter = [-0.6, 0, 0]\nradius = 1\n\
             [[csg.members]]\ntype = \"sphere\"\ncenter = [0.6, 0, 0]\nradius = 1\n"
        ))
    };
    // x = −1.3: the first alone; 0.1: both; 1.3: the second alone; 2: neither.
    let points = [-1.3f32, 0.1, 1.3, 2.0];
    for (operation, want) in [
        ("union", [true, true, true, false]),
        ("merge", [true, true, true, false]),
        ("intersection", [false, true, false, false]),
        ("difference", [true, false, false, false]),
    ] {
        let scene = scene(operation);
        let got = points.map(|x| seen(&scene, x, 0.1) != Vec3::ZERO);
        assert_eq!(got, want, "{operation}");
    }
    // Where the first sphere's front lies inside the second, a difference shows the
    // second's back wall, carved into the first: hit, though the first's surface is not.
    let difference = scene("difference");
    assert_ne!(seen(&difference, -0.3, 0.0), Vec3::ZERO);
}

/// The colour seen from `from` towards `to` (scene coordinates).
fn seen_from(scene: &Scene, from: Vec3, to: Vec3) -> Vec3 {
    common::colour_along(scene, from, to - from)
}

/// A box with a tunnel bored through it (a difference) between a light and a wall: the
/// wall is lit through the tunnel and dark behind the rest of the box, and from in front
/// the tunnel shows the lit wall. Shadow rays follow the solid, not its members.
#[test]
fn shadows_follow_the_solid() {
    let scene = load(
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\
         [render]\nambient = [0, 0, 0]\nbackground = [0, 0, 0]\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0, 0, -1]\n\
         [materials.white]\ncolor = [1, 1, 1]\nambient = 0\ndiffuse = 1\nspecular = 0\n\
         [[planes]]\npoint = [0, 0, -3]\nnormal = [0, 0, 1]\nmaterial = \"white\"\n\
         [[csg]]\noperation = \"difference\"\nmaterial = \"white\"\n\
         [[csg.members]]\ntype = \"box\"\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\n\
         [[csg.members]]\ntype = \"cylinder\"\nbase = [0, -2, 0]\nradius = 0.4\nheight = 4\n\
         rotate = [90, 0, 0]\ntranslate = [0.3, 0.2, 0]\n",
    );
    // Straight through the tunnel, and the box's face head on: both lit.
    for (x, y) in [(0.3f32, 0.2f32), (-0.7, -0.7)] {
        let c = seen_from(&scene, Vec3::new(x, y, 5.0), Vec3::new(x, y, -3.0));
        assert!(
            (c - Vec3::ONE).abs().max_element() < 1e-5,
            "({x}, {y}): {c}"
        );
    }
    // The wall seen at a slant past the box: lit in the tunnel's line, dark behind the box.
    for (x, y, lit) in [
        (0.3f32, 0.2f32, true),
        (0.65, 0.2, true),
        (0.75, 0.2, false),
        (-0.6, -0.6, false),
        (1.5, 0.0, true),
    ] {
        let wall = Vec3::new(x, y, -3.0);
        let c = seen_from(&scene, wall + Vec3::new(6.0, 0.0, 8.0), wall);
        let want = if lit { Vec3::ONE } else { Vec3::ZERO };
        assert!((c - want).abs().max_element() < 1e-5, "({x}, {y}): {c}");
    }
}

/// The combinations at scales from 10⁻³ to 10³ and far from the origin: the same image.
#[test]
fn combinations_render_the_same_at_every_scale() {
    let scene = load(&prism_scene(
        "[render]\nbackground = [0.2, 0.2, 0.3]\nambient = [0.3, 0.3, 0.3]\n\
         [[lights]]\nposition = [-3, 6, 8]\n",
        "ambient = 1\ndiffuse = 0.8\nspecular = 0.3\n",
    ));
    let image = |scene: &Scene| {
        let settings = RenderSettings::new(96, 72, 1);
        common::render_scene(scene, settings)
    };
    let base = image(&scene);
    for (scale, offset) in [
        (1e-3f32, DVec3::ZERO),
        (1e3, DVec3::ZERO),
        (1.0, DVec3::new(1e4, -3e3, 2e4)),
    ] {
        let (far, _) = compare(&base, &image(&scene.transformed(scale, offset)), 2);
        assert!(
            far <= 10,
            "scale {scale}, offset {offset}: {far} pixels differ"
        );
    }
}

#[test]
fn every_bad_combination_is_refused_with_its_line() {
    let head = "[camera]\neye = [0, 0, 5]\nfov = 40\n[[csg]]\n";
    let sphere = "[[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n";
    let cases = [
        (
            format!("operation = \"diference\" # <-\n{sphere}{sphere}"),
            "did you mean \"difference\"?",
        ),
        (
            format!(
                "operation = \"union\"\n{}",
                sphere.replacen("\n", " # <-\n", 1)
            ),
            "two or more members, got 1",
        ),
        (
            format!("operation = \"union\"\n{sphere}[[csg.members]]\ntype = \"disc\" # <-\n"),
            "a disc is flat",
        ),
        (
            format!("operation = \"union\"\n{sphere}[[csg.members]]\ntype = \"mesh\" # <-\n"),
            "a mesh cannot be a member",
        ),
        (
            format!("operation = \"union\"\n{sphere}[[csg.members]]\ntype = \"spher\" # <-\n"),
            "did you mean \"sphere\"?",
        ),
        (
            format!(
                "operation = \"union\"\n{sphere}[[csg.members]]\ntype = \"cylinder\"\n\
                 base = [0, 0, 0]\nradius = 1\nheight = 1\ncaps = false # <-\n"
            ),
            "an open tube has no inside",
        ),
        (
            format!(
                "operation = \"union\"\n{sphere}[[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1 # <-\n"
            ),
            "`radius`",
        ),
        (
            format!(
                "operation = \"union\"\n{sphere}[[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"x\" # <-\n"
            ),
            "no material named \"x\"",
        ),
        (
            format!("operation = \"union\"\n{sphere}[[csg.members]] # <-\nradius = 1\n"),
            "a member needs a `type`",
        ),
    ];
    for (table, message) in cases {
        let text = format!("{head}{table}");
        let error = parse_scene(&text, Path::new("c.toml"), Path::new(".")).unwrap_err();
        let shown = error.to_string();
        assert!(shown.contains(message), "{table}: {shown}");
        assert!(shown.contains("csg[0]"), "{shown}");
        let marked = text.lines().position(|l| l.contains("# <-")).unwrap() + 1;
        assert_eq!(error.line(), Some(marked), "{table}: {shown}");
    }
}

/// A union at the top of an entry is its members: the same image as the members given as
/// separate objects; and past the limit of solids, a combination is refused while a top
/// union of as many is not.
#[test]
fn a_top_union_is_its_members_and_combinations_are_bounded() {
    let head = "[camera]\neye = [0, 4, 14]\nlook_at = [0, 0, 0]\nfov = 45\n\
                [[lights]]\nposition = [-5, 9, 6]\n";
    let balls: Vec<(f32, f32, f32)> = (0..300)
        .map(|i| {
            let a = i as f32 * 2.399;
            let r = (i as f32).sqrt() * 0.35;
            (r * a.cos(), (i % 7) as f32 * 0.3, r * a.sin())
        })
        .collect();
    let member = |(x, y, z): (f32, f32, f32), kind: &str| {
        format!("{kind}\ncenter = [{x}, {y}, {z}]\nradius = 0.3\n")
    };
    let separate: String = balls.iter().map(|&b| member(b, "[[spheres]]")).collect();
    let members: String = balls
        .iter()
        .map(|&b| member(b, "[[csg.members]]\ntype = \"sphere\""))
        .collect();
    let union = format!("{head}[[csg]]\noperation = \"union\"\n{members}");
    let settings = RenderSettings::new(96, 72, 1);
    assert_eq!(
        common::render_scene(&load(&union), settings),
        common::render_scene(&load(&format!("{head}{separate}")), settings)
    );
    let merge = format!("{head}[[csg]]\noperation = \"merge\"\n{members}");
    let shown = parse_scene(&merge, Path::new("c.toml"), Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(shown.contains("at most 256 solids"), "{shown}");
}

/// A member's own material colours its surface, a nested combination's colours its
/// members that give none, and the rest take the whole's: in a union at the top (traced as
/// its members) and in a difference (traced as one solid). Placed again by a transform
/// edit, the members keep theirs.
#[test]
fn members_take_their_own_materials() {
    let dir = common::Dir::new();
    let path = dir.write(
        "members.toml",
        "[camera]\neye = [0, 0, 10]\nlook_at = [0, 0, 0]\nfov = 40\n\
         [render]\nambient = [1, 1, 1]\nbackground = [0, 0, 0]\n\
         [materials.red]\ncolor = [1, 0, 0]\nambient = 1\ndiffuse = 0\nspecular = 0\n\
         [materials.green]\ncolor = [0, 1, 0]\nambient = 1\ndiffuse = 0\nspecular = 0\n\
         [materials.blue]\ncolor = [0, 0, 1]\nambient = 1\ndiffuse = 0\nspecular = 0\n\
         [materials.white]\ncolor = [1, 1, 1]\nambient = 1\ndiffuse = 0\nspecular = 0\n\
         [[csg]]\noperation = \"union\"\nmaterial = \"red\"\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [-3, 1.5, 0]\nradius = 0.5\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [-1, 1.5, 0]\nradius = 0.5\nmaterial = \"green\"\n\
         [[csg.members]]\ntype = \"csg\"\noperation = \"merge\"\nmaterial = \"blue\"\n\
         [[csg.members.members]]\ntype = \"sphere\"\ncenter = [1, 1.5, 0]\nradius = 0.5\n\
         [[csg.members.members]]\ntype = \"sphere\"\ncenter = [3, 1.5, 0]\nradius = 0.5\nmaterial = \"white\"\n\
         [[csg]]\noperation = \"difference\"\nmaterial = \"red\"\n\
         [[csg.members]]\ntype = \"box\"\nmin = [-1, -2.5, -1]\nmax = [1, -0.5, 1]\n\
         [[csg.members]]\ntype = \"sphere\"\ncenter = [0.5, -1.5, 1]\nradius = 0.6\nmaterial = \"green\"\n",
    );
    let loaded = prism::scene_file::load_scene_file(&path).result.unwrap();
    let scene = loaded.scene.clone();
    let (red, green, blue, white) = (Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE);
    for (x, y, want) in [
        (-3.0f32, 1.5f32, red),
        (-1.0, 1.5, green),
        (1.0, 1.5, blue),
        (3.0, 1.5, white),
        (-0.5, -1.5, red),
        (0.5, -1.5, green),
    ] {
        assert_eq!(seen(&scene, x, y), want, "at ({x}, {y})");
    }
    // Moved by the viewer's transform row: the same colours, 0.5 higher.
    let mut moved = scene.clone();
    let placement = prism::scene::ObjectPlacement {
        translate: DVec3::new(0.0, 0.5, 0.0),
        ..Default::default()
    };
    loaded.place_object(&mut moved, 0, placement).unwrap();
    loaded.place_object(&mut moved, 1, placement).unwrap();
    for (x, y, want) in [
        (-1.0f32, 2.0f32, green),
        (3.0, 2.0, white),
        (0.5, -1.0, green),
    ] {
        assert_eq!(seen(&moved, x, y), want, "moved, at ({x}, {y})");
    }
}
