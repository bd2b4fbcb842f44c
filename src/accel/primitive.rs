//! What the acceleration layer indexes: one intersectable piece of an object, either a
//! shape in the scene's space or an instance of a model placed by a transform.

use super::csg::Csg;
use super::instance::Instance;
use crate::geometry::{Aabb, RayQuery, Shape, ShapeHit, SurfacePoint, UvFrame};
use glam::Vec3A;
use std::sync::Arc;

/// One intersectable piece of an object (a polygon becomes a fan of triangles, a
/// tetrahedron four, a mesh one instance), tagged with the object it belongs to.
#[derive(Clone, Debug)]
pub struct Primitive {
    /// The surface itself.
    pub surface: Surface,
    /// Index of the object it belongs to, into the scene's objects.
    pub object: u32,
    /// The material its surface takes, as the appearance numbers them: the object's own
    /// (`object`), or a CSG member's (a union's members are primitives of one object); for
    /// a combination, `CSG_MEMBERS_MATERIAL`: its members name theirs (`Csg::material_slot`).
    pub material: u32,
}

/// A combination's `Primitive::material`: each hit's member names its own.
pub const CSG_MEMBERS_MATERIAL: u32 = u32::MAX;

/// What a primitive is (a closed set).
#[derive(Clone, Debug)]
pub enum Surface {
    /// A shape in the scene's space.
    Shape(Shape),
    /// A model (a mesh under its own hierarchy, or a shape) in its own space, placed by a
    /// transform: the second level of a two-level hierarchy. Models are shared, so many
    /// instances of one mesh cost one mesh.
    Instance(Arc<Instance>),
    /// Closed solids combined (csg.rs), in the scene's space.
    Csg(Arc<Csg>),
}

impl Surface {
    /// The nearest hit with t in (t_min, t_max).
    #[inline(always)]
    pub fn intersect_after(&self, q: &RayQuery, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match self {
            Surface::Shape(shape) => shape.intersect_after(q, t_min, t_max),
            Surface::Instance(instance) => instance.intersect_after(q, t_min, t_max),
            Surface::Csg(csg) => csg.intersect_after(q, t_min, t_max),
        }
    }

    /// The nearest hit in (0, t_max).
    #[inline]
    pub fn intersect(&self, q: &RayQuery, t_max: f32) -> Option<ShapeHit> {
        self.intersect_after(q, 0.0, t_max)
    }

    /// Whether anything of it lies on the segment (0, t_max).
    #[inline]
    pub fn occludes(&self, q: &RayQuery, t_max: f32) -> bool {
        match self {
            Surface::Shape(shape) => shape.intersect(q, t_max).is_some(),
            Surface::Instance(instance) => instance.occludes(q, t_max),
            Surface::Csg(csg) => csg.intersect_after(q, 0.0, t_max).is_some(),
        }
    }

    /// How many times the segment (0, t_max) crosses its surface.
    #[inline(always)]
    pub fn crossings(&self, q: &RayQuery, t_max: f32) -> u32 {
        match self {
            Surface::Shape(shape) => shape.crossings(q, t_max),
            Surface::Instance(instance) => instance.crossings(q, t_max),
            Surface::Csg(csg) => csg.crossings(q, t_max),
        }
    }

    /// The surface point of `hit`, found along `q`, in the scene's space.
    #[inline(always)]
    pub fn surface(&self, q: &RayQuery, hit: &ShapeHit) -> SurfacePoint {
        match self {
            Surface::Shape(shape) => shape.surface(q, hit),
            Surface::Instance(instance) => instance.surface(q, hit),
            Surface::Csg(csg) => csg.surface(q, hit),
        }
    }

    /// Where shadow rays from `hit` start on a smooth mesh, with its error bound; None on
    /// anything else (a mesh is always an instance).
    #[inline]
    pub fn shadow_point(&self, hit: &ShapeHit) -> Option<(Vec3A, Vec3A)> {
        match self {
            Surface::Shape(_) | Surface::Csg(_) => None,
            Surface::Instance(instance) => instance.shadow_point(hit),
        }
    }

    /// The texture coordinates of `surface`, the surface point of `hit` along `q`.
    #[inline]
    pub fn uv(&self, q: &RayQuery, surface: &SurfacePoint, hit: &ShapeHit) -> (f32, f32) {
        match self {
            Surface::Shape(shape) => shape.uv(surface, hit),
            Surface::Instance(instance) => instance.uv(q, hit),
            Surface::Csg(csg) => csg.uv(q, surface, hit),
        }
    }

    /// The texture coordinates of `surface` and their tangents, in the scene's space.
    #[inline]
    pub fn uv_frame(&self, q: &RayQuery, surface: &SurfacePoint, hit: &ShapeHit) -> UvFrame {
        match self {
            Surface::Shape(shape) => shape.uv_frame(surface, hit),
            Surface::Instance(instance) => instance.uv_frame(q, hit),
            Surface::Csg(csg) => csg.uv_frame(q, surface, hit),
        }
    }

    /// The box around it, in the scene's space.
    pub fn bounds(&self) -> Aabb {
        match self {
            Surface::Shape(shape) => shape.bounds(),
            Surface::Instance(instance) => instance.bounds(),
            Surface::Csg(csg) => csg.bounds(),
        }
    }

    /// The shape, when it is one in the scene's space.
    pub fn shape(&self) -> Option<&Shape> {
        match self {
            Surface::Shape(shape) => Some(shape),
            Surface::Instance(_) | Surface::Csg(_) => None,
        }
    }
}
