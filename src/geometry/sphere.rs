//! Spheres, intersected with the cancellation-free quadratic of Ray Tracing Gems chapter 7.

use super::aabb::Aabb;
use super::ray::Ray;
use super::uv_frame::{UvFrame, along_meridian, around_y_axis};
use crate::numerics::{gamma, stable_quadratic_roots};
use glam::{Vec3, Vec3A};
use std::f32::consts::PI;

/// A sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Its centre.
    pub center: Vec3A,
    /// Its radius.
    pub radius: f32,
}

impl Sphere {
    /// The sphere about `center` of radius `radius`.
    pub fn new(center: Vec3, radius: f32) -> Self {
        Self {
            center: center.into(),
            radius,
        }
    }

    /// Both ray parameters where the ray's line meets the sphere, t0 ≤ t1.
    ///
    /// With f = o − c, the textbook discriminant b² − 4ac cancels catastrophically when the
    /// sphere is small or far away. Instead the discriminant is a·(r² − |f⊥|²), where f⊥ is
    /// the part of f perpendicular to the ray: it is computed from a short vector and keeps
    /// its accuracy at any distance (Ray Tracing Gems chapter 7). No square root comes
    /// before the discriminant's own: this test lies on the critical path of most rays, and
    /// forming r² − |f⊥|² or |f|² − r² as (r − |f⊥|)(r + |f⊥|) would add a square root to
    /// it without a better error bound (docs/numerics.md).
    #[inline]
    pub fn roots(&self, ray: &Ray) -> Option<(f32, f32)> {
        self.roots_unless_receding(ray, false)
    }

    /// `roots`, or None early when `receding` is set and the ray starts outside the sphere
    /// and moves away from its centre (c > 0, β ≤ 0): both roots are then ≤ 0, so no test
    /// for t > 0 can accept either, and the division and square root are skipped. This is
    /// every reflected ray leaving the sphere's own outside.
    #[inline(always)]
    fn roots_unless_receding(&self, ray: &Ray, receding: bool) -> Option<(f32, f32)> {
        let f = ray.origin - self.center;
        let d = ray.dir;
        let a = d.length_squared();
        let beta = -f.dot(d);
        let r2 = self.radius * self.radius;
        let c = f.length_squared() - r2;
        if receding && c > 0.0 && beta <= 0.0 {
            return None;
        }
        let f_perp = f + d * (beta / a);
        let disc = a * (r2 - f_perp.length_squared());
        stable_quadratic_roots(a, beta, c, disc)
    }

    /// The nearest t in (0, t_max) where the ray meets the sphere.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        self.intersect_after(ray, 0.0, t_max)
    }

    /// The nearest t in (t_min, t_max).
    #[inline]
    pub fn intersect_after(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        debug_assert!(t_min >= 0.0);
        let (t0, t1) = self.roots_unless_receding(ray, true)?;
        if t0 > t_min && t0 < t_max {
            Some(t0)
        } else if t1 > t_min && t1 < t_max {
            Some(t1)
        } else {
            None
        }
    }

    /// How many times the segment (0, t_max) of the ray crosses the surface.
    #[inline]
    pub fn crossings(&self, ray: &Ray, t_max: f32) -> u32 {
        match self.roots_unless_receding(ray, true) {
            Some((t0, t1)) => (t0 > 0.0 && t0 < t_max) as u32 + (t1 > 0.0 && t1 < t_max) as u32,
            None => 0,
        }
    }

    /// The outward unit normal, the hit point reprojected onto the sphere, and a bound on the
    /// point's per-coordinate error.
    #[inline]
    pub fn surface(&self, ray: &Ray, t: f32) -> (Vec3A, Vec3A, Vec3A) {
        let offset = ray.at(t) - self.center;
        let length = offset.length();
        let normal = if length > 0.0 {
            offset / length
        } else {
            -ray.dir.normalize_or(Vec3A::Y)
        };
        // Reprojecting onto the sphere removes the error of o + t·d (which grows with t);
        // what remains is the rounding of c + r·n.
        let point = self.center + normal * self.radius;
        let error = (self.center.abs() + (normal * self.radius).abs()) * gamma(5);
        (point, normal, error)
    }

    /// Latitude-longitude coordinates of a unit normal: u runs east from longitude −180° at
    /// u = 0 (longitude 0 faces +z, towards the default camera), v runs south from the north
    /// pole (+y) at v = 0, so an equirectangular image maps with north up.
    #[inline]
    pub fn uv(normal: Vec3A) -> (f32, f32) {
        let u = 0.5 + normal.x.atan2(normal.z) / (2.0 * PI);
        let v = 0.5 - normal.y.clamp(-1.0, 1.0).asin() / PI;
        (u, v)
    }

    /// The texture coordinates at the point of outward unit `normal` and their tangents:
    /// u turns once around the equator, v runs pole to pole along a meridian.
    #[inline]
    pub fn uv_frame(&self, normal: Vec3A) -> UvFrame {
        UvFrame {
            uv: Self::uv(normal),
            dpdu: around_y_axis(normal) * self.radius,
            // v grows southwards, against latitude.
            dpdv: along_meridian(normal) * (-PI * self.radius),
        }
    }

    /// The box around the sphere.
    pub fn bounds(&self) -> Aabb {
        let r = Vec3A::splat(self.radius);
        Aabb {
            min: (self.center - r).into(),
            max: (self.center + r).into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_sphere_at(z: f32) -> Sphere {
        Sphere::new(Vec3::new(0.0, 0.0, z), 1.0)
    }

    #[test]
    fn ray_hits_front_of_sphere() {
        let s = unit_sphere_at(-5.0);
        let ray = Ray::new(Vec3::ZERO, -Vec3::Z);
        let t = s.intersect(&ray, f32::INFINITY).unwrap();
        assert_eq!(t, 4.0);
        let (p, n, _) = s.surface(&ray, t);
        assert_eq!(p, Vec3A::new(0.0, 0.0, -4.0));
        assert_eq!(n, Vec3A::Z);
    }

    #[test]
    fn ray_misses_beside_and_behind() {
        let s = unit_sphere_at(-5.0);
        assert!(
            s.intersect(&Ray::new(Vec3::new(1.5, 0.0, 0.0), -Vec3::Z), f32::INFINITY)
                .is_none()
        );
        assert!(
            s.intersect(&Ray::new(Vec3::ZERO, Vec3::Z), f32::INFINITY)
                .is_none()
        );
        assert!(s.intersect(&Ray::new(Vec3::ZERO, -Vec3::Z), 3.9).is_none());
    }

    #[test]
    fn ray_from_inside_hits_the_far_side() {
        let s = unit_sphere_at(0.0);
        let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 2.0, 0.0));
        let t = s.intersect(&ray, f32::INFINITY).unwrap();
        assert_eq!(t, 0.5);
        let (_, n, _) = s.surface(&ray, t);
        assert_eq!(n, Vec3A::Y);
        assert_eq!(s.crossings(&ray, f32::INFINITY), 1);
    }

    #[test]
    fn a_receding_ray_is_rejected_but_its_roots_remain() {
        let s = unit_sphere_at(-5.0);
        // Leaving the sphere's near side outwards, and passing it by going away.
        for ray in [
            Ray::new(Vec3::new(0.0, 0.0, -4.0 + 1e-6), Vec3::Z),
            Ray::new(Vec3::new(0.5, 0.0, -3.0), Vec3::new(0.1, 0.0, 1.0)),
        ] {
            let (t0, t1) = s.roots(&ray).unwrap();
            assert!(t0 < 0.0 && t1 < 0.0, "{t0} {t1}");
            assert_eq!(s.intersect(&ray, f32::INFINITY), None);
            assert_eq!(s.crossings(&ray, f32::INFINITY), 0);
        }
        // Moving away from the centre but starting inside: the far side is still ahead.
        let inside = Ray::new(Vec3::new(0.0, 0.0, -4.5), Vec3::Z);
        assert_eq!(s.intersect(&inside, f32::INFINITY), Some(0.5));
    }

    #[test]
    fn crossings_counts_both_sides() {
        let s = unit_sphere_at(-5.0);
        let ray = Ray::new(Vec3::ZERO, -Vec3::Z);
        assert_eq!(s.crossings(&ray, 100.0), 2);
        assert_eq!(s.crossings(&ray, 5.0), 1);
        assert_eq!(s.crossings(&ray, 1.0), 0);
    }

    #[test]
    fn small_distant_sphere_is_hit_accurately() {
        // Radius 1e-3 at distance 1e4: the textbook discriminant is lost to cancellation
        // in f32 (b² ≈ 1e8 while r² = 1e-6).
        let s = Sphere::new(Vec3::new(0.0, 0.0, -1.0e4), 1.0e-3);
        let ray = Ray::new(Vec3::ZERO, -Vec3::Z);
        let t = s.intersect(&ray, f32::INFINITY).unwrap();
        assert!((t - (1.0e4 - 1.0e-3)).abs() <= 1.0e4 * 1e-6);
        let grazing = Ray::new(Vec3::new(0.9e-3, 0.0, 0.0), -Vec3::Z);
        assert!(s.intersect(&grazing, f32::INFINITY).is_some());
        let outside = Ray::new(Vec3::new(1.1e-3, 0.0, 0.0), -Vec3::Z);
        assert!(s.intersect(&outside, f32::INFINITY).is_none());
    }

    #[test]
    fn uv_of_known_directions() {
        let (u, v) = Sphere::uv(Vec3A::Z);
        assert!((u - 0.5).abs() < 1e-6 && (v - 0.5).abs() < 1e-6);
        let (u, _) = Sphere::uv(Vec3A::X);
        assert!(
            (u - 0.75).abs() < 1e-6,
            "east of the facing meridian is to the right"
        );
        let (_, v) = Sphere::uv(Vec3A::Y);
        assert!(v.abs() < 1e-6);
        let (_, v) = Sphere::uv(-Vec3A::Y);
        assert!((v - 1.0).abs() < 1e-6);
    }
}
