//! Affine transforms between an object's own space and the scene's, with the rounding
//! bounds that keep hit points and spawned rays robust across the change of space
//! (pbrt-v4, section 6.8.6).

use super::aabb::Aabb;
use super::ray::Ray;
use crate::numerics::gamma;
use glam::{Affine3A, Mat3A, Vec3, Vec3A};

/// An invertible affine map from an object's space to the scene's, with its inverse and
/// the inverse transpose that carries normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    to_scene: Affine3A,
    to_object: Affine3A,
    /// The inverse transpose of `to_scene`'s linear part.
    normal_to_scene: Mat3A,
    /// |to_scene|'s linear part and translation, entry by entry: bounds on rounding.
    abs_to_scene: Mat3A,
    abs_translation: Vec3A,
    abs_to_object: Mat3A,
    abs_to_object_translation: Vec3A,
}

impl Transform {
    /// The transform `to_scene`; None when it is not invertible, or its inverse is not
    /// finite.
    pub fn new(to_scene: Affine3A) -> Option<Self> {
        let det = to_scene.matrix3.determinant();
        if !(det.is_finite() && det != 0.0 && to_scene.translation.is_finite()) {
            return None;
        }
        let to_object = to_scene.inverse();
        if !(to_object.matrix3.is_finite() && to_object.translation.is_finite()) {
            return None;
        }
        let abs = |m: Mat3A| Mat3A::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs());
        Some(Self {
            to_scene,
            to_object,
            normal_to_scene: to_object.matrix3.transpose(),
            abs_to_scene: abs(to_scene.matrix3),
            abs_translation: to_scene.translation.abs(),
            abs_to_object: abs(to_object.matrix3),
            abs_to_object_translation: to_object.translation.abs(),
        })
    }

    /// Scale, then rotate by `rotate_degrees` (about x, then y, then z, each right-handed,
    /// as POV-Ray's `rotate`), then translate.
    pub fn from_scale_rotation_translation(
        scale: Vec3,
        rotate_degrees: Vec3,
        translate: Vec3,
    ) -> Option<Self> {
        let [x, y, z] = rotate_degrees.to_array().map(f32::to_radians);
        let rotation =
            Mat3A::from_rotation_z(z) * Mat3A::from_rotation_y(y) * Mat3A::from_rotation_x(x);
        let linear = rotation * Mat3A::from_diagonal(scale);
        Self::new(Affine3A::from_mat3_translation(linear.into(), translate))
    }

    /// The map from object space to the scene's.
    pub fn to_scene(&self) -> Affine3A {
        self.to_scene
    }

    /// `self` after `outer`: object space → this transform's scene → `outer`'s scene.
    pub fn then(&self, outer: Affine3A) -> Option<Self> {
        Self::new(outer * self.to_scene)
    }

    /// The ray in object space. The direction is not renormalised, so a distance parameter
    /// t names the same point in both spaces.
    #[inline]
    pub fn ray_to_object(&self, ray: &Ray) -> Ray {
        Ray {
            origin: self.to_object.transform_point3a(ray.origin),
            dir: self.to_object.matrix3 * ray.dir,
        }
    }

    /// A point of object space in the scene's, with the bound on its error there: the
    /// object-space bound `error` carried through, plus the rounding of this map, plus the
    /// rounding of the map back, so that a ray leaving the point beyond the bound is still
    /// off the surface once it is taken back into object space.
    #[inline]
    pub fn point_to_scene(&self, p: Vec3A, error: Vec3A) -> (Vec3A, Vec3A) {
        let point = self.to_scene.transform_point3a(p);
        let carried = self.abs_to_scene * error * (1.0 + gamma(3));
        let forward = (self.abs_to_scene * p.abs() + self.abs_translation) * gamma(3);
        let back_in_object =
            (self.abs_to_object * point.abs() + self.abs_to_object_translation) * gamma(3);
        let back = self.abs_to_scene * back_in_object * (1.0 + gamma(3));
        (point, carried + forward + back)
    }

    /// An object-space normal in the scene's, unit length.
    #[inline]
    pub fn normal_to_scene(&self, n: Vec3A) -> Vec3A {
        (self.normal_to_scene * n).normalize()
    }

    /// A scene point in object space.
    #[inline]
    pub fn point_to_object(&self, p: Vec3A) -> Vec3A {
        self.to_object.transform_point3a(p)
    }

    /// An object-space direction (a tangent, not a normal) in the scene's, its length
    /// carried with it.
    #[inline]
    pub fn vector_to_scene(&self, v: Vec3A) -> Vec3A {
        self.to_scene.matrix3 * v
    }

    /// The box in the scene's space around an object-space box (its corners mapped, and
    /// widened by the rounding of the map).
    pub fn bounds_to_scene(&self, b: &Aabb) -> Aabb {
        if b.is_empty() {
            return *b;
        }
        let mut out = Aabb::EMPTY;
        for p in b.corners() {
            let (q, e) = self.point_to_scene(p.into(), Vec3A::ZERO);
            out = out.grow((q - e).into()).grow((q + e).into());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3A, b: Vec3A) -> bool {
        (a - b).abs().max_element() < 1e-6
    }

    /// POV-Ray's convention: +90 about y turns +x into −z; x first, then y, then z.
    #[test]
    fn rotation_follows_povray() {
        let t = Transform::from_scale_rotation_translation(
            Vec3::ONE,
            Vec3::new(0.0, 90.0, 0.0),
            Vec3::ZERO,
        )
        .unwrap();
        assert!(close(t.to_scene.transform_point3a(Vec3A::X), -Vec3A::Z));
        // +90 about x turns +y into +z; then +90 about z turns +z into +z and +x into +y.
        let t = Transform::from_scale_rotation_translation(
            Vec3::ONE,
            Vec3::new(90.0, 0.0, 90.0),
            Vec3::ZERO,
        )
        .unwrap();
        assert!(close(t.to_scene.transform_point3a(Vec3A::Y), Vec3A::Z));
        assert!(close(t.to_scene.transform_point3a(Vec3A::X), Vec3A::Y));
    }

    #[test]
    fn scale_then_rotate_then_translate() {
        let t = Transform::from_scale_rotation_translation(
            Vec3::new(2.0, 1.0, 1.0),
            Vec3::new(0.0, 0.0, 90.0),
            Vec3::new(0.0, 0.0, 5.0),
        )
        .unwrap();
        // x scaled to 2, turned onto +y, moved 5 along z.
        assert!(close(
            t.to_scene.transform_point3a(Vec3A::X),
            Vec3A::new(0.0, 2.0, 5.0)
        ));
    }

    /// A ray and its object-space image name the same points by the same t.
    #[test]
    fn rays_keep_their_parameter() {
        let t = Transform::from_scale_rotation_translation(
            Vec3::new(3.0, 0.5, 2.0),
            Vec3::new(10.0, 20.0, 30.0),
            Vec3::new(1.0, -2.0, 3.0),
        )
        .unwrap();
        let ray = Ray::new(Vec3::new(0.3, 0.2, 9.0), Vec3::new(0.1, -0.2, -1.0));
        let local = t.ray_to_object(&ray);
        for s in [0.5f32, 2.0, 7.0] {
            let (back, err) = t.point_to_scene(local.at(s), Vec3A::ZERO);
            assert!((back - ray.at(s)).abs().cmple(err * 4.0 + 1e-5).all());
        }
    }

    /// Normals stay perpendicular to surfaces under non-uniform scale.
    #[test]
    fn normals_use_the_inverse_transpose() {
        let t = Transform::from_scale_rotation_translation(
            Vec3::new(4.0, 1.0, 1.0),
            Vec3::ZERO,
            Vec3::ZERO,
        )
        .unwrap();
        // The plane x + y = 1 in object space has normal (1, 1, 0); scaled, it is
        // x/4 + y = 1, with normal (1/4, 1, 0).
        let n = t.normal_to_scene(Vec3A::new(1.0, 1.0, 0.0).normalize());
        assert!(close(n, Vec3A::new(0.25, 1.0, 0.0).normalize()));
    }

    #[test]
    fn singular_maps_are_refused() {
        assert!(
            Transform::from_scale_rotation_translation(
                Vec3::new(1.0, 0.0, 1.0),
                Vec3::ZERO,
                Vec3::ZERO
            )
            .is_none()
        );
        assert!(Transform::new(Affine3A::from_translation(Vec3::splat(f32::NAN))).is_none());
    }

    #[test]
    fn boxes_contain_their_mapped_corners() {
        let t = Transform::from_scale_rotation_translation(
            Vec3::splat(2.0),
            Vec3::new(0.0, 45.0, 0.0),
            Vec3::new(10.0, 0.0, 0.0),
        )
        .unwrap();
        let b = t.bounds_to_scene(&Aabb::from_points(&[Vec3::splat(-1.0), Vec3::splat(1.0)]));
        let half = 2.0 * std::f32::consts::SQRT_2;
        assert!((b.max.x - (10.0 + half)).abs() < 1e-4 && (b.min.x - (10.0 - half)).abs() < 1e-4);
        assert!((b.max.y - 2.0).abs() < 1e-4);
    }
}
