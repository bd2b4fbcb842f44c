//! Every shortcut the tracer takes must leave the image as the unoptimised path draws it.

mod common;

use common::{render_prepared, seed};
use prism::accel::AccelOptions;
use prism::render::RenderSettings;
use prism::scene::{PreparedScene, Scene};
use std::sync::Arc;

fn image(scene: Arc<PreparedScene>, camera: prism::camera::Camera, s: RenderSettings) -> Vec<u8> {
    render_prepared(scene, camera, s).into_raw()
}

/// `scene` prepared with every shortcut but those `off` turns off.
fn prepared(scene: &Scene, off: impl FnOnce(&mut AccelOptions)) -> Arc<PreparedScene> {
    let mut options = AccelOptions::ALL;
    off(&mut options);
    Arc::new(PreparedScene::with_options(scene, options))
}

/// Sphere number `i` of a crowd added to a scene.
fn bead(
    i: usize,
    center: glam::Vec3,
    radius: f32,
    material: prism::appearance::Material,
) -> prism::scene::SceneObject {
    prism::scene::SceneObject {
        casts_shadow: true,
        placement: Default::default(),
        group: None,
        node: None,
        name: format!("bead {i}"),
        shape: prism::scene::ShapeDesc::Sphere { center, radius },
        material,
    }
}

fn largest_difference(a: &[u8], b: &[u8]) -> u8 {
    a.iter().zip(b).map(|(x, y)| x.abs_diff(*y)).max().unwrap()
}

#[test]
fn skipping_faint_secondary_rays_changes_no_pixel_beyond_rounding() {
    let scene = seed();
    let prepared = Arc::new(PreparedScene::new(&scene));
    let fast = RenderSettings::new(200, 150, 2);
    let exact = RenderSettings {
        min_weight: 0.0,
        ..fast
    };
    let d = largest_difference(
        &image(prepared.clone(), scene.camera, fast),
        &image(prepared, scene.camera, exact),
    );
    assert!(d <= 1, "largest difference {d} levels");
}

#[test]
fn opaque_scenes_take_the_any_hit_shadow_shortcut_unchanged() {
    // Without transparent objects, shadow rays stop at the first occluder without looking
    // at materials; forcing the general path must give the same image.
    // A sun as well as the seed's light: its shadow rays run to infinity.
    let mut scene = seed();
    for o in &mut scene.objects {
        o.material.transparency = 0.0;
    }
    scene.lights.push(prism::appearance::Light {
        kind: prism::appearance::LightKind::Directional {
            direction: glam::Vec3::new(0.3, -1.0, -0.4).normalize(),
        },
        color: glam::Vec3::new(0.4, 0.35, 0.3),
    });
    let shortcut = prepared(&scene, |_| {});
    assert!(!shortcut.appearance.shadow_filters().any_transmission());
    let general = prepared(&scene, |o| o.any_hit_shadows = false);
    let s = RenderSettings::new(200, 150, 1);
    assert_eq!(
        image(shortcut, scene.camera, s),
        image(general, scene.camera, s)
    );
}

#[test]
fn the_bvh_answers_as_a_flat_list_would() {
    // A one-leaf hierarchy (every primitive in the root) is the unoptimised list. The seed's
    // objects fit in one eight-wide node, so a ring of mirror beads among them makes the
    // tree a tree.
    use glam::Vec3;
    use prism::appearance::{Material, Texture};
    let mut scene = seed();
    for i in 0..40 {
        let a = i as f32 * 0.45;
        let center = Vec3::new(
            12.0 * a.cos(),
            -8.0 + (i % 7) as f32 * 2.5,
            -75.0 + 12.0 * a.sin(),
        );
        let material = Material {
            texture: Texture::Solid(Vec3::new(0.3, 0.6, 0.9)),
            reflectivity: if i % 3 == 0 { 0.7 } else { 0.0 },
            ..Material::default()
        };
        scene.objects.push(bead(i, center, 1.2, material));
    }
    let tree = prepared(&scene, |_| {});
    let flat = prepared(&scene, |o| o.bvh = false);
    assert!(tree.geometry.accel().bvh_nodes() > 1);
    assert_eq!(flat.geometry.accel().bvh_nodes(), 1);
    let s = RenderSettings::new(200, 150, 1);
    assert_eq!(image(tree, scene.camera, s), image(flat, scene.camera, s));
}

#[test]
fn first_hit_tiles_draw_the_image_the_bvh_draws() {
    // Primary rays that look up their candidates by tile (first_hit.rs) must see exactly
    // what a traversal of the BVH sees, from the seed camera and from one among the
    // objects whose boxes straddle the eye's plane.
    let scene = seed();
    let tiles = prepared(&scene, |_| {});
    let traversal = prepared(&scene, |o| o.first_hit_tiles = false);
    let low = prism::camera::Camera::looking_along(
        glam::Vec3::new(3.0, -13.0, -50.0),
        glam::Vec3::new(-0.3, -0.05, -1.0),
        70.0,
    )
    .unwrap();
    for camera in [scene.camera, low] {
        let s = RenderSettings::new(203, 150, 2);
        let rays = camera.rays(s.width, s.height);
        let view = |p: &PreparedScene| p.geometry.accel().camera_view(&rays, s.width, s.height);
        assert!(view(&tiles).tiles().is_some() && view(&traversal).tiles().is_none());
        assert_eq!(
            image(tiles.clone(), camera, s),
            image(traversal.clone(), camera, s)
        );
    }
}

#[test]
fn first_hit_tiles_draw_meshes_as_the_bvh_draws_them() {
    // A mesh is listed only in the tiles its own hierarchy's boxes cover (first_hit.rs):
    // the three placed bunnies, smooth, glass and faceted, must come out as a traversal of
    // the BVH draws them.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/bunny.toml");
    let scene = prism::scene_file::load_scene(&path).unwrap();
    let tiles = prepared(&scene, |_| {});
    let traversal = prepared(&scene, |o| o.first_hit_tiles = false);
    let s = RenderSettings::new(240, 180, 2);
    assert_eq!(
        image(tiles, scene.camera, s),
        image(traversal, scene.camera, s)
    );
}

#[test]
fn meshes_listed_by_tile_draw_what_their_hierarchies_draw() {
    // Close to the clay bunny, the first-hit tiles list its triangles
    // (mesh_listing.rs), and primary rays test those instead of walking its hierarchy: the
    // image must be what the walk draws, and what the BVH alone draws. The glass bunny
    // beside it sends refracted rays back through it.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/bunny.toml");
    let mut scene = prism::scene_file::load_scene(&path).unwrap();
    scene.camera = prism::camera::Camera::looking_along(
        glam::Vec3::new(-4.0, -2.0, -40.0),
        glam::Vec3::new(-0.1, -0.25, -1.0),
        50.0,
    )
    .unwrap();
    let listed = prepared(&scene, |_| {});
    let walked = prepared(&scene, |o| o.mesh_triangles = false);
    let traversal = prepared(&scene, |o| o.first_hit_tiles = false);
    let s = RenderSettings::new(640, 480, 2);
    let rays = scene.camera.rays(s.width, s.height);
    let census = |p: &PreparedScene| {
        let view = p.geometry.accel().camera_view(&rays, s.width, s.height);
        view.tiles().unwrap().census()
    };
    assert!(census(&listed).listing > 500, "{:?}", census(&listed));
    assert_eq!(census(&walked).listing, 0);
    let reference = image(listed, scene.camera, s);
    assert_eq!(reference, image(walked, scene.camera, s));
    assert_eq!(reference, image(traversal, scene.camera, s));
}

#[test]
fn meshes_listed_around_a_light_draw_what_their_hierarchies_draw() {
    // With every surface opaque, a shadow ray toward the point light tests the triangles
    // that the light's cell lists for each bunny (shadow_listing.rs), not the bunny's
    // hierarchy: the image, with its self-shadowed smooth, faceted and turned bunnies, must
    // be what the walk draws, and what the BVH alone draws.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/bunny.toml");
    let mut scene = prism::scene_file::load_scene(&path).unwrap();
    for object in &mut scene.objects {
        object.material.transparency = 0.0;
    }
    let listed = prepared(&scene, |_| {});
    assert!(!listed.appearance.shadow_filters().any_transmission());
    let census = listed.geometry.accel().light_buffer(0).unwrap().census();
    assert_eq!(census.listed_meshes, 3, "{census:?}");
    let walked = prepared(&scene, |o| o.light_triangles = false);
    assert_eq!(
        walked
            .geometry
            .accel()
            .light_buffer(0)
            .unwrap()
            .census()
            .listed_meshes,
        0
    );
    let unbuffered = prepared(&scene, |o| o.light_buffers = false);
    let s = RenderSettings::new(400, 300, 2);
    let reference = image(listed, scene.camera, s);
    assert_eq!(reference, image(walked, scene.camera, s));
    assert_eq!(reference, image(unbuffered, scene.camera, s));
}

#[test]
fn light_buffers_draw_the_image_the_bvh_draws() {
    // Shadow rays that look up what they may meet by their direction from the light
    // (light_buffer.rs) must see what a traversal of the BVH sees: for the seed's light;
    // for a second light among the objects, whose boxes straddle its cube's planes; and
    // with a cloud of glass beads over the scene that crowds cells past the list limit
    // and tints shadows through several surfaces.
    use glam::Vec3;
    use prism::accel::MAX_OCCLUDERS;
    use prism::appearance::Light;
    use prism::appearance::Material;
    use prism::appearance::Texture;

    let seed = seed();
    let mut among = seed.clone();
    among.lights.push(Light::point(
        Vec3::new(0.0, -5.0, -70.0),
        Vec3::new(0.5, 0.4, 0.3),
    ));
    let mut beads = seed.clone();
    // A sun too: it has no buffer, and its shadow rays (tinted by the beads) run to infinity
    // through the BVH on both paths.
    beads.lights.push(prism::appearance::Light {
        kind: prism::appearance::LightKind::Directional {
            direction: glam::Vec3::new(-0.2, -1.0, 0.1).normalize(),
        },
        color: glam::Vec3::splat(0.3),
    });
    for i in 0..60 {
        let a = i as f32 * 0.7;
        let center = Vec3::new(
            2.0 + 3.0 * a.cos(),
            12.0 + (i % 5) as f32,
            -60.0 + 3.0 * a.sin(),
        );
        let material = Material {
            texture: Texture::Solid(Vec3::new(0.9, 0.5, 0.2)),
            transparency: 0.6,
            ..Material::default()
        };
        beads.objects.push(bead(i, center, 0.8, material));
    }
    for (name, scene) in [("seed", seed), ("among", among), ("beads", beads)] {
        let lists = prepared(&scene, |_| {});
        let traversal = prepared(&scene, |o| o.light_buffers = false);
        let census = lists.geometry.accel().light_buffer(0).unwrap().census();
        assert!(traversal.geometry.accel().light_buffer(0).is_none());
        assert!(census.empty > 0, "{name}: {census:?}");
        if name == "beads" {
            assert!(
                census.crowded > 0,
                "more than {MAX_OCCLUDERS} beads share a cell"
            );
        }
        let s = RenderSettings::new(200, 150, 1);
        assert_eq!(
            image(lists, scene.camera, s),
            image(traversal, scene.camera, s),
            "{name}"
        );
    }
}

#[test]
fn rays_inside_isolated_solids_find_what_the_bvh_finds() {
    // A ray that starts inside a sphere or cylinder that no other box comes near tests only
    // that solid (ObjectData::isolated_solid). Here: the seed, where the five spheres are
    // isolated and the cylinder, standing on the floor, is not; and a variant with a glass
    // cylinder lifted off the floor (isolated, refracting through its side and caps) and a
    // bead inside the clear green sphere (so neither of those two is isolated).
    use glam::Vec3;
    use prism::appearance::Material;
    use prism::appearance::Texture;
    use prism::scene::{SceneObject, ShapeDesc};

    let seed = seed();
    let mut variant = seed.clone();
    for object in &mut variant.objects {
        if let ShapeDesc::Cylinder { base, .. } = &mut object.shape {
            base.y += 1.0;
            object.material.transparency = 0.8;
            object.material.eta = Some(1.5);
        }
    }
    variant.objects.push(SceneObject {
        casts_shadow: true,
        placement: Default::default(),
        group: None,
        node: None,
        name: "bead".into(),
        shape: ShapeDesc::Sphere {
            center: Vec3::new(-9.0, -10.5, -60.0),
            radius: 1.0,
        },
        material: Material {
            texture: Texture::Solid(Vec3::new(0.9, 0.2, 0.1)),
            ..Material::default()
        },
    });
    let isolated = |prepared: &PreparedScene, name: &str| {
        let object = prepared.geometry.find(name).unwrap();
        prepared.geometry.accel().isolated_solid(object).is_some()
    };
    for (name, scene) in [("seed", seed), ("variant", variant)] {
        let fast = prepared(&scene, |_| {});
        let seed = name == "seed";
        assert!(isolated(&fast, "mirror sphere") && isolated(&fast, "glass sphere (eta 1.43)"));
        assert_eq!(isolated(&fast, "green sphere"), seed, "{name}");
        assert_eq!(isolated(&fast, "striped cylinder"), !seed, "{name}");
        assert!(!isolated(&fast, "floor") && !isolated(&fast, "tetrahedron"));
        let slow = prepared(&scene, |o| o.isolated_solids = false);
        assert!(!isolated(&slow, "mirror sphere"));
        let s = RenderSettings::new(200, 150, 2);
        assert_eq!(
            image(fast, scene.camera, s),
            image(slow, scene.camera, s),
            "{name}"
        );
    }
}

/// Under area, sphere and spot lights, with every shortcut on, the image is the one each
/// shortcut's unoptimised path draws: the spotlight's light buffer and the first-hit tiles
/// serve it, the any-hit path answers the area lights' shadow rays, which end at their own
/// sampled points, and the soft-shadow scene is opaque, so the any-hit path is taken.
#[test]
fn soft_shadows_draw_the_same_image_with_every_shortcut_off() {
    let scene = prism::scene_file::parse_scene(
        include_str!("../assets/scenes/soft_shadows.toml"),
        std::path::Path::new("soft_shadows.toml"),
        std::path::Path::new("."),
    )
    .unwrap();
    let mut s = RenderSettings::new(160, 100, 2);
    s.samples = Some(16);
    let all = prepared(&scene, |_| {});
    assert!(!all.appearance.shadow_filters().any_transmission());
    let reference = image(all, scene.camera, s);
    for (what, off) in [
        (
            "the any-hit shadow path",
            (|o: &mut AccelOptions| o.any_hit_shadows = false) as fn(&mut AccelOptions),
        ),
        ("the light buffers", |o| o.light_buffers = false),
        ("the first-hit tiles", |o| o.first_hit_tiles = false),
        ("the meshes' listed triangles", |o| o.mesh_triangles = false),
        ("the meshes' triangles listed around lights", |o| {
            o.light_triangles = false
        }),
        ("the BVH", |o| o.bvh = false),
    ] {
        let without = image(prepared(&scene, off), scene.camera, s);
        assert_eq!(
            largest_difference(&reference, &without),
            0,
            "without {what}"
        );
    }
}

/// A combination of many members finds the members a ray or a point comes near through
/// hierarchies over their boxes; asking every member must draw the same image: bites out
/// of a box (a difference), a row of boxes touching face to face (hits at one distance on
/// two members), overlapping glass balls merged (refraction and shadows through them), and
/// a union holding a half-space (an inside no box holds).
#[test]
fn combinations_of_many_members_draw_what_asking_every_member_draws() {
    let mut text = String::from(
        "[camera]\neye = [0.5, 5, 13]\nlook_at = [0, 0.5, 0]\nfov = 50\n\
         [render]\nmax_depth = 6\n\
         [[lights]]\nposition = [-6, 10, 8]\n\
         [[lights]]\nposition = [5, 6, 4]\ncolor = [0.3, 0.3, 0.4]\n\
         [materials.glass]\ncolor = [0.9, 0.95, 1]\ntransparency = 0.9\neta = 1.5\n\
         [materials.red]\ncolor = [0.8, 0.2, 0.1]\n\
         [[csg]]\noperation = \"difference\"\nmaterial = \"red\"\ntranslate = [-3, 0, 0]\n\
         [[csg.members]]\ntype = \"box\"\nmin = [-2, -1, -2]\nmax = [2, 1, 2]\n",
    );
    for i in 0..30 {
        let (x, z) = ((i % 6) as f32 * 0.8 - 2.0, (i / 6) as f32 * 0.8 - 1.6);
        text +=
            &format!("[[csg.members]]\ntype = \"sphere\"\ncenter = [{x}, 1, {z}]\nradius = 0.35\n");
    }
    // Overlapping boxes of two materials, their tops and fronts in one plane, inside an
    // intersection with a ball: two members meet many rays at one distance.
    text += "[[csg]]\noperation = \"intersection\"\ntranslate = [3, 0, -1]\n\
             [[csg.members]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 2.2\n\
             [[csg.members]]\ntype = \"csg\"\noperation = \"union\"\n";
    for i in 0..12 {
        let x = i as f32 * 0.5 - 3.0;
        let material = ["red", "glass"][i % 2];
        text += &format!(
            "[[csg.members.members]]\ntype = \"box\"\nmin = [{x}, -1, -1]\nmax = [{}, 1, 1]\n\
             material = \"{material}\"\n",
            x + 0.75
        );
    }
    text += "[[csg]]\noperation = \"merge\"\nmaterial = \"glass\"\ntranslate = [0, 1.5, 2.5]\n";
    for i in 0..20 {
        let a = i as f32 * 2.399;
        let r = (i as f32).sqrt() * 0.3;
        text += &format!(
            "[[csg.members]]\ntype = \"sphere\"\ncenter = [{}, {}, {}]\nradius = 0.4\n",
            r * a.cos(),
            (i % 3) as f32 * 0.2,
            r * a.sin()
        );
    }
    text += "[[csg]]\noperation = \"difference\"\ntranslate = [0, -1, -4]\n\
             [[csg.members]]\ntype = \"box\"\nmin = [-6, -1, -1]\nmax = [6, 0.5, 1]\n\
             [[csg.members]]\ntype = \"csg\"\noperation = \"union\"\n\
             [[csg.members.members]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [1, 0.2, 0]\n";
    for i in 0..10 {
        text += &format!(
            "[[csg.members.members]]\ntype = \"sphere\"\ncenter = [{}, 0.5, 0]\nradius = 0.5\n",
            i as f32 * 0.5 + 0.5
        );
    }
    let scene = prism::scene_file::parse_scene(
        &text,
        std::path::Path::new("many.toml"),
        std::path::Path::new("."),
    )
    .unwrap();
    let s = RenderSettings::new(240, 160, 2);
    let with = image(prepared(&scene, |_| {}), scene.camera, s);
    let without = image(prepared(&scene, |o| o.bvh = false), scene.camera, s);
    assert_eq!(with, without);
    // The scene shows what it should: not a blank image.
    let distinct: std::collections::HashSet<&[u8]> = with.chunks(3).collect();
    assert!(distinct.len() > 100, "{} colours", distinct.len());
}
