//! The fields every object entry of the scene file has (`[[spheres]]`, `[[meshes]]`, …),
//! whatever its shape: the interface placement and the entry machinery share, below both
//! (entry.rs implements it for every kind).

use super::{P3, V3};
use crate::scene::description::ObjectPlacement;

/// The fields every object entry has, whatever its shape.
pub(super) trait EntryDef {
    fn name(&self) -> Option<&str>;
    fn material(&self) -> Option<&str>;
    fn shadow(&self) -> Option<bool>;
    /// Its `translate`, `rotate` and `scale`, as read.
    fn placement(&self) -> (Option<P3>, Option<V3>, Option<&toml::Value>);
    /// Gives it `p`'s `translate`, `rotate` and `scale` in place of its own.
    fn set_placement(&mut self, p: &ObjectPlacement);
}
