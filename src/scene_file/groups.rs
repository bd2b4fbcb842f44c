//! `[[groups]]`: named frames placed by `translate`, `rotate` and `scale` in their parent
//! group's frame (`group = "name"`) or the world's. Objects and lights name the group they
//! are placed in the same way, and follow its transform.

use super::entry_def::placement_fields;
use super::error::SceneError;
use super::validator::{Item, P3, V3, Validator};
use crate::limits;
use crate::messages::{did_you_mean, quoted};
use crate::scene::{GroupKind, ObjectPlacement, SceneGroup, group_chain, group_frame};
use glam::DAffine3;
use serde::Deserialize;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GroupDef {
    pub(super) name: String,
    /// The group it is placed in.
    pub(super) group: Option<String>,
    pub(super) translate: Option<P3>,
    pub(super) rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    pub(super) scale: Option<toml::Value>,
}

impl GroupDef {
    pub(super) fn placement(&self) -> (Option<P3>, Option<V3>, Option<&toml::Value>) {
        (self.translate, self.rotate, self.scale.as_ref())
    }

    /// Gives it `p`'s `translate`, `rotate` and `scale` in place of its own.
    pub(super) fn set_placement(&mut self, p: &ObjectPlacement) {
        (self.translate, self.rotate, self.scale) = placement_fields(p);
    }
}

/// How messages name group entry `i`.
pub(super) fn group_label(i: usize, name: &str) -> String {
    format!("groups[{i}] {}", quoted(name))
}

impl Validator<'_> {
    /// The file's `[[groups]]`, in its order, each with its parent found by name: names
    /// unique, parents known, no group within itself, nesting at most `MAX_GROUP_DEPTH`.
    pub(super) fn groups(&self, defs: &[Spanned<GroupDef>]) -> Result<Vec<SceneGroup>, SceneError> {
        let labels: Vec<String> = defs
            .iter()
            .enumerate()
            .map(|(i, d)| group_label(i, &d.get_ref().name))
            .collect();
        let at = |i: usize| Item {
            span: defs[i].span(),
            name: &labels[i],
        };
        let mut groups: Vec<SceneGroup> = Vec::with_capacity(defs.len());
        for (i, def) in defs.iter().enumerate() {
            let d = def.get_ref();
            if d.name.trim().is_empty() {
                return Err(self.field_error(
                    &at(i),
                    "name",
                    "a group needs a name that is not blank",
                ));
            }
            if let Some(j) = defs[..i].iter().position(|e| e.get_ref().name == d.name) {
                return Err(self.field_error(
                    &at(i),
                    "name",
                    format!("groups[{j}] has this name already: a group's name is its own"),
                ));
            }
            let placement = self.own_placement(&at(i), d.placement())?;
            groups.push(SceneGroup {
                name: d.name.clone(),
                parent: None,
                placement,
                lights: Vec::new(),
                kind: GroupKind::Entry,
            });
        }
        for (i, def) in defs.iter().enumerate() {
            groups[i].parent = match &def.get_ref().group {
                None => None,
                Some(parent) => Some(self.group_index(&at(i), &groups, parent)?),
            };
        }
        // No group within itself (every loop has a first member to report), then every
        // chain of parents within the depth allowed.
        let within_itself = |i: usize| group_chain(&groups, groups[i].parent).contains(&i);
        let depth = |i: usize| group_chain(&groups, Some(i)).len();
        let problem = (0..defs.len())
            .find(|&i| within_itself(i))
            .map(|i| {
                let m = "the group lies within itself (its `group` chain comes back to it)";
                (i, m.to_string())
            })
            .or_else(|| {
                (0..defs.len())
                    .find(|&i| depth(i) > limits::MAX_GROUP_DEPTH)
                    .map(|i| {
                        (
                            i,
                            format!("groups nest at most {} deep", limits::MAX_GROUP_DEPTH),
                        )
                    })
            });
        if let Some((i, message)) = problem {
            return Err(self.field_error(&at(i), "group", message));
        }
        Ok(groups)
    }

    /// The index of the group named `name` among `groups`, or an error at `at`'s `group`.
    fn group_index(
        &self,
        at: &Item,
        groups: &[SceneGroup],
        name: &str,
    ) -> Result<usize, SceneError> {
        groups.iter().position(|g| g.name == name).ok_or_else(|| {
            let hint = did_you_mean(name, groups.iter().map(|g| g.name.as_str()));
            self.field_error(
                at,
                "group",
                format!("no group named {} (see [[groups]]){hint}", quoted(name)),
            )
        })
    }

    /// The group an entry names (None for none) and the map from its frame to the world's.
    pub(super) fn group_frame(
        &self,
        at: &Item,
        name: Option<&str>,
    ) -> Result<(Option<usize>, DAffine3), SceneError> {
        let Some(name) = name else {
            return Ok((None, DAffine3::IDENTITY));
        };
        let groups = self.groups.get().map(Vec::as_slice).unwrap_or(&[]);
        let g = self.group_index(at, groups, name)?;
        Ok((Some(g), group_frame(groups, Some(g))))
    }
}
