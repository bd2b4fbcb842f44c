//! Rays and the shapes they hit; finding which shape a ray hits is the acceleration
//! layer's job (accel/).

mod aabb;
mod cylinder;
mod ray;
mod shape;
mod sphere;
mod triangle;

pub use aabb::Aabb;
pub use cylinder::Cylinder;
pub use ray::{Ray, RayQuery};
pub use shape::{Shape, ShapeHit, SurfacePoint};
pub use sphere::Sphere;
pub use triangle::Triangle;
