//! The closed set of primitive shapes, dispatched by `match` (no vtables on the hot path).

use super::aabb::Aabb;
use super::capsule::Capsule;
use super::cone::Cone;
use super::cuboid::{Cuboid, CuboidFace};
use super::cylinder::{Cylinder, CylinderPart};
use super::disc::Disc;
use super::ray::RayQuery;
use super::sphere::Sphere;
use super::torus::Torus;
use super::triangle::{Triangle, TriangleHit};
use super::uv_frame::UvFrame;
use glam::Vec3A;

/// Every kind of shape a primitive can be (a closed set).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere(Sphere),
    /// A triangle (polygons and tetrahedra are made of these).
    Triangle(Triangle),
    /// A cylinder, capped or open.
    Cylinder(Cylinder),
    /// An axis-aligned solid box.
    Cuboid(Cuboid),
    /// A flat disc (a plane is one far wider than the scene).
    Disc(Disc),
    /// A cone or frustum, capped or open.
    Cone(Cone),
    /// A torus.
    Torus(Torus),
    /// A capsule: an upright side closed by hemispheres.
    Capsule(Capsule),
}

/// What the intersection test found; enough to rebuild the surface point later, once, for
/// the nearest hit only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeHit {
    /// The distance parameter along the ray.
    pub t: f32,
    /// What else the shape needs to rebuild the surface point.
    pub detail: HitDetail,
}

/// Which part of which shape a hit is on, as each kind of shape needs to know it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HitDetail {
    /// A sphere's surface.
    Sphere,
    /// A triangle, at barycentric weights `b`.
    Triangle {
        /// The weights of its three corners.
        b: [f32; 3],
    },
    /// A cylinder's side or cap.
    Cylinder {
        /// Which.
        part: CylinderPart,
    },
    /// A box's face.
    Cuboid {
        /// Which.
        face: CuboidFace,
    },
    /// A disc.
    Disc,
    /// A cone's side or cap.
    Cone {
        /// Which.
        part: CylinderPart,
    },
    /// A torus.
    Torus,
    /// A capsule's side (`Side`) or one of its ends (`Bottom`, `Top`).
    Capsule {
        /// Which.
        part: CylinderPart,
    },
    /// Triangle `triangle` of a mesh, at barycentric weights `b`.
    Mesh {
        /// The triangle's index in the mesh.
        triangle: u32,
        /// The group of four that holds it (`TriangleGroup`), whose copy of its corners the
        /// test has just read: the surface point is made from there, not from the mesh's
        /// vertices, which a large mesh keeps far from the cache.
        group: u32,
        /// The weights of its three corners.
        b: [f32; 3],
    },
    /// Member `leaf` of a CSG solid (counted in its tree's order), on `part` of it.
    Csg {
        /// Which member.
        leaf: u16,
        /// Where on it.
        part: ShapePart,
    },
}

/// Where on a closed shape a hit is, without the shape: what a CSG hit keeps of its
/// member's own detail.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShapePart {
    /// A shape of one surface (a sphere, a torus, a plane).
    Whole,
    /// A cylinder's, cone's or capsule's side or end.
    Part(CylinderPart),
    /// A box's face.
    Face(CuboidFace),
}

impl ShapePart {
    /// The part a shape's own hit detail names.
    #[inline]
    pub fn of(detail: HitDetail) -> ShapePart {
        match detail {
            HitDetail::Cylinder { part }
            | HitDetail::Cone { part }
            | HitDetail::Capsule { part } => ShapePart::Part(part),
            HitDetail::Cuboid { face } => ShapePart::Face(face),
            _ => ShapePart::Whole,
        }
    }

    /// The hit detail of this part of `shape`.
    #[inline]
    pub fn detail(self, shape: &Shape) -> HitDetail {
        match (shape, self) {
            (Shape::Cylinder(_), ShapePart::Part(part)) => HitDetail::Cylinder { part },
            (Shape::Cone(_), ShapePart::Part(part)) => HitDetail::Cone { part },
            (Shape::Capsule(_), ShapePart::Part(part)) => HitDetail::Capsule { part },
            (Shape::Cuboid(_), ShapePart::Face(face)) => HitDetail::Cuboid { face },
            (Shape::Sphere(_), _) => HitDetail::Sphere,
            (Shape::Disc(_), _) => HitDetail::Disc,
            (Shape::Torus(_), _) => HitDetail::Torus,
            (shape, part) => unreachable!("{part:?} is no part of {shape:?}"),
        }
    }
}

impl HitDetail {
    /// Which part of the shape was hit: 0, or for a cylinder or a cone its side or a cap,
    /// for a box its face.
    #[inline]
    pub fn part(&self) -> u32 {
        match self {
            HitDetail::Cylinder { part }
            | HitDetail::Cone { part }
            | HitDetail::Capsule { part } => *part as u32,
            HitDetail::Cuboid { face } => face.axis as u32 * 2 + face.upper as u32,
            // A CSG member's part among all its members' (at most six parts each).
            HitDetail::Csg { leaf, part } => {
                let own = match *part {
                    ShapePart::Whole => 0,
                    ShapePart::Part(p) => p as u32,
                    ShapePart::Face(f) => f.axis as u32 * 2 + f.upper as u32,
                };
                *leaf as u32 * 6 + own
            }
            _ => 0,
        }
    }
}

/// A point on a surface, as shading needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// The hit point.
    pub point: Vec3A,
    /// Per-coordinate bound on the distance of `point` from the true surface.
    pub error: Vec3A,
    /// Outward (for closed shapes) or winding-order (for triangles) unit normal: the true
    /// surface's, which decides sides and where spawned rays start.
    pub normal: Vec3A,
    /// The unit normal shading uses: `normal`, except on a smooth mesh, where it is the
    /// corners' normals interpolated (on the same side as `normal`).
    pub shading: Vec3A,
}

impl Shape {
    /// The nearest hit in (0, t_max).
    #[inline]
    pub fn intersect(&self, q: &RayQuery, t_max: f32) -> Option<ShapeHit> {
        self.intersect_after(q, 0.0, t_max)
    }

    /// The nearest hit with t in (t_min, t_max).
    #[inline(always)]
    pub fn intersect_after(&self, q: &RayQuery, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match self {
            Shape::Sphere(s) => s.intersect_after(&q.ray, t_min, t_max).map(|t| ShapeHit {
                t,
                detail: HitDetail::Sphere,
            }),
            Shape::Triangle(tri) => tri.intersect_after(q, t_min, t_max).map(|h| ShapeHit {
                t: h.t,
                detail: HitDetail::Triangle { b: h.b },
            }),
            Shape::Cylinder(c) => {
                c.intersect_after(&q.ray, t_min, t_max)
                    .map(|(t, part)| ShapeHit {
                        t,
                        detail: HitDetail::Cylinder { part },
                    })
            }
            Shape::Cuboid(b) => b
                .intersect_after(q, t_min, t_max)
                .map(|(t, face)| ShapeHit {
                    t,
                    detail: HitDetail::Cuboid { face },
                }),
            Shape::Disc(d) => d.intersect_after(&q.ray, t_min, t_max).map(|t| ShapeHit {
                t,
                detail: HitDetail::Disc,
            }),
            Shape::Cone(c) => c
                .intersect_after(&q.ray, t_min, t_max)
                .map(|(t, part)| ShapeHit {
                    t,
                    detail: HitDetail::Cone { part },
                }),
            Shape::Torus(tor) => tor.intersect_after(&q.ray, t_min, t_max).map(|t| ShapeHit {
                t,
                detail: HitDetail::Torus,
            }),
            Shape::Capsule(c) => {
                c.intersect_after(&q.ray, t_min, t_max)
                    .map(|(t, part)| ShapeHit {
                        t,
                        detail: HitDetail::Capsule { part },
                    })
            }
        }
    }

    /// How many times the segment (0, t_max) of the ray crosses this shape's surface.
    #[inline]
    pub fn crossings(&self, q: &RayQuery, t_max: f32) -> u32 {
        match self {
            Shape::Sphere(s) => s.crossings(&q.ray, t_max),
            Shape::Triangle(tri) => tri.intersect(q, t_max).is_some() as u32,
            Shape::Cylinder(c) => c.crossings(&q.ray, t_max),
            Shape::Cuboid(b) => b.crossings(q, t_max),
            Shape::Disc(d) => d.intersect_after(&q.ray, 0.0, t_max).is_some() as u32,
            Shape::Cone(c) => c.crossings(&q.ray, t_max),
            Shape::Torus(tor) => tor.crossings(&q.ray, t_max),
            Shape::Capsule(c) => c.crossings(&q.ray, t_max),
        }
    }

    /// The surface point of `hit`, found by `intersect` along `q`.
    #[inline]
    pub fn surface(&self, q: &RayQuery, hit: &ShapeHit) -> SurfacePoint {
        let at = |(point, normal, error)| SurfacePoint {
            point,
            error,
            normal,
            shading: normal,
        };
        match (self, hit.detail) {
            (Shape::Sphere(s), _) => at(s.surface(&q.ray, hit.t)),
            (Shape::Triangle(tri), HitDetail::Triangle { b }) => {
                let (point, error) = tri.surface(&TriangleHit { t: hit.t, b });
                SurfacePoint {
                    point,
                    error,
                    normal: tri.normal,
                    shading: tri.normal,
                }
            }
            (Shape::Cylinder(c), HitDetail::Cylinder { part }) => {
                at(c.surface(&q.ray, hit.t, part))
            }
            (Shape::Cuboid(b), HitDetail::Cuboid { face }) => at(b.surface(&q.ray, hit.t, face)),
            (Shape::Disc(d), _) => at(d.surface(&q.ray, hit.t)),
            (Shape::Cone(c), HitDetail::Cone { part }) => at(c.surface(&q.ray, hit.t, part)),
            (Shape::Torus(tor), _) => at(tor.surface(&q.ray, hit.t)),
            (Shape::Capsule(c), HitDetail::Capsule { part }) => at(c.surface(&q.ray, hit.t, part)),
            (shape, detail) => unreachable!("hit {detail:?} does not belong to {shape:?}"),
        }
    }

    /// Texture coordinates of a surface point: computed only for textures that use them
    /// (the trigonometry is a noticeable share of a pass otherwise).
    pub fn uv(&self, surface: &SurfacePoint, hit: &ShapeHit) -> (f32, f32) {
        match (self, hit.detail) {
            (Shape::Sphere(_), _) => Sphere::uv(surface.normal),
            (Shape::Triangle(_), HitDetail::Triangle { b }) => (b[1], b[2]),
            (Shape::Cylinder(c), HitDetail::Cylinder { part }) => c.uv(surface.point, part),
            (Shape::Cuboid(b), HitDetail::Cuboid { face }) => b.uv(surface.point, face),
            (Shape::Disc(d), _) => d.uv(surface.point),
            (Shape::Cone(c), HitDetail::Cone { part }) => c.uv(surface.point, part),
            (Shape::Torus(tor), _) => tor.uv(surface.point),
            (Shape::Capsule(c), _) => c.uv(surface.point),
            (shape, detail) => unreachable!("hit {detail:?} does not belong to {shape:?}"),
        }
    }

    /// The texture coordinates of a surface point and their tangents ([`UvFrame`]), for
    /// relief; computed only for materials that have it.
    pub fn uv_frame(&self, surface: &SurfacePoint, hit: &ShapeHit) -> UvFrame {
        let p = surface.point;
        match (self, hit.detail) {
            (Shape::Sphere(s), _) => s.uv_frame(surface.normal),
            (Shape::Triangle(tri), HitDetail::Triangle { b }) => UvFrame {
                uv: (b[1], b[2]),
                dpdu: tri.p[1] - tri.p[0],
                dpdv: tri.p[2] - tri.p[0],
            },
            (Shape::Cylinder(c), HitDetail::Cylinder { part }) => c.uv_frame(p, part),
            (Shape::Cuboid(b), HitDetail::Cuboid { face }) => b.uv_frame(p, face),
            (Shape::Disc(d), _) => d.uv_frame(p),
            (Shape::Cone(c), HitDetail::Cone { part }) => c.uv_frame(p, part),
            (Shape::Torus(tor), _) => tor.uv_frame(p),
            (Shape::Capsule(c), _) => c.uv_frame(p),
            (shape, detail) => unreachable!("hit {detail:?} does not belong to {shape:?}"),
        }
    }

    /// The box around the shape.
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Triangle(t) => t.bounds(),
            Shape::Cylinder(c) => c.bounds(),
            Shape::Cuboid(b) => b.bounds(),
            Shape::Disc(d) => d.bounds(),
            Shape::Cone(c) => c.bounds(),
            Shape::Torus(tor) => tor.bounds(),
            Shape::Capsule(c) => c.bounds(),
        }
    }

    /// Whether `p` lies inside the solid it bounds (for CSG); false for a shape with no
    /// inside (a triangle, a disc, an open tube or cone). A point on the surface may count
    /// either way.
    #[inline]
    pub fn contains(&self, p: Vec3A) -> bool {
        match self {
            Shape::Sphere(s) => (p - s.center).length_squared() < s.radius * s.radius,
            Shape::Cuboid(b) => p.cmpgt(b.min).all() && p.cmplt(b.max).all(),
            Shape::Cylinder(c) => {
                let rel = p - Vec3A::from(c.base);
                c.caps
                    && rel.y > 0.0
                    && rel.y < c.height
                    && rel.x * rel.x + rel.z * rel.z < c.radius * c.radius
            }
            Shape::Cone(c) => {
                let rel = p - Vec3A::from(c.base);
                let r = c.radius + (c.top_radius - c.radius) * (rel.y / c.height);
                c.caps && rel.y > 0.0 && rel.y < c.height && rel.x * rel.x + rel.z * rel.z < r * r
            }
            Shape::Torus(tor) => {
                let rel = p - Vec3A::from(tor.center);
                let ring = (rel.x * rel.x + rel.z * rel.z).sqrt() - tor.major_radius;
                ring * ring + rel.y * rel.y < tor.minor_radius * tor.minor_radius
            }
            Shape::Capsule(c) => {
                let rel = p - Vec3A::from(c.base);
                let y = rel.y.clamp(0.0, c.height);
                let d = Vec3A::new(rel.x, rel.y - y, rel.z);
                d.length_squared() < c.radius * c.radius
            }
            Shape::Triangle(_) | Shape::Disc(_) => false,
        }
    }

    /// Whether it is a closed convex solid: a line crosses it at most twice, and a ray
    /// that starts inside meets it before anything beyond it.
    pub fn is_convex_solid(&self) -> bool {
        match self {
            Shape::Sphere(_) | Shape::Cuboid(_) | Shape::Capsule(_) => true,
            Shape::Cylinder(c) => c.caps,
            Shape::Cone(c) => c.caps,
            Shape::Triangle(_) | Shape::Disc(_) | Shape::Torus(_) => false,
        }
    }
}
