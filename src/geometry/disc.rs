//! Flat round discs (and, with a radius far beyond the scene, planes: see
//! `scene/geometry.rs`), met where the ray crosses their plane.

use super::aabb::Aabb;
use super::ray::Ray;
use super::uv_frame::UvFrame;
use crate::numerics::{gamma, orthonormal_basis};
use glam::{Vec3, Vec3A};

/// A disc: the points of a plane within `radius` of `center`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disc {
    /// Its centre.
    pub center: Vec3,
    /// Unit normal of its front.
    pub normal: Vec3,
    /// Its radius.
    pub radius: f32,
    /// The picture's right and up in the disc's plane, over its diameter.
    u_axis: Vec3,
    v_axis: Vec3,
}

impl Disc {
    /// The disc about `center` facing `normal` (unit length) of radius `radius`.
    pub fn new(center: Vec3, normal: Vec3, radius: f32) -> Self {
        let (right, up) = picture_axes(normal);
        let diameter = 2.0 * radius;
        Self {
            center,
            normal,
            radius,
            u_axis: right / diameter,
            v_axis: up / diameter,
        }
    }

    /// The t where the ray's line crosses the disc, if it does within its radius.
    #[inline]
    fn crossing(&self, ray: &Ray) -> Option<f32> {
        let n = Vec3A::from(self.normal);
        let c = Vec3A::from(self.center);
        let along = ray.dir.dot(n);
        if along == 0.0 {
            return None;
        }
        let t = (c - ray.origin).dot(n) / along;
        let offset = ray.at(t) - c;
        (offset.length_squared() <= self.radius * self.radius).then_some(t)
    }

    /// The hit with t in (t_min, t_max).
    #[inline]
    pub fn intersect_after(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        self.crossing(ray).filter(|&t| t > t_min && t < t_max)
    }

    /// Hit point, unit normal (its front's) and error bound.
    #[inline]
    pub fn surface(&self, ray: &Ray, t: f32) -> (Vec3A, Vec3A, Vec3A) {
        let p = ray.at(t);
        // t = (c − o)·n / d·n errs by a few ulps of (|c| + |o|) along n; o + t·d adds its own.
        let error =
            (ray.origin.abs() + (ray.dir * t).abs() + Vec3A::from(self.center).abs()) * gamma(7);
        (p, self.normal.into(), error)
    }

    /// [0, 1]² over the square around the disc, upright as its front is seen (the up of a
    /// disc that faces up or down is −z or +z).
    pub fn uv(&self, p: Vec3A) -> (f32, f32) {
        let d = Vec3::from(p) - self.center;
        (0.5 + d.dot(self.u_axis), 0.5 - d.dot(self.v_axis))
    }

    /// The texture coordinates at `p` and their tangents (constant over the disc).
    pub fn uv_frame(&self, p: Vec3A) -> UvFrame {
        UvFrame::planar(self.uv(p), self.u_axis.into(), self.v_axis.into())
    }

    /// The box around the disc: on each axis, its radius times the sine of the normal's
    /// angle to that axis.
    pub fn bounds(&self) -> Aabb {
        let n2 = self.normal * self.normal;
        let reach = (Vec3::ONE - n2).max(Vec3::ZERO).map(f32::sqrt) * self.radius;
        // A little more, for the rounding of the sines.
        let reach = reach + Vec3::splat(self.radius * gamma(4));
        Aabb {
            min: self.center - reach,
            max: self.center + reach,
        }
    }
}

/// The right and up (unit, in the plane) of a picture on a surface facing `normal`: up is
/// +y projected into the plane, or for a surface facing up −z (and +z facing down), so that
/// seen from the front, right × up points at the viewer.
pub fn picture_axes(normal: Vec3) -> (Vec3, Vec3) {
    let up = Vec3::Y - normal * normal.y;
    let up = if up.length_squared() > 1e-6 {
        up.normalize()
    } else if normal.y > 0.0 {
        -Vec3::Z
    } else {
        Vec3::Z
    };
    let right = up.cross(normal).normalize();
    // Keep `orthonormal_basis` the one way to make a frame when the above degenerates.
    if !right.is_finite() {
        return orthonormal_basis(normal);
    }
    (right, up)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hit_inside_and_miss_outside_the_radius() {
        let d = Disc::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z, 1.0);
        let ray = Ray::new(Vec3::new(0.5, 0.5, 0.0), -Vec3::Z);
        assert_eq!(d.intersect_after(&ray, 0.0, f32::INFINITY), Some(5.0));
        let (p, n, e) = d.surface(&ray, 5.0);
        assert_eq!((p, n), (Vec3A::new(0.5, 0.5, -5.0), Vec3A::Z));
        assert!(e.max_element() < 1e-5);
        let outside = Ray::new(Vec3::new(0.75, 0.75, 0.0), -Vec3::Z);
        assert_eq!(d.intersect_after(&outside, 0.0, f32::INFINITY), None);
        // Behind, beyond t_max, and parallel.
        assert_eq!(d.intersect_after(&ray, 0.0, 4.0), None);
        assert_eq!(
            d.intersect_after(&Ray::new(Vec3::ZERO, Vec3::Z), 0.0, f32::INFINITY),
            None
        );
        assert_eq!(
            d.intersect_after(&Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::X), 0.0, 9.0),
            None
        );
    }

    #[test]
    fn tilted_disc_meets_where_its_plane_does() {
        let n = Vec3::new(0.0, 1.0, 1.0).normalize();
        let d = Disc::new(Vec3::new(0.0, 0.0, -4.0), n, 2.0);
        // The plane y + z = −4; a ray down from (0, 3, −5) meets it at y = 1, t = 2.
        let ray = Ray::new(Vec3::new(0.0, 3.0, -5.0), -Vec3::Y);
        let t = d.intersect_after(&ray, 0.0, f32::INFINITY).unwrap();
        assert!((t - 2.0).abs() < 1e-6);
        let b = d.bounds();
        let half = 2.0 / 2f32.sqrt();
        assert!((b.max.x - 2.0).abs() < 1e-5 && (b.max.y - half).abs() < 1e-5);
        assert!((b.min.z - (-4.0 - half)).abs() < 1e-5);
    }

    #[test]
    fn picture_is_upright_from_the_front() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::Y,
            -Vec3::Y,
            Vec3::ONE.normalize(),
        ] {
            let d = Disc::new(Vec3::ZERO, n, 1.0);
            let (right, up) = picture_axes(n);
            assert!(right.cross(up).dot(n) > 0.999, "{n}");
            let (u, v) = d.uv(((right + up) * 0.5).into());
            assert!(
                (u - 0.75).abs() < 1e-6 && (v - 0.25).abs() < 1e-6,
                "{n}: {u} {v}"
            );
        }
        let (right, up) = picture_axes(Vec3::Z);
        assert_eq!((right, up), (Vec3::X, Vec3::Y));
    }
}
