//! A scene file's parse tree: every table, key and value with its span in the text. The
//! text is parsed once into it; the tree is then read as the file's tables and searched
//! for the spans messages point at, and an animation writes each frame's values into a
//! copy of it.

use super::error::{SceneError, syntax_error};
use std::borrow::Cow;
use std::path::Path;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// A parse tree whose strings borrow from the text it was parsed from.
pub(super) type Tree<'i> = Spanned<DeTable<'i>>;

/// The parse tree of `source` (named `path` in messages), or the syntax error in it.
pub(super) fn parse_tree<'i>(source: &'i str, path: &Path) -> Result<Tree<'i>, SceneError> {
    #[cfg(test)]
    PARSES.with(|count| count.set(count.get() + 1));
    DeTable::parse(source).map_err(|e| syntax_error(source, path, e.span(), e.message()))
}

#[cfg(test)]
thread_local! {
    /// How many texts this thread has parsed, for the tests that a text is parsed once.
    pub(super) static PARSES: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

self_cell::self_cell!(
    /// A scene file's text owned together with its parse tree.
    pub(super) struct ParsedText {
        owner: String,
        #[covariant]
        dependent: Tree,
    }
    impl {Debug}
);

impl ParsedText {
    /// `source` parsed (named `path` in messages).
    pub(super) fn parse(source: String, path: &Path) -> Result<Self, SceneError> {
        Self::try_new(source, |text| parse_tree(text, path))
    }

    /// The text.
    pub(super) fn text(&self) -> &str {
        self.borrow_owner()
    }

    /// The parse tree of the text.
    pub(super) fn tree(&self) -> &Tree<'_> {
        self.borrow_dependent()
    }
}

/// Sets `field` of the table `place` names in `tree` (`camera`, `materials.NAME`,
/// `spheres[2]`) to `value`. The value takes the span of the one it replaces, or of the
/// table's header when the table has no such field, so that a message about it points
/// where the file sets it. False when there is no such table.
pub(super) fn set_field<'i>(
    tree: &mut Tree<'i>,
    place: &str,
    field: &str,
    value: DeValue<'i>,
) -> bool {
    let Some(table) = table_mut(tree.get_mut(), place) else {
        return false;
    };
    let header = table.span().start..table.span().start;
    let DeValue::Table(table) = table.get_mut() else {
        return false;
    };
    match table.get_mut(field) {
        Some(old) => *old = Spanned::new(old.span(), value),
        None => {
            let key = Spanned::new(header.clone(), Cow::Owned(field.to_string()));
            table.insert(key, Spanned::new(header, value));
        }
    }
    true
}

/// The table `place` names (see `set_field`), with its span.
fn table_mut<'t, 'i>(
    root: &'t mut DeTable<'i>,
    place: &str,
) -> Option<&'t mut Spanned<DeValue<'i>>> {
    let table = if let Some(name) = place.strip_prefix("materials.") {
        match root.get_mut("materials")?.get_mut() {
            DeValue::Table(materials) => materials.get_mut(name)?,
            _ => return None,
        }
    } else if let Some((key, index)) = place.strip_suffix(']').and_then(|t| t.split_once('[')) {
        match root.get_mut(key)?.get_mut() {
            DeValue::Array(entries) => entries.get_mut(index.parse::<usize>().ok()?)?,
            _ => return None,
        }
    } else {
        root.get_mut(place)?
    };
    matches!(table.get_ref(), DeValue::Table(_)).then_some(table)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    const TEXT: &str = "[camera]\nfov = 40\n\n[[spheres]]\nradius = 1\n\n[[spheres]]\nradius = 2\n\n\
                        [materials.red]\ncolor = [1, 0, 0]\n";

    fn number(text: &str) -> DeValue<'_> {
        DeValue::parse(text).unwrap().into_inner()
    }

    fn line_of(span: std::ops::Range<usize>) -> usize {
        TEXT[..span.start].matches('\n').count() + 1
    }

    #[test]
    fn a_field_is_set_where_the_file_has_it_or_at_its_table() {
        let parsed = ParsedText::parse(TEXT.to_string(), Path::new("a.toml")).unwrap();
        let values = ["3.5", "[0, 1, 0]", "7"];
        let mut tree = parsed.tree().clone();
        assert!(set_field(
            &mut tree,
            "spheres[1]",
            "radius",
            number(values[0])
        ));
        assert!(set_field(
            &mut tree,
            "materials.red",
            "color",
            number(values[1])
        ));
        assert!(set_field(
            &mut tree,
            "camera",
            "aperture",
            number(values[2])
        ));
        assert!(!set_field(
            &mut tree,
            "spheres[2]",
            "radius",
            number(values[0])
        ));
        assert!(!set_field(
            &mut tree,
            "materials.blue",
            "color",
            number(values[0])
        ));
        assert!(!set_field(&mut tree, "fog", "density", number(values[0])));
        let file: toml::Table =
            toml::Table::deserialize(toml::de::Deserializer::from(tree.clone())).unwrap();
        assert_eq!(file["spheres"][1]["radius"].as_float(), Some(3.5));
        assert_eq!(file["spheres"][0]["radius"].as_integer(), Some(1));
        assert_eq!(file["materials"]["red"]["color"][1].as_integer(), Some(1));
        assert_eq!(file["camera"]["aperture"].as_integer(), Some(7));
        let spans = super::super::spans::FieldSpans::of(&tree);
        let sphere = TEXT.rfind("[[spheres]]").unwrap();
        assert_eq!(spans.field(sphere, "radius").map(line_of), Some(8));
        assert_eq!(spans.field(0, "aperture").map(line_of), Some(1));
        // The text's own tree is unchanged.
        let original =
            toml::Table::deserialize(toml::de::Deserializer::from(parsed.tree().clone())).unwrap();
        assert_eq!(original["spheres"][1]["radius"].as_integer(), Some(2));
    }

    #[test]
    fn a_syntax_error_is_a_scene_error_at_its_line() {
        let e = ParsedText::parse("[camera]\nfov = \n".into(), Path::new("a.toml")).unwrap_err();
        assert!(e.to_string().starts_with("a.toml:2:"), "{e}");
    }
}
