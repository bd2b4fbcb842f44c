//! Triangles, intersected watertight (Woop, Benthin and Wald 2013): a ray aimed exactly at
//! an edge or vertex shared by two triangles hits at least one of them.

use super::aabb::Aabb;
use super::ray::RayQuery;
use crate::numerics::gamma;
use glam::{Vec3, Vec3A};

/// A triangle, with its normal precomputed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// Its corners, in winding order.
    pub p: [Vec3A; 3],
    /// Unit normal by the right-hand rule over p0, p1, p2.
    pub normal: Vec3A,
}

/// Where on a triangle a ray hit it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// The distance parameter along the ray.
    pub t: f32,
    /// Barycentric weights of p0, p1, p2.
    pub b: [f32; 3],
}

impl Triangle {
    /// None when the corners are collinear or coincide (no area, no normal).
    pub fn new(p0: Vec3, p1: Vec3, p2: Vec3) -> Option<Self> {
        let normal = crate::numerics::try_normalize((p1 - p0).cross(p2 - p0))?;
        Some(Self {
            p: [p0.into(), p1.into(), p2.into()],
            normal: normal.into(),
        })
    }

    /// The nearest hit in (0, t_max), watertight (no ray passes between two triangles that share an edge).
    #[inline]
    pub fn intersect(&self, q: &RayQuery, t_max: f32) -> Option<TriangleHit> {
        self.intersect_after(q, 0.0, t_max)
    }

    /// The hit with t in (t_min, t_max), t_min ≥ 0.
    #[inline]
    pub fn intersect_after(&self, q: &RayQuery, t_min: f32, t_max: f32) -> Option<TriangleHit> {
        watertight(&self.p, q, t_min, t_max)
    }

    /// The hit point from the barycentric weights (accurate regardless of the ray's length)
    /// and its error bound (pbrt-v4, section 6.8.4).
    #[inline]
    pub fn surface(&self, hit: &TriangleHit) -> (Vec3A, Vec3A) {
        barycentric_point(&self.p, hit.b)
    }

    /// The box around the triangle.
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.p.map(Vec3::from))
    }
}

/// The watertight test of the ray against the triangle with corners `p` (in winding
/// order): the hit with t in (t_min, t_max), t_min ≥ 0. Shared by lone triangles and
/// mesh triangles, which store their corners differently.
#[inline(always)]
pub fn watertight(p: &[Vec3A; 3], q: &RayQuery, t_min: f32, t_max: f32) -> Option<TriangleHit> {
    let s = q.shear;
    // Translate to the ray origin, permute so the ray's largest axis is z, then shear so
    // the ray runs along +z.
    let [ax, ay, a_z] = q.axes.permute(p[0] - q.ray.origin);
    let [bx, by, b_z] = q.axes.permute(p[1] - q.ray.origin);
    let [cx, cy, c_z] = q.axes.permute(p[2] - q.ray.origin);
    let ax = ax - s.x * a_z;
    let ay = ay - s.y * a_z;
    let bx = bx - s.x * b_z;
    let by = by - s.y * b_z;
    let cx = cx - s.x * c_z;
    let cy = cy - s.y * c_z;
    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    // An edge function of exactly zero is ambiguous in f32: decide it in f64, where the
    // products of f32 values are exact.
    if u == 0.0 || v == 0.0 || w == 0.0 {
        let (ax, ay, bx, by, cx, cy) = (
            ax as f64, ay as f64, bx as f64, by as f64, cx as f64, cy as f64,
        );
        u = (cx * by - cy * bx) as f32;
        v = (ax * cy - ay * cx) as f32;
        w = (bx * ay - by * ax) as f32;
    }
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    let az = s.z * a_z;
    let bz = s.z * b_z;
    let cz = s.z * c_z;
    let t_scaled = u * az + v * bz + w * cz;
    // t = t_scaled / det must lie in (0, t_max); compare without dividing.
    if det < 0.0 && (t_scaled >= 0.0 || t_scaled < t_max * det) {
        return None;
    }
    if det > 0.0 && (t_scaled <= 0.0 || t_scaled > t_max * det) {
        return None;
    }
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    if t <= t_min || t >= t_max || t.is_nan() {
        return None;
    }
    // A t this close to 0 may be rounding of a triangle the ray starts on or beside (a
    // shadow ray leaving a floor, say): only a t beyond its error bound is a hit
    // (pbrt-v4, section 6.5.3).
    let max_x = largest_magnitude(ax, bx, cx);
    let max_y = largest_magnitude(ay, by, cy);
    let max_z = largest_magnitude(az, bz, cz);
    // x and y were sheared by z before z was scaled by 1/d_z: their rounding grows with
    // z in the scene's units. (pbrt takes the scaled z, the same for a unit direction, but
    // far too large for the short directions of rays taken into a large instance's space,
    // where it rejected real hits.)
    let max_z_unscaled = largest_magnitude(a_z, b_z, c_z);
    let delta_x = gamma(5) * (max_x + max_z_unscaled);
    let delta_y = gamma(5) * (max_y + max_z_unscaled);
    let delta_z = gamma(3) * max_z;
    let delta_e = 2.0 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
    let max_e = largest_magnitude(u, v, w);
    let delta_t =
        3.0 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * inv_det.abs();
    if t <= delta_t {
        return None;
    }
    Some(TriangleHit {
        t,
        b: [u * inv_det, v * inv_det, w * inv_det],
    })
}

/// The point with barycentric weights `b` over corners `p`, and its error bound.
#[inline(always)]
pub fn barycentric_point(p: &[Vec3A; 3], b: [f32; 3]) -> (Vec3A, Vec3A) {
    let t0 = p[0] * b[0];
    let t1 = p[1] * b[1];
    let t2 = p[2] * b[2];
    let point = t0 + t1 + t2;
    let error = (t0.abs() + t1.abs() + t2.abs()) * gamma(7);
    (point, error)
}

/// max(|a|, |b|, |c|) for finite values, in plain comparisons (`f32::max` also orders NaN,
/// which costs instructions and cannot occur here).
#[inline(always)]
fn largest_magnitude(a: f32, b: f32, c: f32) -> f32 {
    let (a, b, c) = (a.abs(), b.abs(), c.abs());
    let ab = if a > b { a } else { b };
    if ab > c { ab } else { c }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;

    fn tri() -> Triangle {
        Triangle::new(
            Vec3::new(-1.0, -1.0, -5.0),
            Vec3::new(1.0, -1.0, -5.0),
            Vec3::new(0.0, 1.0, -5.0),
        )
        .unwrap()
    }

    fn query(origin: Vec3, dir: Vec3) -> RayQuery {
        RayQuery::new(Ray::new(origin, dir))
    }

    /// A ray's direction may be far from unit length (a ray taken into the space of an
    /// instance scaled by 1000 is 1000 times shorter there): what it hits, and where,
    /// must not depend on that.
    #[test]
    fn hits_do_not_depend_on_the_directions_length() {
        let t = Triangle::new(
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.1, 0.0, 0.0),
            Vec3::new(0.0, 0.1, 0.0),
        )
        .unwrap();
        let origin = Vec3::new(0.02, 0.03, 67.0);
        for scale in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
            let q = query(origin, Vec3::new(0.0001, 0.0002, -1.0) * scale);
            let h = t
                .intersect(&q, f32::INFINITY)
                .unwrap_or_else(|| panic!("{scale}"));
            let t_unit = 67.0 / scale;
            assert!((h.t - t_unit).abs() < 1e-5 * t_unit, "{scale}: {}", h.t);
        }
    }

    #[test]
    fn a_ray_leaving_just_above_a_large_triangle_does_not_hit_it() {
        // A shadow ray from a point of the seed's floor (80 × 160 units, two triangles),
        // offset above it by the hit point's error bound, towards the light: the computed
        // t of the plane it leaves is rounding, a few ulps either side of 0.
        let (a, b, c, d) = (
            Vec3::new(-40.0, -15.0, -40.0),
            Vec3::new(40.0, -15.0, -40.0),
            Vec3::new(40.0, -15.0, -200.0),
            Vec3::new(-40.0, -15.0, -200.0),
        );
        let floor = [
            Triangle::new(a, b, c).unwrap(),
            Triangle::new(a, c, d).unwrap(),
        ];
        let light = Vec3::new(10.0, 40.0, -3.0);
        for origin in [
            Vec3::new(-37.22461, -14.999994, -118.25191),
            Vec3::new(-32.48696, -14.999994, -103.73628),
            Vec3::new(-19.969675, -14.999994, -81.29124),
        ] {
            let q = query(origin, light - origin);
            for t in &floor {
                assert_eq!(t.intersect(&q, 1.0), None, "from {origin}");
            }
        }
    }

    #[test]
    fn hit_in_the_middle_with_barycentrics() {
        let t = tri();
        let h = t
            .intersect(&query(Vec3::ZERO, -Vec3::Z), f32::INFINITY)
            .unwrap();
        assert!((h.t - 5.0).abs() < 1e-6);
        assert!((h.b.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        let (p, _) = t.surface(&h);
        assert!((p - Vec3A::new(0.0, 0.0, -5.0)).length() < 1e-6);
        assert_eq!(t.normal, Vec3A::Z);
    }

    #[test]
    fn hits_from_behind_too() {
        let t = tri();
        let h = t.intersect(&query(Vec3::new(0.0, 0.0, -10.0), Vec3::Z), f32::INFINITY);
        assert!((h.unwrap().t - 5.0).abs() < 1e-6);
    }

    #[test]
    fn misses_outside_behind_and_parallel() {
        let t = tri();
        assert!(
            t.intersect(&query(Vec3::new(2.0, 0.0, 0.0), -Vec3::Z), f32::INFINITY)
                .is_none()
        );
        assert!(
            t.intersect(&query(Vec3::ZERO, Vec3::Z), f32::INFINITY)
                .is_none()
        );
        assert!(
            t.intersect(&query(Vec3::new(0.0, 0.0, -5.0), Vec3::X), f32::INFINITY)
                .is_none()
        );
        assert!(t.intersect(&query(Vec3::ZERO, -Vec3::Z), 4.0).is_none());
    }

    #[test]
    fn shared_edge_is_watertight() {
        // Two triangles sharing the diagonal of a unit square; rays exactly on the diagonal.
        let a = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0)).unwrap();
        let b = Triangle::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), Vec3::Y).unwrap();
        for i in 0..=64 {
            let s = i as f32 / 64.0;
            let q = query(Vec3::new(s, s, 3.0), Vec3::new(0.0, 0.0, -1.0));
            let hit = a
                .intersect(&q, f32::INFINITY)
                .or(b.intersect(&q, f32::INFINITY));
            assert!(hit.is_some(), "ray at {s} slipped between the triangles");
        }
    }

    #[test]
    fn degenerate_triangle_is_rejected() {
        assert!(Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0).is_none());
        assert!(Triangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::Y).is_none());
    }
}
