//! Kernel timings: one intersection of each shape, a BVH query over many spheres, one
//! full Whitted path in the seed scene, and a primary ray's first hit by BVH and by tile.
//! `cargo bench --bench kernels`.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use prism::accel::{AccelOptions, Accelerator, Primitive, Reach, Surface};
use prism::geometry::{Cylinder, Ray, RayQuery, Shape, Sphere, Triangle};
use prism::integrator::Integrator;
use prism::scene::PreparedScene;
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
    let spheres: Vec<Primitive> = (0..10_000)
        .map(|i| {
            let (x, y) = ((i % 100) as f32 * 3.0, (i / 100) as f32 * 3.0);
            Primitive {
                surface: Surface::Shape(Shape::Sphere(Sphere::new(Vec3::new(x, y, -50.0), 1.0))),
                object: i,
                material: i,
            }
        })
        .collect();
    // The BVH alone: no lights, no isolated solids.
    let options = AccelOptions {
        isolated_solids: false,
        ..AccelOptions::ALL
    };
    let n = spheres.len();
    let tree = Accelerator::build(spheres.clone(), n, &[], options);
    let q = RayQuery::new(Ray::new(
        Vec3::new(150.0, 150.0, 0.0),
        Vec3::new(0.1, 0.05, -1.0),
    ));
    c.bench_function("BVH closest hit, 10k spheres", |b| {
        b.iter(|| tree.nearest_hit(black_box(&q), Reach::After(0.0)))
    });
    c.bench_function("BVH build, 10k spheres", |b| {
        b.iter(|| Accelerator::build(black_box(spheres.clone()), n, &[], options))
    });
}

fn whitted_path(c: &mut Criterion) {
    let scene = prism::seed::scene().unwrap();
    let prepared = PreparedScene::new(&scene);
    let rays = scene.camera.rays(800, 600);
    // Through the 1.43 glass sphere: refraction, reflection and shadows.
    let ray = rays.ray(610.0, 500.0);
    c.bench_function("seed scene, one path through the glass", |b| {
        b.iter(|| {
            Integrator::new(&prepared, 1.0 / 512.0).trace_primary(
                Reach::After(0.0),
                || black_box(ray),
                prism::sampler::SampleStream::new(0, 0, 0),
            )
        })
    });
}

fn first_hit(c: &mut Criterion) {
    let scene = prism::seed::scene().unwrap();
    let prepared = PreparedScene::new(&scene);
    let rays = scene.camera.rays(800, 600);
    let accel = prepared.geometry.accel();
    let view = accel.camera_view(&rays, 800, 600);
    // A floor pixel between the objects, and a sky pixel above them.
    for (name, x, y) in [("floor", 400, 560), ("sky", 400, 20)] {
        let q = RayQuery::new(rays.ray(x as f32 + 0.5, y as f32 + 0.5));
        let reach = view.reach(x, y);
        assert!(matches!(reach, Reach::Among(..)));
        c.bench_function(&format!("primary ray, {name} pixel: BVH"), |b| {
            b.iter(|| accel.nearest_hit(black_box(&q), Reach::After(0.0)))
        });
        c.bench_function(&format!("primary ray, {name} pixel: first-hit tile"), |b| {
            b.iter(|| accel.nearest_hit(black_box(&q), black_box(reach)))
        });
    }
    c.bench_function("first-hit tiles build, seed scene, 800x600", |b| {
        b.iter(|| accel.camera_view(black_box(&rays), 800, 600))
    });
}

criterion_group! {
    name = kernels;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(2));
    targets = shapes, bvh, whitted_path, first_hit
}
criterion_main!(kernels);
