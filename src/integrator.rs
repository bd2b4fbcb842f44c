//! The Whitted integrator: Phong shading with shadow rays at each hit, plus recursive
//! mirror-reflection and transmission (refraction) rays.

use crate::first_hit::Candidate;
use crate::geometry::{Ray, RayQuery, ShapeHit};
use crate::material::{reflect, refract};
use crate::numerics::offset_ray_origin;
use crate::scene::PreparedScene;
use glam::{Vec3, Vec3A};

/// Rays traced, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    pub primary: u64,
    pub shadow: u64,
    pub secondary: u64,
}

impl RayCounts {
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
    pub color: Vec3,
    /// A hash of what the ray's whole tree met: each surface (primitive, and part of a
    /// cylinder), whether each light was blocked, and the cell of a procedural pattern.
    /// Two samples of a pixel with different signatures straddle an edge, however alike
    /// their colours (adaptive sampling, progressive.rs).
    pub signature: u32,
}

/// Folds `value` into a running signature (order matters: a reflection of A seen in B
/// differs from one of B seen in A).
#[inline]
fn mix(signature: u32, value: u32) -> u32 {
    (signature ^ value)
        .wrapping_mul(0x9e37_79b1)
        .rotate_left(15)
}

/// A straight pass through a clear surface does not bend the ray, so it cannot start a
/// cycle and does not count towards the bounce limit; this many in a row end the path.
const MAX_STRAIGHT_CROSSINGS: u32 = 64;

/// Where a ray stands in its sample's tree: what it has spent and what it may still spend.
#[derive(Clone, Copy, Debug)]
struct Path {
    /// Bounces (reflections, refractions) so far.
    depth: u32,
    /// Straight crossings in a row since the last bounce.
    straight: u32,
    /// What this ray's colour is multiplied by on its way to the pixel.
    weight: f32,
    /// How many more secondary rays this ray's subtree may spawn (limits::RAY_BUDGET for
    /// the whole tree). Every ray spends one, so the recursion is at most this deep.
    budget: u32,
}

impl Path {
    const PRIMARY: Path = Path {
        depth: 0,
        straight: 0,
        weight: 1.0,
        budget: crate::limits::RAY_BUDGET,
    };
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
    scene: &'a PreparedScene,
    self_intersection: SelfIntersection,
    /// A secondary ray whose contribution to the pixel is weighted below this is not traced.
    /// 0 traces everything (the reference); 1/512 cannot change an 8-bit pixel by more than
    /// rounding.
    min_weight: f32,
    /// Shadow rays look up what they may meet in each light's buffer (light_buffer.rs)
    /// instead of traversing the BVH.
    light_buffer: bool,
    pub counts: RayCounts,
    /// The signature of the primary ray being traced.
    signature: u32,
}

impl<'a> Integrator<'a> {
    pub fn new(scene: &'a PreparedScene, min_weight: f32) -> Self {
        Self {
            scene,
            self_intersection: SelfIntersection::default(),
            min_weight,
            light_buffer: true,
            counts: RayCounts::default(),
            signature: 0,
        }
    }

    pub fn with_self_intersection(mut self, policy: SelfIntersection) -> Self {
        self.self_intersection = policy;
        self
    }

    pub fn with_light_buffer(mut self, on: bool) -> Self {
        self.light_buffer = on;
        self
    }

    /// Where a ray leaving `surface` towards `w` starts.
    #[inline]
    fn leave(&self, surface: &crate::geometry::SurfacePoint, n: Vec3A, w: Vec3A) -> Vec3A {
        match self.self_intersection {
            SelfIntersection::ErrorBound => offset_ray_origin(surface.point, surface.error, n, w),
            SelfIntersection::FixedEpsilon(eps) => {
                let side = if w.dot(n) < 0.0 { -eps } else { eps };
                surface.point + n * side
            }
        }
    }

    /// The colour seen along a primary ray (unit direction), and its signature.
    #[inline]
    pub fn trace_primary(&mut self, ray: Ray) -> Sample {
        self.primary(|this| this.trace(&RayQuery::new(ray), 0.0, None, Path::PRIMARY))
    }

    /// `trace_primary` for a ray that can only hit `candidates` first (first_hit.rs): the
    /// same colour and signature, found without traversing the BVH.
    #[inline]
    pub fn trace_primary_among(&mut self, ray: Ray, candidates: &[Candidate]) -> Sample {
        self.primary(|this| {
            let q = RayQuery::new(ray);
            match this.scene.intersect_among(&q, candidates) {
                Some((hit, index)) => this.shade(&q, &hit, index, Path::PRIMARY),
                None => this.miss(),
            }
        })
    }

    /// `trace_primary` for a ray known to hit nothing (an empty first-hit tile): the
    /// background, with the signature of a miss, and no ray to build.
    #[inline]
    pub fn trace_primary_miss(&mut self) -> Sample {
        self.primary(|this| this.miss())
    }

    /// Counts one primary ray and returns the colour `trace` finds with the signature it
    /// leaves.
    #[inline]
    fn primary(&mut self, trace: impl FnOnce(&mut Self) -> Vec3A) -> Sample {
        self.counts.primary += 1;
        self.signature = 0;
        let color = trace(self);
        Sample {
            color: color.into(),
            signature: self.signature,
        }
    }

    /// The colour along `q` beyond distance `t_min`. `inside` names the isolated solid
    /// (`ObjectData::isolated_solid`) the ray starts in, if any: its next hit is then on that
    /// solid, found without the BVH.
    fn trace(&mut self, q: &RayQuery, t_min: f32, inside: Option<u32>, path: Path) -> Vec3A {
        let scene = self.scene;
        let found = inside
            .and_then(|solid| scene.intersect_inside(solid, q, t_min))
            .or_else(|| scene.intersect(q, t_min, f32::INFINITY));
        match found {
            Some((hit, index)) => self.shade(q, &hit, index, path),
            None => self.miss(),
        }
    }

    /// The colour of a ray that leaves the scene.
    #[inline]
    fn miss(&mut self) -> Vec3A {
        self.signature = mix(self.signature, u32::MAX);
        self.scene.background
    }

    /// The colour that ray `q` brings back from `hit` on primitive `index`. (The query and
    /// the hit are passed by reference: moved by value, they were copied through the stack
    /// on every call.)
    fn shade(&mut self, q: &RayQuery, hit: &ShapeHit, index: u32, path: Path) -> Vec3A {
        let Path {
            depth,
            straight,
            weight,
            budget,
        } = path;
        let scene = self.scene;
        let ray = q.ray;
        self.signature = mix(self.signature, index ^ (hit.detail.part() << 24));
        let prim = &scene.primitives[index as usize];
        let object = &scene.objects[prim.object as usize];
        let material = &object.material;
        let surface = prim.shape.surface(q, hit);
        let entering = ray.dir.dot(surface.normal) < 0.0;
        // Shade the side the ray arrives on.
        let n = if entering {
            surface.normal
        } else {
            -surface.normal
        };
        let p = surface.point;

        let opacity = 1.0 - material.transparency;
        let mut color = Vec3A::ZERO;
        if opacity > 0.0 || material.specular > 0.0 {
            let uv = if !material.texture.needs_uv() {
                (0.0, 0.0)
            } else if let Some(planar) = object.planar_uv {
                planar.uv(p)
            } else {
                prim.shape.uv(&surface, hit)
            };
            let base = material.texture.eval(uv, p - object.origin);
            if !material.texture.needs_uv() {
                // A pattern's colour names its cell (an image varies within cells instead).
                self.signature = mix(self.signature, base.x.to_bits() ^ base.z.to_bits());
            }
            let mut diffuse = base * scene.ambient * material.ambient;
            let mut specular = Vec3A::ZERO;
            for (light_index, light) in scene.lights.iter().enumerate() {
                let to_light = Vec3A::from(light.position) - p;
                let n_dot = n.dot(to_light);
                if n_dot <= 0.0 {
                    continue; // the light is behind this side: no shadow ray needed
                }
                let distance = to_light.length();
                let l = to_light / distance;
                let origin = self.leave(&surface, n, l);
                self.counts.shadow += 1;
                let leaving = (entering || object.flat).then_some(prim.object);
                let visible = scene.light_reaching(light_index, origin, leaving, self.light_buffer);
                let shadow_class = if visible == Vec3A::ZERO {
                    0
                } else if visible == Vec3A::ONE {
                    1
                } else {
                    2 // through transparent surfaces
                };
                self.signature = mix(self.signature, shadow_class);
                if visible == Vec3A::ZERO {
                    continue;
                }
                let lit = visible * Vec3A::from(light.color);
                diffuse += lit * base * (material.diffuse * n_dot / distance);
                if material.specular > 0.0 {
                    let r = reflect(-l, n);
                    let r_dot_v = r.dot(-ray.dir).max(0.0);
                    // Outside the highlight the power is 0 (unless the exponent is 0 too).
                    if r_dot_v > 0.0 || material.shininess == 0.0 {
                        specular += lit * (material.specular * r_dot_v.powf(material.shininess));
                    }
                }
            }
            // The highlight is light reflected at the surface: it does not fade with opacity.
            color = diffuse * opacity + specular;
        }

        // A ray leaving this surface inwards starts inside the object; when the object is
        // an isolated solid, only the solid can stop it.
        let inside = |dir: Vec3A| {
            object
                .isolated_solid
                .filter(|_| dir.dot(surface.normal) < 0.0)
        };

        // Reflection and refraction spend a bounce; a straight crossing does not.
        let bounces_left = depth < scene.max_depth;
        let reflectivity = material.reflectivity;
        let transparency = material.transparency;
        let bends = matches!(material.eta, Some(eta) if eta != 1.0);
        let reflects =
            bounces_left && reflectivity > 0.0 && weight * reflectivity >= self.min_weight;
        let transmits = transparency > 0.0
            && weight * transparency >= self.min_weight
            && if bends {
                bounces_left
            } else {
                straight < MAX_STRAIGHT_CROSSINGS
            };
        // The rays this hit spawns share what is left of the sample's budget evenly; when
        // it cannot pay for them all, none is traced, as if the depth limit were reached.
        let children = reflects as u32 + transmits as u32;
        if children == 0 || budget < children {
            return color;
        }
        let share = (budget - children) / children;

        if reflects {
            let dir = reflect(ray.dir, n);
            let origin = self.leave(&surface, n, dir);
            self.counts.secondary += 1;
            let reflected = RayQuery::new(Ray::new(origin, dir));
            let inside = inside(dir);
            let path = Path {
                depth: depth + 1,
                straight: 0,
                weight: weight * reflectivity,
                budget: share,
            };
            color += self.trace(&reflected, 0.0, inside, path) * reflectivity;
        }
        if transmits {
            self.counts.secondary += 1;
            let transmitted = if bends {
                let eta = material.eta.unwrap_or(1.0);
                let ratio = if entering { 1.0 / eta } else { eta };
                // Past the critical angle the transmitted light is reflected inside.
                let dir = refract(ray.dir, n, ratio).unwrap_or_else(|| reflect(ray.dir, n));
                let origin = self.leave(&surface, n, dir);
                let q = RayQuery::new(Ray::new(origin, dir));
                let path = Path {
                    depth: depth + 1,
                    straight: 0,
                    weight: weight * transparency,
                    budget: share,
                };
                self.trace(&q, 0.0, inside(dir), path)
            } else {
                // Unbent light goes on along the very same ray, past this hit: exact, so an
                // eta-1 clear object leaves the image untouched.
                let path = Path {
                    depth,
                    straight: straight + 1,
                    weight: weight * transparency,
                    budget: share,
                };
                self.trace(q, hit.t, inside(ray.dir), path)
            };
            color += transmitted * transparency;
        }
        color
    }
}
