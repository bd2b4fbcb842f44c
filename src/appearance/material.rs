//! Phong surface terms and the directions of mirror reflection and refraction.

use super::texture::Texture;
use glam::{Vec3, Vec3A};

/// A Whitted material, as in the seed: Phong local shading, plus a mirror term and a
/// transmitted term that may bend by Snell's law.
///
/// Colour = (1 − transparency)·local + reflectivity·reflected + transparency·transmitted.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The surface colour: a solid colour, a pattern or an image.
    pub texture: Texture,
    /// Multiplies the scene's ambient light.
    pub ambient: f32,
    /// Multiplies the light arriving straight from the lights.
    pub diffuse: f32,
    /// Strength of the Phong highlight.
    pub specular: f32,
    /// Phong exponent: the larger, the smaller and sharper the highlight.
    pub shininess: f32,
    /// Fraction of the mirror-reflected light added, 0..1.
    pub reflectivity: f32,
    /// Fraction of light transmitted through the surface, 0..1.
    pub transparency: f32,
    /// Index of refraction of the inside; None for a surface that transmits without bending.
    pub eta: Option<f32>,
    /// Light the surface gives off itself, added unlit (a glowing lamp, a screen); black
    /// for the seed's materials.
    pub emission: Vec3,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            texture: Texture::Solid(Vec3::splat(0.8)),
            ambient: 1.0,
            diffuse: 1.0,
            specular: 0.5,
            shininess: 50.0,
            reflectivity: 0.0,
            transparency: 0.0,
            eta: None,
            emission: Vec3::ZERO,
        }
    }
}

impl Material {
    /// How much of the light crossing this surface once goes on, tinted by its colour:
    /// the clearer the surface, the less tint (a 90% clear green glass casts a pale green
    /// shadow).
    pub fn shadow_filter(&self) -> Vec3 {
        let t = self.transparency;
        (self.texture.mean() * (1.0 - t) + Vec3::splat(t)) * t
    }
}

/// Mirror reflection of direction `d` about unit normal `n`.
#[inline]
pub fn reflect(d: Vec3A, n: Vec3A) -> Vec3A {
    d - n * (2.0 * d.dot(n))
}

/// Refraction of unit direction `d` through a surface with unit normal `n` facing against
/// `d`, where `eta_ratio` = η(incident side) / η(transmitted side). None on total internal
/// reflection. At a ratio of exactly 1 the direction is returned unchanged, so an eta-1
/// object bends nothing; near 1 the result varies continuously with the ratio.
#[inline]
pub fn refract(d: Vec3A, n: Vec3A, eta_ratio: f32) -> Option<Vec3A> {
    if eta_ratio == 1.0 {
        return Some(d);
    }
    let cos_i = (-d.dot(n)).clamp(0.0, 1.0);
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = eta_ratio * eta_ratio * sin2_i;
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(d * eta_ratio + n * (eta_ratio * cos_i - cos_t))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir_at(angle_deg: f32) -> Vec3A {
        // Travelling down onto the plane y = 0 at `angle` from the normal, in the xy plane.
        let a = angle_deg.to_radians();
        Vec3A::new(a.sin(), -a.cos(), 0.0)
    }

    #[test]
    fn reflection_flips_the_normal_component() {
        let r = reflect(dir_at(30.0), Vec3A::Y);
        assert!((r - Vec3A::new(0.5, 3f32.sqrt() / 2.0, 0.0)).length() < 1e-6);
    }

    #[test]
    fn snell_law_at_a_plane() {
        for (eta, angle) in [(1.5f32, 30.0f32), (1.43, 60.0), (1.002, 45.0), (2.4, 10.0)] {
            let t = refract(dir_at(angle), Vec3A::Y, 1.0 / eta).unwrap();
            assert!((t.length() - 1.0).abs() < 1e-6);
            let sin_t = t.x;
            let expected = angle.to_radians().sin() / eta;
            assert!((sin_t - expected).abs() < 1e-6, "eta {eta} angle {angle}");
            assert!(t.y < 0.0, "the refracted ray continues into the surface");
        }
    }

    #[test]
    fn eta_one_is_the_identity() {
        for angle in [0.0, 10.0, 45.0, 89.9] {
            let d = dir_at(angle);
            assert_eq!(refract(d, Vec3A::Y, 1.0), Some(d));
        }
    }

    #[test]
    fn total_internal_reflection_past_the_critical_angle() {
        // From glass (1.5) into air: critical angle asin(1/1.5) ≈ 41.81°.
        let critical = (1.0f32 / 1.5).asin().to_degrees();
        assert!(refract(dir_at(critical - 0.5), Vec3A::Y, 1.5).is_some());
        assert!(refract(dir_at(critical + 0.5), Vec3A::Y, 1.5).is_none());
        assert!(refract(dir_at(89.999), Vec3A::Y, 1.5).is_none());
    }

    #[test]
    fn refraction_is_continuous_near_eta_one() {
        let d = dir_at(60.0);
        let exact = refract(d, Vec3A::Y, 1.0).unwrap();
        let near = refract(d, Vec3A::Y, 1.0 / 1.002).unwrap();
        let angle = exact.dot(near).clamp(-1.0, 1.0).acos().to_degrees();
        // d(θt)/d(η) = tan θ at η = 1, so 0.002 bends by about 0.002·tan 60° rad ≈ 0.2°.
        assert!(angle > 0.1 && angle < 0.3, "bent by {angle}°");
    }

    #[test]
    fn clear_glass_casts_a_pale_shadow_and_opaque_none() {
        let green = Material {
            texture: Texture::Solid(Vec3::new(0.0, 1.0, 0.0)),
            transparency: 0.9,
            ..Material::default()
        };
        let f = green.shadow_filter();
        assert!((f - Vec3::new(0.81, 0.9, 0.81)).length() < 1e-6);
        let opaque = Material::default();
        assert_eq!(opaque.shadow_filter(), Vec3::ZERO);
    }
}
