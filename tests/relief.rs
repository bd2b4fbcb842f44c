//! Relief (bump and normal maps): the tilt a height field's slope gives, from patterns and
//! from pictures through their texture transform; a normal map baked from a height field
//! shading as that height field's bumps; lights below the true surface staying dark; a
//! depth or strength of 0 leaving the image unchanged; every bad field refused with its
//! line.

mod common;

use glam::Vec3;
use prism::render::RenderSettings;
use prism::scene::Scene;
use prism::scene_file::parse_scene;
use std::path::Path;

fn load_in(text: &str, dir: &Path) -> Scene {
    parse_scene(text, &dir.join("relief.toml"), dir).unwrap()
}

/// The colour seen straight down at (x, z) from above the floor y = 0.
fn seen_from_above(scene: &Scene, x: f32, z: f32) -> Vec3 {
    common::colour_along(scene, Vec3::new(x, 3.0, z), -Vec3::Y)
}

/// A white floor, lit only by a directional light shining along `light`, with `material`
/// fields added and `extra` tables.
fn floor(material: &str, light: [f32; 3], extra: &str) -> String {
    format!(
        "[camera]\neye = [0, 3, 0]\ndirection = [0, -1, 0]\nup = [0, 0, -1]\nfov = 40\n\
         [render]\nambient = [0, 0, 0]\nbackground = [0, 0, 0]\n\
         [[lights]]\ntype = \"directional\"\ndirection = {light:?}\n\
         [materials.m]\ncolor = [1, 1, 1]\nspecular = 0\n{material}\n\
         [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"m\"\n{extra}\n"
    )
}

/// A ramp of slope 3/4 along x (a gradient pattern of scale 0.5 raised 0.375) tilts the
/// normal to (−3, 4, 0)/5: lit from straight above, the floor shows cos = 4/5; lit along
/// the tilted normal, all of the light; and a light below the true floor sends nothing,
/// though the tilted normal faces it.
#[test]
fn a_patterns_slope_tilts_the_normal_by_its_angle() {
    let dir = common::Dir::new();
    let ramp = "[textures.ramp]\ntype = \"gradient\"\ndirection = [1, 0, 0]\nscale = 0.5\n";
    let bumped = |light| {
        load_in(
            &floor("bump = \"ramp\"\nbump_depth = 0.375", light, ramp),
            dir.0.path(),
        )
    };
    // Away from the ramp's drops, at x = 0.5·k.
    let points = [(0.1f32, 0.3f32), (0.2, -1.7), (-0.35, 0.05), (1.85, 2.2)];
    let above = bumped([0.0, -1.0, 0.0]);
    let along = bumped([0.6, -0.8, 0.0]);
    let below = bumped([0.99, 0.14, 0.0]);
    for (x, z) in points {
        let c = seen_from_above(&above, x, z);
        assert!(
            (c - Vec3::splat(0.8)).abs().max_element() < 1e-4,
            "{c} at {x}"
        );
        let c = seen_from_above(&along, x, z);
        assert!((c - Vec3::ONE).abs().max_element() < 1e-4, "{c} at {x}");
        assert_eq!(seen_from_above(&below, x, z), Vec3::ZERO, "at {x}");
    }
    // The colour map shapes the height as it does colour: white to black turns the slope
    // around, black to mid-grey halves it (tan θ = 3/8).
    for (map, light, want) in [
        (
            "[{ at = 0, color = [1, 1, 1] }, { at = 1, color = [0, 0, 0] }]",
            [-0.6f32, -0.8, 0.0],
            1.0f32,
        ),
        (
            "[{ at = 0, color = [0, 0, 0] }, { at = 1, color = [0.5, 0.5, 0.5] }]",
            [0.0, -1.0, 0.0],
            8.0 / 73f32.sqrt(),
        ),
    ] {
        let text = floor(
            "bump = \"ramp\"\nbump_depth = 0.375",
            light,
            &format!("{ramp}color_map = {map}\n"),
        );
        let c = seen_from_above(&load_in(&text, dir.0.path()), 0.1, 0.3);
        assert!(
            (c - Vec3::splat(want)).abs().max_element() < 1e-4,
            "{map}: {c} against {want}"
        );
    }
    // Unbumped, the light below is dark too, and the one above is all of it.
    let flat = load_in(&floor("", [0.0, -1.0, 0.0], ""), dir.0.path());
    assert_eq!(seen_from_above(&flat, 0.1, 0.3), Vec3::ONE);
}

/// A picture's slope, through the texture's transform: a 256-texel ramp (texel i of value
/// i/255) climbs 256/255 per picture width; on the floor (one picture per unit, its right
/// along +x), a depth of 0.75·255/256 tilts the normal to (−3, 4, 0)/5. Shown twice as
/// often (uv_scale = 2) it climbs twice as steeply; turned 90°, the tilt turns with it.
#[test]
fn a_pictures_slope_tilts_the_normal_through_its_transform() {
    let dir = common::Dir::new();
    let ramp: Vec<u8> = (0..16)
        .flat_map(|_| (0..=255u8).flat_map(|i| [i, i, i]))
        .collect();
    image::RgbImage::from_raw(256, 16, ramp)
        .unwrap()
        .save(dir.path("ramp.png"))
        .unwrap();
    let depth = 0.75f32 * 255.0 / 256.0;
    let scene = |texture: &str, light: [f32; 3]| {
        load_in(
            &floor(
                &format!("bump = \"ramp\"\nbump_depth = {depth}"),
                light,
                &format!("[textures.ramp]\ntype = \"image\"\npath = \"ramp.png\"\n{texture}"),
            ),
            dir.0.path(),
        )
    };
    // Texel centres of the middle of the ramp, away from its wrap at u = 0.
    let points = [(0.3f32, 0.25f32), (0.5, -0.4), (0.7, 0.1)];
    let plain = scene("", [0.0, -1.0, 0.0]);
    let along = scene("", [0.6, -0.8, 0.0]);
    for (x, z) in points {
        let c = seen_from_above(&plain, x, z);
        assert!(
            (c - Vec3::splat(0.8)).abs().max_element() < 2e-3,
            "{c} at {x}"
        );
        let c = seen_from_above(&along, x, z);
        assert!((c - Vec3::ONE).abs().max_element() < 2e-3, "{c} at {x}");
    }
    // Twice as steep: tan θ = 1.5, cos θ = 1/√3.25.
    let twice = scene("uv_scale = 2", [0.0, -1.0, 0.0]);
    let c = seen_from_above(&twice, 0.15, 0.2);
    let want = 1.0 / 3.25f32.sqrt();
    assert!((c - Vec3::splat(want)).abs().max_element() < 2e-3, "{c}");
    // Turned a quarter: the ramp now climbs along z, so a light tilted along x sees
    // (0, 4, ±3)/5 · (0.6, −0.8, 0) = 0.64, and one tilted along z sees 1 or 0.28.
    let turned_x = scene("uv_rotate = 90", [0.6, -0.8, 0.0]);
    let c = seen_from_above(&turned_x, 0.1, 0.5);
    assert!((c - Vec3::splat(0.64)).abs().max_element() < 2e-3, "{c}");
    let tilts: Vec<f32> = [[0.0, -0.8, 0.6], [0.0, -0.8, -0.6]]
        .map(|light| seen_from_above(&scene("uv_rotate = 90", light), 0.1, 0.5).x)
        .to_vec();
    assert!(
        tilts.iter().any(|c| (c - 1.0).abs() < 2e-3)
            && tilts.iter().any(|c| (c - 0.28).abs() < 2e-3),
        "{tilts:?}"
    );
}

/// The height field h(x, y) = ½ + ¼·sin(2πx/W)·cos(4πy/H) written as a picture, and the
/// normal map of that same field raised `depth`, computed exactly and written as a
/// picture: on a floor, on a box's face and turned by the texture transform, the two
/// shade alike (the normal map's eight bits are its only difference).
#[test]
fn a_normal_map_shades_as_the_bumps_it_was_baked_from() {
    let dir = common::Dir::new();
    let n = 64u32;
    let depth = 0.1f64;
    let tau = std::f64::consts::TAU;
    let h = |x: f64, y: f64| 0.5 + 0.5 * (tau * x).sin() * (2.0 * tau * y).cos();
    let (mut heights, mut normals) = (vec![], vec![]);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            let v = (h(x, y) * 255.0).round() as u8;
            heights.extend([v, v, v]);
            // Per unit of the picture (one picture per scene unit): ∂h/∂x and ∂h/∂y, y down.
            let hx = 0.5 * tau * (tau * x).cos() * (2.0 * tau * y).cos();
            let hy = -0.5 * 2.0 * tau * (tau * x).sin() * (2.0 * tau * y).sin();
            // Right is +x; up the picture is −y, so the slope up is −hy.
            let m = [-depth * hx, depth * hy, 1.0];
            let len = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
            normals.extend(m.map(|c| ((0.5 + 0.5 * c / len) * 255.0).round() as u8));
        }
    }
    for (name, bytes) in [("height.png", heights), ("normal.png", normals)] {
        image::RgbImage::from_raw(n, n, bytes)
            .unwrap()
            .save(dir.path(name))
            .unwrap();
    }
    // A unit square in y = 0, its picture upright seen from above (v down towards +z),
    // the corners' coordinates given in an order that turns each triangle's own.
    std::fs::write(
        dir.path("quad.obj"),
        "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 0 0.5\nv -0.5 0 0.5\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 3/3 2/2\nf 1/1 4/4 3/3\n",
    )
    .unwrap();
    // A unit cube: each face shows the picture once, so its slopes are as baked.
    let cube = "[[boxes]]\nmin = [-0.5, -1, -0.5]\nmax = [0.5, 0, 0.5]\nmaterial = \"m\"";
    for (placement, transform) in [
        (cube, ""),
        (cube, "uv_rotate = 30\n"),
        (cube, "uv_rotate = -90\nuv_scale = [-1, 1]\n"),
        // A mesh's tangents come from its corners' coordinates.
        ("[[meshes]]\npath = \"quad.obj\"\nmaterial = \"m\"", ""),
    ] {
        let scene = |relief: &str| {
            let text = format!(
                "[camera]\neye = [1.1, 1.1, 1.7]\nlook_at = [0, -0.5, 0]\nfov = 45\n\
                 [render]\nambient = [0, 0, 0]\nbackground = [0, 0, 0]\nwidth = 96\nheight = 72\n\
                 [[lights]]\ntype = \"directional\"\ndirection = [0.5, -0.6, -0.4]\n\
                 [[lights]]\ntype = \"directional\"\ndirection = [-0.6, -0.5, 0.3]\ncolor = [0.4, 0.4, 0.4]\n\
                 [textures.height]\ntype = \"image\"\npath = \"height.png\"\n{transform}\
                 [textures.normal]\ntype = \"image\"\npath = \"normal.png\"\n{transform}\
                 [materials.m]\ncolor = [0.8, 0.8, 0.8]\nspecular = 0.3\nshininess = 20\n{relief}\n\
                 {placement}\n"
            );
            load_in(&text, dir.0.path())
        };
        let settings = RenderSettings::new(96, 72, 1);
        let bumped = common::render_scene(
            &scene(&format!("bump = \"height\"\nbump_depth = {depth}")),
            settings,
        );
        let mapped = common::render_scene(&scene("normal_map = \"normal\""), settings);
        let flat = common::render_scene(&scene(""), settings);
        let mean_difference = |a: &image::RgbImage, b: &image::RgbImage| {
            let sum: u64 = a
                .pixels()
                .zip(b.pixels())
                .flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c]) as u64))
                .sum();
            sum as f64 / (a.width() * a.height() * 3) as f64
        };
        let alike = mean_difference(&bumped, &mapped);
        let relief = mean_difference(&bumped, &flat);
        println!(
            "{transform:?}: bumps against normal map {alike:.2} levels, against flat {relief:.2}"
        );
        assert!(relief > 1.5, "the relief shows: {relief}");
        assert!(
            alike < 0.05 * relief && alike < 0.5,
            "{alike} against {relief}"
        );
    }
}

/// A depth or a strength of 0 is no relief at all: the image is the same, bit for bit.
#[test]
fn no_depth_and_no_strength_leave_the_image_unchanged() {
    let dir = common::Dir::new();
    image::RgbImage::from_fn(8, 8, |x, y| {
        image::Rgb([(x * 30) as u8, (y * 30) as u8, 200])
    })
    .save(dir.path("n.png"))
    .unwrap();
    let scene = |relief: &str| {
        load_in(
            &format!(
                "[camera]\neye = [0, 1, 4]\nlook_at = [0, 0.5, 0]\nfov = 50\n\
                 [[lights]]\nposition = [2, 4, 3]\n\
                 [textures.n]\ntype = \"image\"\npath = \"n.png\"\n\
                 [textures.noise]\ntype = \"noise\"\nscale = 0.2\n\
                 [materials.m]\ncolor = [0.7, 0.5, 0.3]\nreflectivity = 0.3\n{relief}\n\
                 [[spheres]]\ncenter = [0, 0.6, 0]\nradius = 0.6\nmaterial = \"m\"\n\
                 [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"m\"\n"
            ),
            dir.0.path(),
        )
    };
    let settings = RenderSettings::new(64, 48, 2);
    let smooth = common::render_scene(&scene(""), settings);
    for relief in [
        "bump = \"noise\"\nbump_depth = 0",
        "bump = \"n\"\nbump_depth = 0",
        "normal_map = \"n\"\nnormal_strength = 0",
    ] {
        assert_eq!(
            common::render_scene(&scene(relief), settings),
            smooth,
            "{relief}"
        );
    }
    // And above 0 each one changes it.
    for relief in ["bump = \"noise\"\nbump_depth = 0.05", "normal_map = \"n\""] {
        assert_ne!(
            common::render_scene(&scene(relief), settings),
            smooth,
            "{relief}"
        );
    }
}

#[test]
fn every_bad_relief_is_refused_with_its_line_and_field() {
    let head = "[camera]\neye = [0, 0, 0]\nfov = 40\n\
                [[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nmaterial = \"m\"\n\
                [textures.noise]\ntype = \"noise\"\n\
                [textures.checks]\ntype = \"checker\"\ncolors = [[0, 0, 0], [1, 1, 1]]\nsize = 1\n\
                [materials.m]\n";
    let cases = [
        ("bump = \"noise\" # <-", "`bump` needs a `bump_depth`"),
        (
            "bump_depth = 0.1 # <-",
            "`bump_depth` needs a `bump` texture",
        ),
        (
            "normal_strength = 2 # <-",
            "`normal_strength` needs a `normal_map`",
        ),
        (
            "bump = \"nois\" # <-\nbump_depth = 0.1",
            "no texture named \"nois\"; did you mean \"noise\"?",
        ),
        (
            "bump = \"checks\" # <-\nbump_depth = 0.1",
            "flat between its edges",
        ),
        ("normal_map = \"noise\" # <-", "a texture of type \"image\""),
        (
            "bump = \"noise\"\nbump_depth = -1 # <-",
            "`bump_depth` must lie in",
        ),
        (
            "bump = \"noise\"\nbump_depth = 0.1\nnormal_map = \"noise\" # <-",
            "either `bump` or `normal_map`",
        ),
        (
            "bump = \"noise\"\nbump_depth = 0.1\nnormal_strength = 1 # <-",
            "`normal_strength` needs a `normal_map`",
        ),
        ("bump = 3 # <-\nbump_depth = 0.1", "expected a string"),
    ];
    for (fields, message) in cases {
        let text = format!("{head}{fields}\n");
        let error = parse_scene(&text, Path::new("r.toml"), Path::new(".")).unwrap_err();
        let shown = error.to_string();
        assert!(shown.contains(message), "{fields}: {shown}");
        assert!(shown.contains("materials.m"), "{shown}");
        let marked = text.lines().position(|l| l.contains("# <-")).unwrap() + 1;
        assert_eq!(error.line(), Some(marked), "{fields}: {shown}");
    }
    // A normal map's strength beyond its limit.
    let dir = common::Dir::new();
    image::RgbImage::new(2, 2).save(dir.path("n.png")).unwrap();
    let text = format!(
        "{head}normal_map = \"n\"\nnormal_strength = 17\n[textures.n]\ntype = \"image\"\npath = \"n.png\"\n"
    );
    let shown = parse_scene(&text, &dir.path("r.toml"), dir.0.path())
        .unwrap_err()
        .to_string();
    assert!(
        shown.contains("`normal_strength` must lie in [0, 16]"),
        "{shown}"
    );
}
