//! Rays and the shapes they hit; finding which shape a ray hits is the acceleration
//! layer's job (accel/).

mod aabb;
mod capsule;
mod cone;
mod cuboid;
mod cylinder;
mod disc;
mod mesh;
mod polynomial;
mod ray;
mod shape;
mod sphere;
mod torus;
mod transform;
mod triangle;
mod triangle_group;
mod uv_frame;

pub use aabb::Aabb;
pub use capsule::Capsule;
pub use cone::Cone;
pub use cuboid::{Cuboid, CuboidFace};
pub use cylinder::{Cylinder, CylinderPart};
pub use disc::{Disc, picture_axes};
pub use mesh::{Mesh, MeshError};
pub use ray::{Ray, RayQuery};
pub use shape::{HitDetail, Shape, ShapeHit, ShapePart, SurfacePoint};
pub use sphere::Sphere;
pub use torus::Torus;
pub use transform::Transform;
pub use triangle::{Triangle, TriangleHit};
pub use triangle_group::{
    GROUP_WIDTH, GroupPair, GroupRay, LaneRay, ListedTriangle, OCTET_WIDTH, TriangleGroup,
    TriangleOctet,
};
pub use uv_frame::UvFrame;
