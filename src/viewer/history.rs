//! Undo and redo of the viewer's edits: the scene as it was before each edit. A drag of a
//! slider is one edit, not one per frame: changes to the same field that follow each other
//! within `MERGE` are merged into the first.

use prism::scene::Scene;
use std::time::{Duration, Instant};

/// Changes of one field closer together than this are one edit.
pub const MERGE: Duration = Duration::from_millis(800);

/// The most edits kept to undo; the oldest go first.
pub const MAX_UNDO: usize = 256;

/// What an edit changed, to tell a run of changes to one field from a new edit.
#[derive(Clone, Debug, PartialEq)]
pub struct EditKey(pub String);

pub struct History {
    undo: Vec<Scene>,
    redo: Vec<Scene>,
    last: Option<(EditKey, Instant)>,
}

impl History {
    pub fn new() -> Self {
        Self {
            undo: Vec::new(),
            redo: Vec::new(),
            last: None,
        }
    }

    /// Notes that `before` is about to be changed by an edit of `key` at `now`.
    pub fn record(&mut self, before: &Scene, key: EditKey, now: Instant) {
        let merged =
            matches!(&self.last, Some((k, at)) if *k == key && now.duration_since(*at) < MERGE);
        if !merged {
            self.undo.push(before.clone());
            if self.undo.len() > MAX_UNDO {
                self.undo.remove(0);
            }
        }
        self.redo.clear();
        self.last = Some((key, now));
    }

    /// Notes a change that is not an edit of one field (a reload, an undo): the next edit
    /// starts a new step.
    pub fn break_run(&mut self) {
        self.last = None;
    }

    /// The scene before the last edit, with `current` kept to redo; None with nothing to undo.
    pub fn undo(&mut self, current: &Scene) -> Option<Scene> {
        let previous = self.undo.pop()?;
        self.redo.push(current.clone());
        self.last = None;
        Some(previous)
    }

    /// The scene the last undo left, with `current` kept to undo again.
    pub fn redo(&mut self, current: &Scene) -> Option<Scene> {
        let next = self.redo.pop()?;
        self.undo.push(current.clone());
        self.last = None;
        Some(next)
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn ambient(s: &Scene) -> f32 {
        s.ambient.x
    }

    /// Undo walks back edit by edit, redo forward again; a new edit drops what could be
    /// redone; a slider's run of changes is one step.
    #[test]
    fn undo_and_redo_walk_the_edits() {
        let mut scene = prism::seed::scene().unwrap();
        let mut h = History::new();
        let t = Instant::now();
        let key = |k: &str| EditKey(k.into());
        assert!(h.undo(&scene).is_none());
        // A drag: five changes of one field, 0.1 s apart, then another field.
        for (i, a) in [0.1, 0.2, 0.3, 0.4, 0.5].into_iter().enumerate() {
            h.record(
                &scene,
                key("ambient"),
                t + Duration::from_millis(100 * i as u64),
            );
            scene.set_ambient(Vec3::splat(a)).unwrap();
        }
        h.record(&scene, key("depth"), t + Duration::from_secs(1));
        scene.set_max_depth(9).unwrap();
        // The same field again, after a pause: a new step.
        h.record(&scene, key("ambient"), t + Duration::from_secs(5));
        scene.set_ambient(Vec3::splat(0.9)).unwrap();

        let s1 = h.undo(&scene).unwrap();
        assert_eq!((ambient(&s1), s1.render.max_depth), (0.5, 9));
        let s2 = h.undo(&s1).unwrap();
        assert_eq!((ambient(&s2), s2.render.max_depth), (0.5, 5));
        let s3 = h.undo(&s2).unwrap();
        assert_eq!(s3, prism::seed::scene().unwrap(), "the whole drag at once");
        assert!(h.undo(&s3).is_none());
        let r1 = h.redo(&s3).unwrap();
        assert_eq!(r1, s2);
        let r2 = h.redo(&r1).unwrap();
        assert_eq!(r2, s1);
        assert!(h.can_redo());
        // An edit now forgets the redo.
        let mut edited = r2.clone();
        h.record(&r2, key("depth"), t + Duration::from_secs(9));
        edited.set_max_depth(2).unwrap();
        assert!(!h.can_redo());
        assert_eq!(h.undo(&edited).unwrap(), r2);
    }

    #[test]
    fn the_oldest_edits_go_past_the_limit() {
        let scene = prism::seed::scene().unwrap();
        let mut h = History::new();
        let t = Instant::now();
        for i in 0..MAX_UNDO + 10 {
            h.record(&scene, EditKey(format!("field {i}")), t);
        }
        let mut n = 0;
        while h.undo(&scene).is_some() {
            n += 1;
        }
        assert_eq!(n, MAX_UNDO);
    }
}
