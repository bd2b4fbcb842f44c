//! A ray, and the per-ray constants that every intersection test of that ray shares.

use glam::Vec3;

/// A half-line `origin + t·dir`, t > 0. `dir` need not be unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
}

impl Ray {
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self { origin, dir }
    }

    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// A ray together with what the box test and the watertight triangle test precompute once
/// per ray instead of once per primitive.
#[derive(Clone, Copy, Debug)]
pub struct RayQuery {
    pub ray: Ray,
    pub inv_dir: Vec3,
    /// The axis along which `dir` is largest, and the two others in cyclic order (swapped
    /// so the triangle winding is preserved when `dir` points down that axis).
    pub kz: usize,
    pub kx: usize,
    pub ky: usize,
    /// The shear that maps `dir` to the +z unit axis (Woop, Benthin and Wald 2013).
    pub shear: Vec3,
}

impl RayQuery {
    pub fn new(ray: Ray) -> Self {
        let d = ray.dir;
        let abs = d.abs();
        let kz = if abs.x > abs.y {
            if abs.x > abs.z { 0 } else { 2 }
        } else if abs.y > abs.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let shear = Vec3::new(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
        Self {
            ray,
            inv_dir: d.recip(),
            kz,
            kx,
            ky,
            shear,
        }
    }
}
