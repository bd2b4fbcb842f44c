//! A camera written as the scene file's `[camera]` table, so that a view found with the
//! mouse can go back into a file ("Copy camera" in the viewer).

use crate::camera::Camera;
use glam::DVec3;
use std::fmt::Write as _;

/// The `[camera]` table that gives `camera` in a scene whose positions are relative to
/// `origin`: the eye in world coordinates, the view as yaw and pitch about `up`, and the
/// lens when it has an aperture. Every number is written so that it reads back exactly.
pub fn camera_table(camera: &Camera, origin: DVec3) -> String {
    let eye = origin + camera.eye.as_dvec3();
    let mut t = String::from("[camera]\n");
    let _ = writeln!(t, "eye = [{:?}, {:?}, {:?}]", eye.x, eye.y, eye.z);
    let _ = writeln!(t, "yaw = {:?}", camera.yaw);
    let _ = writeln!(t, "pitch = {:?}", camera.pitch);
    let up = camera.up;
    if up != glam::Vec3::Y {
        let _ = writeln!(t, "up = [{:?}, {:?}, {:?}]", up.x, up.y, up.z);
    }
    let _ = writeln!(t, "fov = {:?}", camera.vfov);
    if camera.aperture > 0.0 {
        let _ = writeln!(t, "aperture = {:?}", camera.aperture);
        let _ = writeln!(t, "focus_distance = {:?}", camera.focus_distance);
    }
    if camera.handedness == crate::camera::Handedness::Left {
        let _ = writeln!(t, "handedness = \"left\"");
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// The table, put in a scene file, gives back the same camera: the same world eye (to
    /// f32 rounding of the scene's frame) and exactly the same angles, up and lens.
    #[test]
    fn the_table_reads_back_as_the_same_camera() {
        let origin = DVec3::new(1e3, -2.5, 7.25);
        let cameras = [
            Camera {
                eye: Vec3::new(0.1, 2.0, -3.3),
                yaw: 33.3,
                pitch: -12.125,
                vfov: 28.072487,
                up: Vec3::Y,
                aperture: 0.0,
                focus_distance: 1.0,
                handedness: Default::default(),
            },
            Camera {
                eye: Vec3::new(-4.0, 0.5, 1e-3),
                yaw: -179.9,
                pitch: 88.0,
                vfov: 60.0,
                up: Vec3::new(0.0, 0.6, 0.8),
                aperture: 0.35,
                focus_distance: 12.5,
                handedness: Default::default(),
            },
        ];
        for camera in cameras {
            let text = format!(
                "{}\n[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n",
                camera_table(&camera, origin)
            );
            let scene = crate::scene_file::parse_scene(
                &text,
                std::path::Path::new("camera.toml"),
                std::path::Path::new("."),
            )
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
            let back = scene.camera;
            let world = scene.origin + back.eye.as_dvec3();
            let want = origin + camera.eye.as_dvec3();
            assert!(
                (world - want).length() < 1e-9 * want.length(),
                "{world} against {want}"
            );
            assert_eq!(back.yaw, camera.yaw, "{text}");
            assert_eq!(back.pitch, camera.pitch, "{text}");
            assert_eq!(back.vfov, camera.vfov);
            assert!((back.up - camera.up.normalize()).length() < 1e-7);
            assert_eq!(back.aperture, camera.aperture);
            if camera.aperture > 0.0 {
                assert_eq!(back.focus_distance, camera.focus_distance);
            }
        }
    }
}
