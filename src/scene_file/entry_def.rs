//! The fields every object entry of the scene file has (`[[spheres]]`, `[[meshes]]`, …),
//! whatever its shape: the interface placement and the entry machinery share, below both
//! (entry.rs implements it for every kind).

use super::fixed_array::Fixed;
use super::validator::{P3, V3};
use crate::messages::quoted;
use crate::scene::ObjectPlacement;

/// The fields every object entry has, whatever its shape.
pub(super) trait EntryDef {
    fn name(&self) -> Option<&str>;
    fn material(&self) -> Option<&str>;
    fn shadow(&self) -> Option<bool>;
    /// The name of the group it is placed in.
    fn group(&self) -> Option<&str>;
    /// Its `translate`, `rotate` and `scale`, as read.
    fn placement(&self) -> (Option<P3>, Option<V3>, Option<&toml::Value>);
    /// Gives it `p`'s `translate`, `rotate` and `scale` in place of its own.
    fn set_placement(&mut self, p: &ObjectPlacement);
}

/// How messages name entry `i` of table `kind`: `spheres[2]`, or `spheres[2] "ball"`.
pub(super) fn entry_label(kind: &str, i: usize, name: Option<&str>) -> String {
    match name {
        Some(n) => format!("{kind}[{i}] {}", quoted(n)),
        None => format!("{kind}[{i}]"),
    }
}

/// `p` as an entry's `translate`, `rotate` and `scale` fields.
pub(super) fn placement_fields(
    p: &ObjectPlacement,
) -> (Option<P3>, Option<V3>, Option<toml::Value>) {
    let scale = toml::Value::Array(p.scale.to_array().map(toml::Value::Float).to_vec());
    (
        Some(Fixed(p.translate.to_array())),
        Some(Fixed(p.rotate.to_array())),
        Some(scale),
    )
}
