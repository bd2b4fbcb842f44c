//! The path tracer: one path per subsample from the camera, scattered at each hit by the
//! material's lobes (lobes.rs), with next-event estimation toward every light
//! (light_sample.rs) and multiple importance sampling (the power heuristic) between a
//! light's own samples and scattered rays that hit its visible surface.
//!
//! Bounces are counted as Whitted's are: the light reaching vertex `max_depth` directly
//! still counts, and a ray scattered from it may still meet a glowing surface, so the
//! longest path has `max_depth` + 2 segments (Mitsuba's `max_depth` of that number). A
//! straight crossing of a clear surface is not a bounce. Emissive objects are found by
//! scattered rays only (weight 1); the background is reached the same way.

use super::Integrator;
use super::lobes::{Interface, LobeInputs, Lobes, Scatter};
use super::path::MAX_STRAIGHT_CROSSINGS;
use crate::accel::{Reach, Toward};
use crate::appearance::{EnvironmentDistribution, reflect, refract};
use crate::geometry::{Ray, RayQuery};
use glam::Vec3A;

/// Bounces after which a path may be ended at random (Russian roulette), in proportion to
/// how little it still carries.
const ROULETTE_AFTER: u32 = 3;

/// The power heuristic's weight for a technique of density `a` against one of `b`.
#[inline]
fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

impl<'a> Integrator<'a> {
    /// The radiance arriving along `q` (of unit direction) from the scene, by one path;
    /// `reach` is what the ray can hit first.
    pub(super) fn path_radiance(&mut self, q: RayQuery, reach: Reach) -> Vec3A {
        let radiance = self.follow_path(q, reach);
        // No NaN or infinity reaches the film, whatever a degenerate vertex produced.
        if radiance.is_finite() {
            radiance
        } else {
            Vec3A::ZERO
        }
    }

    fn follow_path(&mut self, mut q: RayQuery, mut reach: Reach) -> Vec3A {
        let max_depth = self.appearance.max_depth();
        let mut radiance = Vec3A::ZERO;
        let mut throughput = Vec3A::ONE;
        let mut t_min = 0.0f32;
        let (mut depth, mut straight) = (0u32, 0u32);
        // Where the ray left and the density its direction was drawn with, when a light's
        // surface it meets must be weighed against that light's own samples; None after
        // the camera or a perfect mirror or refraction, which no light sample can follow.
        let mut scattered_from: Option<(Vec3A, f32)> = None;
        loop {
            let (hit, leaves) = match (reach, self.media.current()) {
                (Reach::After(t), Some(medium)) => self.nearest_in_medium(&q, t, medium),
                (reach, _) => (self.accel().nearest_hit(&q, reach), None),
            };
            let t_hit = hit.map_or(f32::INFINITY, |h| h.shape.t);
            let light_hit = if self.appearance.any_emitter() {
                self.light_along(&q.ray, t_min, t_hit)
            } else {
                None
            };
            let t_end = light_hit.map_or(t_hit, |(_, t)| t);
            // The medium along the segment: what it keeps of the light beyond, and adds.
            let added = self.through_medium(Vec3A::ZERO, &q, t_end - t_min);
            let kept = self.through_medium(Vec3A::ONE, &q, t_end - t_min) - added;
            radiance += throughput * added;
            throughput *= kept;
            if let Some((index, t)) = light_hit {
                let light = &self.appearance.lights()[index];
                let weight = match scattered_from {
                    None => 1.0,
                    Some((p, pdf)) => power_heuristic(pdf, self.light_pdf(light, p, q.ray.dir, t)),
                };
                radiance += throughput * self.light_radiance(light) * weight;
                break;
            }
            let Some(hit) = hit else {
                // A background image is also found by its own samples (`direct_light`).
                let weight = match (scattered_from, self.environment_light()) {
                    (Some((_, pdf)), Some(environment)) => {
                        power_heuristic(pdf, environment.pdf(q.ray.dir))
                    }
                    _ => 1.0,
                };
                radiance += throughput * self.miss(q.ray.dir) * weight;
                break;
            };
            let at = self.shading(&q, &hit, leaves);
            let emission = Vec3A::from(at.material.emission);
            if emission != Vec3A::ZERO {
                // A glowing object is also found by its own samples (`direct_light`), when
                // its shape can be sampled.
                let weight = match (scattered_from, self.emitters) {
                    (Some((p, pdf)), Some(emitters)) => {
                        let pdf_area = emitters.pdf_area(hit.primitive);
                        let d2 = (at.surface.point - p).length_squared();
                        let cos = q.ray.dir.dot(at.surface.normal).abs();
                        if pdf_area > 0.0 {
                            power_heuristic(pdf, pdf_area * d2 / cos)
                        } else {
                            1.0
                        }
                    }
                    _ => 1.0,
                };
                radiance += throughput * emission * weight;
            }
            if depth > max_depth {
                break;
            }
            let material = at.material;
            let wo = -q.ray.dir;
            let (reflected, transmitted) = self.split(&at);
            let base = if material.diffuse > 0.0 && material.transparency < 1.0 {
                self.texture_color(at.q, at.hit, at.object, material, &at.surface)
            } else {
                Vec3A::ZERO
            };
            let lobes = Lobes::new(
                LobeInputs {
                    diffuse: base * (material.diffuse * (1.0 - material.transparency)),
                    specular: material.specular,
                    shininess: material.shininess,
                    reflected,
                    transmitted,
                    conductor: material.conductor.map(Vec3A::from),
                    roughness: material.roughness,
                    // Only a rough interface needs its ratio (smooth glass splits in
                    // `split`), so smooth glass skips the lookup.
                    interface: (material.bends() && material.roughness > 0.0).then(|| Interface {
                        eta: self.eta_ratio(&at),
                        fresnel: material.fresnel,
                    }),
                },
                at.ns,
                at.n,
                wo,
            );
            if lobes.spreads() {
                radiance += throughput * self.direct_light(&at, &lobes);
            }
            if depth >= ROULETTE_AFTER {
                let carry = throughput.max_element().min(0.95);
                if self.stream.next_2d().0 >= carry {
                    break;
                }
                throughput /= carry;
            }
            let d = q.ray.dir;
            let u = self.stream.next_2d();
            let (dir, weight) = match lobes.sample(u, || self.stream.next_2d().0) {
                Scatter::Absorbed => break,
                Scatter::Spread { wi, weight, pdf } => {
                    scattered_from = Some((at.surface.point, pdf));
                    (wi, weight)
                }
                Scatter::Mirror { weight } => {
                    scattered_from = None;
                    (self.turned(&at, |n| (reflect(d, n), true)), weight)
                }
                Scatter::Transmit { weight } if !material.bends() => {
                    // Straight on along the same ray, past this hit; not a bounce.
                    straight += 1;
                    if straight > MAX_STRAIGHT_CROSSINGS {
                        break;
                    }
                    throughput *= weight;
                    self.media = self.media_beyond(&at);
                    reach = match self.inside(&at, d) {
                        Some(solid) => Reach::Inside {
                            solid,
                            t_min: hit.shape.t,
                        },
                        None => Reach::After(hit.shape.t),
                    };
                    t_min = hit.shape.t;
                    continue;
                }
                Scatter::Refract { wi, weight } => {
                    // No light's samples reach through a surface that bends light.
                    scattered_from = None;
                    self.media = self.media_beyond(&at);
                    (wi, weight)
                }
                Scatter::Transmit { weight } => {
                    scattered_from = None;
                    let ratio = self.eta_ratio(&at);
                    // Past the critical angle the light is reflected inside instead.
                    let dir = self.turned(&at, |n| match refract(d, n, ratio) {
                        Some(dir) => (dir, false),
                        None => (reflect(d, n), true),
                    });
                    if dir.dot(at.n) < 0.0 {
                        self.media = self.media_beyond(&at);
                    }
                    (dir, weight)
                }
            };
            throughput *= weight;
            if throughput == Vec3A::ZERO {
                break;
            }
            self.counts.secondary += 1;
            depth += 1;
            straight = 0;
            let origin = self.leave(&at.surface, at.n, dir);
            reach = match self.inside(&at, dir) {
                Some(solid) => Reach::Inside { solid, t_min: 0.0 },
                None => Reach::After(0.0),
            };
            q = RayQuery::new(Ray::new(origin, dir));
            t_min = 0.0;
        }
        radiance
    }

    /// The light reaching `at` straight from every light and scattered toward the viewer
    /// by `lobes`: one shadow ray per light, weighed against scattered rays that could hit
    /// the light's surface.
    fn direct_light(&mut self, at: &super::Shading, lobes: &Lobes) -> Vec3A {
        let start = self.shadow_start(at);
        let p = at.surface.point;
        let accel = self.accel();
        let filters = self.appearance.path_shadow_filters();
        let mut sum = Vec3A::ZERO;
        for (index, light) in self.appearance.lights().iter().enumerate() {
            let u = self.stream.next_2d();
            let Some(sample) = self.sample_light(light, p, u) else {
                continue;
            };
            let cos = at.ns.dot(sample.wi);
            if !start.faces(at, cos, sample.wi) {
                continue;
            }
            let (f, scatter_pdf) = lobes.eval(sample.wi);
            if f == Vec3A::ZERO {
                continue;
            }
            let origin = self.shadow_origin(at, &start, sample.wi);
            self.counts.shadow += 1;
            let visible =
                accel.light_reaching(index, sample.toward, origin, start.leaving, filters);
            self.signature.shadow(visible);
            if visible == Vec3A::ZERO {
                continue;
            }
            // A light no scattered ray can meet (a point, a direction, a hidden surface)
            // is found by its own samples alone.
            let weight = if sample.pdf > 0.0 && light.emitter().is_some() {
                power_heuristic(sample.pdf, scatter_pdf)
            } else {
                1.0
            };
            sum += visible * sample.light * f * (cos * weight);
        }
        if let Some(emitters) = self.emitters {
            let choose = self.stream.next_2d().0;
            let on = self.stream.next_2d();
            if let Some(e) = emitters.sample(choose, on) {
                let to = e.point - p;
                let (wi, d2) = (to.normalize_or_zero(), to.length_squared());
                let pdf = e.pdf_area * d2 / wi.dot(e.normal).abs();
                let cos = at.ns.dot(wi);
                let (f, scatter_pdf) = lobes.eval(wi);
                if pdf.is_finite() && pdf > 0.0 && start.faces(at, cos, wi) && f != Vec3A::ZERO {
                    let origin = self.shadow_origin(at, &start, wi);
                    self.counts.shadow += 1;
                    // The ray stops just short of the glowing surface, which would block it.
                    let end = origin + (e.point - origin) * (1.0 - 1e-4);
                    let toward = Toward::Point(end);
                    let visible =
                        accel.light_reaching(usize::MAX, toward, origin, start.leaving, filters);
                    if visible != Vec3A::ZERO {
                        let weight = power_heuristic(pdf, scatter_pdf);
                        sum += visible * e.radiance * f * (cos * weight / pdf);
                    }
                }
            }
        }
        if let Some(environment) = self.environment_light() {
            let (wi, pdf) = environment.sample(self.stream.next_2d());
            let cos = at.ns.dot(wi);
            let (f, scatter_pdf) = lobes.eval(wi);
            if pdf > 0.0 && start.faces(at, cos, wi) && f != Vec3A::ZERO {
                let origin = self.shadow_origin(at, &start, wi);
                self.counts.shadow += 1;
                // A direction, not a light: the index names no light's buffer.
                let toward = Toward::Direction(wi);
                let visible =
                    accel.light_reaching(usize::MAX, toward, origin, start.leaving, filters);
                if visible != Vec3A::ZERO {
                    let sky = self.appearance.background().along(wi);
                    sum += visible * sky * f * (cos * power_heuristic(pdf, scatter_pdf) / pdf);
                }
            }
        }
        sum
    }

    /// The background image as a light its own samples find: None for a colour or a
    /// gradient (scattered rays find those well), and in fog, which hides everything
    /// infinitely far.
    fn environment_light(&self) -> Option<&'a EnvironmentDistribution> {
        self.appearance
            .environment()
            .filter(|_| self.appearance.fog().is_none())
    }

    /// The media a ray that crosses the surface at `at` travels in beyond it: the object's
    /// entered or left, and a touching medium left there too (coincident.rs).
    fn media_beyond(&self, at: &super::Shading) -> super::path::Media {
        let here = at
            .leaves
            .map_or(self.media, |touching| self.media.left(touching));
        if at.entering {
            here.entered(at.object)
        } else {
            here.left(at.object)
        }
    }
}
