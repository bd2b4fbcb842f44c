//! Axis-aligned bounding boxes and the slab test.

use super::ray::RayQuery;
use crate::numerics::gamma;
use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn from_points(points: &[Vec3]) -> Self {
        points.iter().fold(Self::EMPTY, |b, &p| b.grow(p))
    }

    pub fn grow(self, p: Vec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    pub fn union(self, other: Aabb) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    pub fn centroid(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x
    }

    /// Half the surface area: the SAH only compares areas, so the factor 2 is dropped.
    pub fn half_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.max - self.min;
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// The entry distance of the ray into the box if it enters before `t_max`.
    /// Robust against rounding (the far distance is widened by 2γ(3), pbrt-v4 6.1.2) and
    /// against zero direction components (the NaN of 0·∞ falls out of min/max).
    #[inline]
    pub fn hit(&self, q: &RayQuery, t_max: f32) -> Option<f32> {
        let t0 = (self.min - q.ray.origin) * q.inv_dir;
        let t1 = (self.max - q.ray.origin) * q.inv_dir;
        let near = t0.min(t1);
        let far = t0.max(t1) * (1.0 + 2.0 * gamma(3));
        let t_enter = near.max_element().max(0.0);
        let t_exit = far.min_element().min(t_max);
        (t_enter <= t_exit).then_some(t_enter)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;

    #[test]
    fn slab_test_hits_and_misses() {
        let b = Aabb::from_points(&[Vec3::splat(-1.0), Vec3::splat(1.0)]);
        let q = RayQuery::new(Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z));
        assert_eq!(b.hit(&q, f32::INFINITY), Some(4.0));
        assert_eq!(b.hit(&q, 3.0), None);
        let miss = RayQuery::new(Ray::new(Vec3::new(2.0, 0.0, 5.0), -Vec3::Z));
        assert_eq!(b.hit(&miss, f32::INFINITY), None);
        let inside = RayQuery::new(Ray::new(Vec3::ZERO, Vec3::X));
        assert_eq!(b.hit(&inside, f32::INFINITY), Some(0.0));
    }

    #[test]
    fn flat_box_is_hit_by_axis_parallel_ray_on_its_face() {
        // A box of zero thickness (a floor polygon) seen edge-on along its own plane.
        let b = Aabb::from_points(&[Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0)]);
        let q = RayQuery::new(Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X));
        assert_eq!(b.hit(&q, f32::INFINITY), Some(4.0));
    }
}
