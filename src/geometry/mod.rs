//! Rays and the shapes they hit; finding which shape a ray hits is the acceleration
//! layer's job (accel/).

mod aabb;
mod cylinder;
mod mesh;
mod ray;
mod shape;
mod sphere;
mod transform;
mod triangle;

pub use aabb::Aabb;
pub use cylinder::{Cylinder, CylinderPart};
pub use mesh::{Mesh, MeshError};
pub use ray::{Ray, RayQuery};
pub use shape::{HitDetail, Shape, ShapeHit, SurfacePoint};
pub use sphere::Sphere;
pub use transform::Transform;
pub use triangle::{Triangle, TriangleHit};
