//! Cones and frustums along +y, with or without caps. The side is the quadratic
//! x² + z² = r(y)², r(y) = r₀ + k·y: solved from an origin moved to the ray's closest
//! approach to the axis's middle (so the coefficients are small wherever the ray starts),
//! with the discriminant formed in f64, where its products are exact.

use super::aabb::Aabb;
use super::cylinder::{CylinderPart, crossing_count, nearest_candidate, outward_from_y_axis};
use super::ray::Ray;
use super::uv_frame::{UvFrame, around_y_axis};
use crate::numerics::gamma;
use glam::{Vec2, Vec3, Vec3A};
use std::f32::consts::PI;

/// A cone (top radius 0) or frustum standing on the centre of its base.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// Centre of the base.
    pub base: Vec3,
    /// Radius at the base.
    pub radius: f32,
    /// Radius at the top (0 for a pointed cone).
    pub top_radius: f32,
    /// Height from the base to the top.
    pub height: f32,
    /// Whether the base and the top (if it has a radius) are closed by flat caps.
    pub caps: bool,
}

impl Cone {
    /// The radius's change per unit of height.
    #[inline]
    fn slope(&self) -> f32 {
        (self.top_radius - self.radius) / self.height
    }

    /// Every place the ray's line meets the cone's surface, as (t, part); NaN for none.
    #[inline]
    fn candidates(&self, ray: &Ray) -> [(f32, CylinderPart); 4] {
        let none = (f32::NAN, CylinderPart::Side);
        let mut out = [none; 4];
        let k = self.slope();
        let d = ray.dir;
        let a = d.x * d.x + d.z * d.z - k * k * d.y * d.y;
        let middle = Vec3A::from(self.base) + Vec3A::new(0.0, 0.5 * self.height, 0.0);
        let shift = (middle - ray.origin).dot(d) / d.length_squared();
        let f = ray.origin + d * shift - Vec3A::from(self.base);
        let r_f = self.radius + k * f.y;
        let beta = -(f.x * d.x + f.z * d.z - k * d.y * r_f);
        let c = f.x * f.x + f.z * f.z - r_f * r_f;
        let disc = (beta as f64) * (beta as f64) - (a as f64) * (c as f64);
        if disc >= 0.0 {
            let root = disc.sqrt() as f32;
            let roots = if a != 0.0 {
                // The root that does not cancel, and the other from the product of the two.
                let q = beta + root.copysign(beta);
                [q / a, c / q]
            } else if beta != 0.0 {
                // Parallel to the slant: one crossing, of 2β·t = c.
                [c / (2.0 * beta), f32::NAN]
            } else {
                [f32::NAN; 2]
            };
            for (slot, s) in roots.into_iter().enumerate() {
                let y = f.y + s * d.y;
                if y >= 0.0 && y <= self.height {
                    out[slot] = (s + shift, CylinderPart::Side);
                }
            }
        }
        if self.caps && d.y != 0.0 {
            let caps = [
                (0.0, self.radius, CylinderPart::Bottom),
                (self.height, self.top_radius, CylinderPart::Top),
            ];
            for (slot, (y, r, part)) in caps.into_iter().enumerate() {
                let t = (self.base.y + y - ray.origin.y) / d.y;
                let x = ray.origin.x + t * d.x - self.base.x;
                let z = ray.origin.z + t * d.z - self.base.z;
                if r > 0.0 && x * x + z * z <= r * r {
                    out[2 + slot] = (t, part);
                }
            }
        }
        out
    }

    /// The nearest t in (t_min, t_max) and the part that was hit.
    #[inline]
    pub fn intersect_after(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
    ) -> Option<(f32, CylinderPart)> {
        nearest_candidate(&self.candidates(ray), t_min, t_max)
    }

    /// How many times the segment (0, t_max) crosses the surface.
    #[inline]
    pub fn crossings(&self, ray: &Ray, t_max: f32) -> u32 {
        crossing_count(&self.candidates(ray), t_max)
    }

    /// Hit point (the side's moved onto the surface at its height), outward unit normal and
    /// error bound.
    #[inline]
    pub fn surface(&self, ray: &Ray, t: f32, part: CylinderPart) -> (Vec3A, Vec3A, Vec3A) {
        let mut p = ray.at(t);
        let base = Vec3A::from(self.base);
        let size = self.radius.max(self.top_radius);
        let scale = base.abs() + Vec3A::new(size, self.height, size);
        match part {
            CylinderPart::Side => {
                let k = self.slope();
                let y = (p.y - base.y).clamp(0.0, self.height);
                let r = self.radius + k * y;
                let radial = Vec2::new(p.x - base.x, p.z - base.z);
                let len = radial.length();
                let dir = if len > 0.0 { radial / len } else { Vec2::X };
                p.x = base.x + dir.x * r;
                p.z = base.z + dir.y * r;
                // y comes from o + t·d; x and z follow it through the slope.
                let y_error =
                    gamma(7) * (ray.origin.y.abs() + (t * ray.dir.y).abs()) + gamma(3) * scale.y;
                let error = Vec3A::new(
                    gamma(6) * scale.x + k.abs() * y_error,
                    y_error,
                    gamma(6) * scale.z + k.abs() * y_error,
                );
                let n = Vec3A::new(dir.x, -k, dir.y).normalize();
                (p, n, error)
            }
            CylinderPart::Bottom | CylinderPart::Top => {
                let top = part == CylinderPart::Top;
                p.y = if top { base.y + self.height } else { base.y };
                let error = Vec3A::new(
                    gamma(7) * (ray.origin.x.abs() + (t * ray.dir.x).abs()),
                    gamma(2) * scale.y,
                    gamma(7) * (ray.origin.z.abs() + (t * ray.dir.z).abs()),
                );
                (p, if top { Vec3A::Y } else { -Vec3A::Y }, error)
            }
        }
    }

    /// As a cylinder's: u around the axis from +z towards +x, v the height's fraction on
    /// the side and the distance's from the axis on a cap.
    pub fn uv(&self, p: Vec3A, part: CylinderPart) -> (f32, f32) {
        let rel = Vec3::from(p) - self.base;
        let u = 0.5 + rel.x.atan2(rel.z) / (2.0 * PI);
        let v = match part {
            CylinderPart::Side => rel.y / self.height,
            CylinderPart::Bottom => Vec2::new(rel.x, rel.z).length() / self.radius,
            CylinderPart::Top => Vec2::new(rel.x, rel.z).length() / self.top_radius,
        };
        (u, v.clamp(0.0, 1.0))
    }

    /// The texture coordinates at `p` on `part` and their tangents: up the side, the
    /// point also moves out as the radius changes.
    pub fn uv_frame(&self, p: Vec3A, part: CylinderPart) -> UvFrame {
        let rel = p - Vec3A::from(self.base);
        let out = outward_from_y_axis(rel);
        let dpdv = match part {
            CylinderPart::Side => {
                out * (self.top_radius - self.radius) + Vec3A::new(0.0, self.height, 0.0)
            }
            CylinderPart::Bottom => out * self.radius,
            CylinderPart::Top => out * self.top_radius,
        };
        UvFrame {
            uv: self.uv(p, part),
            dpdu: around_y_axis(rel),
            dpdv,
        }
    }

    /// The box around the cone.
    pub fn bounds(&self) -> Aabb {
        let r = self.radius.max(self.top_radius);
        Aabb {
            min: self.base - Vec3::new(r, 0.0, r),
            max: self.base + Vec3::new(r, self.height, r),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cone(caps: bool) -> Cone {
        // Radius 2 at y = −1 narrowing to a point at y = 3.
        Cone {
            base: Vec3::new(0.0, -1.0, -10.0),
            radius: 2.0,
            top_radius: 0.0,
            height: 4.0,
            caps,
        }
    }

    #[test]
    fn side_hit_at_the_radius_of_its_height() {
        // At y = 1 the radius is 1: a ray along −z at height 1 meets z = −9.
        let c = cone(true);
        let ray = Ray::new(Vec3::new(0.0, 1.0, 0.0), -Vec3::Z);
        let (t, part) = c.intersect_after(&ray, 0.0, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Side);
        assert!((t - 9.0).abs() < 1e-5, "{t}");
        let (p, n, _) = c.surface(&ray, t, part);
        assert!((p - Vec3A::new(0.0, 1.0, -9.0)).length() < 1e-5);
        // The slope is −1/2: the normal leans up by atan(1/2).
        let expected = Vec3A::new(0.0, 0.5, 1.0).normalize();
        assert!((n - expected).length() < 1e-6, "{n}");
        assert_eq!(c.crossings(&ray, f32::INFINITY), 2);
    }

    #[test]
    fn a_frustum_and_its_caps() {
        let f = Cone {
            top_radius: 1.0,
            ..cone(true)
        };
        let down = Ray::new(Vec3::new(0.5, 10.0, -10.0), -Vec3::Y);
        let (t, part) = f.intersect_after(&down, 0.0, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Top);
        assert!((t - 7.0).abs() < 1e-6);
        // Through the top ring (radius 1) but inside the base's (radius 2): side, then base.
        let slant = Ray::new(Vec3::new(1.5, 10.0, -10.0), -Vec3::Y);
        let (t, part) = f.intersect_after(&slant, 0.0, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Side);
        // r(y) = 2 − (y + 1)/4 = 1.5 at y = 1.
        assert!((t - 9.0).abs() < 1e-5, "{t}");
        assert_eq!(f.crossings(&slant, f32::INFINITY), 2);
    }

    #[test]
    fn open_cone_shows_its_inside() {
        let c = Cone {
            top_radius: 1.0,
            ..cone(false)
        };
        let down = Ray::new(Vec3::new(0.5, 10.0, -10.0), -Vec3::Y);
        // Straight through both open ends: no hit.
        assert!(c.intersect_after(&down, 0.0, f32::INFINITY).is_none());
        // Across the inside: the far wall's inside, whose outward normal faces away.
        let across = Ray::new(Vec3::new(0.0, 1.0, -10.0), Vec3::X);
        let (t, part) = c.intersect_after(&across, 0.0, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Side);
        assert!((t - 1.5).abs() < 1e-5);
        let (_, n, _) = c.surface(&across.clone(), t, part);
        assert!(n.dot(across.dir) > 0.0);
    }

    #[test]
    fn far_rays_keep_their_accuracy() {
        // From 10⁵ away the shifted origin keeps the hit within a few ulps of the cone.
        let c = cone(true);
        let ray = Ray::new(Vec3::new(0.0, 1.0, 1.0e5), -Vec3::Z);
        let (t, _) = c.intersect_after(&ray, 0.0, f32::INFINITY).unwrap();
        let want = 1.0e5 + 9.0;
        assert!(((t as f64) - want).abs() < 0.02, "{t}");
    }

    #[test]
    fn misses_beside_above_and_the_other_nappe() {
        let c = cone(true);
        for ray in [
            Ray::new(Vec3::new(2.5, 0.0, 0.0), -Vec3::Z),
            Ray::new(Vec3::new(0.0, 3.5, 0.0), -Vec3::Z),
            // Above the apex, where the mirrored cone of the quadratic lies.
            Ray::new(Vec3::new(0.0, 4.0, 0.0), -Vec3::Z),
        ] {
            assert!(
                c.intersect_after(&ray, 0.0, f32::INFINITY).is_none(),
                "{ray:?}"
            );
        }
    }
}
