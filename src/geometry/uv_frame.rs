//! How a surface's texture coordinates sit on it: at a point, (u, v) and the directions in
//! which the point moves as u and as v grow (∂p/∂u, ∂p/∂v). Relief (bump and normal maps)
//! needs them to turn a picture's slopes and directions into the surface's.

use glam::Vec3A;
use std::f32::consts::TAU;

/// The texture coordinates at a surface point and their tangents there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvFrame {
    /// The texture coordinates.
    pub uv: (f32, f32),
    /// How far the point moves per unit of u (scene units, tangent to the surface); zero
    /// where u does not change along the surface (a pole).
    pub dpdu: Vec3A,
    /// How far the point moves per unit of v.
    pub dpdv: Vec3A,
}

impl UvFrame {
    /// The frame of a linear map: (u, v) = ((p − origin)·u_axis, offset − (p − origin)·v_axis),
    /// as discs and planar polygons lay a picture (v runs down it).
    #[inline]
    pub fn planar(uv: (f32, f32), u_axis: Vec3A, v_axis: Vec3A) -> UvFrame {
        UvFrame {
            uv,
            dpdu: u_axis / u_axis.length_squared(),
            dpdv: -v_axis / v_axis.length_squared(),
        }
    }

    /// The frame carried into another space by the linear map `to`.
    #[inline]
    pub fn mapped(&self, to: impl Fn(Vec3A) -> Vec3A) -> UvFrame {
        UvFrame {
            uv: self.uv,
            dpdu: to(self.dpdu),
            dpdv: to(self.dpdv),
        }
    }
}

/// ∂p/∂u for the u that shapes about the y axis share, u = ½ + atan2(x, z)/2π, at `rel`
/// (the point relative to a point of the axis): a full turn per unit of u.
#[inline]
pub(super) fn around_y_axis(rel: Vec3A) -> Vec3A {
    Vec3A::new(rel.z, 0.0, -rel.x) * TAU
}

/// ∂p/∂λ, the move along a meridian per radian of latitude, of `rel` on a sphere about the
/// origin (north is +y); zero at a pole, where every direction is south.
#[inline]
pub(super) fn along_meridian(rel: Vec3A) -> Vec3A {
    let rho = (rel.x * rel.x + rel.z * rel.z).sqrt();
    if rho > 0.0 {
        Vec3A::new(-rel.y * rel.x / rho, rho, -rel.y * rel.z / rho)
    } else {
        Vec3A::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Capsule, Cone, Cuboid, Cylinder, Disc, Ray, RayQuery, Shape, Sphere};
    use super::super::{Torus, Triangle};
    use super::*;
    use glam::Vec3;

    /// Every kind of shape, away from the origin and not square to the axes where it can
    /// be turned.
    fn shapes() -> Vec<(&'static str, Shape)> {
        let c = Vec3::new(0.3, -0.2, -6.0);
        vec![
            ("sphere", Shape::Sphere(Sphere::new(c, 1.3))),
            (
                "cylinder",
                Shape::Cylinder(Cylinder::new(c - Vec3::Y, 0.9, 2.1)),
            ),
            (
                "cone",
                Shape::Cone(Cone {
                    base: c - Vec3::Y,
                    radius: 1.2,
                    top_radius: 0.4,
                    height: 2.0,
                    caps: true,
                }),
            ),
            (
                "box",
                Shape::Cuboid(Cuboid::new(
                    c - Vec3::new(1.0, 0.8, 0.6),
                    c + Vec3::new(0.7, 0.9, 1.1),
                )),
            ),
            (
                "disc",
                Shape::Disc(Disc::new(c, Vec3::new(0.3, 0.5, 0.8).normalize(), 1.4)),
            ),
            (
                "torus",
                Shape::Torus(Torus {
                    center: c,
                    major_radius: 1.2,
                    minor_radius: 0.45,
                }),
            ),
            (
                "capsule",
                Shape::Capsule(Capsule::new(c - 0.6 * Vec3::Y, 0.7, 1.2)),
            ),
            (
                "triangle",
                Shape::Triangle(
                    Triangle::new(
                        c + Vec3::new(-1.5, -1.0, 0.2),
                        c + Vec3::new(1.4, -0.8, -0.3),
                        c + Vec3::new(0.1, 1.6, 0.4),
                    )
                    .unwrap(),
                ),
            ),
        ]
    }

    /// A frame's tangents are the derivatives of the shape's own (u, v): a small step
    /// across the surface, written in the tangents (least squares in their plane), changes
    /// (u, v) by its coefficients. Checked from eyes on several sides, over a grid of
    /// points, for every shape.
    #[test]
    fn tangents_are_the_derivatives_of_the_texture_coordinates() {
        let eyes = [
            Vec3A::new(0.5, 0.4, 0.0),
            Vec3A::new(4.0, 3.0, -6.0),
            Vec3A::new(-3.0, -4.0, -9.0),
        ];
        for (name, shape) in shapes() {
            let center = Vec3A::from((shape.bounds().min + shape.bounds().max) * 0.5);
            let mut checked = 0;
            for eye in eyes {
                for i in 0..15 {
                    for j in 0..15 {
                        let aim = center
                            + Vec3A::new(i as f32 - 7.0, j as f32 - 7.0, (i + j) as f32 - 14.0)
                                * 0.11;
                        let hit_at = |target: Vec3A| {
                            let q = RayQuery::new(Ray::new(eye, target - eye));
                            let hit = shape.intersect(&q, f32::INFINITY)?;
                            Some((shape.surface(&q, &hit), hit))
                        };
                        let Some((surface, hit)) = hit_at(aim) else {
                            continue;
                        };
                        let frame = shape.uv_frame(&surface, &hit);
                        assert_eq!(frame.uv, shape.uv(&surface, &hit), "{name}");
                        let (a, b) = (frame.dpdu, frame.dpdv);
                        let det = a.length_squared() * b.length_squared() - a.dot(b).powi(2);
                        if det <= 1e-6 * a.length_squared() * b.length_squared() {
                            continue;
                        }
                        for dir in [a, b, a - b] {
                            let step = dir.normalize() * 3e-4;
                            let Some((moved, moved_hit)) = hit_at(surface.point + step) else {
                                continue;
                            };
                            // Across a seam, an edge or onto another part: not one chart.
                            if moved_hit.detail != hit.detail
                                && !matches!(
                                    moved_hit.detail,
                                    super::super::HitDetail::Triangle { .. }
                                )
                            {
                                continue;
                            }
                            let (u0, v0) = frame.uv;
                            let (u1, v1) = shape.uv(&moved, &moved_hit);
                            let du = u1 - u0 - (u1 - u0).round();
                            let dv = v1 - v0;
                            let d = moved.point - surface.point;
                            let (ra, rb) = (d.dot(a), d.dot(b));
                            let ea = (ra * b.length_squared() - rb * a.dot(b)) / det;
                            let eb = (rb * a.length_squared() - ra * a.dot(b)) / det;
                            let scale = ea.abs().max(eb.abs()).max(1e-4);
                            // Clamped v at a rim: not a derivative.
                            if v1 <= 0.0 || v1 >= 1.0 || v0 <= 0.0 || v0 >= 1.0 {
                                continue;
                            }
                            assert!(
                                (du - ea).abs() <= 0.03 * scale && (dv - eb).abs() <= 0.03 * scale,
                                "{name} at {:?}: moved ({du}, {dv}), tangents say ({ea}, {eb})",
                                surface.point
                            );
                            checked += 1;
                        }
                    }
                }
            }
            assert!(checked > 100, "{name}: only {checked} points checked");
        }
    }

    #[test]
    fn a_planar_frame_inverts_its_axes() {
        let f = UvFrame::planar(
            (0.0, 0.0),
            Vec3A::new(0.5, 0.0, 0.0),
            Vec3A::new(0.0, 0.25, 0.0),
        );
        assert_eq!(f.dpdu, Vec3A::new(2.0, 0.0, 0.0));
        assert_eq!(f.dpdv, Vec3A::new(0.0, -4.0, 0.0));
    }
}
