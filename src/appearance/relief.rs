//! Relief: a material's surface tilted in shading only. A bump map raises the surface by a
//! height field (a texture's brightness) and shading takes the normal of
//! the raised surface; a normal map gives that normal outright, in the frame of the
//! picture's right, up and the surface's normal (tangent space, as glTF and most tools bake
//! them). The true surface still decides sides, shadows and where rays start.

use super::pattern::Pattern;
use super::texture::{Texture, UvTransform};
use crate::geometry::UvFrame;
use glam::Vec3A;

/// How a material's shading normal is tilted.
#[derive(Clone, Debug, PartialEq)]
pub enum Relief {
    /// The surface raised by `depth` × height along its normal, the height from 0 to 1.
    Bump {
        /// The height field: a pattern or an image, its height the brightness of its colour
        /// (the mean of red, green and blue).
        height: Texture,
        /// How far white stands above black, in scene units; 0 is flat.
        depth: f32,
    },
    /// Normals read from a tangent-space picture: red right, green up the picture, blue
    /// out of the surface, each 0 to 1 standing for −1 to 1.
    NormalMap {
        /// The picture (an image texture).
        map: Texture,
        /// Multiplies the tilt (the red and green parts): 0 is flat, 1 the picture's own.
        strength: f32,
    },
}

impl Relief {
    /// Whether it reads the surface's texture coordinates (its tangents, `UvFrame`).
    pub fn needs_uv(&self) -> bool {
        match self {
            Relief::Bump { height, .. } => height.needs_uv(),
            Relief::NormalMap { .. } => true,
        }
    }

    /// Whether it leaves every normal as it is (a depth or strength of 0).
    pub fn is_flat(&self) -> bool {
        match self {
            Relief::Bump { depth, .. } => *depth == 0.0,
            Relief::NormalMap { strength, .. } => *strength == 0.0,
        }
    }

    /// The tilted shading normal at a point whose shading normal is `ns` (unit, on the
    /// side the surface's normal faces). `solid` gives a pattern's brightness gradient at
    /// the point, in the scene's space (the object's solid textures are in its own);
    /// `frame` gives its texture frame (read only when `needs_uv`). Where the frame gives
    /// no direction (a pole, a degenerate map), `ns` is returned unchanged.
    pub fn shading_normal(
        &self,
        ns: Vec3A,
        solid: impl FnOnce(&Pattern) -> Vec3A,
        frame: impl FnOnce() -> UvFrame,
    ) -> Vec3A {
        if self.is_flat() {
            return ns;
        }
        let tilted = match self {
            Relief::Bump { height, depth } => {
                let gradient = match height {
                    Texture::Pattern(pattern) => solid(pattern),
                    Texture::Image { image, uv } => {
                        let frame = frame();
                        let (u, v) = uv.apply(frame.uv);
                        let slope = image.brightness_slope(u, v);
                        surface_gradient(ns, &frame, picture_to_surface(uv, slope))
                    }
                    // The file takes only patterns and images; anything else is flat.
                    _ => Vec3A::ZERO,
                };
                // The raised surface p + depth·h·n has the normal n − depth·∇h, ∇h taken
                // along the surface.
                ns - (gradient - ns * gradient.dot(ns)) * *depth
            }
            Relief::NormalMap { map, strength } => {
                let Texture::Image { image, uv } = map else {
                    return ns;
                };
                let frame = frame();
                let (u, v) = uv.apply(frame.uv);
                let texel = image.sample(u, v) * 2.0 - Vec3A::ONE;
                let Some((right, up)) = picture_axes(ns, &frame, uv) else {
                    return ns;
                };
                (right * texel.x + up * texel.y) * *strength + ns * texel.z.max(0.0)
            }
        };
        match tilted.try_normalize() {
            Some(n) => n,
            None => ns,
        }
    }

    /// The same relief in a scene scaled by `factor` (for scale-invariance tests).
    pub fn scaled(&self, factor: f32) -> Relief {
        match self {
            Relief::Bump { height, depth } => Relief::Bump {
                height: height.scaled(factor),
                depth: depth * factor,
            },
            normal_map => normal_map.clone(),
        }
    }
}

/// A slope per unit of the picture's (u, v) as a slope per unit of the surface's: the
/// chain rule through the picture's transform.
#[inline]
fn picture_to_surface(uv: &UvTransform, (hx, hy): (f32, f32)) -> (f32, f32) {
    let [a, b, c, d] = uv.jacobian();
    (hx * a + hy * c, hx * b + hy * d)
}

/// The gradient along the surface (perpendicular to `ns`) of a function whose slopes per
/// unit of u and v are `(hu, hv)`: ∇h = hu·∇u + hv·∇v, where ∇u and ∇v are the dual basis
/// of the tangents ∂p/∂u and ∂p/∂v (flattened onto the plane of `ns`). Zero where the
/// tangents span no area.
fn surface_gradient(ns: Vec3A, frame: &UvFrame, (hu, hv): (f32, f32)) -> Vec3A {
    let a = frame.dpdu - ns * frame.dpdu.dot(ns);
    let b = frame.dpdv - ns * frame.dpdv.dot(ns);
    let (aa, bb, ab) = (a.dot(a), b.dot(b), a.dot(b));
    let det = aa * bb - ab * ab;
    if !(det > f32::MIN_POSITIVE && det.is_finite()) {
        return Vec3A::ZERO;
    }
    let grad_u = (a * bb - b * ab) / det;
    let grad_v = (b * aa - a * ab) / det;
    grad_u * hu + grad_v * hv
}

/// The picture's right and up on the surface at a point of shading normal `ns`: the
/// directions in which the picture's u grows and its v shrinks (v runs down a picture),
/// made perpendicular to `ns` and to each other, up keeping the picture's handedness (a
/// mirrored map stays mirrored). None where the tangents give no direction.
fn picture_axes(ns: Vec3A, frame: &UvFrame, uv: &UvTransform) -> Option<(Vec3A, Vec3A)> {
    // ∂p/∂(picture u, v): the surface's tangents through the inverse of the transform.
    let [a, b, c, d] = uv.jacobian();
    let det = a * d - b * c;
    let along_u = (frame.dpdu * d - frame.dpdv * c) / det;
    let along_v = (frame.dpdv * a - frame.dpdu * b) / det;
    let right = (along_u - ns * along_u.dot(ns)).try_normalize()?;
    let up = ns.cross(right);
    let handed = if up.dot(-along_v) < 0.0 { -1.0 } else { 1.0 };
    Some((right, up * handed))
}
