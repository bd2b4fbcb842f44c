//! Triangle meshes from OBJ files, transforms on objects, and instancing: what is drawn
//! against what is known (the same solid as polygons, an analytic ellipsoid, POV-Ray's
//! rotation convention), shared models, and every bad mesh or placement refused with its
//! file and line.

mod common;

use glam::Vec3;
use prism::accel::{Reach, Surface};
use prism::geometry::{Ray, RayQuery};
use prism::render::RenderSettings;
use prism::scene::{PreparedScene, Scene, ShapeDesc};
use prism::scene_file::{SceneError, load_scene, parse_scene};
use std::path::Path;
use std::sync::Arc;

const CAMERA: &str = "[camera]\neye = [0, 3, 8]\nlook_at = [0, 0, 0]\nfov = 40\n\n\
                      [render]\nambient = [0.1, 0.1, 0.1]\n\n\
                      [[lights]]\nposition = [4, 8, 6]\n\n\
                      [materials.red]\ncolor = [0.9, 0.2, 0.1]\n\n";

/// A unit cube from −1 to 1, each face two outward-wound triangles, written as OBJ.
const CUBE_OBJ: &str = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n\
                        v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
                        f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

/// The same cube as six polygons (corners as in CUBE_OBJ's faces).
fn cube_polygons() -> String {
    let v = [
        [-1, -1, -1],
        [1, -1, -1],
        [1, 1, -1],
        [-1, 1, -1],
        [-1, -1, 1],
        [1, -1, 1],
        [1, 1, 1],
        [-1, 1, 1],
    ];
    let faces = [
        [1, 4, 3, 2],
        [5, 6, 7, 8],
        [1, 2, 6, 5],
        [4, 8, 7, 3],
        [1, 5, 8, 4],
        [2, 3, 7, 6],
    ];
    faces
        .iter()
        .map(|f| {
            let corners: Vec<String> = f.iter().map(|&i| format!("{:?}", v[i - 1])).collect();
            format!(
                "[[polygons]]\nmaterial = \"red\"\nvertices = [{}]\n",
                corners.join(", ")
            )
        })
        .collect()
}

/// A folder with `files` in it and `scene.toml` holding `scene`; the scene loaded.
fn load_with(
    files: &[(&str, &str)],
    scene: &str,
) -> (tempfile::TempDir, Result<Scene, SceneError>) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        let path = dir.path().join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, scene).unwrap();
    let loaded = load_scene(&path);
    (dir, loaded)
}

fn image(scene: &Scene, w: u32, h: u32) -> Vec<u8> {
    common::render_scene(scene, RenderSettings::new(w, h, 2)).into_raw()
}

fn bunny_path() -> String {
    format!("{}/assets/meshes/bunny.obj", env!("CARGO_MANIFEST_DIR"))
}

/// A faceted OBJ cube draws what the same cube as polygons draws, rotated or not.
#[test]
fn an_obj_cube_draws_as_the_same_polygons() {
    for placement in ["", "rotate = [20, 35, 0]\ntranslate = [0.5, 0, 0]\n"] {
        let mesh_scene = format!(
            "{CAMERA}[[meshes]]\npath = \"cube.obj\"\nmaterial = \"red\"\nsmooth = false\n{placement}"
        );
        let (_dir, mesh) = load_with(&[("cube.obj", CUBE_OBJ)], &mesh_scene);
        let polygons: String = cube_polygons()
            .split("[[polygons]]\n")
            .filter(|s| !s.is_empty())
            .map(|p| format!("[[polygons]]\n{placement}{p}"))
            .collect();
        let (_dir2, poly) = load_with(&[], &format!("{CAMERA}{polygons}"));
        let (a, b) = (
            image(&mesh.unwrap(), 160, 120),
            image(&poly.unwrap(), 160, 120),
        );
        let differing = a
            .iter()
            .zip(&b)
            .filter(|(x, y)| x.abs_diff(**y) > 1)
            .count();
        // Only pixels on the silhouette, where the two triangulations' edges cross one
        // pixel's subsamples differently, may differ, and by little.
        assert!(
            differing <= a.len() / 500,
            "{differing} channels differ ({placement:?})"
        );
        assert!(a.iter().any(|&c| c > 100), "the cube is drawn");
    }
}

/// The bunny loads with its 3,674 triangles, smooth unless asked not to be; the same file
/// placed twice is built once (one model shared by both instances).
#[test]
fn the_bunny_loads_once_for_many_instances() {
    let scene = format!(
        "{CAMERA}[[meshes]]\nname = \"a\"\npath = \"{0}\"\nscale = 0.2\n\n\
         [[meshes]]\nname = \"b\"\npath = \"{0}\"\nscale = 0.2\ntranslate = [2, 0, 0]\nrotate = [0, 90, 0]\n\n\
         [[meshes]]\nname = \"c\"\npath = \"{0}\"\nscale = 0.2\nsmooth = false\ntranslate = [-2, 0, 0]\n",
        bunny_path()
    );
    let scene = parse_scene(&scene, Path::new("s.toml"), Path::new(".")).unwrap();
    let meshes: Vec<_> = scene
        .objects
        .iter()
        .map(|o| match &o.shape {
            ShapeDesc::Mesh { mesh, .. } => mesh.clone(),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(meshes.len(), 3);
    assert_eq!(meshes[0].triangle_count(), 3674);
    assert!(meshes[0].is_smooth() && !meshes[2].is_smooth());
    assert!(Arc::ptr_eq(&meshes[0], &meshes[1]));
    assert!(!Arc::ptr_eq(&meshes[0], &meshes[2]));
    let prepared = PreparedScene::new(&scene);
    let models: Vec<_> = prepared
        .geometry
        .accel()
        .primitives()
        .iter()
        .map(|p| match &p.surface {
            Surface::Instance(i) => i.model().clone(),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(models.len(), 3);
    let shared = models.iter().filter(|m| Arc::ptr_eq(m, &models[0])).count();
    assert_eq!(shared, 2, "a and b share one model");
}

/// The nearest hit along a ray from `origin` towards `dir` (scene coordinates are relative
/// to the camera's eye).
fn first_hit(scene: &Scene, origin: Vec3, dir: Vec3) -> Option<Vec3> {
    let prepared = PreparedScene::new(scene);
    let o = origin - scene.origin.as_vec3();
    let q = RayQuery::new(Ray::new(o, dir));
    let accel = prepared.geometry.accel();
    let hit = accel.nearest_hit(&q, Reach::After(0.0))?;
    Some(Vec3::from(accel.surface(&q, &hit).point) + scene.origin.as_vec3())
}

/// Transforms follow POV-Ray: scale, then rotate about x, y, z (right-handed: +90 about y
/// turns +x into −z), then translate; a sphere scaled unevenly is an ellipsoid, a cylinder
/// turned about z lies along x.
#[test]
fn transforms_put_shapes_where_povray_would() {
    let scene = format!(
        "{CAMERA}[[spheres]]\ncenter = [1, 0, 0]\nradius = 0.25\nrotate = [0, 90, 0]\ntranslate = [0, 0, -3]\n\n\
         [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nscale = [2, 1, 1]\ntranslate = [0, 5, 0]\n\n\
         [[cylinders]]\nbase = [0, 0, 0]\nradius = 0.5\nheight = 4\nrotate = [0, 0, -90]\ntranslate = [0, -5, 0]\n"
    );
    let scene = parse_scene(&scene, Path::new("s.toml"), Path::new(".")).unwrap();
    // The small sphere: (1, 0, 0) turned to (0, 0, −1), moved to (0, 0, −4); turned, it
    // is traced through its transform, so a texture on it turns with it.
    assert!(matches!(
        scene.objects[0].shape,
        ShapeDesc::Transformed { .. }
    ));
    let small = first_hit(&scene, Vec3::new(0.0, 3.0, -4.0), Vec3::NEG_Y).unwrap();
    assert!(
        (small - Vec3::new(0.0, 0.25, -4.0)).length() < 1e-5,
        "{small}"
    );
    // The ellipsoid reaches x = ±2 at y = 5 and y = 5 ± 1 at x = 0.
    let side = first_hit(&scene, Vec3::new(-10.0, 5.0, 0.0), Vec3::X).unwrap();
    assert!((side - Vec3::new(-2.0, 5.0, 0.0)).length() < 1e-5, "{side}");
    let top = first_hit(&scene, Vec3::new(0.0, 9.0, 0.0), Vec3::NEG_Y).unwrap();
    assert!((top - Vec3::new(0.0, 6.0, 0.0)).length() < 1e-5, "{top}");
    // The cylinder, turned −90 about z, runs from x = 0 to x = 4 at y = −5.
    let end = first_hit(&scene, Vec3::new(10.0, -5.0, 0.0), Vec3::NEG_X).unwrap();
    assert!((end - Vec3::new(4.0, -5.0, 0.0)).length() < 1e-5, "{end}");
    let round = first_hit(&scene, Vec3::new(2.0, -5.0, 10.0), Vec3::NEG_Z).unwrap();
    assert!(
        (round - Vec3::new(2.0, -5.0, 0.5)).length() < 1e-5,
        "{round}"
    );
    assert!(first_hit(&scene, Vec3::new(-0.5, -5.0, 10.0), Vec3::NEG_Z).is_none());
}

/// A smooth mesh shades like the surface it approximates, and its shading normals let no
/// light through to the side facing away: the bunny lit from straight above is black
/// underneath wherever the true surface faces down, and nowhere is NaN.
#[test]
fn smooth_shading_does_not_leak_light() {
    let scene = format!(
        "[camera]\neye = [0, -20, 0]\nlook_at = [0, 5, 0]\nup = [0, 0, -1]\nfov = 50\n\n\
         [render]\nambient = [0, 0, 0]\nbackground = [0, 0, 0]\n\n\
         [[lights]]\nposition = [0, 100, 0]\n\n\
         [materials.white]\ncolor = [1, 1, 1]\nspecular = 0\n\n\
         [[meshes]]\npath = \"{}\"\nmaterial = \"white\"\n",
        bunny_path()
    );
    let scene = parse_scene(&scene, Path::new("s.toml"), Path::new(".")).unwrap();
    let prepared = PreparedScene::new(&scene);
    let mut integrator = prism::integrator::Integrator::new(&prepared, 0.0);
    let accel = prepared.geometry.accel();
    let mut seen = 0;
    for i in 0..40 {
        for j in 0..40 {
            let target = Vec3::new(-5.0 + i as f32 * 0.25, 0.0, -4.0 + j as f32 * 0.2);
            let eye = Vec3::new(target.x, -20.0, target.z) - scene.origin.as_vec3();
            let q = RayQuery::new(Ray::new(eye, Vec3::Y));
            let Some(hit) = accel.nearest_hit(&q, Reach::After(0.0)) else {
                continue;
            };
            let surface = accel.surface(&q, &hit);
            let color = integrator
                .trace_primary(
                    Reach::After(0.0),
                    || Ray::new(eye, Vec3::Y),
                    prism::sampler::SampleStream::new(0, 0, 0),
                )
                .color;
            assert!(color.is_finite());
            // Where the shading normal faces down, no light; where only the facet does,
            // the curved surface it stands for may still face the light (the terminator),
            // and the shadow ray from the lifted point decides.
            if surface.normal.y < 0.0 && surface.shading.y <= 0.0 {
                assert_eq!(color, Vec3::ZERO, "light leaked at {target}");
                seen += 1;
            }
        }
    }
    assert!(seen > 100, "{seen} points seen");
}

/// A smooth mesh of a subdivided octahedron pushed onto the unit sphere shades within a
/// few per cent of the sphere itself.
#[test]
fn a_smooth_mesh_sphere_shades_like_the_sphere() {
    // An octahedron subdivided three times, its vertices on the unit sphere.
    let corners = [
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
    ];
    let faces = [
        [0, 2, 4],
        [4, 2, 1],
        [1, 2, 5],
        [5, 2, 0],
        [4, 3, 0],
        [1, 3, 4],
        [5, 3, 1],
        [0, 3, 5],
    ];
    let obj = sphere_obj(&corners, &faces, 3);
    let body = "[materials.white]\ncolor = [1, 1, 1]\nspecular = 0\n";
    let camera = "[camera]\neye = [0, 0, 6]\nlook_at = [0, 0, 0]\nfov = 30\n\n\
                  [render]\nambient = [0, 0, 0]\n\n[[lights]]\nposition = [5, 5, 5]\n\n";
    let (_d, mesh) = load_with(
        &[("ball.obj", &obj)],
        &format!("{camera}{body}[[meshes]]\npath = \"ball.obj\"\nmaterial = \"white\"\n"),
    );
    let (_d2, sphere) = load_with(
        &[],
        &format!(
            "{camera}{body}[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"white\"\n"
        ),
    );
    let (a, b) = (
        image(&mesh.unwrap(), 120, 120),
        image(&sphere.unwrap(), 120, 120),
    );
    let inside: Vec<usize> = (0..a.len()).filter(|&i| a[i] > 20 && b[i] > 20).collect();
    assert!(inside.len() > 3000);
    let mean_difference: f64 = inside
        .iter()
        .map(|&i| (a[i] as f64 - b[i] as f64).abs())
        .sum::<f64>()
        / inside.len() as f64;
    assert!(mean_difference < 3.0, "mean difference {mean_difference}");
}

/// An icosahedron subdivided once (80 faces) on the unit sphere, with the sphere's normals,
/// as OBJ text.
fn icosphere_obj() -> String {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let corners: Vec<Vec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|p| Vec3::from_array(*p).normalize())
    .collect();
    let faces: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let obj = sphere_obj(&corners, &faces, 1);
    assert_eq!(obj.matches("\nf ").count(), 80);
    obj
}

/// The polyhedron of unit-length `corners` and `faces` with each face split in four
/// `levels` times, the new corners pushed onto the unit sphere, with the sphere's normals,
/// as OBJ text.
fn sphere_obj(corners: &[Vec3], faces: &[[usize; 3]], levels: usize) -> String {
    let mut v = corners.to_vec();
    let mut f = faces.to_vec();
    for _ in 0..levels {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::new();
        for [a, b, c] in f {
            let mut m = |x: usize, y: usize| {
                *mid.entry((x.min(y), x.max(y))).or_insert_with(|| {
                    v.push(((v[x] + v[y]) / 2.0).normalize());
                    v.len() - 1
                })
            };
            let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
            next.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        f = next;
    }
    let mut obj = String::new();
    for p in &v {
        obj += &format!("v {} {} {}\nvn {} {} {}\n", p.x, p.y, p.z, p.x, p.y, p.z);
    }
    for [a, b, c] in &f {
        obj += &format!("f {0}//{0} {1}//{1} {2}//{2}\n", a + 1, b + 1, c + 1);
    }
    obj
}

/// The shadow terminator: a smooth low-poly sphere (80 faces) lit from the side shades as
/// the true sphere does up to the terminator, instead of going black a facet early and in
/// jagged patches where a facet turns from the light while its shading normal does not.
#[test]
fn a_low_poly_smooth_sphere_keeps_its_light_to_the_terminator() {
    let camera = "[camera]\neye = [0, 0, 6]\nlook_at = [0, 0, 0]\nfov = 25\n\n\
                  [render]\nambient = [0, 0, 0]\n\n[[lights]]\ntype = \"directional\"\n\
                  direction = [-1, -0.2, 0.15]\n\n\
                  [materials.white]\ncolor = [1, 1, 1]\nspecular = 0\n";
    let (_d, mesh) = load_with(
        &[("ball.obj", &icosphere_obj())],
        &format!("{camera}[[meshes]]\npath = \"ball.obj\"\nmaterial = \"white\"\n"),
    );
    let (_d2, sphere) = load_with(
        &[],
        &format!("{camera}[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"white\"\n"),
    );
    let (w, h) = (160, 160);
    let (a, b) = (image(&mesh.unwrap(), w, h), image(&sphere.unwrap(), w, h));
    // Pixels where the true sphere is clearly lit (a cosine above 0.15) and the mesh is
    // there: the mesh must be lit there too, and about as bright.
    let mut lit = 0;
    let mut dark = 0;
    let mut difference = 0.0;
    for i in (0..a.len()).step_by(3) {
        let covered = (0..3).any(|c| a[i + c] > 0) || {
            // A mesh pixel may be black: count it when the sphere's is well inside.
            let (x, y) = ((i / 3) as u32 % w, (i / 3) as u32 / w);
            let (dx, dy) = (x as f32 - 79.5, y as f32 - 79.5);
            (dx * dx + dy * dy).sqrt() < 50.0
        };
        if b[i] as f32 > 0.15 * 255.0 && covered {
            lit += 1;
            if a[i] < 8 {
                dark += 1;
            }
            difference += (a[i] as f64 - b[i] as f64).abs();
        }
    }
    let mean = difference / lit as f64;
    println!("{lit} lit pixels, {dark} dark on the mesh, mean difference {mean:.2}");
    assert!(lit > 2500, "{lit}");
    // Shadow rays from the facet itself leave a band a facet wide black at the terminator.
    assert!(dark * 200 < lit, "{dark} of {lit} pixels black on the mesh");
    // The facets' own shape (hits deeper than the sphere's) keeps the rest a few per cent off.
    assert!(mean < 14.0, "mean difference {mean}");
}

/// MTL materials: the diffuse colour, a highlight, transparency and, for `illum 7`, the
/// index of refraction; the entry's own `material` wins over the file's.
#[test]
fn mtl_materials_map_onto_prisms() {
    let obj = format!("mtllib m.mtl\nusemtl glass\n{CUBE_OBJ}usemtl\n");
    let obj = obj.replace("usemtl\n", "");
    let mtl = "newmtl glass\nKd 0.2 0.4 0.6\nKa 0.5 0.5 0.5\nKs 0.3 0.3 0.3\nNs 80\nd 0.25\nNi 1.5\nillum 7\n";
    let scene = format!("{CAMERA}[[meshes]]\npath = \"m/cube.obj\"\n");
    let (_dir, loaded) = load_with(&[("m/cube.obj", &obj), ("m/m.mtl", mtl)], &scene);
    let scene = loaded.unwrap();
    let m = &scene.objects[0].material;
    assert_eq!(m.texture.mean(), Vec3::new(0.2, 0.4, 0.6));
    assert!((m.ambient - 0.5).abs() < 1e-6 && (m.specular - 0.3).abs() < 1e-6);
    assert_eq!(m.shininess, 80.0);
    assert!((m.transparency - 0.75).abs() < 1e-6);
    assert_eq!(m.eta, Some(1.5));
    assert!((m.reflectivity - 0.3).abs() < 1e-6);
    assert_eq!(scene.objects[0].name, "meshes 0");
    // With a material of its own, the library is not even read.
    let own = format!("{CAMERA}[[meshes]]\npath = \"cube.obj\"\nmaterial = \"red\"\n");
    let (_dir, loaded) = load_with(&[("cube.obj", &obj)], &own);
    assert_eq!(
        loaded.unwrap().objects[0].material.texture.mean(),
        Vec3::new(0.9, 0.2, 0.1)
    );
}

/// MTL relief: `norm` is a normal map of strength `-bm`; `map_Bump` is a normal map too
/// when its picture is bluish (as Blender writes one there), and otherwise a height map
/// raising white `-bm` × 0.5% of the file's size (the cube's diagonal, 2√3).
#[test]
fn mtl_bump_and_normal_maps_become_relief() {
    use prism::appearance::{Relief, Texture};
    let dir = tempfile::tempdir().unwrap();
    let save = |name: &str, rgb: [u8; 3]| {
        image::RgbImage::from_pixel(4, 4, image::Rgb(rgb))
            .save(dir.path().join(name))
            .unwrap();
    };
    save("grey.png", [120, 120, 120]);
    save("blue.png", [128, 128, 255]);
    let obj = format!(
        "mtllib m.mtl\nusemtl height\n{}usemtl normal\n{}usemtl blender\n{}",
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nf 1 4 3 2\nf 5 6 7 8\n",
        "f 1 2 6 5\nf 4 8 7 3\n",
        "f 1 5 8 4\nf 2 3 7 6\n"
    );
    let mtl = "newmtl height\nmap_Bump -bm 2 grey.png\n\
               newmtl normal\nnorm -bm 0.5 blue.png\n\
               newmtl blender\nmap_Bump -bm 1.0 blue.png\n";
    std::fs::write(dir.path().join("cube.obj"), obj).unwrap();
    std::fs::write(dir.path().join("m.mtl"), mtl).unwrap();
    let scene_path = dir.path().join("scene.toml");
    std::fs::write(
        &scene_path,
        format!("{CAMERA}[[meshes]]\npath = \"cube.obj\"\n"),
    )
    .unwrap();
    let scene = load_scene(&scene_path).unwrap();
    let relief = |part: &str| {
        let object = scene
            .objects
            .iter()
            .find(|o| o.name.ends_with(part))
            .unwrap();
        object.material.relief.clone().unwrap()
    };
    match relief("height") {
        Relief::Bump {
            height: Texture::Image { .. },
            depth,
        } => {
            let want = 2.0 * 0.005 * 2.0 * 3f32.sqrt();
            assert!((depth - want).abs() < 1e-6, "{depth} against {want}");
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        relief("normal"),
        Relief::NormalMap { strength: 0.5, .. }
    ));
    assert!(matches!(
        relief("blender"),
        Relief::NormalMap { strength: 1.0, .. }
    ));
    // A strength beyond the limit is refused at its line.
    std::fs::write(
        dir.path().join("m.mtl"),
        "newmtl height\n\nnorm -bm 40 blue.png\n",
    )
    .unwrap();
    let shown = load_scene(&scene_path).unwrap_err().to_string();
    assert!(
        shown.contains("m.mtl:3:") && shown.contains("strength of 40"),
        "{shown}"
    );
}

/// Every bad mesh, library and placement is refused with the file and line to fix.
#[test]
fn bad_meshes_and_placements_name_file_and_line() {
    // (files beside the scene, the scene's entry, where the message points, what it says)
    type Case = (
        Vec<(&'static str, String)>,
        String,
        &'static str,
        &'static str,
    );
    let cases: Vec<Case> = vec![
        (
            vec![],
            "[[meshes]]\npath = \"none.obj\"\n".into(),
            "scene.toml:",
            "cannot read mesh",
        ),
        (
            vec![("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n".into())],
            "[[meshes]]\npath = \"a.obj\"\n".into(),
            "a.obj:4:",
            "vertex index 7 is out of range",
        ),
        (
            vec![("a.obj", "v 0 0 0\nv 1 0 x\n".into())],
            "[[meshes]]\npath = \"a.obj\"\n".into(),
            "a.obj:2:",
            "not a number",
        ),
        (
            vec![("a.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n".into())],
            "[[meshes]]\npath = \"a.obj\"\n".into(),
            "a.obj:2:",
            "not a finite number",
        ),
        (
            vec![("a.obj", "# nothing\nv 0 0 0\n".into())],
            "[[meshes]]\npath = \"a.obj\"\n".into(),
            "a.obj:2:",
            "no faces",
        ),
        (
            vec![("a.obj", format!("mtllib gone.mtl\nusemtl x\n{CUBE_OBJ}"))],
            "[[meshes]]\npath = \"a.obj\"\n".into(),
            "a.obj:1:",
            "cannot read material library",
        ),
        (
            vec![
                ("a.obj", format!("mtllib a.mtl\nusemtl y\n{CUBE_OBJ}")),
                ("a.mtl", "newmtl x\nKd 1 1 1\n".into()),
            ],
            "[[meshes]]\npath = \"a.obj\"\n".into(),
            "a.obj:2:",
            "defines \"y\"",
        ),
        (
            vec![
                ("a.obj", format!("mtllib a.mtl\nusemtl x\n{CUBE_OBJ}")),
                ("a.mtl", "newmtl x\nKd 1 1 1\nNi 0\nillum 7\n".into()),
            ],
            "[[meshes]]\npath = \"a.obj\"\n".into(),
            "a.mtl:3:",
            "`Ni` must lie in",
        ),
        (
            vec![
                ("a.obj", format!("mtllib a.mtl\nusemtl x\n{CUBE_OBJ}")),
                ("a.mtl", "newmtl x\nKd 2 1 1\n".into()),
            ],
            "[[meshes]]\npath = \"a.obj\"\n".into(),
            "a.mtl:2:",
            "`Kd` must lie in",
        ),
        (
            vec![("a.obj", CUBE_OBJ.into())],
            "[[meshes]]\npath = \"a.obj\"\nscale = 0\n".into(),
            "scene.toml:",
            "`scale` must be greater than zero",
        ),
        (
            vec![],
            "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nscale = [1, -2, 1]\n".into(),
            "scene.toml:",
            "`scale` must be greater than zero",
        ),
        (
            vec![],
            "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nscale = \"big\"\n".into(),
            "scene.toml:",
            "`scale` must be a number",
        ),
        (
            vec![],
            "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nrotate = [0, nan, 0]\n".into(),
            "scene.toml:",
            "`rotate` must hold finite numbers",
        ),
        (
            vec![("a.obj", CUBE_OBJ.into())],
            "[[meshes]]\npath = \"a.obj\"\ntranslate = [1e13, 0, 0]\n".into(),
            "scene.toml:",
            "`translate` must hold finite numbers",
        ),
    ];
    for (files, entry, place, words) in cases {
        let files: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
        let (_dir, loaded) = load_with(&files, &format!("{CAMERA}{entry}"));
        let message = loaded.unwrap_err().to_string();
        assert!(message.contains(place), "{entry:?}: {message}");
        assert!(message.contains(words), "{entry:?}: {message}");
        if place == "scene.toml:" {
            // The line of the entry's field, past the shared preamble.
            let line: usize = message.split(':').nth(1).unwrap().trim().parse().unwrap();
            assert!(line > CAMERA.lines().count(), "{message}");
        } else {
            assert!(message.contains("read by meshes[0]"), "{message}");
        }
    }
}
