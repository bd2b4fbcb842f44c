//! Light sources: what kind of light, how bright, how it falls off, and for lights with an
//! area, where on them a shadow ray ends.

use crate::geometry::{Ray, Sphere};
use crate::limits::{self, MAX_COORDINATE, MIN_LENGTH};
use crate::messages::FieldProblem;
use glam::{Vec3, Vec3A};

/// A light: its kind and where it shines from, and its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Where the light comes from.
    pub kind: LightKind,
    /// Its intensity per channel. A point light without falloff lights a surface facing it
    /// with this at any distance (as the seed's does); with inverse-square falloff, with
    /// this times `intensity / distance²`.
    pub color: Vec3,
}

/// The kinds of light (a closed set).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Light from one point, in every direction.
    Point {
        /// Where the light is, relative to the scene's origin.
        position: Vec3,
        /// How it fades with distance.
        falloff: Falloff,
    },
    /// Light from one point, or from a disc about it facing along the cone, into a cone.
    Spot {
        /// Where the light is, relative to the scene's origin.
        position: Vec3,
        /// How it fades with distance.
        falloff: Falloff,
        /// Where it shines.
        cone: SpotCone,
        /// The radius of the disc that emits, facing along the cone's axis: 0 for a point
        /// (hard shadows); above 0, one point of the disc per subsample (soft shadows).
        radius: f32,
    },
    /// Parallel light from infinitely far away, like the sun's.
    Directional {
        /// The unit direction the light travels in (from the sky towards the scene).
        direction: Vec3,
    },
    /// Light from a surface, sampled at one point of it per subsample: soft shadows.
    Area {
        /// The emitting surface.
        shape: AreaShape,
        /// How the light of each sampled point fades with its distance.
        falloff: Falloff,
        /// Whether rays from the camera (and mirrors) see the surface, glowing in the
        /// light's colour.
        visible: bool,
    },
}

/// The surface of an area light. As POV-Ray's `area_light`, the light's colour is the whole
/// light's: a point that sees all of the surface is lit as by a point light of that colour at
/// the sampled points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AreaShape {
    /// The parallelogram `corner + u·edge_u + v·edge_v`, u and v in [0, 1].
    Rectangle {
        /// One corner.
        corner: Vec3,
        /// The edge from it along u.
        edge_u: Vec3,
        /// The edge from it along v.
        edge_v: Vec3,
    },
    /// A sphere. Seen from a shading point it is sampled over its great disc facing that
    /// point (POV-Ray's `area_light` with `circular` and `orient`), so POV-Ray can check it.
    Sphere {
        /// Its centre, relative to the scene's origin.
        center: Vec3,
        /// Its radius.
        radius: f32,
    },
}

impl AreaShape {
    /// The point of the surface that sample `u` (in [0, 1)²) stands for, as seen from `p`:
    /// stratified samples stay stratified over the surface.
    #[inline]
    pub fn sample(&self, p: Vec3A, u: (f32, f32)) -> Vec3A {
        match *self {
            AreaShape::Rectangle {
                corner,
                edge_u,
                edge_v,
            } => Vec3A::from(corner) + Vec3A::from(edge_u) * u.0 + Vec3A::from(edge_v) * u.1,
            AreaShape::Sphere { center, radius } => {
                let c = Vec3A::from(center);
                let w = crate::numerics::try_normalize((p - c).into()).unwrap_or(Vec3::Z);
                crate::sampler::disc_point(c, w, radius, u)
            }
        }
    }

    /// Where the ray first meets the surface in (t_min, t_max), if it does.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        match *self {
            AreaShape::Rectangle {
                corner,
                edge_u,
                edge_v,
            } => {
                let (corner, eu, ev) = (
                    Vec3A::from(corner),
                    Vec3A::from(edge_u),
                    Vec3A::from(edge_v),
                );
                let n = eu.cross(ev);
                let denom = ray.dir.dot(n);
                if denom == 0.0 {
                    return None;
                }
                let t = (corner - ray.origin).dot(n) / denom;
                if !(t > t_min && t < t_max) {
                    return None;
                }
                // The hit's coordinates along the edges, by the dual basis of the plane.
                let d = ray.origin + ray.dir * t - corner;
                let nn = n.length_squared();
                let u = d.cross(ev).dot(n) / nn;
                let v = eu.cross(d).dot(n) / nn;
                ((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)).then_some(t)
            }
            AreaShape::Sphere { center, radius } => {
                Sphere::new(center, radius).intersect_after(ray, t_min, t_max)
            }
        }
    }

    /// A point inside the surface's extent: its centre.
    pub fn center(&self) -> Vec3 {
        match *self {
            AreaShape::Rectangle {
                corner,
                edge_u,
                edge_v,
            } => corner + (edge_u + edge_v) * 0.5,
            AreaShape::Sphere { center, .. } => center,
        }
    }

    /// Half the surface's widest extent: the size the viewer's panel edits.
    pub fn size(&self) -> f32 {
        match *self {
            AreaShape::Rectangle { edge_u, edge_v, .. } => {
                (edge_u + edge_v).length().max((edge_u - edge_v).length()) * 0.5
            }
            AreaShape::Sphere { radius, .. } => radius,
        }
    }

    /// The same surface about the same centre, `factor` times as large.
    pub fn resized(&self, factor: f32) -> AreaShape {
        match *self {
            AreaShape::Rectangle { edge_u, edge_v, .. } => {
                let c = self.center();
                let (edge_u, edge_v) = (edge_u * factor, edge_v * factor);
                AreaShape::Rectangle {
                    corner: c - (edge_u + edge_v) * 0.5,
                    edge_u,
                    edge_v,
                }
            }
            AreaShape::Sphere { center, radius } => AreaShape::Sphere {
                center,
                radius: radius * factor,
            },
        }
    }

    /// The same surface moved by `offset`.
    pub fn moved_by(&self, offset: Vec3) -> AreaShape {
        match *self {
            AreaShape::Rectangle {
                corner,
                edge_u,
                edge_v,
            } => AreaShape::Rectangle {
                corner: corner + offset,
                edge_u,
                edge_v,
            },
            AreaShape::Sphere { center, radius } => AreaShape::Sphere {
                center: center + offset,
                radius,
            },
        }
    }

    /// The same surface with its lengths scaled by `scale` about the origin.
    pub fn scaled(&self, scale: f32) -> AreaShape {
        match *self {
            AreaShape::Rectangle {
                corner,
                edge_u,
                edge_v,
            } => AreaShape::Rectangle {
                corner: corner * scale,
                edge_u: edge_u * scale,
                edge_v: edge_v * scale,
            },
            AreaShape::Sphere { center, radius } => AreaShape::Sphere {
                center: center * scale,
                radius: radius * scale,
            },
        }
    }
}

/// A spotlight's cone: full light within `angle·(1 − softness)` of its axis, fading
/// smoothly to none at `angle`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotCone {
    /// The unit direction of the cone's axis.
    pub direction: Vec3,
    /// The angle between the axis and the cone's edge, in degrees.
    pub angle: f32,
    /// The fraction of `angle`, from its edge inwards, over which the light fades.
    pub softness: f32,
    cos_outer: f32,
    cos_inner: f32,
}

impl SpotCone {
    /// A cone about unit `direction` of half-angle `angle` degrees (0..=90) whose edge fades over
    /// `softness` (0..=1) of it.
    pub fn new(direction: Vec3, angle: f32, softness: f32) -> Self {
        let outer = angle.to_radians();
        Self {
            direction,
            angle,
            softness,
            cos_outer: outer.cos(),
            cos_inner: (outer * (1.0 - softness)).cos(),
        }
    }

    /// The share of the light sent along unit direction `w` (from the light).
    #[inline]
    pub fn gain(&self, w: Vec3A) -> f32 {
        let c = w.dot(self.direction.into());
        if c >= self.cos_inner {
            1.0
        } else if c <= self.cos_outer {
            0.0
        } else {
            let x = (c - self.cos_outer) / (self.cos_inner - self.cos_outer);
            x * x * (3.0 - 2.0 * x)
        }
    }
}

/// How a point light's light fades with distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Falloff {
    /// It does not: the seed's lights, and Whitted's.
    None,
    /// As physical light does: `intensity / distance²` times the light's colour.
    InverseSquare {
        /// The colour's multiplier at a distance of one scene unit.
        intensity: f32,
    },
}

/// The most an inverse-square light may multiply its colour by, however near a surface
/// comes to it: keeps every product finite where a surface touches the light.
pub const MAX_FALLOFF_GAIN: f32 = 1.0e20;

impl Falloff {
    /// What the light's colour is multiplied by at `distance`.
    #[inline]
    pub fn gain(&self, distance: f32) -> f32 {
        match *self {
            Falloff::None => 1.0,
            Falloff::InverseSquare { intensity } => {
                (intensity / (distance * distance)).min(MAX_FALLOFF_GAIN)
            }
        }
    }
}

/// A point of `field` (relative to the scene's origin at the camera) within
/// `MAX_COORDINATE` of it on every axis.
fn within_reach(field: &'static str, p: Vec3) -> Result<(), FieldProblem> {
    if p.is_finite() && p.abs().max_element() as f64 <= MAX_COORDINATE {
        Ok(())
    } else {
        Err(FieldProblem::new(
            field,
            format!(
                "`{field}` must hold finite numbers within {MAX_COORDINATE:e} of the camera on \
                 every axis, got {:?}",
                p.to_array()
            ),
        ))
    }
}

impl Falloff {
    /// An inverse-square intensity within `limits::MAX_LIGHT_INTENSITY`.
    pub fn check(&self) -> Result<(), FieldProblem> {
        match *self {
            Falloff::None => Ok(()),
            Falloff::InverseSquare { intensity } => FieldProblem::check_range(
                "intensity",
                intensity,
                &(0.0..=limits::MAX_LIGHT_INTENSITY),
            ),
        }
    }
}

impl AreaShape {
    /// A rectangle whose corner is within reach and whose edges are, spanning a
    /// parallelogram (neither edge zero nor parallel to the other, or its samples would
    /// all lie on a line); a sphere within reach of a radius `limits::LENGTH` takes.
    pub fn check(&self) -> Result<(), FieldProblem> {
        match *self {
            AreaShape::Rectangle {
                corner,
                edge_u,
                edge_v,
            } => {
                within_reach("corner", corner)?;
                for (field, e) in [("edge_u", edge_u), ("edge_v", edge_v)] {
                    if !(e.is_finite() && e.abs().max_element() as f64 <= MAX_COORDINATE) {
                        return Err(FieldProblem::new(
                            field,
                            format!("`{field}` must lie within {MAX_COORDINATE:e} on every axis"),
                        ));
                    }
                }
                let area = edge_u.as_dvec3().cross(edge_v.as_dvec3()).length();
                let lengths = edge_u.as_dvec3().length() * edge_v.as_dvec3().length();
                if area > 1e-6 * lengths && area.sqrt() >= MIN_LENGTH {
                    Ok(())
                } else {
                    Err(FieldProblem::new(
                        "edge_v",
                        "`edge_u` and `edge_v` must span a rectangle: neither zero nor parallel",
                    ))
                }
            }
            AreaShape::Sphere { center, radius } => {
                within_reach("position", center)?;
                FieldProblem::check_length("radius", radius)
            }
        }
    }
}

impl Light {
    /// Checks the rules every light follows, whether a scene file or an edit made it:
    /// where it is within reach of the camera, a spotlight's cone (`limits::SPOT_ANGLE`, a
    /// softness from 0 to 1), an area light's surface, an intensity within its limit, and a
    /// colour within `limits::MAX_RADIANCE`. (A direction is a unit vector by construction.)
    pub fn check(&self) -> Result<(), FieldProblem> {
        match self.kind {
            LightKind::Point { position, falloff } => {
                within_reach("position", position)?;
                falloff.check()?;
            }
            LightKind::Spot {
                position,
                falloff,
                cone,
                radius,
            } => {
                within_reach("position", position)?;
                FieldProblem::check_range("angle", cone.angle, &limits::SPOT_ANGLE)?;
                FieldProblem::check_range("softness", cone.softness, &(0.0..=1.0))?;
                // 0 is a point; a disc has a radius the tracer can square.
                if radius != 0.0 {
                    FieldProblem::check_length("radius", radius)?;
                }
                falloff.check()?;
            }
            LightKind::Directional { .. } => {}
            LightKind::Area { shape, falloff, .. } => {
                shape.check()?;
                falloff.check()?;
            }
        }
        FieldProblem::check_color(
            "color",
            self.color.to_array(),
            limits::MAX_RADIANCE,
            limits::RADIANCE_BOUND,
        )
    }

    /// A point light at `position` of colour `color`, without falloff.
    pub fn point(position: Vec3, color: Vec3) -> Light {
        Light {
            kind: LightKind::Point {
                position,
                falloff: Falloff::None,
            },
            color,
        }
    }

    /// The one point every shadow ray toward the light ends at (a point light's or a
    /// spotlight's position); None for a directional or an area light, or a spotlight with
    /// a disc.
    pub fn position(&self) -> Option<Vec3> {
        self.anchor().filter(|_| !self.is_soft())
    }

    /// A point light's or a spotlight's position, a disc's or not; None for a directional
    /// or an area light.
    pub fn anchor(&self) -> Option<Vec3> {
        match self.kind {
            LightKind::Point { position, .. } | LightKind::Spot { position, .. } => Some(position),
            LightKind::Directional { .. } | LightKind::Area { .. } => None,
        }
    }

    /// Where the light is: its position or its surface's centre; None for a directional light.
    pub fn center(&self) -> Option<Vec3> {
        match self.kind {
            LightKind::Area { shape, .. } => Some(shape.center()),
            _ => self.anchor(),
        }
    }

    /// Whether its shadows are soft: it is sampled at one point of a surface per subsample.
    pub fn is_soft(&self) -> bool {
        match self.kind {
            LightKind::Area { .. } => true,
            LightKind::Spot { radius, .. } => radius > 0.0,
            LightKind::Point { .. } | LightKind::Directional { .. } => false,
        }
    }

    /// The same light moved by `offset` (a directional light, which has no place, unmoved).
    pub fn moved_by(&self, offset: Vec3) -> Light {
        let mut moved = *self;
        match &mut moved.kind {
            LightKind::Point { position, .. } | LightKind::Spot { position, .. } => {
                *position += offset
            }
            LightKind::Area { shape, .. } => *shape = shape.moved_by(offset),
            LightKind::Directional { .. } => {}
        }
        moved
    }

    /// `placed`'s place, direction and size (this light placed anew, by its group) with this
    /// light's colour, falloff, cone angle and softness, and visibility: what an edit may
    /// have changed of it stays.
    pub fn placed_as(&self, placed: &Light) -> Light {
        let mut out = *placed;
        out.color = self.color;
        let mut was = *self;
        if let (Some(to), Some(from)) = (out.falloff_mut(), was.falloff_mut()) {
            *to = *from;
        }
        match (&mut out.kind, self.kind) {
            (LightKind::Spot { cone, .. }, LightKind::Spot { cone: was, .. }) => {
                *cone = SpotCone::new(cone.direction, was.angle, was.softness);
            }
            (LightKind::Area { visible, .. }, LightKind::Area { visible: was, .. }) => {
                *visible = was;
            }
            _ => {}
        }
        out
    }

    /// How the light fades with distance; None for a directional light, which does not.
    pub fn falloff_mut(&mut self) -> Option<&mut Falloff> {
        match &mut self.kind {
            LightKind::Point { falloff, .. }
            | LightKind::Spot { falloff, .. }
            | LightKind::Area { falloff, .. } => Some(falloff),
            LightKind::Directional { .. } => None,
        }
    }

    /// The surface that rays from the camera see glowing, if the light has one and shows it.
    #[inline]
    pub fn emitter(&self) -> Option<AreaShape> {
        match self.kind {
            LightKind::Area {
                shape,
                visible: true,
                ..
            } => Some(shape),
            _ => None,
        }
    }

    /// The same light in a scene scaled by `scale` about the origin: positions and sizes scale,
    /// and inverse-square intensity with the square, so that what it lights stays as bright.
    pub fn scaled(&self, scale: f32) -> Light {
        let falloff = |f: Falloff| match f {
            Falloff::None => Falloff::None,
            Falloff::InverseSquare { intensity } => Falloff::InverseSquare {
                intensity: intensity * scale * scale,
            },
        };
        let kind = match self.kind {
            LightKind::Point {
                position,
                falloff: f,
            } => LightKind::Point {
                position: position * scale,
                falloff: falloff(f),
            },
            LightKind::Spot {
                position,
                falloff: f,
                cone,
                radius,
            } => LightKind::Spot {
                position: position * scale,
                falloff: falloff(f),
                cone,
                radius: radius * scale,
            },
            kind @ LightKind::Directional { .. } => kind,
            LightKind::Area {
                shape,
                falloff: f,
                visible,
            } => LightKind::Area {
                shape: shape.scaled(scale),
                falloff: falloff(f),
                visible,
            },
        };
        Light { kind, ..*self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule of `Light::check` at its limit and just past it; the field named is the
    /// one at fault.
    #[test]
    fn check_holds_each_rule_at_its_limit() {
        let falloff = Falloff::InverseSquare { intensity: 1.0e30 };
        let spot = |angle: f32, softness: f32| Light {
            kind: LightKind::Spot {
                position: Vec3::splat(1.0e12),
                falloff,
                cone: SpotCone::new(Vec3::NEG_Y, angle, softness),
                radius: 0.0,
            },
            color: Vec3::splat(1.0e4),
        };
        let rectangle = |edge_v: Vec3| Light {
            kind: LightKind::Area {
                shape: AreaShape::Rectangle {
                    corner: Vec3::ZERO,
                    edge_u: Vec3::X,
                    edge_v,
                },
                falloff: Falloff::None,
                visible: true,
            },
            color: Vec3::ONE,
        };
        let sphere = |radius: f32| Light {
            kind: LightKind::Area {
                shape: AreaShape::Sphere {
                    center: Vec3::ZERO,
                    radius,
                },
                falloff: Falloff::None,
                visible: true,
            },
            color: Vec3::ONE,
        };
        let disc_spot = |radius: f32| {
            let mut light = spot(30.0, 0.0);
            if let LightKind::Spot { radius: r, .. } = &mut light.kind {
                *r = radius;
            }
            light
        };
        for ok in [
            spot(180.0, 1.0),
            spot(0.01, 0.0),
            disc_spot(1.0e-12),
            disc_spot(1.0e12),
            rectangle(Vec3::Y),
            sphere(1.0e-12),
            sphere(1.0e12),
            Light::point(Vec3::ZERO, Vec3::ZERO),
        ] {
            assert_eq!(ok.check(), Ok(()), "{ok:?}");
        }
        let mut far = Light::point(Vec3::new(0.0, 0.0, -2.0e12), Vec3::ONE);
        let mut bright = Light::point(Vec3::ZERO, Vec3::new(0.0, 1.0e5, 0.0));
        let mut intense = Light::point(Vec3::ZERO, Vec3::ONE);
        *intense.falloff_mut().unwrap() = Falloff::InverseSquare { intensity: 2.0e30 };
        let refused = [
            ("position", far),
            ("color", bright),
            ("intensity", intense),
            ("radius", disc_spot(-1.0)),
            ("radius", disc_spot(f32::NAN)),
            ("radius", disc_spot(2.0e12)),
            ("angle", spot(180.5, 0.0)),
            ("angle", spot(0.001, 0.0)),
            ("softness", spot(30.0, 1.5)),
            ("edge_v", rectangle(Vec3::X * 2.0)),
            ("edge_v", rectangle(Vec3::ZERO)),
            ("edge_v", rectangle(Vec3::new(0.0, 2.0e12, 0.0))),
            ("radius", sphere(0.0)),
            ("radius", sphere(f32::NAN)),
            ("radius", sphere(2.0e12)),
        ];
        for (field, light) in refused {
            let problem = light.check().unwrap_err();
            assert_eq!(problem.field, field, "{light:?}");
            assert!(
                problem.message.contains(&format!("`{field}`")),
                "{problem:?}"
            );
        }
        far.color = Vec3::NAN;
        bright.color = Vec3::NAN;
        assert_eq!(
            far.check().unwrap_err().field,
            "position",
            "the place first"
        );
        assert_eq!(bright.check().unwrap_err().field, "color");
    }

    #[test]
    fn sphere_samples_lie_on_the_disc_facing_the_point() {
        let shape = AreaShape::Sphere {
            center: Vec3::new(1.0, 2.0, 3.0),
            radius: 0.5,
        };
        let p = Vec3A::new(4.0, -2.0, 3.0);
        let w = (p - Vec3A::new(1.0, 2.0, 3.0)).normalize();
        for u in [(0.1, 0.2), (0.9, 0.5), (0.5, 0.5), (0.0, 0.99)] {
            let q = shape.sample(p, u) - Vec3A::new(1.0, 2.0, 3.0);
            assert!(q.dot(w).abs() < 1e-5 && q.length() <= 0.5 + 1e-5, "{q}");
        }
    }

    #[test]
    fn rectangle_hits_inside_and_misses_outside() {
        let shape = AreaShape::Rectangle {
            corner: Vec3::new(-1.0, 5.0, -1.0),
            edge_u: Vec3::new(2.0, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, 2.0),
        };
        let up = |x: f32, z: f32| Ray::new(Vec3A::new(x, 0.0, z), Vec3A::Y);
        assert_eq!(
            shape.intersect(&up(0.0, 0.0), 0.0, f32::INFINITY),
            Some(5.0)
        );
        assert_eq!(
            shape.intersect(&up(0.99, -0.99), 0.0, f32::INFINITY),
            Some(5.0)
        );
        assert_eq!(shape.intersect(&up(1.01, 0.0), 0.0, f32::INFINITY), None);
        assert_eq!(
            shape.intersect(&up(0.0, 0.0), 0.0, 4.0),
            None,
            "beyond t_max"
        );
        assert_eq!(shape.center(), Vec3::new(0.0, 5.0, 0.0));
        assert!((shape.resized(2.0).size() - 2.0 * shape.size()).abs() < 1e-6);
    }

    #[test]
    fn spot_cone_is_full_inside_and_dark_outside() {
        let cone = SpotCone::new(Vec3::NEG_Y, 30.0, 0.5);
        let at = |deg: f32| {
            let (s, c) = deg.to_radians().sin_cos();
            cone.gain(Vec3A::new(s, -c, 0.0))
        };
        assert_eq!(at(0.0), 1.0);
        assert_eq!(at(14.9), 1.0);
        assert_eq!(at(30.1), 0.0);
        // Between, smoothstep in the cosine.
        let x = (22.5f32.to_radians().cos() - 30f32.to_radians().cos())
            / (15f32.to_radians().cos() - 30f32.to_radians().cos());
        let mid = at(22.5);
        assert!((mid - x * x * (3.0 - 2.0 * x)).abs() < 1e-5, "{mid}");
        assert!(at(20.0) > at(25.0));
        let hard = SpotCone::new(Vec3::NEG_Y, 30.0, 0.0);
        assert_eq!(hard.gain(Vec3A::new(0.49, -0.87, 0.0).normalize()), 1.0);
        assert_eq!(hard.gain(Vec3A::new(0.51, -0.86, 0.0).normalize()), 0.0);
    }

    #[test]
    fn inverse_square_falls_off_with_the_square_and_stays_finite_at_the_light() {
        let f = Falloff::InverseSquare { intensity: 50.0 };
        assert_eq!(f.gain(1.0), 50.0);
        assert_eq!(f.gain(5.0), 2.0);
        assert_eq!(f.gain(10.0), 0.5);
        assert_eq!(f.gain(0.0), MAX_FALLOFF_GAIN);
        assert_eq!(Falloff::None.gain(1e6), 1.0);
    }
}
