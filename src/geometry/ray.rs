//! A ray, and the per-ray constants that every intersection test of that ray shares.

use glam::Vec3A;

/// A half-line `origin + t·dir`, t > 0. `dir` need not be unit length.
///
/// Vectors on the hot path are glam's `Vec3A`: one SIMD register each, so that every
/// operation is one instruction instead of three scalar ones or a shuffle. Lane by lane the
/// arithmetic is the same IEEE arithmetic in the same order, so results are bit for bit
/// those of `Vec3`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3A,
    /// Its direction (unit length for camera rays; a shadow ray's spans to the light).
    pub dir: Vec3A,
}

impl Ray {
    /// A ray from `origin` along `dir`.
    #[inline]
    pub fn new(origin: impl Into<Vec3A>, dir: impl Into<Vec3A>) -> Self {
        Self {
            origin: origin.into(),
            dir: dir.into(),
        }
    }

    /// The point at distance parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3A {
        self.origin + self.dir * t
    }

    /// How far the origin lies from 0, in units of the direction (largest coordinates):
    /// with t, the scale of the rounding of points along the ray.
    #[inline]
    pub fn origin_scale(&self) -> f32 {
        self.origin.abs().max_element() / self.dir.abs().max_element()
    }
}

/// A ray together with what the box test and the watertight triangle test precompute once
/// per ray instead of once per primitive.
#[derive(Clone, Copy, Debug)]
pub struct RayQuery {
    /// The ray itself.
    pub ray: Ray,
    /// 1 / direction, per axis, for box tests.
    pub inv_dir: Vec3A,
    /// The axis along which `dir` is largest (z), and the two others in cyclic order (x, y;
    /// swapped so the triangle winding is preserved when `dir` points down that axis).
    pub axes: Axes,
    /// The shear that maps `dir` to the +z unit axis (Woop, Benthin and Wald 2013).
    pub shear: Vec3A,
}

/// A permutation of the coordinate axes, applied without branches: glam's `v[k]` with a
/// run-time `k` compiles to a chain of compares, and on rays of mixed directions those
/// branches mispredict.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Axes {
    pub x: usize,
    pub y: usize,
    pub z: usize,
}

impl Axes {
    /// `v`'s coordinates along the permuted x, y and z axes.
    #[inline(always)]
    pub fn permute(&self, v: Vec3A) -> [f32; 3] {
        let a = v.extend(0.0).to_array();
        // `& 3` proves the index in bounds of the four-element array: no check, no branch.
        [a[self.x & 3], a[self.y & 3], a[self.z & 3]]
    }
}

impl RayQuery {
    /// The query for `ray`, with what its intersection tests share precomputed.
    #[inline]
    pub fn new(ray: Ray) -> Self {
        let d = ray.dir;
        let abs = d.abs();
        let z = if abs.x > abs.y {
            if abs.x > abs.z { 0 } else { 2 }
        } else if abs.y > abs.z {
            1
        } else {
            2
        };
        // The next axes in cyclic order, swapped when dir points down z.
        const NEXT: [usize; 4] = [1, 2, 0, 0];
        let (mut x, mut y) = (NEXT[z & 3], NEXT[NEXT[z & 3] & 3]);
        let [dx0, dy0, dz] = Axes { x, y, z }.permute(d);
        let (mut dx, mut dy) = (dx0, dy0);
        if dz < 0.0 {
            std::mem::swap(&mut x, &mut y);
            std::mem::swap(&mut dx, &mut dy);
        }
        // Two packed divisions instead of six scalar ones (the same quotients, each
        // correctly rounded): division is the slowest step of setting up a ray.
        let shear = Vec3A::new(dx, dy, 1.0) / dz;
        let inv_dir = Vec3A::ONE / d;
        Self {
            ray,
            inv_dir,
            axes: Axes { x, y, z },
            shear,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ray_runs_along_the_permuted_z_with_the_winding_kept() {
        for (dir, z) in [
            (Vec3A::new(3.0, 1.0, -2.0), 0),
            (Vec3A::new(-3.0, 1.0, -2.0), 0),
            (Vec3A::new(0.1, 5.0, 2.0), 1),
            (Vec3A::new(0.1, -5.0, 2.0), 1),
            (Vec3A::new(0.0, 0.0, 1.0), 2),
            (Vec3A::new(1.0, -1.0, -1.5), 2),
        ] {
            let q = RayQuery::new(Ray::new(Vec3A::ZERO, dir));
            let Axes { x, y, z: kz } = q.axes;
            assert_eq!(kz, z, "{dir}");
            let mut all = [x, y, kz];
            all.sort();
            assert_eq!(all, [0, 1, 2]);
            // x, y, z cyclic (an even permutation) exactly when dir points up its z axis.
            let cyclic = (x + 1) % 3 == y;
            assert_eq!(cyclic, dir[z] > 0.0, "{dir}");
            // The shear maps dir onto (0, 0, 1).
            let [px, py, pz] = q.axes.permute(dir);
            let s = q.shear;
            assert!((px - s.x * pz).abs() < 1e-6 && (py - s.y * pz).abs() < 1e-6);
            assert!((s.z * pz - 1.0).abs() < 1e-6);
            assert_eq!(q.inv_dir, dir.recip());
        }
    }
}
