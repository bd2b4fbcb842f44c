//! The Whitted integrator: Phong shading with shadow rays at each hit (local_light.rs),
//! plus recursive mirror-reflection (reflection.rs) and transmission (transmission.rs) rays.
//! It asks the acceleration layer two questions, the nearest hit and the light reaching a
//! point, and reads materials and lights from the appearance.

mod local_light;
mod path;
mod reflection;
mod signature;
mod transmission;

pub use signature::Signature;

use crate::accel::{Accelerator, Hit, Reach};
use crate::appearance::{Appearance, Material, fresnel_reflectance};
use crate::geometry::{Ray, RayQuery, SurfacePoint};
use crate::numerics::offset_ray_origin;
use crate::scene::{Geometry, PreparedScene};
use glam::{Vec3, Vec3A};
use path::Path;

/// Rays traced, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// From the camera.
    pub primary: u64,
    /// Towards lights.
    pub shadow: u64,
    /// Reflected and transmitted.
    pub secondary: u64,
}

impl RayCounts {
    /// Every ray, of any kind.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.secondary
    }
}

impl std::ops::Add for RayCounts {
    type Output = RayCounts;
    fn add(self, o: RayCounts) -> RayCounts {
        RayCounts {
            primary: self.primary + o.primary,
            shadow: self.shadow + o.shadow,
            secondary: self.secondary + o.secondary,
        }
    }
}

impl std::ops::AddAssign for RayCounts {
    fn add_assign(&mut self, o: RayCounts) {
        *self = *self + o;
    }
}

/// What one primary ray found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The colour it brings back, unclamped.
    pub color: Vec3,
    /// What its whole tree met ([`Signature`]).
    pub signature: u32,
}

/// How secondary rays avoid re-hitting the surface they start on.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum SelfIntersection {
    /// Offset by the hit point's own error bound (numerics.rs): scale-independent.
    #[default]
    ErrorBound,
    /// Offset along the normal by a fixed distance, as most simple tracers do; kept to
    /// measure what the robust method buys (docs/numerics.md).
    FixedEpsilon(f32),
}

/// Traces rays through one prepared scene.
pub struct Integrator<'a> {
    geometry: &'a Geometry,
    appearance: &'a Appearance,
    self_intersection: SelfIntersection,
    /// A secondary ray whose contribution to the pixel is weighted below this is not traced.
    /// 0 traces everything (the reference); 1/512 cannot change an 8-bit pixel by more than
    /// rounding.
    min_weight: f32,
    /// Rays traced so far, by kind.
    pub counts: RayCounts,
    /// What the primary ray being traced has met.
    signature: Signature,
    /// The background's colour when it is the same in every direction: then a primary ray
    /// known to hit nothing needs no ray built.
    solid_background: Option<Vec3A>,
}

/// What shading knows at a hit.
struct Shading<'s> {
    /// The ray that arrived.
    q: &'s RayQuery,
    hit: &'s Hit,
    /// The object hit.
    object: u32,
    material: &'s Material,
    surface: SurfacePoint,
    /// Whether the ray arrives from the side the surface normal faces.
    entering: bool,
    /// The true surface's normal on the side the ray arrives on: it decides sides and
    /// where spawned rays start.
    n: Vec3A,
    /// The shading normal on that side (`n` but on a smooth mesh): it lights and turns
    /// rays, never so far that one starts on the wrong side of the true surface.
    ns: Vec3A,
}

impl<'a> Integrator<'a> {
    /// An integrator that skips secondary rays weighted below `min_weight`.
    pub fn new(scene: &'a PreparedScene, min_weight: f32) -> Self {
        Self {
            geometry: &scene.geometry,
            appearance: &scene.appearance,
            self_intersection: SelfIntersection::default(),
            min_weight,
            counts: RayCounts::default(),
            signature: Signature::default(),
            solid_background: scene.appearance.background().solid(),
        }
    }

    /// Chooses how secondary rays leave a surface.
    pub fn with_self_intersection(mut self, policy: SelfIntersection) -> Self {
        self.self_intersection = policy;
        self
    }

    #[inline]
    fn accel(&self) -> &'a Accelerator {
        self.geometry.accel()
    }

    /// Where a ray leaving `surface` towards `w` starts.
    #[inline]
    fn leave(&self, surface: &SurfacePoint, n: Vec3A, w: Vec3A) -> Vec3A {
        match self.self_intersection {
            SelfIntersection::ErrorBound => offset_ray_origin(surface.point, surface.error, n, w),
            SelfIntersection::FixedEpsilon(eps) => {
                let side = if w.dot(n) < 0.0 { -eps } else { eps };
                surface.point + n * side
            }
        }
    }

    /// The colour seen along a primary ray (`ray()`, of unit direction) and its signature;
    /// `reach` is what the camera view knows it can hit first
    /// ([`crate::accel::CameraView::reach`]). A ray known to hit nothing is not built,
    /// unless the background varies with direction.
    #[inline]
    pub fn trace_primary(&mut self, reach: Reach, ray: impl FnOnce() -> Ray) -> Sample {
        self.counts.primary += 1;
        self.signature = Signature::default();
        let color = match (reach, self.solid_background) {
            (Reach::Among([]), Some(background)) => {
                self.signature.miss();
                background
            }
            (reach, _) => {
                let q = RayQuery::new(ray());
                match self.accel().nearest_hit(&q, reach) {
                    Some(hit) => self.shade(&q, &hit, Path::PRIMARY),
                    None => self.miss(q.ray.dir),
                }
            }
        };
        Sample {
            color: color.into(),
            signature: self.signature.value(),
        }
    }

    /// The colour along `q` beyond distance `t_min`. `inside` names the isolated solid
    /// ([`Accelerator::isolated_solid`]) the ray starts in, if any: its next hit is then on
    /// that solid, found without the BVH.
    fn trace(&mut self, q: &RayQuery, t_min: f32, inside: Option<u32>, path: Path) -> Vec3A {
        let reach = match inside {
            Some(solid) => Reach::Inside { solid, t_min },
            None => Reach::After(t_min),
        };
        match self.accel().nearest_hit(q, reach) {
            Some(hit) => self.shade(q, &hit, path),
            None => self.miss(q.ray.dir),
        }
    }

    /// The colour of a ray along `dir` that leaves the scene.
    #[inline]
    fn miss(&mut self, dir: Vec3A) -> Vec3A {
        self.signature.miss();
        self.appearance.background().along(dir)
    }

    /// The colour that ray `q` brings back from `hit`: the light at the surface, plus
    /// what the reflected and transmitted rays bring. (The query and the hit are passed by
    /// reference: moved by value, they were copied through the stack on every call.)
    fn shade(&mut self, q: &RayQuery, hit: &Hit, path: Path) -> Vec3A {
        self.signature
            .surface(hit.primitive, hit.shape.detail.part());
        let object = self.accel().object(hit);
        let material = self.appearance.material(object);
        let surface = self.accel().surface(q, hit);
        let entering = q.ray.dir.dot(surface.normal) < 0.0;
        // Shade the side the ray arrives on.
        let (n, ns) = if entering {
            (surface.normal, surface.shading)
        } else {
            (-surface.normal, -surface.shading)
        };
        let at = Shading {
            q,
            hit,
            object,
            material,
            n,
            ns,
            surface,
            entering,
        };
        // Emission is added unlit (zero for most materials: adding it costs less than a test).
        let mut color = self.local_light(&at) + Vec3A::from(material.emission);

        // Reflection and refraction spend a bounce; a straight crossing does not.
        let bounces_left = path.depth < self.appearance.max_depth();
        let (reflectivity, transparency) = self.split(&at);
        let reflects = self.reflects(reflectivity, path, bounces_left);
        let transmits = self.transmits(material, transparency, path, bounces_left);
        // The rays this hit spawns share what is left of the sample's budget evenly; when
        // it cannot pay for them all, none is traced, as if the depth limit were reached.
        let children = reflects as u32 + transmits as u32;
        if children == 0 || path.budget < children {
            return color;
        }
        let share = (path.budget - children) / children;
        if reflects {
            color += self.reflection(&at, path.bounce(reflectivity, share)) * reflectivity;
        }
        if transmits {
            color += self.transmission(&at, transparency, path, share) * transparency;
        }
        color
    }

    /// The shares of the light at `at` that are reflected and transmitted: the material's
    /// own, or for a Fresnel dielectric its reflectance at this angle of all that is not
    /// diffuse (reflectivity + transparency), and the rest transmitted.
    #[inline]
    fn split(&self, at: &Shading) -> (f32, f32) {
        let material = at.material;
        match material.eta {
            Some(eta) if material.fresnel && eta != 1.0 => {
                let ratio = if at.entering { 1.0 / eta } else { eta };
                let d = at.q.ray.dir;
                let cos_i = -d.dot(at.ns) / d.length();
                let r = fresnel_reflectance(cos_i, ratio);
                let specular = (material.reflectivity + material.transparency).min(1.0);
                (specular * r, specular * (1.0 - r))
            }
            _ => (material.reflectivity, material.transparency),
        }
    }

    /// The direction `turn` gives about the shading normal, when it leaves on the side of
    /// the true surface it claims (`turn` returns the direction and whether it goes back out
    /// on the side the ray arrived on), else the one it gives about the true normal: a shading
    /// normal never sends a reflected ray into the surface or a refracted one back out.
    #[inline]
    fn turned(&self, at: &Shading, turn: impl Fn(Vec3A) -> (Vec3A, bool)) -> Vec3A {
        let (dir, outward) = turn(at.ns);
        if at.ns == at.n || (dir.dot(at.n) > 0.0) == outward {
            dir
        } else {
            turn(at.n).0
        }
    }

    /// The isolated solid a ray leaving the surface at `at` in direction `dir` starts in:
    /// the surface's own object, when the ray goes inwards and the object is one.
    #[inline]
    fn inside(&self, at: &Shading, dir: Vec3A) -> Option<u32> {
        self.accel()
            .isolated_solid(at.object)
            .filter(|_| dir.dot(at.surface.normal) < 0.0)
    }
}
