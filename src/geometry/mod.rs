//! Rays, the shapes they hit, and the bounding volume hierarchy that finds the hits fast.

pub mod aabb;
pub mod bvh;
pub mod bvh_build;
pub mod cylinder;
pub mod ray;
pub mod shape;
pub mod sphere;
pub mod triangle;

pub use aabb::Aabb;
pub use bvh::Bvh;
pub use cylinder::Cylinder;
pub use ray::{Ray, RayQuery};
pub use shape::{Shape, ShapeHit, SurfacePoint};
pub use sphere::Sphere;
pub use triangle::Triangle;
