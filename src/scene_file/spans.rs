//! Where each key and value of a scene file lies, so that a message about a field points
//! at the field's own line rather than at its table's header.

use std::ops::Range;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// The spans of a parsed file's keys and values.
pub struct FieldSpans<'a> {
    root: &'a Spanned<DeTable<'a>>,
}

impl<'a> FieldSpans<'a> {
    /// The spans of the file `root` is the parse tree of (parse_tree.rs).
    pub fn of(root: &'a Spanned<DeTable<'a>>) -> Self {
        Self { root }
    }

    /// The span of `field` in the table whose span starts at `table_start`: a key's own
    /// span, or for `key[i]` (and `key[i][j]`) the span of that element of its array. None
    /// when the table or the field is not found (a field the file leaves out).
    pub fn field(&self, table_start: usize, field: &str) -> Option<Range<usize>> {
        let table = find_table(self.root.get_ref(), table_start)?;
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

/// The entry of the file that the byte `offset` lies in, as messages name it: an element
/// of an array of tables with its index and name (`spheres[2] "glass ball"`), or a table
/// (`[camera]`, `[materials.glass]`). None before every entry, or when the text does not
/// parse. An entry is the one whose header starts last at or before `offset` (the parser
/// spans a table from its header).
pub fn entry_at(source: &str, offset: usize) -> Option<String> {
    use crate::messages::{quoted, shown};
    let root = DeTable::parse(source).ok()?;
    let mut best: Option<(usize, String)> = None;
    let mut consider = |start: usize, label: &dyn Fn() -> String| {
        if start <= offset && best.as_ref().is_none_or(|(b, _)| start >= *b) {
            best = Some((start, label()));
        }
    };
    for (key, value) in root.get_ref().iter() {
        let key = shown(key.get_ref());
        match value.get_ref() {
            DeValue::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    let DeValue::Table(table) = item.get_ref() else {
                        continue;
                    };
                    let name = table.iter().find_map(|(k, v)| match v.get_ref() {
                        DeValue::String(n) if k.get_ref() == "name" => Some(n.to_string()),
                        _ => None,
                    });
                    consider(item.span().start, &|| match &name {
                        Some(n) => format!("{key}[{i}] {}", quoted(n)),
                        None => format!("{key}[{i}]"),
                    });
                }
            }
            DeValue::Table(table) => {
                consider(value.span().start, &|| format!("[{key}]"));
                // A table of named tables ([materials.glass]) names the inner one.
                // Spans are headers': `[materials.glass]` spans the inner table from its
                // `[`, and the implicit outer one from `materials`, one byte later; an inner
                // table is taken from no earlier than its outer one, so it wins the tie.
                for (inner, v) in table.iter() {
                    if matches!(v.get_ref(), DeValue::Table(_)) {
                        let inner = shown(inner.get_ref());
                        let start = v.span().start.max(value.span().start);
                        consider(start, &|| format!("[{key}.{inner}]"));
                    }
                }
            }
            _ => {}
        }
    }
    best.map(|(_, label)| label)
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

    #[test]
    fn the_entry_around_an_offset_is_named() {
        let source = "[camera]\nfov = 40\n\n[[spheres]]\nradius = 1\n\n[[spheres]]\nname = \"glass ball\"\nradius = \"x\"\n\n[materials.red]\ncolor = 1\n[materials.blue]\ncolor = 2\n";
        let at = |needle: &str| entry_at(source, source.find(needle).unwrap());
        assert_eq!(at("fov").as_deref(), Some("[camera]"));
        assert_eq!(at("radius = 1").as_deref(), Some("spheres[0]"));
        assert_eq!(
            at("radius = \"x\"").as_deref(),
            Some("spheres[1] \"glass ball\"")
        );
        assert_eq!(at("color = 1").as_deref(), Some("[materials.red]"));
        assert_eq!(at("color = 2").as_deref(), Some("[materials.blue]"));
    }

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
        let tree = DeTable::parse(TEXT).unwrap();
        let spans = FieldSpans::of(&tree);
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
