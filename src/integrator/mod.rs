//! The Whitted integrator: Phong shading with shadow rays at each hit (local_light.rs),
//! plus recursive mirror-reflection (reflection.rs) and transmission (transmission.rs) rays.
//! It asks the acceleration layer two questions, the nearest hit and the light reaching a
//! point, and reads materials and lights from the appearance.

mod coincident;
mod emitter_shape;
mod emitters;
mod first_surface;
mod guide;
pub mod kind;
mod light_sample;
mod lobes;
mod local_light;
mod microfacet;
mod path;
mod path_tracer;
mod reflection;
mod relief;
mod signature;
mod transmission;

pub use emitters::Emitters;
pub use guide::Guide;
pub use kind::IntegratorKind;
pub use signature::Signature;

use crate::accel::{Accelerator, Hit, Reach};
use crate::appearance::{Appearance, Material, fresnel_reflectance, schlick_reflectance};
use crate::geometry::{Ray, RayQuery, SurfacePoint};
use crate::numerics::offset_ray_origin;
use crate::sampler::SampleStream;
use crate::scene::{Geometry, PreparedScene};
use glam::{Vec3, Vec3A};
use path::{Media, Path};

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
    /// The background's colour when it is the same in every direction and nothing else
    /// (fog, a glowing light) lies along a ray: then a primary ray known to hit nothing needs
    /// no ray built.
    solid_background: Option<Vec3A>,
    /// The random numbers of the subsample being traced (lens, area lights, glossy lobes).
    stream: SampleStream,
    /// The transparent objects the ray being traced is inside: set by a transmitted ray for
    /// its subtree and put back after it (kept here, not in each ray's `Path`, which then
    /// still fits in two registers).
    media: Media,
    /// Which light transport is computed.
    kind: IntegratorKind,
    /// The centre of the scene's bounds: the path tracer reads a light without falloff as
    /// one as bright there (light_sample.rs).
    scene_center: Option<Vec3A>,
    /// The glowing objects the path tracer samples as lights (none: scattered rays alone
    /// find them).
    emitters: Option<&'a Emitters>,
}

/// What shading knows at a hit.
struct Shading<'s> {
    /// The ray that arrived.
    q: &'s RayQuery,
    hit: &'s Hit,
    /// The object hit.
    object: u32,
    material: &'s Material,
    /// The object's own material, whose inside is the medium (a CSG member's surface may
    /// have another).
    medium: &'s Material,
    surface: SurfacePoint,
    /// Whether the ray arrives from the side the surface normal faces.
    entering: bool,
    /// The true surface's normal on the side the ray arrives on: it decides sides and
    /// where spawned rays start.
    n: Vec3A,
    /// The shading normal on that side (`n` but on a smooth mesh): it lights and turns
    /// rays, never so far that one starts on the wrong side of the true surface.
    ns: Vec3A,
    /// The medium the ray leaves at this point as well, where the surface touches that
    /// medium's (coincident.rs): a ray transmitted here is no longer in it.
    leaves: Option<u32>,
}

impl Shading<'_> {
    /// The cosine between the arriving ray and the shading normal.
    #[inline]
    fn cos_incidence(&self) -> f32 {
        let d = self.q.ray.dir;
        -d.dot(self.ns) / d.length()
    }
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
            solid_background: scene
                .appearance
                .background()
                .solid()
                .filter(|_| scene.appearance.fog().is_none() && !scene.appearance.any_emitter()),
            stream: SampleStream::new(0, 0, 0),
            media: Media::AIR,
            kind: IntegratorKind::Whitted,
            scene_center: scene
                .geometry
                .accel()
                .bounds()
                .map(|b| Vec3A::from((b.min + b.max) * 0.5))
                .filter(|c| c.is_finite()),
            emitters: None,
        }
    }

    /// Samples the glowing objects of `emitters` as lights (the path tracer's; built from
    /// the same prepared scene).
    pub fn with_emitters(mut self, emitters: Option<&'a Emitters>) -> Self {
        self.emitters = emitters.filter(|e| !e.is_empty());
        self
    }

    /// Chooses the light transport.
    pub fn with_kind(mut self, kind: IntegratorKind) -> Self {
        self.kind = kind;
        self
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
    /// ([`crate::accel::CameraView::reach`]), `stream` the subsample's random numbers. A ray
    /// known to hit nothing is not built, unless the background varies with direction or
    /// something else lies along it.
    #[inline]
    pub fn trace_primary(
        &mut self,
        reach: Reach,
        ray: impl FnOnce() -> Ray,
        stream: SampleStream,
    ) -> Sample {
        self.counts.primary += 1;
        self.signature = Signature::default();
        self.stream = stream;
        self.media = Media::AIR;
        let color = match (reach, self.solid_background) {
            (Reach::Among([], _), Some(background)) => {
                self.signature.miss();
                background
            }
            (reach, _) => match self.kind {
                IntegratorKind::Whitted => {
                    self.trace_reaching(&RayQuery::new(ray()), 0.0, reach, Path::PRIMARY)
                }
                IntegratorKind::Path => self.path_radiance(RayQuery::new(ray()), reach),
            },
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
        self.trace_reaching(q, t_min, reach, path)
    }

    /// The colour along `q` from `t_min` on, where `reach` says what it can hit: what it
    /// meets (a surface, a glowing light, or the background), seen through the medium it
    /// travels in (absorption inside an object, fog in the air).
    #[inline(always)]
    fn trace_reaching(&mut self, q: &RayQuery, t_min: f32, reach: Reach, path: Path) -> Vec3A {
        // Where the medium it travels in touches another object, the ray passes from one
        // into the other (coincident.rs). (Nothing touches an isolated solid.)
        let (hit, leaves) = match (reach, self.media.current()) {
            (Reach::After(t_min), Some(medium)) => self.nearest_in_medium(q, t_min, medium),
            (reach, _) => (self.accel().nearest_hit(q, reach), None),
        };
        let t_end = hit.map_or(f32::INFINITY, |h| h.shape.t);
        let emitter = if self.appearance.any_emitter() {
            self.emitter_along(&q.ray, t_min, t_end)
        } else {
            None
        };
        let (color, t_end) = match (emitter, hit) {
            (Some((color, t)), _) => (color, t),
            (None, Some(hit)) => (self.shade(q, &hit, leaves, path), t_end),
            (None, None) => (self.miss(q.ray.dir), t_end),
        };
        self.through_medium(color, q, t_end - t_min)
    }

    /// The nearest glowing light surface along `ray` in (t_min, t_max): its colour and
    /// distance.
    fn emitter_along(&mut self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(Vec3A, f32)> {
        let (index, t) = self.light_along(ray, t_min, t_max)?;
        Some((self.appearance.lights()[index].color.into(), t))
    }

    /// The nearest visible light surface along `ray` in (t_min, t_max): its index and
    /// distance.
    fn light_along(&mut self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(usize, f32)> {
        let mut nearest = None;
        let mut t_max = t_max;
        for (index, light) in self.appearance.lights().iter().enumerate() {
            if let Some(shape) = light.emitter()
                && let Some(t) = shape.intersect(ray, t_min, t_max)
            {
                t_max = t;
                nearest = Some((index, t));
            }
        }
        let (index, t) = nearest?;
        self.signature.surface(u32::MAX - index as u32, 0);
        Some((index, t))
    }

    /// `color`, seen from `dt` (in units of the ray's direction) along `q` through the
    /// medium the ray travels in: an object's absorption, or in the air, the fog.
    #[inline]
    fn through_medium(&self, color: Vec3A, q: &RayQuery, dt: f32) -> Vec3A {
        match self.media.current() {
            Some(object) => {
                let absorption = self.appearance.material(object).absorption;
                if absorption == Vec3::ZERO {
                    return color;
                }
                let d = dt * q.ray.dir.length();
                // No light crosses an endless absorbing medium (an open mesh seen from inside).
                let kept = (-Vec3A::from(absorption) * d).exp();
                color * Vec3A::select(kept.cmpeq(kept), kept, Vec3A::ZERO)
            }
            None => match self.appearance.fog() {
                Some(fog) => fog.apply(color, dt * q.ray.dir.length()),
                None => color,
            },
        }
    }

    /// The colour of a ray along `dir` that leaves the scene.
    #[inline]
    fn miss(&mut self, dir: Vec3A) -> Vec3A {
        self.signature.miss();
        self.appearance.background().along(dir)
    }

    /// The colour that ray `q` brings back from `hit`: the light at the surface, plus
    /// what the reflected and transmitted rays bring. `leaves` is the medium the ray also
    /// leaves there, where the surface touches it (coincident.rs). (The query and the hit
    /// are passed by reference: moved by value, they were copied through the stack on every
    /// call.)
    fn shade(&mut self, q: &RayQuery, hit: &Hit, leaves: Option<u32>, path: Path) -> Vec3A {
        let at = self.shading(q, hit, leaves);
        let material = at.material;
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
            let reflected = self.reflection(&at, path.bounce(reflectivity, share)) * reflectivity;
            color += match material.conductor {
                None => reflected,
                Some(f0) => reflected * schlick_reflectance(at.cos_incidence(), f0.into()),
            };
        }
        if transmits {
            color += self.transmission(&at, transparency, path, share) * transparency;
        }
        color
    }

    /// What shading knows at `hit`, the nearest hit of `q`: its material (a CSG member's
    /// own, or the object's), its surface point with any relief applied, and the side the ray
    /// arrives on.
    #[inline(always)]
    fn shading<'s>(&mut self, q: &'s RayQuery, hit: &'s Hit, leaves: Option<u32>) -> Shading<'s>
    where
        'a: 's,
    {
        self.signature
            .surface(hit.primitive, hit.shape.detail.part());
        let (object, slot) = self.accel().object_and_material(hit);
        let material = self.appearance.material(slot);
        let mut surface = self.accel().surface(q, hit);
        if let Some(relief) = &material.relief {
            surface.shading = self.relief_normal(relief, q, hit, object, &surface);
        }
        let entering = q.ray.dir.dot(surface.normal) < 0.0;
        // Shade the side the ray arrives on.
        let (n, ns) = if entering {
            (surface.normal, surface.shading)
        } else {
            (-surface.normal, -surface.shading)
        };
        Shading {
            q,
            hit,
            object,
            material,
            medium: if slot == object {
                material
            } else {
                self.appearance.material(object)
            },
            n,
            ns,
            surface,
            entering,
            leaves,
        }
    }

    /// The shares of the light at `at` that are reflected and transmitted: the material's
    /// own, or for a Fresnel dielectric its reflectance at this angle of all that is not
    /// diffuse (reflectivity + transparency), and the rest transmitted.
    #[inline]
    fn split(&self, at: &Shading) -> (f32, f32) {
        let material = at.material;
        match material.eta {
            Some(eta) if material.fresnel && eta != 1.0 => {
                let r = fresnel_reflectance(at.cos_incidence(), self.eta_ratio(at));
                let specular = (material.reflectivity + material.transparency).min(1.0);
                (specular * r, specular * (1.0 - r))
            }
            _ => (material.reflectivity, material.transparency),
        }
    }

    /// η(incident side) / η(other side) at `at`: entering, the medium the ray travels in
    /// against the object's; leaving, the object's against the medium around it (air, unless
    /// it is inside another object).
    #[inline]
    fn eta_ratio(&self, at: &Shading) -> f32 {
        let eta_of = |object: Option<u32>| match object {
            Some(o) => self.appearance.material(o).eta.unwrap_or(1.0),
            None => 1.0,
        };
        // The medium inside is the object's (a CSG solid's whole, whatever member's surface
        // is crossed).
        let own = at.medium.eta.unwrap_or(1.0);
        if at.entering {
            eta_of(self.media.current()) / own
        } else {
            own / eta_of(self.media.outside(at.object))
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
