//! Capsules: an upright open cylinder closed at both ends by hemispheres of its radius (a
//! pill, POV-Ray's two-point `sphere_sweep`). The side and the two spheres keep their own
//! cancellation-free tests; each sphere counts only on its own side of the side's ends.

use super::aabb::Aabb;
use super::cylinder::{Cylinder, CylinderPart, crossing_count, nearest_candidate};
use super::ray::Ray;
use super::sphere::Sphere;
use super::uv_frame::{UvFrame, along_meridian, around_y_axis};
use glam::{Vec3, Vec3A};
use std::f32::consts::PI;

/// An upright capsule (along +y): the points within `radius` of the segment from `base`
/// to `base + height·y`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// The centre of the bottom hemisphere (the segment's lower end).
    pub base: Vec3,
    /// Its radius, the side's and the ends'.
    pub radius: f32,
    /// The length of the segment: the side's height.
    pub height: f32,
}

impl Capsule {
    /// The capsule about the segment from `base` up `height`, of radius `radius`.
    pub fn new(base: Vec3, radius: f32, height: f32) -> Self {
        Self {
            base,
            radius,
            height,
        }
    }

    fn side(&self) -> Cylinder {
        Cylinder::new(self.base, self.radius, self.height).with_caps(false)
    }

    fn end(&self, part: CylinderPart) -> Sphere {
        let y = if part == CylinderPart::Top {
            self.height
        } else {
            0.0
        };
        Sphere::new(self.base + Vec3::new(0.0, y, 0.0), self.radius)
    }

    /// Every place the ray's line meets the capsule, as (t, part) (`Bottom` and `Top` are
    /// the ends); NaN for none. A line meets it at most twice; one through the seam of the
    /// side and an end may count both.
    #[inline]
    fn candidates(&self, ray: &Ray) -> [(f32, CylinderPart); 6] {
        let none = (f32::NAN, CylinderPart::Side);
        let mut out = [none; 6];
        let side = self.side().candidates(ray);
        out[0] = side[0];
        out[1] = side[1];
        let (y_lo, y_hi) = (self.base.y, self.base.y + self.height);
        for (k, part) in [CylinderPart::Bottom, CylinderPart::Top]
            .into_iter()
            .enumerate()
        {
            if let Some((t0, t1)) = self.end(part).roots(ray) {
                for (j, t) in [t0, t1].into_iter().enumerate() {
                    let y = ray.origin.y + t * ray.dir.y;
                    let beyond = match part {
                        CylinderPart::Bottom => y <= y_lo,
                        _ => y >= y_hi,
                    };
                    if beyond {
                        out[2 + 2 * k + j] = (t, part);
                    }
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

    /// How many times the segment (0, t_max) crosses the surface (at most twice: it is
    /// convex).
    #[inline]
    pub fn crossings(&self, ray: &Ray, t_max: f32) -> u32 {
        crossing_count(&self.candidates(ray), t_max)
    }

    /// Hit point (moved exactly onto the surface), outward unit normal and error bound.
    #[inline]
    pub fn surface(&self, ray: &Ray, t: f32, part: CylinderPart) -> (Vec3A, Vec3A, Vec3A) {
        match part {
            CylinderPart::Side => self.side().surface(ray, t, CylinderPart::Side),
            end => self.end(end).surface(ray, t),
        }
    }

    /// u: angle around the axis from +z towards +x, in [0, 1); v: height along the whole
    /// capsule, from the bottom end's pole (0) to the top end's (1).
    pub fn uv(&self, p: Vec3A) -> (f32, f32) {
        let rel = Vec3::from(p) - self.base;
        let u = 0.5 + rel.x.atan2(rel.z) / (2.0 * PI);
        let v = (rel.y + self.radius) / (self.height + 2.0 * self.radius);
        (u, v.clamp(0.0, 1.0))
    }

    /// The texture coordinates at `p` and their tangents. On an end, v still grows with
    /// height: the point moves along the meridian as far as one unit of height takes it.
    pub fn uv_frame(&self, p: Vec3A) -> UvFrame {
        let rel = p - Vec3A::from(self.base);
        let length = self.height + 2.0 * self.radius;
        let end = if rel.y < 0.0 {
            Some(rel)
        } else if rel.y > self.height {
            Some(rel - Vec3A::new(0.0, self.height, 0.0))
        } else {
            None
        };
        let per_height = match end {
            None => Vec3A::Y,
            // ∂p/∂λ over ∂y/∂λ, the meridian's climb; none at a pole.
            Some(q) => {
                let rho2 = q.x * q.x + q.z * q.z;
                if rho2 > 0.0 {
                    along_meridian(q) * (rho2.sqrt().recip())
                } else {
                    Vec3A::ZERO
                }
            }
        };
        UvFrame {
            uv: self.uv(p),
            dpdu: around_y_axis(rel),
            dpdv: per_height * length,
        }
    }

    /// The box around the capsule.
    pub fn bounds(&self) -> Aabb {
        let r = self.radius;
        Aabb {
            min: self.base - Vec3::splat(r),
            max: self.base + Vec3::new(r, self.height + r, r),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distance from `p` to `c`'s axis segment.
    fn distance_to_axis(c: &Capsule, p: Vec3A) -> f32 {
        let rel = Vec3::from(p) - c.base;
        let y = rel.y.clamp(0.0, c.height);
        glam::Vec2::new(rel.x, rel.z).length().hypot(rel.y - y)
    }

    fn pill() -> Capsule {
        Capsule::new(Vec3::new(0.0, -1.0, -10.0), 1.0, 2.0)
    }

    /// Rays at the side, at each end and through its length find the surface where the
    /// distance to the axis is the radius, with the normal pointing out from the axis.
    #[test]
    fn hits_lie_on_the_surface_with_outward_normals() {
        let c = pill();
        let cases = [
            (Ray::new(Vec3::ZERO, -Vec3::Z), CylinderPart::Side, 9.0),
            (
                Ray::new(Vec3::new(0.0, 5.0, -10.0), -Vec3::Y),
                CylinderPart::Top,
                3.0,
            ),
            (
                Ray::new(Vec3::new(0.0, -5.0, -10.0), Vec3::Y),
                CylinderPart::Bottom,
                3.0,
            ),
            (
                Ray::new(Vec3::new(0.0, 1.5, 0.0), -Vec3::Z),
                CylinderPart::Top,
                10.0 - 0.75f32.sqrt(),
            ),
        ];
        for (ray, part, t_expected) in cases {
            let (t, hit) = c.intersect_after(&ray, 0.0, f32::INFINITY).unwrap();
            assert_eq!(hit, part, "{ray:?}");
            assert!((t - t_expected).abs() < 1e-5, "{t} vs {t_expected}");
            let (p, n, e) = c.surface(&ray, t, hit);
            assert!((distance_to_axis(&c, p) - 1.0).abs() < 1e-5);
            assert!((n.length() - 1.0).abs() < 1e-6 && n.dot(ray.dir) < 0.0);
            assert!(e.max_element() < 1e-4);
            let (u, v) = c.uv(p);
            assert!((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v));
        }
    }

    /// A ray from inside leaves once; one through the whole capsule crosses twice; rays
    /// beside it, behind it or short of it cross nothing.
    #[test]
    fn crossings_count_entries_and_exits() {
        let c = pill();
        let through = Ray::new(Vec3::new(0.0, 5.0, -10.0), -Vec3::Y);
        assert_eq!(c.crossings(&through, f32::INFINITY), 2);
        assert_eq!(c.crossings(&through, 4.0), 1);
        let inside = Ray::new(Vec3::new(0.0, 0.0, -10.0), Vec3::new(0.3, 1.0, 0.2));
        assert_eq!(c.crossings(&inside, f32::INFINITY), 1);
        let (t, part) = c.intersect_after(&inside, 0.0, f32::INFINITY).unwrap();
        let (p, n, _) = c.surface(&inside, t, part);
        assert!((distance_to_axis(&c, p) - 1.0).abs() < 1e-5 && n.dot(inside.dir) > 0.0);
        let beside = Ray::new(Vec3::new(1.01, 0.0, 0.0), -Vec3::Z);
        assert_eq!(c.crossings(&beside, f32::INFINITY), 0);
        assert!(c.intersect_after(&beside, 0.0, f32::INFINITY).is_none());
        let away = Ray::new(Vec3::ZERO, Vec3::Z);
        assert!(c.intersect_after(&away, 0.0, f32::INFINITY).is_none());
        assert!(
            c.intersect_after(&Ray::new(Vec3::ZERO, -Vec3::Z), 0.0, 8.9)
                .is_none()
        );
    }

    #[test]
    fn bounds_hold_both_ends() {
        let b = pill().bounds();
        assert_eq!(b.min, Vec3::new(-1.0, -2.0, -11.0));
        assert_eq!(b.max, Vec3::new(1.0, 2.0, -9.0));
    }
}
