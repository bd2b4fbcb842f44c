//! Scenes made for measuring: many spheres, for the cost against object count; the
//! bunny, and a herd of it under two lights.

use glam::{DVec3, Vec3};
use prism::appearance::Light;
use prism::appearance::Material;
use prism::appearance::Texture;
use prism::camera::Camera;
use prism::scene::{RenderDefaults, Scene, SceneObject, ShapeDesc};
use prism::scene_file::{Assets, SceneError, parse_scene_with};
use std::path::Path;

/// The Stanford bunny, as shipped in assets/meshes/.
pub(super) const BUNNY_OBJ: &str = include_str!("../../assets/meshes/bunny.obj");

/// Five placed bunnies (turned, scaled, one faceted, one squashed, one lying on its side)
/// on a floor under two point lights.
pub fn herd() -> Result<Scene, SceneError> {
    let text = "[camera]\neye = [0, 6, 10]\nlook_at = [0, -8, -60]\nfov = 45\n\n\
        [[lights]]\nposition = [-3, 40, -20]\n\n\
        [[lights]]\nposition = [30, 25, -40]\ncolor = [0.5, 0.45, 0.4]\n\n\
        [[polygons]]\nname = \"floor\"\n\
        vertices = [[-60, -15, 10], [60, -15, 10], [60, -15, -200], [-60, -15, -200]]\n\n\
        [[meshes]]\nname = \"big\"\npath = \"bunny.obj\"\nscale = 2.0\nrotate = [0, 20, 0]\n\
        translate = [-10, -15, -70]\n\n\
        [[meshes]]\nname = \"faceted\"\npath = \"bunny.obj\"\nsmooth = false\nscale = 1.4\n\
        rotate = [0, -40, 0]\ntranslate = [8, -15, -60]\n\n\
        [[meshes]]\nname = \"squashed\"\npath = \"bunny.obj\"\nscale = [1.8, 0.8, 1.4]\n\
        rotate = [0, 100, 0]\ntranslate = [0, -15, -95]\n\n\
        [[meshes]]\nname = \"tipped\"\npath = \"bunny.obj\"\nscale = 1.2\nrotate = [0, 0, 90]\n\
        translate = [20, -9, -85]\n\n\
        [[meshes]]\nname = \"small\"\npath = \"bunny.obj\"\nscale = 0.8\nrotate = [0, 200, 0]\n\
        translate = [-20, -15, -50]\n";
    let files = [("bunny.obj", BUNNY_OBJ.as_bytes())];
    parse_scene_with(text, Path::new("herd.toml"), Assets::Embedded(&files))
}

/// `n` spheres of radius 1 scattered over a square field above a floor, the field growing
/// with √n so their density stays the same, seen from above at an angle that keeps the
/// whole field in view. Deterministic.
pub fn sphere_field(n: usize) -> Scene {
    let side = (n as f32).sqrt() * 4.0 + 8.0;
    let mut rng = prism::xorshift::XorShift32::new(0x9e37_79b9);
    let mut next = move || rng.next_f32();
    let mut objects: Vec<SceneObject> = (0..n)
        .map(|i| {
            let center = Vec3::new(
                (next() - 0.5) * side,
                1.0 + next() * 2.0,
                -(next() * side) - 4.0,
            );
            SceneObject {
                casts_shadow: true,
                placement: Default::default(),
                group: None,
                node: None,
                name: format!("sphere {i}"),
                shape: ShapeDesc::Sphere {
                    center,
                    radius: 1.0,
                },
                material: Material {
                    texture: Texture::Solid(Vec3::new(next(), next(), next())),
                    reflectivity: if i % 5 == 0 { 0.5 } else { 0.0 },
                    ..Material::default()
                },
            }
        })
        .collect();
    let half = side * 0.6;
    objects.push(SceneObject {
        casts_shadow: true,
        placement: Default::default(),
        group: None,
        node: None,
        name: "floor".into(),
        shape: ShapeDesc::Polygon {
            vertices: vec![
                Vec3::new(-half, 0.0, 2.0),
                Vec3::new(half, 0.0, 2.0),
                Vec3::new(half, 0.0, -side - 8.0),
                Vec3::new(-half, 0.0, -side - 8.0),
            ],
        },
        material: Material {
            specular: 0.0,
            ..Material::default()
        },
    });
    let eye = Vec3::new(0.0, side * 0.5, side * 0.25);
    let target = Vec3::new(0.0, 0.0, -side * 0.5);
    Scene {
        origin: DVec3::ZERO,
        camera: Camera::looking_along(eye, target - eye, 60.0).expect("non-zero"),
        render: RenderDefaults::default(),
        background: prism::appearance::Background::Solid(Vec3::new(0.1, 0.1, 0.15)),
        ambient: Vec3::splat(0.2),
        lights: vec![Light::point(
            Vec3::new(side, side * 2.0, side * 0.5),
            Vec3::ONE,
        )],
        fog: None,
        objects,
        groups: Vec::new(),
    }
}
