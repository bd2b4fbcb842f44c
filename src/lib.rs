//! prism: a fast and accurate Whitted-style CPU ray tracer.
//!
//! The library has no window dependency: it loads scenes, traces them pass by pass into an
//! accumulator, and writes images. The `prism` binary adds the command line, the
//! interactive viewer and the bench on top.

#![warn(missing_docs)]

pub mod accel;
pub mod appearance;
pub mod camera;
pub mod color;
pub mod geometry;
pub mod integrator;
pub mod isa;
pub mod limits;
pub mod messages;
pub mod numerics;
pub mod render;
pub mod sampler;
pub mod scene;
pub mod scene_file;
pub mod seed;
mod simd;
pub mod xorshift;
