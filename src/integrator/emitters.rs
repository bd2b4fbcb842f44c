//! Objects that glow (a material with `emission`) as lights the path tracer samples: each
//! such sphere, disc, triangle or mesh by area, one chosen per shading point in proportion to
//! its power. Shapes that cannot be sampled by area here (boxes, cylinders, cones, tori,
//! capsules, a shape under a shear or uneven scale, CSG solids, planes) are found by
//! scattered rays alone, as before.

use crate::accel::{CSG_MEMBERS_MATERIAL, Model, Surface};
use crate::geometry::Shape;
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
}

/// One glowing surface.
#[derive(Clone, Debug)]
struct Emitter {
    shape: EmitterShape,
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
            let Some(shape) = emitter_shape(&primitive.surface) else {
                continue;
            };
            let area = shape.area();
            if !(area.is_finite() && area > 0.0) {
                continue;
            }
            emitters.by_primitive[index] = emitters.emitters.len() as u32;
            let power = (radiance.x + radiance.y + radiance.z) / 3.0 * area;
            let before = emitters.powers.last().copied().unwrap_or(0.0);
            emitters.powers.push(before + power);
            emitters.emitters.push(Emitter {
                shape,
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
        let (point, normal) = e.shape.sample(v);
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

/// The shape of a glowing surface that can be sampled by area, in the scene's space.
fn emitter_shape(surface: &Surface) -> Option<EmitterShape> {
    match surface {
        Surface::Shape(shape) => shape_emitter(shape),
        Surface::Instance(instance) => match &**instance.model() {
            Model::Mesh { mesh, .. } => {
                let t = instance.transform();
                let positions = mesh.positions();
                let corners: Vec<[Vec3A; 3]> = mesh
                    .triangles()
                    .iter()
                    .map(|tri| tri.map(|i| t.point_to_scene(positions[i as usize], Vec3A::ZERO).0))
                    .collect();
                Some(EmitterShape::triangles(corners))
            }
            // A shape under a shear or an uneven scale: its area is not simply sampled.
            Model::Shape(_) => None,
        },
        Surface::Csg(_) => None,
    }
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
        _ => None,
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
}
