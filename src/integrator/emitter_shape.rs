//! The shapes of glowing surfaces, each sampled uniformly by area: spheres, discs, sets of
//! triangles, boxes, cylinders, cones, tori and capsules, in their own space (an instance's
//! transform places the point afterwards).

use crate::geometry::Shape;
use crate::numerics::orthonormal_basis;
use glam::{Vec3, Vec3A};
use std::f32::consts::{PI, TAU};

/// A glowing surface's shape, in the scene's space or an instance's own.
#[derive(Clone, Debug)]
pub(super) enum EmitterShape {
    Sphere {
        center: Vec3A,
        radius: f32,
    },
    Disc {
        center: Vec3A,
        normal: Vec3A,
        radius: f32,
    },
    /// Triangles, with the running sum of their areas.
    Triangles {
        corners: Vec<[Vec3A; 3]>,
        areas: Vec<f32>,
    },
    /// An axis-aligned box's six faces.
    Cuboid {
        min: Vec3A,
        max: Vec3A,
    },
    /// An upright cylinder's side, and its two caps when it has them.
    Cylinder {
        base: Vec3A,
        radius: f32,
        height: f32,
        caps: bool,
    },
    /// An upright cone or frustum's side, and its caps (a pointed top has none).
    Cone {
        base: Vec3A,
        radius: f32,
        top_radius: f32,
        height: f32,
        caps: bool,
    },
    /// A torus about the y axis.
    Torus {
        center: Vec3A,
        major_radius: f32,
        minor_radius: f32,
    },
    /// An upright capsule: an open side and two hemispheres.
    Capsule {
        base: Vec3A,
        radius: f32,
        height: f32,
    },
}

impl EmitterShape {
    /// The shape `shape` samples as.
    pub(super) fn of(shape: &Shape) -> EmitterShape {
        match shape {
            Shape::Sphere(s) => EmitterShape::Sphere {
                center: s.center,
                radius: s.radius,
            },
            Shape::Disc(d) => EmitterShape::Disc {
                center: d.center.into(),
                normal: d.normal.into(),
                radius: d.radius,
            },
            Shape::Triangle(t) => EmitterShape::triangles(vec![t.p]),
            Shape::Cuboid(b) => EmitterShape::Cuboid {
                min: b.min,
                max: b.max,
            },
            Shape::Cylinder(c) => EmitterShape::Cylinder {
                base: c.base.into(),
                radius: c.radius,
                height: c.height,
                caps: c.caps,
            },
            Shape::Cone(c) => EmitterShape::Cone {
                base: c.base.into(),
                radius: c.radius,
                top_radius: c.top_radius,
                height: c.height,
                caps: c.caps,
            },
            Shape::Torus(t) => EmitterShape::Torus {
                center: t.center.into(),
                major_radius: t.major_radius,
                minor_radius: t.minor_radius,
            },
            Shape::Capsule(c) => EmitterShape::Capsule {
                base: c.base.into(),
                radius: c.radius,
                height: c.height,
            },
        }
    }

    pub(super) fn triangles(corners: Vec<[Vec3A; 3]>) -> EmitterShape {
        let mut sum = 0.0f64;
        let areas = corners
            .iter()
            .map(|[a, b, c]| {
                sum += 0.5 * (*b - *a).cross(*c - *a).length() as f64;
                sum as f32
            })
            .collect();
        EmitterShape::Triangles { corners, areas }
    }

    pub(super) fn area(&self) -> f32 {
        match self {
            EmitterShape::Sphere { radius, .. } => 2.0 * TAU * radius * radius,
            EmitterShape::Disc { radius, .. } => PI * radius * radius,
            EmitterShape::Triangles { areas, .. } => areas.last().copied().unwrap_or(0.0),
            EmitterShape::Cuboid { min, max } => {
                let d = max - min;
                2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
            }
            EmitterShape::Cylinder {
                radius,
                height,
                caps,
                ..
            } => TAU * radius * height + if *caps { TAU * radius * radius } else { 0.0 },
            EmitterShape::Cone {
                radius,
                top_radius,
                height,
                caps,
                ..
            } => {
                let [side, bottom, top] = cone_parts(*radius, *top_radius, *height, *caps);
                side + bottom + top
            }
            EmitterShape::Torus {
                major_radius,
                minor_radius,
                ..
            } => TAU * TAU * major_radius * minor_radius,
            EmitterShape::Capsule { radius, height, .. } => TAU * radius * (height + 2.0 * radius),
        }
    }

    /// The point (uniform by area) that `u` stands for, and the unit normal there.
    pub(super) fn sample(&self, u: (f32, f32)) -> (Vec3A, Vec3A) {
        match *self {
            EmitterShape::Sphere { center, radius } => {
                let z = 1.0 - 2.0 * u.0;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (s, c) = (TAU * u.1).sin_cos();
                let n = Vec3A::new(r * c, r * s, z);
                (center + n * radius, n)
            }
            EmitterShape::Disc {
                center,
                normal,
                radius,
            } => {
                let (t, b) = orthonormal_basis(Vec3::from(normal));
                let (x, y) = crate::sampler::concentric_disc(u);
                (
                    center + (Vec3A::from(t) * x + Vec3A::from(b) * y) * radius,
                    normal,
                )
            }
            EmitterShape::Triangles {
                ref corners,
                ref areas,
            } => {
                // The first number picks the triangle by area, then is stretched back over
                // [0, 1) to place the point in it.
                let total = *areas.last().expect("a mesh has triangles");
                let target = u.0 * total;
                let i = areas.partition_point(|&a| a <= target).min(areas.len() - 1);
                let before = if i > 0 { areas[i - 1] } else { 0.0 };
                let x = ((target - before) / (areas[i] - before)).clamp(0.0, 1.0);
                let [a, b, c] = corners[i];
                let s = x.sqrt();
                let (b0, b1) = (1.0 - s, u.1 * s);
                let p = a * b0 + b * b1 + c * (1.0 - b0 - b1);
                let n = (b - a).cross(c - a).normalize_or_zero();
                (p, n)
            }
            EmitterShape::Cuboid { min, max } => {
                // The first number picks a face by area (pairs of faces along x, y, z),
                // then is stretched back over [0, 1) to place the point on it.
                let d = max - min;
                let faces = [d.y * d.z, d.z * d.x, d.x * d.y];
                let mut x = u.0 * (faces[0] + faces[1] + faces[2]);
                let mut axis = 0;
                while axis < 2 && x >= faces[axis] {
                    x -= faces[axis];
                    axis += 1;
                }
                // Within the pair, the lower face for the first half.
                let x = (x / faces[axis]).clamp(0.0, 1.0);
                let upper = x >= 0.5;
                let along = if upper { 2.0 * x - 1.0 } else { 2.0 * x };
                let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
                let mut p = min;
                p[axis] = if upper { max[axis] } else { min[axis] };
                p[a] = min[a] + d[a] * along.min(1.0);
                p[b] = min[b] + d[b] * u.1;
                let mut n = Vec3A::ZERO;
                n[axis] = if upper { 1.0 } else { -1.0 };
                (p, n)
            }
            EmitterShape::Cylinder {
                base,
                radius,
                height,
                caps,
            } => {
                let side = height;
                let cap = if caps { radius / 2.0 } else { 0.0 };
                // Areas in proportion: side 2πrh, each cap πr².
                let x = u.0 * (side + 2.0 * cap);
                if x < side {
                    let (s, c) = (TAU * u.1).sin_cos();
                    let n = Vec3A::new(c, 0.0, s);
                    (base + n * radius + Vec3A::Y * x, n)
                } else {
                    let top = x >= side + cap;
                    let along = ((x - side - if top { cap } else { 0.0 }) / cap).clamp(0.0, 1.0);
                    cap_point(base, radius, height, top, (along, u.1))
                }
            }
            EmitterShape::Cone {
                base,
                radius,
                top_radius,
                height,
                caps,
            } => {
                let [side, bottom, top] = cone_parts(radius, top_radius, height, caps);
                let x = u.0 * (side + bottom + top);
                if x < side {
                    // The side's area below height t·h grows as r(t)² − r₀², so the
                    // radius is drawn first and the height follows (in a form that
                    // stays exact when the radii are equal).
                    let s = x / side;
                    let r = (radius * radius + s * (top_radius * top_radius - radius * radius))
                        .max(0.0)
                        .sqrt();
                    let t = if r + radius > 0.0 {
                        s * (radius + top_radius) / (r + radius)
                    } else {
                        s
                    };
                    let (sin, cos) = (TAU * u.1).sin_cos();
                    let slope = (top_radius - radius) / height;
                    let n = Vec3A::new(cos, -slope, sin).normalize();
                    let p = base + Vec3A::new(cos * r, t.clamp(0.0, 1.0) * height, sin * r);
                    (p, n)
                } else {
                    let is_top = x >= side + bottom;
                    let (start, area, r) = if is_top {
                        (side + bottom, top, top_radius)
                    } else {
                        (side, bottom, radius)
                    };
                    let along = ((x - start) / area).clamp(0.0, 1.0);
                    cap_point(base, r, height, is_top, (along, u.1))
                }
            }
            EmitterShape::Torus {
                center,
                major_radius,
                minor_radius,
            } => {
                let phi = torus_tube_angle(u.0, major_radius, minor_radius);
                let (sin_t, cos_t) = (TAU * u.1).sin_cos();
                let (sin_p, cos_p) = phi.sin_cos();
                let n = Vec3A::new(cos_p * cos_t, sin_p, cos_p * sin_t);
                let ring = Vec3A::new(cos_t, 0.0, sin_t) * major_radius;
                (center + ring + n * minor_radius, n)
            }
            EmitterShape::Capsule {
                base,
                radius,
                height,
            } => {
                // Archimedes: a sphere's area is spread evenly along its axis, as a
                // cylinder's is, so the whole capsule is even in height from −r to h + r.
                let y = u.0 * (height + 2.0 * radius) - radius;
                let (sin, cos) = (TAU * u.1).sin_cos();
                let centre = if y < 0.0 {
                    base
                } else if y > height {
                    base + Vec3A::Y * height
                } else {
                    let n = Vec3A::new(cos, 0.0, sin);
                    return (base + n * radius + Vec3A::Y * y, n);
                };
                let z = ((base.y + y - centre.y) / radius).clamp(-1.0, 1.0);
                let ring = (1.0 - z * z).max(0.0).sqrt();
                let n = Vec3A::new(ring * cos, z, ring * sin);
                (centre + n * radius, n)
            }
        }
    }
}

/// The point `u` stands for on the flat cap of radius `radius` at the bottom (at `base`)
/// or the top (`height` above it) of an upright shape, and its outward normal.
fn cap_point(base: Vec3A, radius: f32, height: f32, top: bool, u: (f32, f32)) -> (Vec3A, Vec3A) {
    let (dx, dz) = crate::sampler::concentric_disc(u);
    let (y, n) = if top {
        (height, Vec3A::Y)
    } else {
        (0.0, -Vec3A::Y)
    };
    (base + Vec3A::new(dx * radius, y, dz * radius), n)
}

/// A cone's side, bottom cap and top cap areas (the caps 0 without `caps`).
fn cone_parts(radius: f32, top_radius: f32, height: f32, caps: bool) -> [f32; 3] {
    let slant = (height * height + (top_radius - radius).powi(2)).sqrt();
    let side = PI * (radius + top_radius) * slant;
    if caps {
        [side, PI * radius * radius, PI * top_radius * top_radius]
    } else {
        [side, 0.0, 0.0]
    }
}

/// The angle around a torus's tube (0 on the outer equator) below which a share `u` of its
/// area lies: the inverse of (Rφ + r·sin φ) / 2πR, by Newton's method kept within a
/// shrinking bracket (the function rises everywhere, since r < R).
fn torus_tube_angle(u: f32, major: f32, minor: f32) -> f32 {
    let target = TAU * major * u;
    let (mut low, mut high) = (0.0f32, TAU);
    let mut phi = TAU * u;
    for _ in 0..32 {
        let (sin, cos) = phi.sin_cos();
        let f = major * phi + minor * sin - target;
        if f > 0.0 {
            high = phi;
        } else {
            low = phi;
        }
        let step = f / (major + minor * cos);
        let next = phi - step;
        phi = if (low..=high).contains(&next) {
            next
        } else {
            0.5 * (low + high)
        };
        if step.abs() <= 1e-6 || high - low <= 1e-6 {
            break;
        }
    }
    phi
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points drawn on each shape lie on it, spread by area: their mean is the shape's
    /// centroid.
    #[test]
    fn samples_lie_on_the_surface_and_spread_by_area() {
        let sphere = EmitterShape::Sphere {
            center: Vec3A::new(1.0, 2.0, 3.0),
            radius: 0.5,
        };
        let disc = EmitterShape::Disc {
            center: Vec3A::ZERO,
            normal: Vec3A::Y,
            radius: 2.0,
        };
        // Two triangles, one three times the other's area.
        let pair = EmitterShape::triangles(vec![
            [Vec3A::ZERO, Vec3A::X, Vec3A::Y],
            [
                Vec3A::new(5.0, 0.0, 0.0),
                Vec3A::new(8.0, 0.0, 0.0),
                Vec3A::new(5.0, 1.0, 0.0),
            ],
        ]);
        assert!((pair.area() - 2.0).abs() < 1e-6);
        let n = 64;
        let mut means = [Vec3A::ZERO; 3];
        for i in 0..n {
            for j in 0..n {
                let u = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let (p, normal) = sphere.sample(u);
                assert!(((p - Vec3A::new(1.0, 2.0, 3.0)).length() - 0.5).abs() < 1e-5);
                assert!((normal.length() - 1.0).abs() < 1e-5);
                means[0] += p;
                let (p, _) = disc.sample(u);
                assert!(p.y.abs() < 1e-6 && p.length() <= 2.0 + 1e-5);
                means[1] += p;
                let (p, normal) = pair.sample(u);
                assert_eq!(normal, Vec3A::Z);
                means[2] += p;
            }
        }
        let count = (n * n) as f32;
        assert!((means[0] / count - Vec3A::new(1.0, 2.0, 3.0)).length() < 1e-3);
        assert!((means[1] / count).length() < 1e-3);
        // Centroids (1/3, 1/3) and (6, 1/3), weighted 1 : 3.
        let expected =
            (Vec3A::new(1.0 / 3.0, 1.0 / 3.0, 0.0) + Vec3A::new(6.0, 1.0 / 3.0, 0.0) * 3.0) / 4.0;
        assert!(
            (means[2] / count - expected).length() < 1e-2,
            "{}",
            means[2] / count
        );
    }

    /// A box's and a capped cylinder's points lie on them, spread by area: centred, and
    /// on each part in proportion to its area.
    #[test]
    fn boxes_and_cylinders_are_sampled_by_area() {
        let cuboid = EmitterShape::Cuboid {
            min: Vec3A::ZERO,
            max: Vec3A::new(1.0, 2.0, 3.0),
        };
        assert!((cuboid.area() - 22.0).abs() < 1e-5);
        let cylinder = EmitterShape::Cylinder {
            base: Vec3A::new(1.0, 0.0, 0.0),
            radius: 1.0,
            height: 2.0,
            caps: true,
        };
        assert!((cylinder.area() - 3.0 * TAU).abs() < 1e-4);
        let n = 128;
        let (mut box_mean, mut cylinder_mean) = (Vec3A::ZERO, Vec3A::ZERO);
        let (mut on_x_faces, mut on_caps) = (0, 0);
        for i in 0..n {
            for j in 0..n {
                let u = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let (p, normal) = cuboid.sample(u);
                let on = |a: usize| p[a].abs() < 1e-6 || (p[a] - [1.0, 2.0, 3.0][a]).abs() < 1e-6;
                assert!((0..3).any(on), "{p} is on no face");
                assert!(p.cmpge(Vec3A::ZERO).all() && p.cmple(Vec3A::new(1.0, 2.0, 3.0)).all());
                assert_eq!(normal.abs().max_element(), 1.0);
                on_x_faces += (normal.x != 0.0) as u32;
                box_mean += p;
                let (p, normal) = cylinder.sample(u);
                let q = p - Vec3A::new(1.0, 0.0, 0.0);
                let across = (q.x * q.x + q.z * q.z).sqrt();
                if normal.y == 0.0 {
                    assert!((across - 1.0).abs() < 1e-5 && (0.0..=2.0).contains(&q.y));
                    assert!((normal - Vec3A::new(q.x, 0.0, q.z)).length() < 1e-5);
                } else {
                    assert!(across <= 1.0 + 1e-5 && (q.y == 0.0 || q.y == 2.0));
                    assert_eq!(normal.y, if q.y == 0.0 { -1.0 } else { 1.0 });
                    on_caps += 1;
                }
                cylinder_mean += p;
            }
        }
        let count = (n * n) as f32;
        // The first number places the face and the point on it: a coarse grid each.
        assert!((box_mean / count - Vec3A::new(0.5, 1.0, 1.5)).length() < 2e-2);
        assert!((on_x_faces as f32 / count - 6.0 / 11.0).abs() < 1e-2);
        assert!((cylinder_mean / count - Vec3A::new(1.0, 1.0, 0.0)).length() < 2e-2);
        assert!((on_caps as f32 / count - 1.0 / 3.0).abs() < 1e-2);
    }

    /// Points drawn on a frustum, a torus and a capsule lie on them with the outward unit
    /// normal, spread by area: the share below a frustum's middle height, on a torus's outer
    /// half and on a capsule's ends each match their areas.
    #[test]
    fn cones_tori_and_capsules_are_sampled_by_area() {
        // A frustum of radii 1 and 0.25, 2 high, with caps.
        let cone = EmitterShape::Cone {
            base: Vec3A::new(0.0, -1.0, 0.0),
            radius: 1.0,
            top_radius: 0.25,
            height: 2.0,
            caps: true,
        };
        let slant = (4.0f32 + 0.75 * 0.75).sqrt();
        let side = PI * 1.25 * slant;
        let cone_area = side + PI * (1.0 + 0.0625);
        assert!((cone.area() - cone_area).abs() < 1e-5);
        let torus = EmitterShape::Torus {
            center: Vec3A::new(2.0, 0.0, 0.0),
            major_radius: 1.0,
            minor_radius: 0.25,
        };
        assert!((torus.area() - 4.0 * PI * PI * 0.25).abs() < 1e-5);
        let capsule = EmitterShape::Capsule {
            base: Vec3A::ZERO,
            radius: 0.5,
            height: 1.0,
        };
        assert!((capsule.area() - (TAU * 0.5 + 4.0 * PI * 0.25)).abs() < 1e-5);

        let n = 128;
        let (mut on_side, mut low_side, mut outer, mut on_ends) = (0, 0, 0, 0);
        let (mut torus_mean, mut capsule_mean) = (Vec3A::ZERO, Vec3A::ZERO);
        for i in 0..n {
            for j in 0..n {
                let u = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);

                let (p, normal) = cone.sample(u);
                assert!((normal.length() - 1.0).abs() < 1e-5);
                let y = p.y + 1.0;
                let across = (p.x * p.x + p.z * p.z).sqrt();
                if normal.y.abs() == 1.0 {
                    assert!(y == 0.0 || y == 2.0, "{p}");
                    assert!(across <= if y == 0.0 { 1.0 } else { 0.25 } + 1e-5);
                } else {
                    on_side += 1;
                    low_side += (y < 1.0) as u32;
                    assert!((across - (1.0 - 0.375 * y)).abs() < 1e-5, "{p}");
                    // At right angles to the slant line through the point, facing out.
                    let radial = Vec3A::new(p.x, 0.0, p.z) / across;
                    let slant_line = radial * -0.75 + Vec3A::Y * 2.0;
                    assert!(normal.dot(slant_line).abs() < 1e-5);
                    assert!(normal.dot(radial) > 0.0);
                }

                let (p, normal) = torus.sample(u);
                let q = p - Vec3A::new(2.0, 0.0, 0.0);
                let from_axis = (q.x * q.x + q.z * q.z).sqrt();
                let tube = Vec3A::new(q.x / from_axis, 0.0, q.z / from_axis);
                let to_tube = q - tube;
                assert!((to_tube.length() - 0.25).abs() < 1e-5, "{p}");
                assert!((normal - to_tube / 0.25).length() < 1e-4);
                outer += (from_axis > 1.0) as u32;
                torus_mean += p;

                let (p, normal) = capsule.sample(u);
                let nearest = Vec3A::new(0.0, p.y.clamp(0.0, 1.0), 0.0);
                assert!(((p - nearest).length() - 0.5).abs() < 1e-5, "{p}");
                assert!((normal - (p - nearest) / 0.5).length() < 1e-4);
                on_ends += !(0.0..=1.0).contains(&p.y) as u32;
                capsule_mean += p;
            }
        }
        let count = (n * n) as f32;
        // Side: its share of the area; below the middle, ∫₀¹ r / ∫₀² r = 0.8125 / 1.25.
        assert!((on_side as f32 / count - side / cone_area).abs() < 1e-2);
        assert!((low_side as f32 / on_side as f32 - 0.65).abs() < 1e-2);
        // The torus's outer half: (πR + 2r) / 2πR of its area.
        assert!((outer as f32 / count - (PI + 0.5) / TAU).abs() < 1e-2);
        assert!((torus_mean / count - Vec3A::new(2.0, 0.0, 0.0)).length() < 1e-2);
        // The ends: 4πr² of 2πr(h + 2r), here a half.
        assert!((on_ends as f32 / count - 0.5).abs() < 1e-2);
        assert!((capsule_mean / count - Vec3A::new(0.0, 0.5, 0.0)).length() < 1e-2);
    }

    /// The torus's tube angle inverts its area's share: (Rφ + r sin φ) / 2πR = u.
    #[test]
    fn the_tube_angle_inverts_the_share_of_area() {
        for (major, minor) in [(1.0f32, 0.25f32), (1.0, 0.99), (3.0, 0.001)] {
            for k in 0..=100 {
                let u = k as f32 / 100.0;
                let phi = torus_tube_angle(u, major, minor);
                let share = (major * phi + minor * phi.sin()) / (TAU * major);
                assert!((share - u).abs() < 1e-5, "{major} {minor} {u}: {share}");
            }
        }
    }
}
