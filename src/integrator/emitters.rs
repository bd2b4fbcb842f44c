//! Objects that glow (a material with `emission`) as lights the path tracer samples: each
//! such sphere, disc, triangle, box, cylinder or mesh by area, turned, moved and evenly
//! scaled as the scene places it, one chosen per shading point in proportion to its power.
//! Shapes that cannot be sampled by area here (cones, tori, capsules, a shape under a shear
//! or uneven scale, CSG solids, planes) are found by scattered rays alone.

use crate::accel::{CSG_MEMBERS_MATERIAL, Model, Surface};
use crate::geometry::{Shape, Transform};
use crate::numerics::orthonormal_basis;
use crate::scene::PreparedScene;
use glam::{Vec3, Vec3A};
use std::f32::consts::{PI, TAU};

/// No emitter: the primitive does not glow, or cannot be sampled.
const NONE: u32 = u32::MAX;

/// A glowing surface's shape in the scene's space.
#[derive(Clone, Debug)]
enum EmitterShape {
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
}

/// One glowing surface.
#[derive(Clone, Debug)]
struct Emitter {
    shape: EmitterShape,
    /// Where an instance places its shape (turned, moved and evenly scaled); None for a
    /// shape already in the scene's space.
    placed: Option<Transform>,
    /// The area in the scene's space.
    area: f32,
    radiance: Vec3A,
}

/// A point drawn on an emitter.
pub(super) struct EmitterSample {
    /// The point and the unit normal of its surface there.
    pub point: Vec3A,
    pub normal: Vec3A,
    /// Its radiance (the same on both sides).
    pub radiance: Vec3A,
    /// The density per unit area of drawing it, its emitter's choice included.
    pub pdf_area: f32,
}

/// Every glowing surface that can be sampled by area.
#[derive(Clone, Debug, Default)]
pub struct Emitters {
    emitters: Vec<Emitter>,
    /// The running sum of the emitters' powers.
    powers: Vec<f32>,
    /// Each primitive's emitter (or NONE), by the acceleration layer's numbering.
    by_primitive: Vec<u32>,
}

impl Emitters {
    /// The glowing surfaces of `scene`.
    pub fn new(scene: &PreparedScene) -> Emitters {
        let accel = scene.geometry.accel();
        let mut emitters = Emitters {
            by_primitive: vec![NONE; accel.primitives().len()],
            ..Emitters::default()
        };
        for (index, primitive) in accel.primitives().iter().enumerate() {
            if primitive.material == CSG_MEMBERS_MATERIAL
                || scene.geometry.object(primitive.object).unbounded
            {
                continue;
            }
            let radiance = Vec3A::from(scene.appearance.material(primitive.material).emission);
            if radiance == Vec3A::ZERO {
                continue;
            }
            let Some((shape, placed)) = emitter_shape(&primitive.surface) else {
                continue;
            };
            let area = shape.area() * placed.as_ref().map_or(1.0, |t| even_scale(t).powi(2));
            if !(area.is_finite() && area > 0.0) {
                continue;
            }
            emitters.by_primitive[index] = emitters.emitters.len() as u32;
            let power = (radiance.x + radiance.y + radiance.z) / 3.0 * area;
            let before = emitters.powers.last().copied().unwrap_or(0.0);
            emitters.powers.push(before + power);
            emitters.emitters.push(Emitter {
                shape,
                placed,
                area,
                radiance,
            });
        }
        emitters
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.emitters.is_empty()
    }

    /// A point drawn on one of the emitters with `u` (choosing) and `v` (where on it).
    pub(super) fn sample(&self, u: f32, v: (f32, f32)) -> Option<EmitterSample> {
        let total = *self.powers.last()?;
        let target = u * total;
        let i = self
            .powers
            .partition_point(|&p| p <= target)
            .min(self.powers.len() - 1);
        let before = if i > 0 { self.powers[i - 1] } else { 0.0 };
        let chosen = (self.powers[i] - before) / total;
        let e = &self.emitters[i];
        let (point, normal) = match &e.placed {
            None => e.shape.sample(v),
            Some(t) => {
                let (p, n) = e.shape.sample(v);
                (t.point_to_scene(p, Vec3A::ZERO).0, t.normal_to_scene(n))
            }
        };
        Some(EmitterSample {
            point,
            normal,
            radiance: e.radiance,
            pdf_area: chosen / e.area,
        })
    }

    /// The density per unit area with which `sample` draws a point of primitive
    /// `primitive`; 0 when it is not an emitter drawn from.
    pub(super) fn pdf_area(&self, primitive: u32) -> f32 {
        match self.by_primitive.get(primitive as usize) {
            Some(&i) if i != NONE => {
                let total = *self.powers.last().expect("an emitter exists");
                let before = if i > 0 {
                    self.powers[i as usize - 1]
                } else {
                    0.0
                };
                (self.powers[i as usize] - before) / total / self.emitters[i as usize].area
            }
            _ => 0.0,
        }
    }
}

/// The shape of a glowing surface that can be sampled by area, and where an instance places
/// it.
fn emitter_shape(surface: &Surface) -> Option<(EmitterShape, Option<Transform>)> {
    match surface {
        Surface::Shape(shape) => Some((shape_emitter(shape)?, None)),
        Surface::Instance(instance) => match &**instance.model() {
            Model::Mesh { mesh, .. } => {
                let t = instance.transform();
                let positions = mesh.positions();
                let corners: Vec<[Vec3A; 3]> = mesh
                    .triangles()
                    .iter()
                    .map(|tri| tri.map(|i| t.point_to_scene(positions[i as usize], Vec3A::ZERO).0))
                    .collect();
                Some((EmitterShape::triangles(corners), None))
            }
            // Under a shear or an uneven scale a shape's area is not simply sampled.
            Model::Shape(shape) => {
                let t = instance.transform();
                (even_scale(t) > 0.0).then_some(())?;
                Some((shape_emitter(shape)?, Some(*t)))
            }
        },
        Surface::Csg(_) => None,
    }
}

/// The factor by which `t` scales every length, when it turns, moves and scales evenly
/// (its linear part's columns at right angles and of one length); 0 otherwise.
fn even_scale(t: &Transform) -> f32 {
    let m = t.to_scene().matrix3;
    let (x, y, z) = (m.x_axis, m.y_axis, m.z_axis);
    let length = x.length();
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * length * length;
    let even = close(x.dot(y), 0.0)
        && close(y.dot(z), 0.0)
        && close(z.dot(x), 0.0)
        && close(y.length_squared(), length * length)
        && close(z.length_squared(), length * length);
    if even { length } else { 0.0 }
}

fn shape_emitter(shape: &Shape) -> Option<EmitterShape> {
    match shape {
        Shape::Sphere(s) => Some(EmitterShape::Sphere {
            center: s.center,
            radius: s.radius,
        }),
        Shape::Disc(d) => Some(EmitterShape::Disc {
            center: d.center.into(),
            normal: d.normal.into(),
            radius: d.radius,
        }),
        Shape::Triangle(t) => Some(EmitterShape::triangles(vec![t.p])),
        Shape::Cuboid(b) => Some(EmitterShape::Cuboid {
            min: b.min,
            max: b.max,
        }),
        Shape::Cylinder(c) => Some(EmitterShape::Cylinder {
            base: c.base.into(),
            radius: c.radius,
            height: c.height,
            caps: c.caps,
        }),
        Shape::Cone(_) | Shape::Torus(_) | Shape::Capsule(_) => None,
    }
}

impl EmitterShape {
    fn triangles(corners: Vec<[Vec3A; 3]>) -> EmitterShape {
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

    fn area(&self) -> f32 {
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
        }
    }

    /// The point (uniform by area) that `u` stands for, and the unit normal there.
    fn sample(&self, u: (f32, f32)) -> (Vec3A, Vec3A) {
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
                    let (dx, dz) = crate::sampler::concentric_disc((along, u.1));
                    let y = if top { height } else { 0.0 };
                    let n = if top { Vec3A::Y } else { -Vec3A::Y };
                    (base + Vec3A::new(dx * radius, y, dz * radius), n)
                }
            }
        }
    }
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

    /// A turn, a move and an even scale are sampled through; a shear or an uneven scale
    /// is not.
    #[test]
    fn only_even_scales_are_sampled_through() {
        let turned = Transform::from_scale_rotation_translation(
            Vec3::splat(2.0),
            Vec3::new(10.0, 30.0, -20.0),
            Vec3::new(1.0, 2.0, 3.0),
        )
        .unwrap();
        assert!((even_scale(&turned) - 2.0).abs() < 1e-5);
        let stretched = Transform::from_scale_rotation_translation(
            Vec3::new(1.0, 2.0, 1.0),
            Vec3::ZERO,
            Vec3::ZERO,
        )
        .unwrap();
        assert_eq!(even_scale(&stretched), 0.0);
    }
}
