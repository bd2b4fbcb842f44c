//! Tori about the y axis: (|p|² + R² − r²)² = 4R²(x² + z²), a quartic along a ray.
//!
//! The quartic is formed in f64 from an origin moved to the ray's closest approach to the
//! centre and scaled by the bounding sphere's radius, so every root of interest lies in
//! [−1, 1] and the coefficients are of order one wherever the ray starts; its roots are
//! isolated by the derivative's (polynomial.rs), which keeps two roots apart however close
//! they come (grazing the silhouette or the inner rim). The hit point is then put back onto
//! the torus, as a sphere's is.

use super::aabb::Aabb;
use super::polynomial::{MAX_ROOTS, roots_in};
use super::ray::Ray;
use super::uv_frame::{UvFrame, around_y_axis};
use crate::numerics::gamma;
use glam::{DVec3, Vec3, Vec3A};
use std::f32::consts::PI;

/// A torus about an axis along +y through `center`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Torus {
    /// Its centre.
    pub center: Vec3,
    /// From the centre to the middle of the tube.
    pub major_radius: f32,
    /// The tube's radius (below `major_radius`).
    pub minor_radius: f32,
}

impl Torus {
    /// Every t where the ray's line meets the torus within (t_min, t_max), ascending.
    #[inline]
    fn hits(&self, ray: &Ray, t_min: f32, t_max: f32) -> ([f32; MAX_ROOTS], usize) {
        let mut out = ([0.0; MAX_ROOTS], 0);
        let o = DVec3::from(Vec3::from(ray.origin)) - DVec3::from(self.center);
        let d = DVec3::from(Vec3::from(ray.dir));
        let dd = d.length_squared();
        let reach = (self.major_radius + self.minor_radius) as f64;
        let shift = -o.dot(d) / dd;
        let closest = o + d * shift;
        if closest.length_squared() > reach * reach {
            return out;
        }
        // s = (t − shift)·|d| / reach: the bounding sphere spans s ∈ [−1, 1].
        let length = dd.sqrt();
        let to_s = length / reach;
        let p = closest / reach;
        let e = d / length;
        let big = self.major_radius as f64 / reach;
        let small = self.minor_radius as f64 / reach;
        let pe = p.dot(e);
        let g = p.length_squared() + big * big - small * small;
        let four_b2 = 4.0 * big * big;
        let c = [
            g * g - four_b2 * (p.x * p.x + p.z * p.z),
            4.0 * pe * g - 2.0 * four_b2 * (p.x * e.x + p.z * e.z),
            4.0 * pe * pe + 2.0 * g - four_b2 * (e.x * e.x + e.z * e.z),
            4.0 * pe,
            1.0,
        ];
        let lo = ((t_min as f64 - shift) * to_s).max(-1.0 - 1e-9);
        let hi = ((t_max as f64 - shift) * to_s).min(1.0 + 1e-9);
        for &s in roots_in(&c, lo, hi).as_slice() {
            let t = (shift + s / to_s) as f32;
            if t > t_min && t < t_max {
                out.0[out.1] = t;
                out.1 += 1;
            }
        }
        out
    }

    /// The nearest t in (t_min, t_max).
    #[inline]
    pub fn intersect_after(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        let (ts, n) = self.hits(ray, t_min, t_max);
        (n > 0).then_some(ts[0])
    }

    /// How many times the segment (0, t_max) crosses the surface (up to four).
    #[inline]
    pub fn crossings(&self, ray: &Ray, t_max: f32) -> u32 {
        self.hits(ray, 0.0, t_max).1 as u32
    }

    /// The point of the tube's middle circle nearest `p` (relative to the centre), and the
    /// outward unit normal there.
    #[inline]
    fn ring_and_normal(&self, rel: Vec3A) -> (Vec3A, Vec3A) {
        let flat = Vec3A::new(rel.x, 0.0, rel.z);
        let len = flat.length();
        let ring = if len > 0.0 { flat / len } else { Vec3A::X } * self.major_radius;
        let n = (rel - ring).normalize_or(Vec3A::Y);
        (ring, n)
    }

    /// Hit point (put back onto the torus), outward unit normal and error bound.
    #[inline]
    pub fn surface(&self, ray: &Ray, t: f32) -> (Vec3A, Vec3A, Vec3A) {
        let c = Vec3A::from(self.center);
        let (ring, n) = self.ring_and_normal(ray.at(t) - c);
        let point = c + ring + n * self.minor_radius;
        let error = (c.abs() + ring.abs() + (n * self.minor_radius).abs()) * gamma(7);
        (point, n, error)
    }

    /// u around the axis from +z towards +x (as a sphere's); v around the tube from its
    /// inner rim, over the top, to its outer rim and back underneath.
    pub fn uv(&self, p: Vec3A) -> (f32, f32) {
        let rel = p - Vec3A::from(self.center);
        let (ring, n) = self.ring_and_normal(rel);
        let u = 0.5 + rel.x.atan2(rel.z) / (2.0 * PI);
        let outward = n.dot(ring / self.major_radius);
        let v = 0.5 - n.y.atan2(outward) / (2.0 * PI);
        (u, v)
    }

    /// The texture coordinates at `p` and their tangents: u around the axis, v around the
    /// tube (over the top first, so against the tube angle measured from the outer rim up).
    pub fn uv_frame(&self, p: Vec3A) -> UvFrame {
        let rel = p - Vec3A::from(self.center);
        let (ring, n) = self.ring_and_normal(rel);
        let outward = n.dot(ring / self.major_radius);
        let radial = ring / self.major_radius;
        // ∂p/∂θ for θ = atan2(n.y, outward) is r·(−n.y·radial + outward·y); v = ½ − θ/2π.
        let dpdtheta = (Vec3A::Y * outward - radial * n.y) * self.minor_radius;
        UvFrame {
            uv: self.uv(p),
            dpdu: around_y_axis(rel),
            dpdv: dpdtheta * -std::f32::consts::TAU,
        }
    }

    /// The box around the torus.
    pub fn bounds(&self) -> Aabb {
        let r = self.major_radius + self.minor_radius;
        let reach = Vec3::new(r, self.minor_radius, r);
        Aabb {
            min: self.center - reach,
            max: self.center + reach,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn torus() -> Torus {
        Torus {
            center: Vec3::new(0.0, 0.0, -10.0),
            major_radius: 2.0,
            minor_radius: 0.5,
        }
    }

    #[test]
    fn a_ray_along_the_equator_crosses_four_times() {
        let t = torus();
        let ray = Ray::new(Vec3::ZERO, -Vec3::Z);
        let (ts, n) = t.hits(&ray, 0.0, f32::INFINITY);
        assert_eq!(n, 4);
        for (got, want) in ts.iter().zip([7.5, 8.5, 11.5, 12.5]) {
            assert!((got - want).abs() < 1e-5, "{got} vs {want}");
        }
        assert_eq!(t.crossings(&ray, 10.0), 2);
        let (p, n, _) = t.surface(&ray, ts[0]);
        assert!((p - Vec3A::new(0.0, 0.0, -7.5)).length() < 1e-6);
        assert!((n - Vec3A::Z).length() < 1e-6);
        // From the tube's inside, along it.
        let (p, n, _) = t.surface(&ray, ts[1]);
        assert!((p.z + 8.5).abs() < 1e-6 && (n + Vec3A::Z).length() < 1e-6);
    }

    #[test]
    fn through_the_hole_misses_and_down_onto_the_tube_hits_its_top() {
        let t = torus();
        assert!(
            t.intersect_after(&Ray::new(Vec3::new(0.0, 5.0, -10.0), -Vec3::Y), 0.0, 1e9)
                .is_none()
        );
        let down = Ray::new(Vec3::new(2.0, 5.0, -10.0), -Vec3::Y);
        let hit = t.intersect_after(&down, 0.0, f32::INFINITY).unwrap();
        assert!((hit - 4.5).abs() < 1e-5);
        let (_, n, _) = t.surface(&down, hit);
        assert!((n - Vec3A::Y).length() < 1e-6);
        let (u, v) = t.uv(Vec3A::new(2.0, 0.5, -10.0));
        assert!(
            (u - 0.75).abs() < 1e-6 && (v - 0.25).abs() < 1e-6,
            "{u} {v}"
        );
    }

    #[test]
    fn roots_agree_with_f64_sampling_where_roots_nearly_meet() {
        // Fans of rays grazing the top of the tube and the inner rim (through the hole),
        // where two roots nearly meet: every sign change of the exact (f64) implicit
        // function along the ray must be found, and each hit must lie on the torus.
        let t = torus();
        let implicit = |p: DVec3| {
            let p = p - DVec3::from(t.center);
            let (big, small) = (t.major_radius as f64, t.minor_radius as f64);
            let q = p.length_squared() + big * big - small * small;
            q * q - 4.0 * big * big * (p.x * p.x + p.z * p.z)
        };
        let mut fans: Vec<(Vec3, Vec3)> = Vec::new();
        for i in 1..200 {
            let off = 1e-4 * i as f32;
            // Along x, just under the top of the tube.
            fans.push((Vec3::new(-20.0, 0.5 - off, -10.0), Vec3::X));
            // Down through the hole, just outside the inner rim (radius 1.5).
            fans.push((Vec3::new(1.5 + off, 20.0, -10.0), -Vec3::Y));
        }
        for (origin, dir) in fans {
            let ray = Ray::new(origin, dir);
            let (ts, n) = t.hits(&ray, 0.0, f32::INFINITY);
            let at = |s: f64| DVec3::from(origin) + DVec3::from(dir) * s;
            let mut changes = 0;
            let mut last = implicit(at(0.0));
            for k in 1..=40_000 {
                let v = implicit(at(k as f64 * 1e-3));
                changes += (v.signum() != last.signum()) as usize;
                last = v;
            }
            assert_eq!(n, changes, "{origin}");
            for &tt in &ts[..n] {
                let rel = at(tt as f64) - DVec3::from(t.center);
                let ring = DVec3::new(rel.x, 0.0, rel.z).normalize() * 2.0;
                let off = ((rel - ring).length() - 0.5).abs();
                assert!(off < 1e-5, "{origin}: {off}");
            }
        }
    }
}
