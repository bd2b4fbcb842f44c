//! Distribution effects against analytic answers: the penumbra of a sphere light, the thin
//! lens's focus and circle of confusion, Beer–Lambert absorption, nested media, conductor
//! tints, glossy reflection and fog; and with each effect on, no NaN and the same image at
//! every scale.

mod common;

use glam::{DVec3, Vec3, Vec3A};
use prism::accel::Reach;
use prism::appearance::schlick_reflectance;
use prism::geometry::Ray;
use prism::integrator::Integrator;
use prism::render::{RenderSettings, fraction_differing};
use prism::sampler::SampleStream;
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::parse_scene;
use std::path::Path;

fn load(text: &str) -> Scene {
    parse_scene(text, Path::new("effects.toml"), Path::new(".")).unwrap()
}

/// The mean colour seen along `ray` over subsamples 0..n of pixel (px, py).
fn mean_along(prepared: &PreparedScene, ray: Ray, n: u32, px: u32) -> Vec3 {
    let mut integrator = Integrator::new(prepared, 0.0);
    let mut sum = Vec3::ZERO;
    for k in 0..n {
        sum += integrator
            .trace_primary(Reach::After(0.0), || ray, SampleStream::new(px, 7, k))
            .color;
    }
    sum / n as f32
}

/// A floor lit by `light` (TOML: a disc of radius 1 at height 10) over a half-plane occluder
/// at height 5 that covers x < 0: by similar triangles the penumbra spans |x| < R·h/(H − h)
/// = 1, and at x the light's visible share is that of the unit disc beyond −x: (acos c −
/// c·√(1 − c²))/π for c = −x.
fn penumbra_has_the_analytic_width_and_profile(light: &str) {
    let scene = |occluder: bool| {
        let wall = if occluder {
            "[[boxes]]\nmin = [-100, 4.99, -100]\nmax = [0, 5, 100]\nmaterial = \"matte\"\n"
        } else {
            ""
        };
        load(&format!(
            "[camera]\neye = [0, 20, 0]\ndirection = [0, -1, 0]\nup = [0, 0, -1]\nfov = 40\n\
             [render]\nambient = [0, 0, 0]\n\
             [[lights]]\n{light}\n\
             [materials.matte]\ncolor = [1, 1, 1]\nspecular = 0\n\
             [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"matte\"\n{wall}"
        ))
    };
    let (shadowed, open) = (scene(true), scene(false));
    let (shadowed_p, open_p) = (PreparedScene::new(&shadowed), PreparedScene::new(&open));
    let origin = shadowed.origin.as_vec3();
    let expected = |x: f64| {
        let c = (-x).clamp(-1.0, 1.0);
        (c.acos() - c * (1.0 - c * c).sqrt()) / std::f64::consts::PI
    };
    let mut worst = 0.0f64;
    for (i, x) in [
        -1.3f32, -1.05, -0.9, -0.6, -0.3, 0.0, 0.25, 0.5, 0.8, 0.95, 1.05, 1.4,
    ]
    .into_iter()
    .enumerate()
    {
        // Seen from just above the floor, under the occluder.
        let p = Vec3::new(x, 0.5, 0.3) - origin;
        let ray = Ray::new(p, -Vec3::Y);
        let n = 1024;
        let lit = mean_along(&shadowed_p, ray, n, i as u32).x as f64;
        let full = mean_along(&open_p, ray, n, i as u32).x as f64;
        let share = lit / full;
        let want = expected(x as f64);
        println!("x {x:+.2}: visible {share:.4}, analytic {want:.4}");
        worst = worst.max((share - want).abs());
        if x.abs() > 1.0 {
            // Outside the penumbra: fully lit or fully dark, in every sample.
            assert_eq!(share, want.round(), "x {x}");
        }
    }
    assert!(
        worst < 0.02,
        "largest difference from the analytic share {worst}"
    );
}

/// A sphere light is sampled over its disc facing the shading point (within 6° of level
/// here).
#[test]
fn a_sphere_lights_penumbra_has_the_analytic_width_and_profile() {
    penumbra_has_the_analytic_width_and_profile(
        "type = \"sphere\"\nposition = [0, 10, 0]\nradius = 1\nvisible = false",
    );
}

/// A spotlight with a disc: the disc faces along the cone's axis, level here; the cone is
/// wide enough to light the whole floor seen.
#[test]
fn a_spotlights_disc_casts_the_analytic_penumbra() {
    penumbra_has_the_analytic_width_and_profile(
        "type = \"spot\"\nposition = [0, 10, 0]\ndirection = [0, -1, 0]\nangle = 60\nradius = 1",
    );
}

/// A spotlight whose disc has radius 0 is the point spotlight, to the bit; one with a disc
/// lights its cone as the point one does (where nothing casts a shadow) and softens its
/// shadows.
#[test]
fn a_spotlight_of_radius_0_is_a_point_and_a_disc_only_softens_shadows() {
    let scene = |radius: &str| {
        load(&format!(
            "[camera]\neye = [0, 6, 8]\nlook_at = [0, 0, 0]\nfov = 50\n\
             [render]\nambient = [0, 0, 0]\nwidth = 96\nheight = 72\n\
             [[lights]]\ntype = \"spot\"\nposition = [0, 8, 0]\ndirection = [0, -1, 0]\n\
             angle = 30\nsoftness = 0.2\n{radius}\n\
             [materials.matte]\ncolor = [1, 1, 1]\nspecular = 0\n\
             [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"matte\"\n\
             [[spheres]]\ncenter = [0.5, 1, 0]\nradius = 1\nmaterial = \"matte\"\n"
        ))
    };
    let settings = RenderSettings::new(96, 72, 64);
    let point = common::render_scene(&scene(""), settings);
    assert_eq!(point, common::render_scene(&scene("radius = 0"), settings));
    let sampled = |scene: &Scene| PreparedScene::new(scene).appearance.is_stochastic();
    assert!(!sampled(&scene("")), "a point spot is not sampled");
    let soft = scene("radius = 0.8");
    assert!(sampled(&soft));
    let disc = common::render_scene(&soft, settings);
    // The cone's edge and the lit floor away from the shadow stay (within the noise of
    // 64 subsamples); the shadow's edge, a small share of the image, moves.
    let differing = fraction_differing(&point, &disc, 8);
    assert!(
        differing > 0.002 && differing < 0.05,
        "{:.3} of pixels differ",
        differing
    );
}

/// A point on the plane in focus is met by every lens ray through its image point; one at
/// depth z is met by lens rays through image points spread over the thin lens's circle of
/// confusion, A·|z − f|/z across on the plane in focus.
#[test]
fn the_lens_focuses_on_its_plane_and_blurs_by_the_circle_of_confusion() {
    let (w, h) = (200u32, 150u32);
    let scene = load(
        "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40\naperture = 0.8\n\
         focus_distance = 10\n[[spheres]]\ncenter = [0, 0, -10]\nradius = 1\n",
    );
    let camera = scene.camera;
    let rays = camera.rays(w, h);
    let pixel_size = 2.0 * 10.0 * (20f64.to_radians()).tan() / h as f64;
    let lens_samples: Vec<(f32, f32)> = (0..256)
        .map(|k| SampleStream::new(3, 4, k).next_2d())
        .collect();
    // In focus: the pinhole pixel of a point 10 away, traced through the lens, meets it.
    let q = DVec3::new(1.3, -0.7, -10.0);
    let (qx, qy) = rays.project(q, w, h).unwrap();
    for &u in &lens_samples {
        let r = rays.ray_through_lens(qx as f32, qy as f32, u);
        let (o, d) = (r.origin.as_dvec3(), r.dir.as_dvec3());
        let miss = (q - o).cross(d).length();
        assert!(
            miss < 1e-4,
            "in focus, a lens ray passes {miss} from the point"
        );
    }
    // Out of focus: for each lens point L, the image point whose ray from L meets Q lies
    // where the line L→Q crosses the plane in focus; their spread is the circle of confusion.
    for z in [5.0f64, 20.0, 40.0] {
        let q = DVec3::new(0.0, 0.0, -z);
        let (cx, cy) = rays.project(q, w, h).unwrap();
        let mut widest = 0.0f64;
        for &u in &lens_samples {
            let l = rays.ray_through_lens(0.0, 0.0, u).origin.as_dvec3();
            let f = l + (q - l) * ((10.0 - 0.0) / z); // the eye looks down −z: depth is −z
            let (fx, fy) = rays.project(f, w, h).unwrap();
            // That image point's ray from L does pass through Q.
            let r = rays.ray_through_lens(fx as f32, fy as f32, u);
            let miss = (q - r.origin.as_dvec3()).cross(r.dir.as_dvec3()).length();
            assert!(miss < 1e-3 * z, "z {z}: {miss}");
            widest = widest.max(((fx - cx).powi(2) + (fy - cy).powi(2)).sqrt());
        }
        let coc = 0.8 * (z - 10.0).abs() / z / pixel_size;
        println!(
            "depth {z}: blur radius {widest:.2} px, thin-lens circle of confusion {:.2} px across",
            coc
        );
        // 256 stratified points reach within a few percent of the disc's rim.
        assert!(
            widest <= coc / 2.0 * 1.0001 && widest >= coc / 2.0 * 0.95,
            "z {z}: {widest} vs {}",
            coc / 2.0
        );
    }
}

/// The image of an unlit clear object over a white sky, one ray per pixel centre.
fn image(scene: &Scene, samples: u32) -> image::RgbImage {
    let mut settings = RenderSettings::new(64, 48, 1);
    settings.samples = Some(samples);
    common::render_scene(scene, settings)
}

fn colour_at(scene: &Scene, dir: Vec3) -> Vec3 {
    let prepared = PreparedScene::new(scene);
    mean_along(&prepared, Ray::new(Vec3::ZERO, dir.normalize()), 1, 0)
}

const CLEAR: &str = "transparency = 1\nambient = 0\ndiffuse = 0\nspecular = 0\n";

#[test]
fn absorption_follows_beer_lambert_along_the_path_inside() {
    for (shape, length) in [
        (
            "[[boxes]]\nmin = [-1, -1, -6]\nmax = [1, 1, -4]\nmaterial = \"tinted\"",
            2.0f32,
        ),
        (
            "[[spheres]]\ncenter = [0, 0, -8]\nradius = 1.5\nmaterial = \"tinted\"",
            3.0,
        ),
    ] {
        let scene = load(&format!(
            "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 30\n\
             [render]\nbackground = [1, 1, 1]\n\
             [materials.tinted]\n{CLEAR}eta = 1.5\nabsorption = [0.1, 0.5, 1.0]\n{shape}\n"
        ));
        let c = colour_at(&scene, -Vec3::Z);
        for (found, sigma) in c.to_array().into_iter().zip([0.1f32, 0.5, 1.0]) {
            let want = (-sigma * length).exp();
            assert!(
                (found - want).abs() < 1e-5,
                "{shape}: {found} against exp(-{sigma}·{length}) = {want}"
            );
        }
    }
}

/// Water inside glass of the same index bends nothing where they meet: the image is the
/// same as without the water. (Taking air to be outside the water would bend the rays by
/// 1/1.33 there and back by 1.33.) With water of a lower index, it differs.
#[test]
fn nested_media_bend_by_the_ratio_of_their_indices() {
    let scene = |inner: &str| {
        load(&format!(
            "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 30\n\
             [render]\nbackground = {{ bottom = [0, 0, 0], top = [1, 1, 1] }}\n\
             [materials.glass]\n{CLEAR}eta = 1.33\n[materials.water]\n{CLEAR}eta = {inner}\n\
             [[spheres]]\ncenter = [0, 0, -10]\nradius = 2\nmaterial = \"glass\"\n\
             [[spheres]]\ncenter = [0.3, 0.2, -10]\nradius = 1\nmaterial = \"water\"\n"
        ))
    };
    let mut alone = scene("1.33");
    alone.objects.pop();
    let reference = image(&alone, 1);
    let same = image(&scene("1.33"), 1);
    assert_eq!(fraction_differing(&reference, &same, 1), 0.0);
    let lower = image(&scene("1.1"), 1);
    assert!(fraction_differing(&reference, &lower, 1) > 0.05);
}

/// Surfaces that touch, as a user writes them: a clear disc of glass (eta 1.5) standing on
/// a checked table, and one standing on a block of water (1.33) over the table. Seen from
/// above, each image is the one with a hair of air between the faces (1e-4: parallel faces
/// then bend nothing more, and shift the checks by less than a pixel). Taking the table's or
/// the water's face for the glass's own, as rounding did at random, gave salt-and-pepper
/// speckle; keeping the ray in the glass after it entered the water bent it by 1.33/1.5, not
/// 1.33, on leaving the water.
#[test]
fn touching_surfaces_render_as_if_a_hair_apart() {
    let scene = |water: bool, gap: f32| {
        let (table_top, water) = if water {
            let water = format!(
                "[[boxes]]\nmin = [-1, -0.5, -1]\nmax = [1, {gap}, 1]\nmaterial = \"water\"\n"
            );
            (-1.0, water)
        } else {
            (-gap, String::new())
        };
        load(&format!(
            "[camera]\neye = [0.3, 4, 0.2]\nlook_at = [0, 0, 0]\nfov = 16\n\
             [render]\nbackground = [1, 1, 1]\nambient = [0.3, 0.3, 0.3]\n\
             [[lights]]\nposition = [2, 6, 3]\n\
             [textures.checks]\ntype = \"checker\"\ncolors = [[0.9, 0.9, 0.9], [0.1, 0.2, 0.6]]\n\
             size = 0.2\naxes = \"xz\"\n\
             [materials.table]\ntexture = \"checks\"\nspecular = 0\n\
             [materials.glass]\n{CLEAR}eta = 1.5\n[materials.water]\n{CLEAR}eta = 1.33\n\
             [[boxes]]\nmin = [-3, -2, -3]\nmax = [3, {table_top}, 3]\nmaterial = \"table\"\n\
             {water}\
             [[cylinders]]\nbase = [0, {glass}, 0]\nradius = 1\nheight = 0.5\nmaterial = \"glass\"\n",
            glass = 2.0 * gap,
        ))
    };
    for water in [false, true] {
        let touching = image(&scene(water, 0.0), 1);
        let apart = image(&scene(water, 1e-4), 1);
        // Only the edges of checks, moved by the gaps, may differ.
        let differing = fraction_differing(&touching, &apart, 8);
        assert!(differing < 0.005, "water {water}: {differing}");
        // The same again: the choice between touching surfaces is not left to rounding.
        assert_eq!(touching, image(&scene(water, 0.0), 1));
    }
}

#[test]
fn a_conductor_tints_its_reflection_by_schlicks_curve() {
    let scene = load(
        "[camera]\neye = [0, 1, 0]\ndirection = [0, 0, -1]\nfov = 30\n\
         [render]\nbackground = [1, 1, 1]\nambient = [0, 0, 0]\n\
         [materials.gold]\ncolor = [0, 0, 0]\nspecular = 0\nreflectivity = 0.9\n\
         conductor = [1.0, 0.78, 0.34]\n\
         [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"gold\"\n",
    );
    for angle in [0.0f32, 30.0, 60.0, 85.0] {
        // A ray at `angle` from the normal, down onto the floor from 1 above.
        let a = angle.to_radians();
        let dir = Vec3::new(0.0, -a.cos(), -a.sin());
        let c = colour_at(&scene, dir);
        let want = schlick_reflectance(a.cos(), Vec3A::new(1.0, 0.78, 0.34)) * 0.9;
        assert!(
            (Vec3A::from(c) - want).abs().max_element() < 1e-4,
            "{angle}°: {c} against {want}"
        );
    }
}

/// A rough mirror under a uniform sky still reflects exactly its reflectivity of it, and
/// under a sky bright only near the zenith it spreads the reflection: the zenith's light
/// reaches it from directions the mirror alone would not.
#[test]
fn glossy_reflection_spreads_the_mirror_into_a_lobe() {
    let scene = |roughness: f32, sky: &str| {
        load(&format!(
            "[camera]\neye = [0, 1, 0]\ndirection = [0, -1, -1]\nfov = 30\n\
             [render]\nbackground = {sky}\nambient = [0, 0, 0]\n\
             [materials.m]\ncolor = [0, 0, 0]\nspecular = 0\nreflectivity = 0.8\nroughness = {roughness}\n\
             [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"m\"\n"
        ))
    };
    let dir = Vec3::new(0.0, -1.0, -1.0);
    for r in [0.2f32, 0.6] {
        let s = scene(r, "[0.5, 0.5, 0.5]");
        let c = mean_along(
            &PreparedScene::new(&s),
            Ray::new(Vec3::ZERO, dir.normalize()),
            64,
            1,
        );
        assert!((c - Vec3::splat(0.4)).abs().max_element() < 1e-5, "{c}");
    }
    // A gradient sky from black below to white above: a mirror reflecting 45° up sees
    // its middle value; a rough one sees a spread of directions, and their average
    // differs, more the rougher it is. Every sample stays within the sky's range.
    let sky = "{ bottom = [0, 0, 0], top = [1, 1, 1] }";
    let mirror = mean_along(
        &PreparedScene::new(&scene(0.0, sky)),
        Ray::new(Vec3::ZERO, dir.normalize()),
        1,
        1,
    );
    let mut last = 0.0;
    for r in [0.3f32, 0.7] {
        let c = mean_along(
            &PreparedScene::new(&scene(r, sky)),
            Ray::new(Vec3::ZERO, dir.normalize()),
            256,
            1,
        );
        let spread = (c.x - mirror.x).abs();
        assert!(
            c.x.is_finite() && c.x <= 0.8 && spread > last,
            "roughness {r}: {c} against the mirror's {mirror}"
        );
        last = spread;
    }
}

/// Rough glass that bends light spreads the refracted ray as a rough mirror spreads the
/// reflected one: through a clear slab under a uniform sky it still passes all of it (a
/// ray a facet turns back inside finds its way out later), and under a sky bright only near the zenith, looked through at a
/// slant, the result moves away from the smooth slab's (which sends the ray on parallel),
/// more the rougher it is.
#[test]
fn rough_glass_spreads_the_refracted_ray() {
    let scene = |roughness: f32, sky: &str| {
        load(&format!(
            "[camera]\neye = [0, 2, 0]\ndirection = [0, 1, -1]\nfov = 30\n\
             [render]\nbackground = {sky}\nambient = [0, 0, 0]\nmax_depth = 32\n\
             [materials.g]\ncolor = [1, 1, 1]\ndiffuse = 0\nspecular = 0\ntransparency = 1\n\
             eta = 1.5\nroughness = {roughness}\n\
             [[boxes]]\nmin = [-50, 3, -50]\nmax = [50, 3.5, 50]\nmaterial = \"g\"\n"
        ))
    };
    // Rays start at the eye, the prepared scene's origin.
    let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 1.0, -1.0).normalize());
    for r in [0.2f32, 0.6] {
        let c = mean_along(
            &PreparedScene::new(&scene(r, "[0.5, 0.5, 0.5]")),
            ray,
            64,
            1,
        );
        assert!((c - Vec3::splat(0.5)).abs().max_element() < 1e-5, "{c}");
    }
    let sky = "{ bottom = [0, 0, 0], top = [1, 1, 1] }";
    let smooth = mean_along(&PreparedScene::new(&scene(0.0, sky)), ray, 1, 1);
    let mut last = 0.0;
    for r in [0.3f32, 0.7] {
        let c = mean_along(&PreparedScene::new(&scene(r, sky)), ray, 256, 1);
        let spread = (c.x - smooth.x).abs();
        assert!(
            c.x.is_finite() && c.x <= 1.0 && spread > last + 0.005,
            "roughness {r}: {c} against the smooth slab's {smooth}"
        );
        last = spread;
    }
}

#[test]
fn fog_fades_each_segment_by_its_length() {
    let scene = |fog: &str| {
        load(&format!(
            "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 30\n\
             [render]\nbackground = [0, 0, 0]\nambient = [1, 1, 1]\n{fog}\n\
             [materials.white]\ncolor = [1, 1, 1]\nambient = 1\ndiffuse = 0\nspecular = 0\n\
             [[planes]]\npoint = [0, 0, -5]\nnormal = [0, 0, 1]\nmaterial = \"white\"\n"
        ))
    };
    let exp = scene("[fog]\ncolor = [0.2, 0.4, 0.6]\ndensity = 0.3");
    let c = colour_at(&exp, -Vec3::Z);
    let t = (-0.3f32 * 5.0).exp();
    let want = Vec3::ONE * t + Vec3::new(0.2, 0.4, 0.6) * (1.0 - t);
    assert!((c - want).abs().max_element() < 1e-5, "{c} against {want}");
    // A ray that leaves the scene sees the fog's colour.
    let up = colour_at(&exp, Vec3::Y);
    assert!(
        (up - Vec3::new(0.2, 0.4, 0.6)).abs().max_element() < 1e-6,
        "{up}"
    );
    let linear = scene("[fog]\ncolor = [0, 0, 0]\nstart = 3\nend = 7");
    let c = colour_at(&linear, -Vec3::Z);
    assert!((c - Vec3::splat(0.5)).abs().max_element() < 1e-5, "{c}");
    // A ray at 60° off the axis travels 10 to the wall: past the end.
    let c = colour_at(&linear, Vec3::new(0.0, 3f32.sqrt(), -1.0));
    assert!(c.max_element() < 1e-6, "{c}");
}

/// Every effect at once (a marble pattern and bumps among them), at scales from 10⁻³ to 10³ and far
/// from the origin: the same image, and no NaN.
#[test]
fn effects_render_the_same_at_every_scale() {
    let scene = load(
        "[camera]\neye = [0, 3, 8]\nlook_at = [0, 0.8, 0]\nfov = 40\naperture = 0.3\n\
         [render]\nambient = [0.1, 0.1, 0.1]\nbackground = [0.3, 0.4, 0.5]\n\
         [fog]\ncolor = [0.5, 0.5, 0.55]\ndensity = 0.03\n\
         [[lights]]\ntype = \"area\"\ncorner = [-1, 4, -1]\nedge_u = [2, 0, 0]\nedge_v = [0, 0, 2]\n\
         [[lights]]\ntype = \"sphere\"\nposition = [3, 3, 2]\nradius = 0.4\nfalloff = \"inverse_square\"\nintensity = 12\n\
         [[lights]]\ntype = \"spot\"\nposition = [-3, 4, 2]\ndirection = [0.5, -1, -0.3]\nangle = 25\nsoftness = 0.4\nradius = 0.3\n\
         [textures.marble]\ntype = \"marble\"\nscale = 0.4\nturbulence = 1.5\n\
         color_map = [{ at = 0, color = [0.9, 0.9, 0.9] }, { at = 1, color = [0.2, 0.1, 0.1] }]\n\
         [textures.dents]\ntype = \"noise\"\nscale = 0.2\noctaves = 3\n\
         [materials.glossy]\ntexture = \"marble\"\nreflectivity = 0.5\nroughness = 0.3\nbump = \"marble\"\nbump_depth = 0.03\n\
         [materials.gold]\ncolor = [0.2, 0.2, 0.1]\nreflectivity = 0.8\nconductor = [1, 0.78, 0.34]\nbump = \"dents\"\nbump_depth = 0.02\n\
         [materials.glass]\ntransparency = 0.9\nreflectivity = 0.1\neta = 1.5\nfresnel = true\nabsorption = [0.5, 0.1, 0.1]\n\
         [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\n\
         [[spheres]]\ncenter = [-1.5, 1, 0]\nradius = 1\nmaterial = \"glossy\"\n\
         [[spheres]]\ncenter = [1.5, 1, 0]\nradius = 1\nmaterial = \"glass\"\n\
         [[boxes]]\nmin = [-0.4, 0, 1.5]\nmax = [0.4, 0.8, 2.3]\nmaterial = \"gold\"\n",
    );
    let base = image(&scene, 16);
    assert!(
        base.pixels().any(|p| p.0 != base.get_pixel(0, 0).0),
        "an image, not one colour"
    );
    for (scale, offset) in [
        (1e-3f32, DVec3::ZERO),
        (1e3, DVec3::ZERO),
        (1.0, DVec3::new(1e4, -3e3, 2e4)),
    ] {
        let moved = scene.transformed(scale, offset);
        let d = fraction_differing(&base, &image(&moved, 16), 2);
        println!(
            "scale {scale:e}, offset {offset}: {:.3}% of pixels differ",
            d * 100.0
        );
        assert!(d < 0.01, "scale {scale}: {:.3}% differ", d * 100.0);
    }
}
