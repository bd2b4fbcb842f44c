//! Axis-aligned boxes as solids (a turned box is one under a transform), by the slab test:
//! one interval per axis, so no ray slips between two faces at an edge.

use super::aabb::Aabb;
use super::ray::{Ray, RayQuery};
use super::uv_frame::UvFrame;
use crate::numerics::gamma;
use glam::{Vec3, Vec3A};

/// A solid box between two corners.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid {
    /// The corner with the smallest coordinates.
    pub min: Vec3A,
    /// The corner with the largest coordinates.
    pub max: Vec3A,
}

/// One of a box's six faces: the axis it faces along (0 = x, 1 = y, 2 = z) and whether
/// it is the face at the larger coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CuboidFace {
    /// 0, 1 or 2.
    pub axis: u8,
    /// The face at `max` (its normal points along +axis).
    pub upper: bool,
}

impl Cuboid {
    /// The box between `min` and `max` (every coordinate of `min` below `max`'s).
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self {
            min: min.into(),
            max: max.into(),
        }
    }

    /// Where the ray's line enters and leaves the box, with the faces, when it meets it.
    #[inline]
    fn span(&self, q: &RayQuery) -> Option<((f32, CuboidFace), (f32, CuboidFace))> {
        let o = q.ray.origin;
        let inv = q.inv_dir;
        let a = (self.min - o) * inv;
        let b = (self.max - o) * inv;
        let mut near = (f32::NEG_INFINITY, CuboidFace::X_LOWER);
        let mut far = (f32::INFINITY, CuboidFace::X_LOWER);
        for axis in 0..3 {
            let (lo, hi) = (a[axis], b[axis]);
            // A ray lying in a face's plane gives 0·∞ = NaN there: that axis then bounds
            // nothing, and the other two decide.
            if lo.is_nan() || hi.is_nan() {
                continue;
            }
            let enters_upper = inv[axis] < 0.0;
            let (t_in, t_out) = if enters_upper { (hi, lo) } else { (lo, hi) };
            if t_in > near.0 {
                near = (t_in, CuboidFace::new(axis, enters_upper));
            }
            if t_out < far.0 {
                far = (t_out, CuboidFace::new(axis, !enters_upper));
            }
        }
        (near.0 <= far.0 && near.0.is_finite() && far.0.is_finite()).then_some((near, far))
    }

    /// The nearest hit with t in (t_min, t_max), and its face.
    #[inline]
    pub fn intersect_after(
        &self,
        q: &RayQuery,
        t_min: f32,
        t_max: f32,
    ) -> Option<(f32, CuboidFace)> {
        let (near, far) = self.span(q)?;
        [near, far]
            .into_iter()
            .find(|&(t, _)| t > t_min && t < t_max)
    }

    /// How many times the segment (0, t_max) crosses the surface.
    #[inline]
    pub fn crossings(&self, q: &RayQuery, t_max: f32) -> u32 {
        match self.span(q) {
            Some((near, far)) => {
                (near.0 > 0.0 && near.0 < t_max) as u32 + (far.0 > 0.0 && far.0 < t_max) as u32
            }
            None => 0,
        }
    }

    /// Hit point (put exactly on its face's plane), outward unit normal and error bound.
    #[inline]
    pub fn surface(&self, ray: &Ray, t: f32, face: CuboidFace) -> (Vec3A, Vec3A, Vec3A) {
        let k = face.axis as usize;
        let mut p = ray.at(t);
        p[k] = if face.upper { self.max[k] } else { self.min[k] };
        // The two other coordinates come from o + t·d (t from one slab's division).
        let mut error = (ray.origin.abs() + (ray.dir * t).abs()) * gamma(7);
        error[k] = 0.0;
        let mut n = Vec3A::ZERO;
        n[k] = if face.upper { 1.0 } else { -1.0 };
        (p, n, error)
    }

    /// Each face shows the whole of [0, 1]², upright as seen from outside (v runs down,
    /// as an image's does); the top and bottom are upright seen from +z.
    pub fn uv(&self, p: Vec3A, face: CuboidFace) -> (f32, f32) {
        let f = ((p - self.min) / (self.max - self.min)).clamp(Vec3A::ZERO, Vec3A::ONE);
        match (face.axis, face.upper) {
            (0, true) => (1.0 - f.z, 1.0 - f.y),
            (0, false) => (f.z, 1.0 - f.y),
            (1, true) => (f.x, f.z),
            (1, false) => (f.x, 1.0 - f.z),
            (_, true) => (f.x, 1.0 - f.y),
            (_, false) => (1.0 - f.x, 1.0 - f.y),
        }
    }

    /// The texture coordinates at `p` on `face` and their tangents (constant on a face).
    pub fn uv_frame(&self, p: Vec3A, face: CuboidFace) -> UvFrame {
        let s = self.max - self.min;
        let (x, y, z) = (
            Vec3A::new(s.x, 0.0, 0.0),
            Vec3A::new(0.0, s.y, 0.0),
            Vec3A::new(0.0, 0.0, s.z),
        );
        let (dpdu, dpdv) = match (face.axis, face.upper) {
            (0, true) => (-z, -y),
            (0, false) => (z, -y),
            (1, true) => (x, z),
            (1, false) => (x, -z),
            (_, true) => (x, -y),
            (_, false) => (-x, -y),
        };
        UvFrame {
            uv: self.uv(p, face),
            dpdu,
            dpdv,
        }
    }

    /// The box itself.
    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: self.min.into(),
            max: self.max.into(),
        }
    }
}

impl CuboidFace {
    const X_LOWER: CuboidFace = CuboidFace {
        axis: 0,
        upper: false,
    };

    fn new(axis: usize, upper: bool) -> Self {
        Self {
            axis: axis as u8,
            upper,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Cuboid {
        Cuboid::new(Vec3::new(-1.0, 0.0, -12.0), Vec3::new(1.0, 2.0, -8.0))
    }

    fn query(o: Vec3, d: Vec3) -> RayQuery {
        RayQuery::new(Ray::new(o, d))
    }

    #[test]
    fn enters_front_face_and_leaves_back() {
        let q = query(Vec3::new(0.25, 1.0, 0.0), -Vec3::Z);
        let (t, face) = unit().intersect_after(&q, 0.0, f32::INFINITY).unwrap();
        assert_eq!((t, face), (8.0, CuboidFace::new(2, true)));
        let (p, n, _) = unit().surface(&q.ray, t, face);
        assert_eq!(p, Vec3A::new(0.25, 1.0, -8.0));
        assert_eq!(n, Vec3A::Z);
        let (t, face) = unit().intersect_after(&q, 8.0, f32::INFINITY).unwrap();
        assert_eq!((t, face), (12.0, CuboidFace::new(2, false)));
        assert_eq!(unit().crossings(&q, f32::INFINITY), 2);
        assert_eq!(unit().crossings(&q, 10.0), 1);
    }

    #[test]
    fn oblique_hit_on_a_side_face() {
        // From (5, 1, −10) towards −x and a little +y: meets x = 1 at t = 4.
        let d = Vec3::new(-1.0, 0.125, 0.0);
        let q = query(Vec3::new(5.0, 1.0, -10.0), d);
        let (t, face) = unit().intersect_after(&q, 0.0, f32::INFINITY).unwrap();
        assert_eq!(face, CuboidFace::new(0, true));
        assert!((t - 4.0).abs() < 1e-6);
        let (p, n, e) = unit().surface(&q.ray, t, face);
        assert_eq!(n, Vec3A::X);
        assert_eq!(p.x, 1.0);
        assert!((p.y - 1.5).abs() <= e.y && e.x == 0.0);
    }

    #[test]
    fn misses_beside_and_behind_and_along_a_face_plane() {
        let b = unit();
        let miss = [
            query(Vec3::new(1.5, 1.0, 0.0), -Vec3::Z),
            query(Vec3::new(0.0, 1.0, 0.0), Vec3::Z),
            query(Vec3::new(0.0, 3.0, -10.0), Vec3::X),
        ];
        for q in miss {
            assert!(b.intersect_after(&q, 0.0, f32::INFINITY).is_none(), "{q:?}");
        }
    }

    #[test]
    fn from_inside_leaves_through_one_face() {
        let q = query(Vec3::new(0.0, 1.0, -10.0), Vec3::Y);
        let (t, face) = unit().intersect_after(&q, 0.0, f32::INFINITY).unwrap();
        assert_eq!((t, face), (1.0, CuboidFace::new(1, true)));
        assert_eq!(unit().crossings(&q, f32::INFINITY), 1);
    }

    #[test]
    fn every_face_shows_its_picture_upright_from_outside() {
        let b = Cuboid::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        // Seen from outside, the point up and to the right of each face's centre must have
        // u > 0.5 (right) and v < 0.5 (up): right = up × outward normal.
        let faces = [
            (Vec3A::X, Vec3A::Y),
            (-Vec3A::X, Vec3A::Y),
            (Vec3A::Z, Vec3A::Y),
            (-Vec3A::Z, Vec3A::Y),
            (Vec3A::Y, -Vec3A::Z),
            (-Vec3A::Y, Vec3A::Z),
        ];
        for (n, up) in faces {
            let right = up.cross(n);
            let p = n + (right + up) * 0.5;
            let axis = n.abs().max_position();
            let face = CuboidFace::new(axis, n[axis] > 0.0);
            let (u, v) = b.uv(p, face);
            assert!(
                (u - 0.75).abs() < 1e-6 && (v - 0.25).abs() < 1e-6,
                "{n}: {u} {v}"
            );
        }
    }
}
