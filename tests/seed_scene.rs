//! The seed scene, rendered headless: the properties a person checks by eye, as numbers.

mod common;

use common::seed;
use glam::Vec3;
use prism::accel::Reach;
use prism::camera::Camera;
use prism::geometry::Ray;
use prism::integrator::Integrator;
use prism::render::{self, RenderSettings};
use prism::scene::{PreparedScene, Scene, ShapeDesc};
use std::sync::Arc;

fn object_mut<'a>(scene: &'a mut Scene, name: &str) -> &'a mut prism::scene::SceneObject {
    scene.objects.iter_mut().find(|o| o.name == name).unwrap()
}

/// The colour seen from the seed's eye towards world point `target` (exact, no sampling).
fn look_at(scene: &Scene, target: Vec3) -> Vec3 {
    look_from(scene, scene.camera.eye, target)
}

/// The colour seen from `eye` towards `target`.
fn look_from(scene: &Scene, eye: Vec3, target: Vec3) -> Vec3 {
    let prepared = PreparedScene::new(scene);
    let mut integrator = Integrator::new(&prepared, 0.0);
    integrator
        .trace_primary(
            Reach::After(0.0),
            || Ray::new(eye, (target - eye).normalize()),
            prism::sampler::SampleStream::new(0, 0, 0),
        )
        .color
}

/// The floor at `p` seen from just above it (below every occluder).
fn floor_at(scene: &Scene, p: Vec3) -> Vec3 {
    look_from(scene, p + Vec3::new(0.0, 0.5, 0.1), p)
}

fn render_small(scene: &Scene, width: u32, height: u32, aa: u32) -> prism::render::Accumulator {
    let job = render::render(
        Arc::new(PreparedScene::new(scene)),
        scene.camera,
        RenderSettings::new(width, height, aa),
        |_, _| {},
    );
    job.accumulator().clone()
}

#[test]
fn seed_scene_has_every_object_of_the_report() {
    let scene = seed();
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    for expected in [
        "floor",
        "mirror sphere",
        "earth",
        "glass sphere (eta 1.43)",
        "glass sphere (eta 1.002)",
        "green sphere",
        "striped cylinder",
        "tetrahedron",
    ] {
        assert!(names.contains(&expected), "missing {expected}");
    }
    let eta = |n: &str| {
        scene
            .objects
            .iter()
            .find(|o| o.name == n)
            .unwrap()
            .material
            .eta
    };
    assert_eq!(eta("glass sphere (eta 1.43)"), Some(1.43));
    assert_eq!(eta("glass sphere (eta 1.002)"), Some(1.002));
    let fov = 2.0 * (10.0f32 / 40.0).atan().to_degrees();
    assert!((scene.camera.vfov - fov).abs() < 1e-4);
    assert_eq!(scene.render.max_depth, 5);
}

#[test]
fn no_pixel_is_nan_or_infinite() {
    let acc = render_small(&seed(), 200, 150, 2);
    for p in &acc.pixels {
        assert!(p.color.is_finite(), "non-finite pixel sum {:?}", p.color);
        assert_eq!(p.count, 4);
    }
}

#[test]
fn earth_centre_carries_the_texture_colour_lit_by_phong() {
    let mut scene = seed();
    // Without the highlight, the pixel must be texture × (ambient + diffuse·cos θ) exactly.
    object_mut(&mut scene, "earth").material.specular = 0.0;
    let (center, radius) = match object_mut(&mut scene, "earth").shape {
        ShapeDesc::Sphere { center, radius } => (center, radius),
        _ => unreachable!(),
    };
    let seen = look_at(&scene, center);
    // Where the eye's ray meets the sphere, and the texel there.
    let dir = (center - scene.camera.eye).normalize();
    let hit = scene.camera.eye + dir * ((center - scene.camera.eye).length() - radius);
    let n = (hit - center).normalize();
    let (u, v) = prism::geometry::Sphere::uv(n.into());
    let prism::appearance::Texture::Image { image, .. } =
        &object_mut(&mut scene, "earth").material.texture
    else {
        panic!("the earth is image textured");
    };
    let texel = glam::Vec3::from(image.sample(u, v));
    let l = (scene.lights[0].position().unwrap() - hit).normalize();
    let expected = texel * (0.2 + n.dot(l).max(0.0));
    assert!(
        (seen - expected).abs().max_element() < 2e-3,
        "seen {seen}, expected {expected} from texel {texel}"
    );
    assert!(texel.max_element() > 0.05, "the centre texel is not black");
}

#[test]
fn shadow_of_the_mirror_sphere_is_darker_than_its_lit_neighbour() {
    let scene = seed();
    // Project the mirror sphere's centre from the light onto the floor y = −15.
    let light = scene.lights[0].position().unwrap();
    let c = Vec3::new(-5.0, 0.0, -100.0);
    let t = (light.y + 15.0) / (light.y - c.y);
    let shadow = light + (c - light) * t;
    // Two checker cells (10 units) further in x: the same floor colour, in the light.
    let lit = shadow + Vec3::new(30.0, 0.0, 0.0);
    let (s, l) = (floor_at(&scene, shadow), floor_at(&scene, lit));
    assert!(
        s.max_element() < 0.5 * l.max_element(),
        "shadow {s} vs lit {l}"
    );
}

#[test]
fn green_sphere_casts_a_lighter_green_tinted_shadow() {
    let scene = seed();
    let light = scene.lights[0].position().unwrap();
    let c = Vec3::new(-9.0, -10.0, -60.0);
    let t = (light.y + 15.0) / (light.y - c.y);
    let in_shadow = light + (c - light) * t;
    let mut opaque = scene.clone();
    object_mut(&mut opaque, "green sphere")
        .material
        .transparency = 0.0;
    let mut removed = scene.clone();
    removed.objects.retain(|o| o.name != "green sphere");
    let tinted = floor_at(&scene, in_shadow);
    let dark = floor_at(&opaque, in_shadow);
    let bare = floor_at(&removed, in_shadow);
    assert!(
        tinted.max_element() > dark.max_element() + 0.1,
        "{tinted} vs {dark}"
    );
    assert!(
        tinted.max_element() < bare.max_element(),
        "{tinted} vs {bare}"
    );
    // Green passes more than red and blue.
    assert!(tinted.y / bare.y > tinted.x / bare.x + 0.05);
}

#[test]
fn mirror_sphere_shows_the_floor() {
    let scene = seed();
    let mut no_floor = scene.clone();
    no_floor.objects.retain(|o| o.name != "floor");
    // The lower part of the mirror sphere reflects the floor; without a floor it is dark.
    let target = Vec3::new(-5.0, -9.0, -90.0);
    let with = look_at(&scene, target);
    let without = look_at(&no_floor, target);
    assert!(
        (with - without).max_element() > 0.2,
        "with floor {with}, without {without}"
    );
}

#[test]
fn the_143_sphere_bends_the_floor_seen_through_it() {
    let scene = seed();
    let mut straight = scene.clone();
    object_mut(&mut straight, "glass sphere (eta 1.43)")
        .material
        .eta = Some(1.0);
    let acc_bent = render_small(&scene, 160, 120, 1);
    let acc_straight = render_small(&straight, 160, 120, 1);
    // Inside the sphere's disc on screen, most pixels change when the glass stops bending.
    let cam = scene.camera;
    let rays = cam.rays(160, 120);
    let mut changed = 0;
    let mut total = 0;
    for y in 0..120 {
        for x in 0..160 {
            let r = rays.ray(x as f32 + 0.5, y as f32 + 0.5);
            let s = prism::geometry::Sphere::new(Vec3::new(9.0, -10.0, -60.0), 3.0);
            if s.intersect(&r, f32::INFINITY).is_some() {
                total += 1;
                let d = (acc_bent.mean(x, y) - acc_straight.mean(x, y))
                    .abs()
                    .max_element();
                changed += (d > 0.05) as u32;
            }
        }
    }
    assert!(total > 50);
    assert!(changed * 2 > total, "{changed} of {total} pixels changed");
}

#[test]
fn image_is_identical_with_one_and_two_threads() {
    let scene = seed();
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render_small(&scene, 120, 90, 2))
    };
    let one = run(1);
    let two = run(2);
    assert!(one.pixels == two.pixels, "thread count changed the image");
}

#[test]
fn camera_from_look_at_matches_direction() {
    let a = Camera::looking_along(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), 30.0).unwrap();
    assert_eq!(a.yaw, 0.0);
    assert_eq!(a.pitch, 0.0);
}
