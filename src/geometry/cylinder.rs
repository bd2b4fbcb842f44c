//! Finite cylinders along +y, closed by caps or open tubes. The side solves the seed's quadratic in x and
//! z, written in the same cancellation-free form as the sphere.

use super::aabb::Aabb;
use super::ray::Ray;
use super::uv_frame::{UvFrame, around_y_axis};
use crate::numerics::{gamma, stable_quadratic_roots};
use glam::{Vec2, Vec3, Vec3A};
use std::f32::consts::PI;

/// An upright cylinder (along +y), closed by two caps or open at both ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder {
    /// Centre of the bottom cap.
    pub base: Vec3,
    /// Radius of the side.
    pub radius: f32,
    /// Height from the bottom cap to the top cap.
    pub height: f32,
    /// Whether the ends are closed (a solid) or open (a tube, seen inside and out).
    pub caps: bool,
}

/// Which part of the cylinder a ray hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CylinderPart {
    /// The curved side.
    Side,
    /// The cap at the base.
    Bottom,
    /// The cap at the top.
    Top,
}

impl Cylinder {
    /// The closed cylinder standing on `base` (the centre of its bottom cap).
    pub fn new(base: Vec3, radius: f32, height: f32) -> Self {
        Self {
            base,
            radius,
            height,
            caps: true,
        }
    }

    /// The same cylinder, closed or open.
    pub fn with_caps(self, caps: bool) -> Self {
        Self { caps, ..self }
    }

    /// Every place the ray's line meets the cylinder, as (t, part); at most four
    /// candidates of which at most two are real, unordered.
    #[inline]
    pub(super) fn candidates(&self, ray: &Ray) -> [(f32, CylinderPart); 4] {
        let none = (f32::NAN, CylinderPart::Side);
        let mut out = [none; 4];
        let f = Vec2::new(ray.origin.x - self.base.x, ray.origin.z - self.base.z);
        let d = Vec2::new(ray.dir.x, ray.dir.z);
        let a = d.length_squared();
        let (y_lo, y_hi) = (self.base.y, self.base.y + self.height);
        if a > 0.0 {
            let beta = -f.dot(d);
            let f_perp = f + d * (beta / a);
            let r = self.radius;
            let l = f_perp.length();
            let fl = f.length();
            let roots =
                stable_quadratic_roots(a, beta, (fl - r) * (fl + r), a * ((r - l) * (r + l)));
            if let Some((t0, t1)) = roots {
                for (slot, t) in [t0, t1].into_iter().enumerate() {
                    let y = ray.origin.y + t * ray.dir.y;
                    if y >= y_lo && y <= y_hi {
                        out[slot] = (t, CylinderPart::Side);
                    }
                }
            }
        }
        if self.caps && ray.dir.y != 0.0 {
            let r2 = self.radius * self.radius;
            for (slot, (y, part)) in [(y_lo, CylinderPart::Bottom), (y_hi, CylinderPart::Top)]
                .into_iter()
                .enumerate()
            {
                let t = (y - ray.origin.y) / ray.dir.y;
                let x = ray.origin.x + t * ray.dir.x - self.base.x;
                let z = ray.origin.z + t * ray.dir.z - self.base.z;
                if x * x + z * z <= r2 {
                    out[2 + slot] = (t, part);
                }
            }
        }
        out
    }

    /// The nearest t in (0, t_max) and the part that was hit.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(f32, CylinderPart)> {
        self.intersect_after(ray, 0.0, t_max)
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

    /// Hit point (moved exactly onto the surface), outward unit normal and error bound.
    #[inline]
    pub fn surface(&self, ray: &Ray, t: f32, part: CylinderPart) -> (Vec3A, Vec3A, Vec3A) {
        let mut p = ray.at(t);
        let scale = self.base.abs() + Vec3::new(self.radius, self.height, self.radius);
        match part {
            CylinderPart::Side => {
                let radial = Vec2::new(p.x - self.base.x, p.z - self.base.z);
                let len = radial.length();
                let n = if len > 0.0 { radial / len } else { Vec2::X };
                p.x = self.base.x + n.x * self.radius;
                p.z = self.base.z + n.y * self.radius;
                // y comes from o + t·d; its error grows with the ray's length.
                let error = Vec3A::new(
                    gamma(5) * scale.x,
                    gamma(7) * (ray.origin.y.abs() + (t * ray.dir.y).abs()) + gamma(3) * scale.y,
                    gamma(5) * scale.z,
                );
                (p, Vec3A::new(n.x, 0.0, n.y), error)
            }
            CylinderPart::Bottom | CylinderPart::Top => {
                let top = part == CylinderPart::Top;
                p.y = if top {
                    self.base.y + self.height
                } else {
                    self.base.y
                };
                let error = Vec3A::new(
                    gamma(7) * (ray.origin.x.abs() + (t * ray.dir.x).abs()),
                    gamma(2) * scale.y,
                    gamma(7) * (ray.origin.z.abs() + (t * ray.dir.z).abs()),
                );
                let n = if top { Vec3A::Y } else { -Vec3A::Y };
                (p, n, error)
            }
        }
    }

    /// u: angle around the axis from +z towards +x, in [0, 1); v: height from the base on
    /// the side, distance from the axis on the caps, in [0, 1].
    pub fn uv(&self, p: Vec3A, part: CylinderPart) -> (f32, f32) {
        let rel = Vec3::from(p) - self.base;
        let u = 0.5 + rel.x.atan2(rel.z) / (2.0 * PI);
        let v = match part {
            CylinderPart::Side => rel.y / self.height,
            _ => Vec2::new(rel.x, rel.z).length() / self.radius,
        };
        (u, v.clamp(0.0, 1.0))
    }

    /// The texture coordinates at `p` on `part` and their tangents.
    pub fn uv_frame(&self, p: Vec3A, part: CylinderPart) -> UvFrame {
        let rel = p - Vec3A::from(self.base);
        let dpdv = match part {
            CylinderPart::Side => Vec3A::new(0.0, self.height, 0.0),
            _ => outward_from_y_axis(rel) * self.radius,
        };
        UvFrame {
            uv: self.uv(p, part),
            dpdu: around_y_axis(rel),
            dpdv,
        }
    }

    /// The box around the cylinder.
    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: self.base - Vec3::new(self.radius, 0.0, self.radius),
            max: self.base + Vec3::new(self.radius, self.height, self.radius),
        }
    }
}

/// The unit direction away from the y axis at `rel` (horizontal); zero on the axis.
#[inline]
pub(super) fn outward_from_y_axis(rel: Vec3A) -> Vec3A {
    Vec3A::new(rel.x, 0.0, rel.z).normalize_or_zero()
}

/// How many of a cylinder's, cone's or capsule's candidates lie in (0, t_max). A line
/// crosses a closed one at most twice (one through a rim or a seam may count two parts
/// both), and an open one's side alone at most twice too.
#[inline]
pub(super) fn crossing_count(candidates: &[(f32, CylinderPart)], t_max: f32) -> u32 {
    candidates
        .iter()
        .filter(|(t, _)| *t > 0.0 && *t < t_max)
        .count()
        .min(2) as u32
}

/// The nearest of a cylinder's, cone's or capsule's candidates (NaN for none) in
/// (t_min, t_max).
#[inline]
pub(super) fn nearest_candidate(
    candidates: &[(f32, CylinderPart)],
    t_min: f32,
    t_max: f32,
) -> Option<(f32, CylinderPart)> {
    let mut best: Option<(f32, CylinderPart)> = None;
    for &(t, part) in candidates {
        if t > t_min && t < t_max && best.is_none_or(|(bt, _)| t < bt) {
            best = Some((t, part));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cyl() -> Cylinder {
        Cylinder::new(Vec3::new(0.0, -1.0, -10.0), 2.0, 3.0)
    }

    #[test]
    fn side_hit_has_radial_normal() {
        let c = cyl();
        let ray = Ray::new(Vec3::ZERO, -Vec3::Z);
        let (t, part) = c.intersect(&ray, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Side);
        assert!((t - 8.0).abs() < 1e-5);
        let (p, n, _) = c.surface(&ray, t, part);
        assert!((p - Vec3A::new(0.0, 0.0, -8.0)).length() < 1e-5);
        assert_eq!(n, Vec3A::Z);
        let (u, v) = c.uv(p, part);
        assert!((u - 0.5).abs() < 1e-6 && (v - 1.0 / 3.0).abs() < 1e-6);
    }

    #[test]
    fn normal_matches_seed_formula_off_axis() {
        let c = cyl();
        let ray = Ray::new(Vec3::new(1.0, 0.5, 0.0), -Vec3::Z);
        let (t, part) = c.intersect(&ray, f32::INFINITY).unwrap();
        let (p, n, _) = c.surface(&ray, t, part);
        // The seed: n = (x − xc, 0, z − zc) / R.
        let expected = Vec3A::new(p.x - c.base.x, 0.0, p.z - c.base.z) / c.radius;
        assert!((n - expected).length() < 1e-5);
        assert!((p.x - 1.0).abs() < 1e-5 && (p.z - (-10.0 + 3f32.sqrt())).abs() < 1e-5);
    }

    #[test]
    fn caps_are_closed() {
        let c = cyl();
        let down = Ray::new(Vec3::new(0.5, 10.0, -10.0), -Vec3::Y);
        let (t, part) = c.intersect(&down, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Top);
        assert!((t - 8.0).abs() < 1e-6);
        let (_, n, _) = c.surface(&down, t, part);
        assert_eq!(n, Vec3A::Y);
        let up = Ray::new(Vec3::new(0.5, -5.0, -10.0), Vec3::Y);
        let (t, part) = c.intersect(&up, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Bottom);
        assert!((t - 4.0).abs() < 1e-6);
        assert_eq!(c.crossings(&up, f32::INFINITY), 2);
    }

    #[test]
    fn misses_above_beside_and_behind() {
        let c = cyl();
        assert!(
            c.intersect(&Ray::new(Vec3::new(0.0, 2.5, 0.0), -Vec3::Z), f32::INFINITY)
                .is_none()
        );
        assert!(
            c.intersect(&Ray::new(Vec3::new(2.5, 0.0, 0.0), -Vec3::Z), f32::INFINITY)
                .is_none()
        );
        assert!(
            c.intersect(&Ray::new(Vec3::ZERO, Vec3::Z), f32::INFINITY)
                .is_none()
        );
        // Parallel to the axis, outside the radius.
        assert!(
            c.intersect(
                &Ray::new(Vec3::new(3.0, 5.0, -10.0), -Vec3::Y),
                f32::INFINITY
            )
            .is_none()
        );
    }

    #[test]
    fn open_tube_lets_rays_through_its_ends_and_shows_its_inside() {
        let c = cyl().with_caps(false);
        let down = Ray::new(Vec3::new(0.5, 10.0, -10.0), -Vec3::Y);
        assert!(c.intersect(&down, f32::INFINITY).is_none());
        assert_eq!(c.crossings(&down, f32::INFINITY), 0);
        // Down into the tube at a slant: the inside of the far wall.
        let slant = Ray::new(Vec3::new(0.0, 3.0, -10.0), Vec3::new(1.0, -1.0, 0.0));
        let (t, part) = c.intersect(&slant, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Side);
        assert!((t - 2.0).abs() < 1e-6);
        let (p, n, _) = c.surface(&slant, t, part);
        assert!((p - Vec3A::new(2.0, 1.0, -10.0)).length() < 1e-5);
        assert!(n.dot(slant.dir) > 0.0, "seen from inside");
    }

    #[test]
    fn ray_from_inside_exits_through_side() {
        let c = cyl();
        let ray = Ray::new(Vec3::new(0.0, 0.0, -10.0), Vec3::X);
        let (t, part) = c.intersect(&ray, f32::INFINITY).unwrap();
        assert_eq!(part, CylinderPart::Side);
        assert!((t - 2.0).abs() < 1e-6);
        assert_eq!(c.crossings(&ray, f32::INFINITY), 1);
    }
}
