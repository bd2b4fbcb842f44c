//! Where each key and value of a scene file lies, so that a message about a field points
//! at the field's own line rather than at its table's header.

use std::ops::Range;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// The parsed file with a span on every key and value.
pub struct FieldSpans<'i> {
    root: Option<Spanned<DeTable<'i>>>,
}

impl<'i> FieldSpans<'i> {
    /// The spans of `source` (which has already parsed as a scene file).
    pub fn new(source: &'i str) -> Self {
        Self {
            root: DeTable::parse(source).ok(),
        }
    }

    /// The span of `field` in the table whose span starts at `table_start`: a key's own
    /// span, or for `key[i]` (and `key[i][j]`) the span of that element of its array. None
    /// when the table or the field is not found (a field the file leaves out).
    pub fn field(&self, table_start: usize, field: &str) -> Option<Range<usize>> {
        let root = self.root.as_ref()?;
        let table = find_table(root.get_ref(), table_start)?;
        let (key, indices) = split_field(field)?;
        let mut indices = indices.as_slice();
        let (key_span, value) = table
            .iter()
            .find(|(k, _)| k.get_ref() == key)
            .map(|(k, v)| (k.span(), v))?;
        if indices.is_empty() {
            return Some(key_span);
        }
        let mut value = value;
        while let Some((&i, rest)) = indices.split_first() {
            let DeValue::Array(items) = value.get_ref() else {
                return Some(value.span());
            };
            value = items.get(i)?;
            indices = rest;
        }
        Some(value.span())
    }
}

/// `key[i][j]` as the key and its indices; None for text of any other shape.
fn split_field(field: &str) -> Option<(&str, Vec<usize>)> {
    let (key, mut rest) = field.split_once('[').map_or((field, ""), |(k, r)| (k, r));
    let mut indices = Vec::new();
    while !rest.is_empty() {
        let (index, after) = rest.split_once(']')?;
        indices.push(index.parse().ok()?);
        rest = after.strip_prefix('[').unwrap_or(after);
    }
    Some((key, indices))
}

/// The table (at any depth, in arrays of tables too) whose span starts at `start`.
fn find_table<'a, 'i>(table: &'a DeTable<'i>, start: usize) -> Option<&'a DeTable<'i>> {
    table.iter().find_map(|(_, value)| find_in(value, start))
}

fn find_in<'a, 'i>(value: &'a Spanned<DeValue<'i>>, start: usize) -> Option<&'a DeTable<'i>> {
    match value.get_ref() {
        DeValue::Table(t) if value.span().start == start => Some(t),
        DeValue::Table(t) => find_table(t, start),
        DeValue::Array(items) => items.iter().find_map(|item| find_in(item, start)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[[spheres]]\ncenter = [0, 0, -5]\n\
                        radius = 1\n\n[[polygons]]\nvertices = [\n  [0, 0, 0],\n  [1, 0, 0],\n  \
                        [0, 1, 0],\n]\n";

    fn line_of(span: Range<usize>) -> usize {
        TEXT[..span.start].matches('\n').count() + 1
    }

    fn table_start(header: &str) -> usize {
        TEXT.find(header).unwrap()
    }

    #[test]
    fn a_field_and_an_array_element_are_found_on_their_own_lines() {
        let spans = FieldSpans::new(TEXT);
        let sphere = table_start("[[spheres]]");
        let polygon = table_start("[[polygons]]");
        // What serde reports as the tables' spans starts at the same places.
        let file: toml::Table = TEXT.parse().unwrap();
        assert!(file.contains_key("spheres"));
        assert_eq!(spans.field(sphere, "radius").map(line_of), Some(7));
        assert_eq!(spans.field(polygon, "vertices").map(line_of), Some(10));
        assert_eq!(spans.field(polygon, "vertices[2]").map(line_of), Some(13));
        assert_eq!(
            spans.field(table_start("[camera]"), "fov").map(line_of),
            Some(3)
        );
        assert_eq!(spans.field(sphere, "material"), None);
        assert_eq!(spans.field(sphere + 1, "radius"), None);
    }
}
