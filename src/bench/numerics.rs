//! `prism bench numerics`: the measured tables of docs/numerics.md.

use super::timing::median_of;
use anyhow::Result;
use glam::{DVec3, Vec3};
use prism::geometry::{Ray, Sphere};
use prism::integrator::SelfIntersection;
use prism::render::fraction_differing;
use prism::render::{self, RenderSettings};
use prism::scene::{PreparedScene, Scene};
use std::fmt::Write;
use std::sync::Arc;
use std::time::Instant;

/// The textbook root: (−b − √(b² − 4ac)) / 2a, all in f32.
fn naive_near_root(ray: &Ray, c: Vec3, r: f32) -> Option<f32> {
    let f = Vec3::from(ray.origin) - c;
    let d = Vec3::from(ray.dir);
    let a = d.dot(d);
    let b = 2.0 * f.dot(d);
    let cc = f.dot(f) - r * r;
    let disc = b * b - 4.0 * a * cc;
    (disc >= 0.0).then(|| (-b - disc.sqrt()) / (2.0 * a))
}

fn reference_near_root(ray: &Ray, c: Vec3, r: f32) -> Option<f64> {
    let (o, d, c, r) = (
        ray.origin.as_dvec3(),
        ray.dir.as_dvec3(),
        c.as_dvec3(),
        r as f64,
    );
    let f = o - c;
    let a = d.dot(d);
    let b = f.dot(d);
    let disc = b * b - a * (f.dot(f) - r * r);
    (disc >= 0.0).then(|| (-b - disc.sqrt()) / a)
}

/// Error of the hit distance, in sphere radii, for a unit sphere at growing distances hit
/// half-way between its centre and its rim; and for ray origins just above the surface.
pub fn quadratic_table() -> String {
    let mut out = String::from(
        "| sphere distance / radius | textbook f32 error (radii) | stable f32 error (radii) | one f32 step of t (radii) |\n|---|---|---|---|\n",
    );
    let cell = |e: Option<f64>| match e {
        Some(e) if e.is_finite() => format!("{e:.1e}"),
        _ => "miss".to_string(),
    };
    for k in 0..=7 {
        let distance = 10f32.powi(k) * 3.0;
        let c = Vec3::new(0.0, 0.0, -distance);
        let r = 1.0;
        // Aim at the point half a radius off-centre, so the hit is well defined.
        let ray = Ray::new(Vec3::ZERO, Vec3::new(0.5, 0.0, -distance).normalize());
        let truth = reference_near_root(&ray, c, r).expect("the f64 ray hits");
        let naive = naive_near_root(&ray, c, r).map(|t| (t as f64 - truth).abs() / r as f64);
        let stable = Sphere::new(c, r)
            .roots(&ray)
            .map(|(t, _)| (t as f64 - truth).abs() / r as f64);
        let ulp = (prism::numerics::next_float_up(truth as f32) - truth as f32) as f64 / r as f64;
        writeln!(
            out,
            "| {:.0e} | {} | {} | {ulp:.1e} |",
            distance,
            cell(naive),
            cell(stable)
        )
        .unwrap();
    }
    out.push_str(
        "\n| origin height above the surface / radius | textbook f32 error of the near root (f32 steps of the hit point) | stable f32 |\n|---|---|---|\n",
    );
    for k in 1..=6 {
        let h = 10f32.powi(-k);
        let c = Vec3::new(3.0, -2.0, -10.0);
        let r = 5.0;
        // From just outside the surface, at 30° to the inward normal: the near root is
        // about h·r / cos 30°, a secondary ray's situation.
        let n = Vec3::new(1.0, 2.0, 3.0).normalize();
        let (t1, _) = prism::numerics::orthonormal_basis(n);
        let dir = (-n * 30f32.to_radians().cos() + t1 * 30f32.to_radians().sin()).normalize();
        let ray = Ray::new(c + n * (r + h * r), dir);
        let truth = reference_near_root(&ray, c, r).unwrap();
        // One step of f32 at the hit point's magnitude: the least error a position can have.
        let p = (c + n * r).abs().max_element();
        let step = (prism::numerics::next_float_up(p) - p) as f64;
        let steps = |t: f32| (t as f64 - truth).abs() / step;
        let naive = naive_near_root(&ray, c, r).map(steps);
        let stable = Sphere::new(c, r).roots(&ray).map(|(t, _)| steps(t));
        writeln!(out, "| {h:.0e} | {} | {} |", cell(naive), cell(stable)).unwrap();
    }
    out
}

fn render(scene: &Scene, w: u32, h: u32, policy: SelfIntersection) -> (image::RgbImage, f64) {
    let mut settings = RenderSettings::new(w, h, 1);
    settings.self_intersection = policy;
    let prepared = Arc::new(PreparedScene::new(scene));
    let start = Instant::now();
    let job = render::render(prepared, scene.camera, settings, |_, _| {});
    (job.accumulator().to_rgb8(), start.elapsed().as_secs_f64())
}

/// Pixels (of 240×180) that differ by more than two levels from the unscaled render.
pub fn acne_table(seed: &Scene) -> String {
    let (w, h) = (240, 180);
    let (reference, _) = render(seed, w, h, SelfIntersection::ErrorBound);
    let mut out =
        String::from("| scene scale | fixed ε = 1e-3 | error-bound offset |\n|---|---|---|\n");
    for k in -4..=5 {
        let s = seed.transformed(10f32.powi(k), DVec3::ZERO);
        let (fixed, _) = render(&s, w, h, SelfIntersection::FixedEpsilon(1e-3));
        let (robust, _) = render(&s, w, h, SelfIntersection::ErrorBound);
        writeln!(
            out,
            "| 1e{k:+} | {:.3}% | {:.3}% |",
            fraction_differing(&fixed, &reference, 2) * 100.0,
            fraction_differing(&robust, &reference, 2) * 100.0
        )
        .unwrap();
    }
    out
}

/// Median time of a full 800×600 pass with each self-intersection policy.
pub fn cost_table(seed: &Scene, runs: usize) -> String {
    let mut out =
        String::from("| policy | median time per 800×600 pass (1 subsample) |\n|---|---|\n");
    for (name, policy) in [
        ("fixed ε = 1e-3", SelfIntersection::FixedEpsilon(1e-3)),
        ("error-bound offset", SelfIntersection::ErrorBound),
    ] {
        let times = (0..runs.max(1))
            .map(|_| render(seed, 800, 600, policy).1)
            .collect();
        writeln!(out, "| {name} | {:.1} ms |", median_of(times) * 1e3).unwrap();
    }
    out
}

pub fn run(runs: usize) -> Result<()> {
    let seed = prism::seed::scene()?;
    println!(
        "## Ray–sphere roots: textbook against stable\n\n{}",
        quadratic_table()
    );
    println!(
        "## Self-intersection across scales\n\n{}",
        acne_table(&seed)
    );
    println!("## The cost of robustness\n\n{}", cost_table(&seed, runs));
    Ok(())
}
