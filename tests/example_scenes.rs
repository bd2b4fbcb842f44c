//! Every example scene in assets/scenes loads and renders: a small image of each, at two
//! subsamples per pixel with its own integrator, holds only finite colours and shows
//! something (more than one colour, some of it lit). The scenes are what a new user opens
//! first, and the docs' pictures come from them.

mod common;

use prism::render::{RenderSettings, render};
use prism::scene::PreparedScene;
use prism::scene_file::load_scene;
use std::sync::Arc;

#[test]
fn every_example_scene_loads_and_renders() {
    for path in &common::example_scenes() {
        let name = path.file_name().unwrap().to_string_lossy();
        let scene = load_scene(path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut settings =
            RenderSettings::for_scene(&scene.render, Some(40), Some(30), Some(1)).unwrap();
        settings.samples = Some(2);
        let prepared = Arc::new(PreparedScene::new(&scene));
        let job = render(prepared, scene.camera, settings, |_, _| {});
        let acc = job.accumulator();
        let mut first = None;
        let (mut varied, mut lit) = (false, 0);
        for y in 0..acc.height {
            for x in 0..acc.width {
                let c = acc.mean(x, y);
                assert!(
                    c.is_finite() && c.min_element() >= 0.0,
                    "{name}: {c} at {x}, {y}"
                );
                lit += (c.max_element() > 0.05) as u32;
                varied |= *first.get_or_insert(c) != c;
            }
        }
        assert!(varied, "{name}: one colour everywhere");
        assert!(lit >= 20, "{name}: only {lit} pixels lit");
    }
}
