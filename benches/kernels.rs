//! Kernel timings: one intersection of each shape, a BVH query over many spheres, and one
//! full Whitted path in the seed scene. `cargo bench --bench kernels`.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use prism::geometry::{Aabb, Bvh, Cylinder, Ray, RayQuery, Sphere, Triangle};
use prism::integrator::Integrator;
use prism::scene::{PreparedScene, load_scene};
use std::hint::black_box;

fn shapes(c: &mut Criterion) {
    let ray = Ray::new(
        Vec3::new(0.3, 0.2, 0.0),
        Vec3::new(0.01, -0.02, -1.0).normalize(),
    );
    let q = RayQuery::new(ray);
    let sphere = Sphere::new(Vec3::new(0.0, 0.0, -10.0), 2.0);
    let triangle = Triangle::new(
        Vec3::new(-2.0, -2.0, -10.0),
        Vec3::new(2.0, -2.0, -10.0),
        Vec3::new(0.0, 2.0, -10.0),
    )
    .unwrap();
    let cylinder = Cylinder::new(Vec3::new(0.0, -2.0, -10.0), 2.0, 4.0);
    c.bench_function("ray-sphere", |b| {
        b.iter(|| black_box(&sphere).intersect(black_box(&ray), f32::INFINITY))
    });
    c.bench_function("ray-triangle (watertight)", |b| {
        b.iter(|| black_box(&triangle).intersect(black_box(&q), f32::INFINITY))
    });
    c.bench_function("ray-cylinder", |b| {
        b.iter(|| black_box(&cylinder).intersect(black_box(&ray), f32::INFINITY))
    });
    c.bench_function("ray query setup", |b| {
        b.iter(|| RayQuery::new(black_box(ray)))
    });
}

fn bvh(c: &mut Criterion) {
    let spheres: Vec<Sphere> = (0..10_000)
        .map(|i| {
            let (x, y) = ((i % 100) as f32 * 3.0, (i / 100) as f32 * 3.0);
            Sphere::new(Vec3::new(x, y, -50.0), 1.0)
        })
        .collect();
    let bounds: Vec<Aabb> = spheres.iter().map(|s| s.bounds()).collect();
    let (tree, order) = Bvh::build(&bounds);
    let stored: Vec<Sphere> = order.iter().map(|&i| spheres[i as usize]).collect();
    let q = RayQuery::new(Ray::new(
        Vec3::new(150.0, 150.0, 0.0),
        Vec3::new(0.1, 0.05, -1.0),
    ));
    c.bench_function("BVH closest hit, 10k spheres", |b| {
        b.iter(|| {
            tree.closest(black_box(&q), f32::INFINITY, |i, t| {
                stored[i as usize].intersect(&q.ray, t)
            })
        })
    });
    c.bench_function("BVH build, 10k spheres", |b| {
        b.iter(|| Bvh::build(black_box(&bounds)))
    });
}

fn whitted_path(c: &mut Criterion) {
    let scene = load_scene(&prism::seed_scene_path()).unwrap();
    let prepared = PreparedScene::new(&scene);
    let rays = scene.camera.rays(800, 600);
    // Through the 1.43 glass sphere: refraction, reflection and shadows.
    let ray = rays.ray(610.0, 500.0);
    c.bench_function("seed scene, one path through the glass", |b| {
        b.iter(|| Integrator::new(&prepared, 1.0 / 512.0).trace_primary(black_box(ray)))
    });
}

criterion_group! {
    name = kernels;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(2));
    targets = shapes, bvh, whitted_path
}
criterion_main!(kernels);
