//! Objects that glow (a material with `emission`) as lights the path tracer samples: each
//! such shape or mesh by area (emitter_shape.rs), turned, moved and evenly scaled as the
//! scene places it, one chosen per shading point in proportion to its power. A shape under
//! a shear or an uneven scale, a CSG solid's trimmed surface and a plane cannot be sampled
//! by area and are found by scattered rays alone.

use super::emitter_shape::EmitterShape;
use crate::accel::{CSG_MEMBERS_MATERIAL, Model, Surface};
use crate::geometry::Transform;
use crate::scene::PreparedScene;
use glam::Vec3A;

/// No emitter: the primitive does not glow, or cannot be sampled.
const NONE: u32 = u32::MAX;

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
        Surface::Shape(shape) => Some((EmitterShape::of(shape), None)),
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
                Some((EmitterShape::of(shape), Some(*t)))
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

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
