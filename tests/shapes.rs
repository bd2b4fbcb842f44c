//! Boxes, discs, planes, cones and frustums, open cylinders and tori: each hit where its
//! equation says, with the normal its gradient gives, placed directly and under transforms
//! alike; and every degenerate or malformed entry refused with its line and field.

mod common;

use glam::{DVec3, Vec3};
use prism::accel::Reach;
use prism::geometry::{Ray, RayQuery};
use prism::render::RenderSettings;
use prism::scene::{PreparedScene, Scene, ShapeDesc};
use prism::scene_file::parse_scene;
use std::path::Path;

const CAMERA: &str = "[camera]\neye = [0, 3, 8]\nlook_at = [0, 0, 0]\nfov = 40\n\n\
                      [render]\nambient = [0.1, 0.1, 0.1]\n\n\
                      [[lights]]\nposition = [4, 8, 6]\n\n\
                      [materials.red]\ncolor = [0.9, 0.2, 0.1]\n\n";

fn scene(objects: &str) -> Scene {
    parse_scene(
        &format!("{CAMERA}{objects}"),
        Path::new("s.toml"),
        Path::new("."),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// The nearest hit from `origin` along `dir` (world coordinates): its point and normal.
fn hit(prepared: &PreparedScene, scene: &Scene, origin: Vec3, dir: Vec3) -> Option<(Vec3, Vec3)> {
    let o = origin - scene.origin.as_vec3();
    let q = RayQuery::new(Ray::new(o, dir));
    let accel = prepared.geometry.accel();
    let h = accel.nearest_hit(&q, Reach::After(0.0))?;
    let s = accel.surface(&q, &h);
    Some((
        Vec3::from(s.point) + scene.origin.as_vec3(),
        Vec3::from(s.normal),
    ))
}

/// A ray's origin and direction, and the point and outward normal it must hit (None: miss).
type Case = (Vec3, Vec3, Option<(Vec3, Vec3)>);

/// Asserts every case's ray hits where, and with the normal, it says.
fn check(s: &Scene, cases: &[Case]) {
    let prepared = PreparedScene::new(s);
    for &(origin, dir, want) in cases {
        let got = hit(&prepared, s, origin, dir);
        match (got, want) {
            (Some((p, n)), Some((wp, wn))) => {
                assert!((p - wp).length() < 2e-5, "{origin} {dir}: at {p}, not {wp}");
                assert!(
                    (n - wn.normalize()).length() < 2e-5,
                    "{origin} {dir}: normal {n}, not {wn}"
                );
            }
            (None, None) => {}
            (got, want) => panic!("{origin} {dir}: {got:?}, not {want:?}"),
        }
    }
}

#[test]
fn boxes_are_hit_on_their_faces_axis_aligned_and_turned() {
    let s = scene(
        "[[boxes]]\nmin = [-1, 0, -1]\nmax = [1, 2, 1]\n\n\
         [[boxes]]\nmin = [-1, 0, -1]\nmax = [1, 2, 1]\nrotate = [0, 45, 0]\ntranslate = [10, 0, 0]\n",
    );
    assert!(matches!(s.objects[0].shape, ShapeDesc::Cuboid { .. }));
    assert!(matches!(s.objects[1].shape, ShapeDesc::Transformed { .. }));
    let r2 = 2f32.sqrt();
    check(
        &s,
        &[
            (
                Vec3::new(0.25, 1.0, 9.0),
                -Vec3::Z,
                Some((Vec3::new(0.25, 1.0, 1.0), Vec3::Z)),
            ),
            (
                Vec3::new(0.5, 9.0, 0.5),
                -Vec3::Y,
                Some((Vec3::new(0.5, 2.0, 0.5), Vec3::Y)),
            ),
            (
                Vec3::new(-9.0, 0.5, 0.0),
                Vec3::X,
                Some((Vec3::new(-1.0, 0.5, 0.0), -Vec3::X)),
            ),
            (Vec3::new(1.5, 1.0, 9.0), -Vec3::Z, None),
            // Turned 45° about y: its faces are |x − 10| + |z| = √2 there.
            (
                Vec3::new(10.3, 1.0, 9.0),
                -Vec3::Z,
                Some((Vec3::new(10.3, 1.0, r2 - 0.3), Vec3::new(1.0, 0.0, 1.0))),
            ),
            (
                Vec3::new(9.5, 1.0, 9.0),
                -Vec3::Z,
                Some((Vec3::new(9.5, 1.0, r2 - 0.5), Vec3::new(-1.0, 0.0, 1.0))),
            ),
            (Vec3::new(10.0 + r2 + 0.01, 1.0, 9.0), -Vec3::Z, None),
        ],
    );
}

#[test]
fn discs_and_planes_are_hit_where_their_planes_are() {
    let s = scene(
        "[[discs]]\ncenter = [0, 1, -2]\nnormal = [0, 0, 2]\nradius = 1\n\n\
         [[discs]]\ncenter = [0, 0, 0]\nnormal = [0, 0, 1]\nradius = 1\nscale = [2, 1, 1]\ntranslate = [0, 5, 0]\n\n\
         [[planes]]\npoint = [0, -3, 0]\nnormal = [0, 1, 0]\n\n\
         [[planes]]\npoint = [0, 0, -50]\nnormal = [1, 0, 1]\nrotate = [0, 45, 0]\n",
    );
    check(
        &s,
        &[
            (
                Vec3::new(0.5, 1.5, 9.0),
                -Vec3::Z,
                Some((Vec3::new(0.5, 1.5, -2.0), Vec3::Z)),
            ),
            (Vec3::new(0.8, 1.8, 9.0), -Vec3::Z, None),
            // Scaled unevenly, an ellipse with semi-axes 2 and 1.
            (
                Vec3::new(1.9, 5.0, 9.0),
                -Vec3::Z,
                Some((Vec3::new(1.9, 5.0, 0.0), Vec3::Z)),
            ),
            (Vec3::new(2.1, 5.0, 9.0), -Vec3::Z, None),
            // The floor plane, far out towards the horizon too.
            (
                Vec3::new(3.0, 9.0, 3.0),
                -Vec3::Y,
                Some((Vec3::new(3.0, -3.0, 3.0), Vec3::Y)),
            ),
            (
                Vec3::new(0.0, 1.0, 0.0),
                Vec3::new(1000.0, -4.0, 0.0),
                Some((Vec3::new(1000.0, -3.0, 0.0), Vec3::Y)),
            ),
            // (1, 0, 1) turned +45° about y is (√2, 0, 0): the plane x = −50/√2·… through
            // (0, 0, −50) turned to (−50/√2, 0, −50/√2), facing +x.
            (
                Vec3::new(0.0, 20.0, 0.0),
                -Vec3::X,
                Some((Vec3::new(-50.0 / 2f32.sqrt(), 20.0, 0.0), Vec3::X)),
            ),
        ],
    );
    // Away from a plane there is nothing to hit.
    let prepared = PreparedScene::new(&s);
    assert!(hit(&prepared, &s, Vec3::new(0.0, 9.0, 0.0), Vec3::Y).is_none());
}

#[test]
fn cones_and_frustums_are_hit_at_the_radius_of_their_height() {
    let s = scene(
        "[[cones]]\nbase = [0, 0, 0]\nradius = 2\nheight = 4\n\n\
         [[cones]]\nbase = [10, 0, 0]\nradius = 2\ntop_radius = 1\nheight = 2\ncaps = false\n\n\
         [[cones]]\nbase = [0, 0, 0]\nradius = 1\nheight = 2\nrotate = [0, 0, -90]\ntranslate = [0, 10, 0]\n",
    );
    check(
        &s,
        &[
            // r(y) = 2 − y/2: 1 at y = 2; the slope leans the normal up by atan(1/2).
            (
                Vec3::new(0.0, 2.0, 9.0),
                -Vec3::Z,
                Some((Vec3::new(0.0, 2.0, 1.0), Vec3::new(0.0, 0.5, 1.0))),
            ),
            (
                Vec3::new(0.5, -9.0, 0.0),
                Vec3::Y,
                Some((Vec3::new(0.5, 0.0, 0.0), -Vec3::Y)),
            ),
            (Vec3::new(0.0, 4.5, 9.0), -Vec3::Z, None),
            // The open frustum: r(y) = 2 − y/2, no caps: straight down through both ends…
            (Vec3::new(10.5, 9.0, 0.0), -Vec3::Y, None),
            // …but slanting in at the top, the inside of the far wall (normal facing away).
            (
                Vec3::new(10.0, 2.0, 0.0),
                Vec3::new(1.0, -0.5, 0.0),
                Some((
                    Vec3::new(10.0 + 4.0 / 3.0, 2.0 - 2.0 / 3.0, 0.0),
                    Vec3::new(1.0, 0.5, 0.0),
                )),
            ),
            // Turned −90° about z, the cone points along +x from x = 0.
            (
                Vec3::new(1.0, 19.0, 0.0),
                -Vec3::Y,
                Some((Vec3::new(1.0, 10.5, 0.0), Vec3::new(0.5, 1.0, 0.0))),
            ),
            (
                Vec3::new(-9.0, 10.0, 0.0),
                Vec3::X,
                Some((Vec3::new(0.0, 10.0, 0.0), -Vec3::X)),
            ),
        ],
    );
}

#[test]
fn open_cylinders_show_their_inside() {
    let s = scene(
        "[[cylinders]]\nbase = [0, 0, 0]\nradius = 1\nheight = 2\ncaps = false\n\n\
         [[cylinders]]\nbase = [5, 0, 0]\nradius = 1\nheight = 2\n",
    );
    check(
        &s,
        &[
            (Vec3::new(0.5, 9.0, 0.0), -Vec3::Y, None),
            (
                Vec3::new(5.5, 9.0, 0.0),
                -Vec3::Y,
                Some((Vec3::new(5.5, 2.0, 0.0), Vec3::Y)),
            ),
            (
                Vec3::new(0.0, 3.0, 0.0),
                Vec3::new(1.0, -2.0, 0.0),
                Some((Vec3::new(1.0, 1.0, 0.0), Vec3::X)),
            ),
        ],
    );
    let closed = PreparedScene::new(&s);
    let geometry = &closed.geometry;
    assert!(!geometry.object(0).convex && geometry.object(1).convex);
}

#[test]
fn tori_are_hit_on_their_tube_upright_tilted_and_squashed() {
    let s = scene(
        "[[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 2\nminor_radius = 0.5\n\n\
         [[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 2\nminor_radius = 0.5\nrotate = [90, 0, 0]\ntranslate = [10, 0, 0]\n\n\
         [[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 2\nminor_radius = 0.5\nscale = [1, 2, 1]\ntranslate = [20, 0, 0]\n",
    );
    assert!(matches!(s.objects[0].shape, ShapeDesc::Torus { .. }));
    assert!(matches!(s.objects[1].shape, ShapeDesc::Transformed { .. }));
    check(
        &s,
        &[
            (
                Vec3::new(2.0, 9.0, 0.0),
                -Vec3::Y,
                Some((Vec3::new(2.0, 0.5, 0.0), Vec3::Y)),
            ),
            (Vec3::new(0.0, 9.0, 0.0), -Vec3::Y, None),
            // Along the equator: the outer rim, then (from inside the hole) the inner rim.
            (
                Vec3::new(-9.0, 0.0, 0.0),
                Vec3::X,
                Some((Vec3::new(-2.5, 0.0, 0.0), -Vec3::X)),
            ),
            (
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::X,
                Some((Vec3::new(1.5, 0.0, 0.0), -Vec3::X)),
            ),
            // At 45° round the axis: the tube's top at (√2, 0.5, √2).
            (
                Vec3::new(2f32.sqrt(), 9.0, 2f32.sqrt()),
                -Vec3::Y,
                Some((Vec3::new(2f32.sqrt(), 0.5, 2f32.sqrt()), Vec3::Y)),
            ),
            // Turned +90° about x: y goes to z, so the torus stands in the xy plane.
            (
                Vec3::new(12.0, 0.0, 9.0),
                -Vec3::Z,
                Some((Vec3::new(12.0, 0.0, 0.5), Vec3::Z)),
            ),
            (
                Vec3::new(10.0, 2.0, 9.0),
                -Vec3::Z,
                Some((Vec3::new(10.0, 2.0, 0.5), Vec3::Z)),
            ),
            (Vec3::new(10.0, 0.0, 9.0), -Vec3::Z, None),
            // Squashed to twice its height: the tube's top at y = 1.
            (
                Vec3::new(22.0, 9.0, 0.0),
                -Vec3::Y,
                Some((Vec3::new(22.0, 1.0, 0.0), Vec3::Y)),
            ),
        ],
    );
}

/// Two tori (one tilted, so traced through its transform, and one thin) draw the same
/// image from 10⁻³ to 10⁵ times their size, far from the origin: the quartic, formed about
/// the ray's closest approach and scaled to the bounding sphere, leaves no speckles on the
/// silhouette or the inner rim at any scale.
#[test]
fn a_tori_scene_renders_the_same_at_every_scale() {
    let s = scene(
        "[[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 2\nminor_radius = 0.6\nrotate = [35, 0, 10]\nmaterial = \"red\"\n\n\
         [[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 0.8\nminor_radius = 0.1\ntranslate = [2.2, -1.4, 2.5]\nmaterial = \"red\"\n",
    );
    let image = |scene: &Scene| common::render_scene(scene, RenderSettings::new(200, 150, 2));
    let reference = image(&s);
    let lit = reference.pixels().filter(|p| p[0] > 60).count();
    assert!(lit > 2000, "the tori are drawn ({lit} lit pixels)");
    for k in [-3, 3, 5] {
        let scaled = s.transformed(10f32.powi(k), DVec3::new(1e5, -2e5, 3e5));
        let differ = prism::render::fraction_differing(&image(&scaled), &reference, 2);
        assert!(differ <= 0.001, "scale 1e{k}: {:.3}%", differ * 100.0);
    }
}

#[test]
fn bad_shapes_are_refused_with_their_line_and_field() {
    let cases: [(&str, &str); 16] = [
        (
            "[[boxes]]\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n",
            "`min` below `max` on every axis",
        ),
        (
            "[[boxes]]\nmin = [0, 0, 0]\nmax = [1, 1]\n",
            "this array has 2 values; it must have exactly 3",
        ),
        (
            "[[discs]]\ncenter = [0, 0, 0]\nnormal = [0, 0, 0]\nradius = 1\n",
            "`normal` must not be zero",
        ),
        (
            "[[discs]]\ncenter = [0, 0, 0]\nnormal = [0, 1, 0]\nradius = -1\n",
            "`radius` must be greater than zero",
        ),
        (
            "[[planes]]\npoint = [0, 0, 0]\nnormal = [0, nan, 0]\n",
            "`normal` must hold finite numbers",
        ),
        ("[[planes]]\npoint = [0, 0, 0]\n", "missing field `normal`"),
        (
            "[[cones]]\nbase = [0, 0, 0]\nradius = 0\nheight = 1\n",
            "a `radius` or a `top_radius` greater than zero",
        ),
        (
            "[[cones]]\nbase = [0, 0, 0]\nradius = 1\ntop_radius = -1\nheight = 1\n",
            "`top_radius` must be greater than zero",
        ),
        (
            "[[cones]]\nbase = [0, 0, 0]\nradius = 1\nheight = 0\n",
            "`height` must be greater than zero",
        ),
        (
            "[[cylinders]]\nbase = [0, 0, 0]\nradius = 1\nheight = 1\ncaps = \"no\"\n",
            "expected a boolean",
        ),
        (
            "[[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 1\nminor_radius = 1\n",
            "`minor_radius` below `major_radius`",
        ),
        (
            "[[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 1\nminor_radius = 0\n",
            "`minor_radius` must be greater than zero",
        ),
        (
            "[[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 2\nminor_radius = 1\nscale = [1, 0, 1]\n",
            "`scale` must be greater than zero",
        ),
        (
            "[[capsules]]\nbase = [0, 0, 0]\nradius = 0\nheight = 1\n",
            "`radius` must be greater than zero",
        ),
        (
            "[[capsules]]\nbase = [0, 0, 0]\nradius = 1\nheight = -2\n",
            "`height` must be greater than zero",
        ),
        (
            "[[capsules]]\nbase = [0, 0, 0]\nradius = 1\nheight = 1\ncaps = false\n",
            "unknown field `caps`",
        ),
    ];
    for (entry, words) in cases {
        let message = parse_scene(
            &format!("{CAMERA}{entry}"),
            Path::new("s.toml"),
            Path::new("."),
        )
        .unwrap_err()
        .to_string();
        assert!(message.contains(words), "{entry:?}: {message}");
        let line: usize = message.split(':').nth(1).unwrap().trim().parse().unwrap();
        assert!(line > CAMERA.lines().count(), "{entry:?}: {message}");
    }
}

/// A turned shape's picture turns with it (the Earth can be turned): a sphere turned +90°
/// about y shows at its +z point what the unturned one shows at its −x point.
#[test]
fn turned_shapes_turn_their_textures() {
    let s = scene(
        "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n\n\
         [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nrotate = [0, 90, 0]\ntranslate = [10, 0, 0]\n\n\
         [[cylinders]]\nbase = [0, 0, 0]\nradius = 1\nheight = 1\nrotate = [0, 90, 0]\ntranslate = [20, 0, 0]\n",
    );
    let prepared = PreparedScene::new(&s);
    let accel = prepared.geometry.accel();
    let uv_at = |origin: Vec3, dir: Vec3| {
        let q = RayQuery::new(Ray::new(origin - s.origin.as_vec3(), dir));
        let h = accel.nearest_hit(&q, Reach::After(0.0)).unwrap();
        accel.uv(&q, &accel.surface(&q, &h), &h)
    };
    let close = |a: (f32, f32), b: (f32, f32)| (a.0 - b.0).abs() < 1e-5 && (a.1 - b.1).abs() < 1e-5;
    let plain_front = uv_at(Vec3::new(0.0, 0.0, 9.0), -Vec3::Z);
    let plain_left = uv_at(Vec3::new(-9.0, 0.0, 0.0), Vec3::X);
    let turned_front = uv_at(Vec3::new(10.0, 0.0, 9.0), -Vec3::Z);
    assert!(close(plain_front, (0.5, 0.5)), "{plain_front:?}");
    assert!(
        close(turned_front, plain_left),
        "{turned_front:?} vs {plain_left:?}"
    );
    // The cylinder's seam turns too: u at its front is what the unturned one has at −x.
    let cylinder_front = uv_at(Vec3::new(20.0, 0.5, 9.0), -Vec3::Z);
    assert!((cylinder_front.0 - 0.25).abs() < 1e-5, "{cylinder_front:?}");
}
