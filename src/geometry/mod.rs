//! Rays and the shapes they hit; finding which shape a ray hits is the acceleration
//! layer's job (accel/).

pub mod aabb;
pub mod cylinder;
pub mod ray;
pub mod shape;
pub mod sphere;
pub mod triangle;

pub use aabb::Aabb;
pub use cylinder::Cylinder;
pub use ray::{Ray, RayQuery};
pub use shape::{Shape, ShapeHit, SurfacePoint};
pub use sphere::Sphere;
pub use triangle::Triangle;
