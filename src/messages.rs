//! Text for messages: what the file system said, without the wrappers that repeat a cause
//! or name an internal temporary file, and names from a scene file made safe to print.

use crate::limits::MAX_NAME_CHARS;

/// The cause of an I/O error in plain words ("No such file or directory (os error 2)"),
/// without the context (a temporary file's path, say) that other layers wrapped it in.
pub fn io_message(e: &std::io::Error) -> String {
    match e.raw_os_error() {
        Some(code) => std::io::Error::from_raw_os_error(code).to_string(),
        None => match e.get_ref() {
            Some(inner) => inner.to_string(),
            None => e.kind().to_string(),
        },
    }
}

/// `text` as it may appear in a message: control characters (escape sequences, newlines)
/// written as escapes, and shortened to `MAX_NAME_CHARS` characters with an ellipsis.
pub fn shown(text: &str) -> String {
    shown_within(text, MAX_NAME_CHARS)
}

/// `shown`, for longer text (a parser's message that quotes the file): at most `max`
/// characters before the ellipsis.
pub fn shown_within(text: &str, max: usize) -> String {
    let mut out = String::new();
    for (count, c) in text.chars().enumerate() {
        if count == max {
            out.push('…');
            break;
        }
        if c.is_control() || matches!(c, '\u{200B}'..='\u{200F}' | '\u{202A}'..='\u{202E}') {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// The candidate closest to `typed`, if one is close enough to be what was meant (a typo
/// or a case slip: a normalised edit similarity of at least 0.7, or equal ignoring case).
pub fn closest<'a>(typed: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let lower = typed.to_lowercase();
    candidates
        .into_iter()
        .map(|c| {
            let score = if c.to_lowercase() == lower {
                1.0
            } else {
                strsim::normalized_damerau_levenshtein(&lower, &c.to_lowercase())
            };
            (score, c)
        })
        .filter(|(score, _)| *score >= 0.7)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}

/// "; did you mean \"X\"?" when a candidate is close to `typed`, else nothing: for the end
/// of a message about a name that is not known.
pub fn did_you_mean<'a>(typed: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    match closest(typed, candidates) {
        Some(c) if c != typed => format!("; did you mean {}?", quoted(c)),
        _ => String::new(),
    }
}

/// A message from the TOML reader (serde's words) in the words of the scene format: "a
/// number" for f32, "a whole number" for u32, an array's length said plainly, and for an
/// unknown field the known one it is closest to.
pub fn plain_type_words(message: &str) -> String {
    let mut out = message.to_string();
    for (rust, plain) in [
        ("f32", "a number"),
        ("f64", "a number"),
        ("u8", "a whole number"),
        ("u16", "a whole number"),
        ("u32", "a whole number"),
        ("u64", "a whole number"),
        ("usize", "a whole number"),
        ("i32", "a whole number"),
        ("i64", "a whole number"),
    ] {
        out = out.replace(&format!("expected {rust}"), &format!("expected {plain}"));
    }
    // serde's word for a list of any length (a colour map, animation keys, vertices).
    out = out.replace("expected a sequence", "expected a list");
    if let Some(rest) = out.strip_prefix("invalid length ")
        && let Some((count, expected)) = rest.split_once(", expected an array of ")
        && count.parse::<usize>().is_ok()
    {
        let n = expected.trim();
        out = format!("this array has {count} values; it must have exactly {n}");
    }
    if let Some(rest) = out.strip_prefix("unknown field `")
        && let Some((field, known)) = rest.split_once('`')
    {
        let candidates: Vec<&str> = known.split('`').skip(1).step_by(2).collect();
        let hint = did_you_mean(field, candidates.iter().copied());
        out.push_str(&hint);
    }
    out
}

/// A path as it may appear in a message: control characters (a terminal escape typed into
/// `-o`, a newline) written as escapes, as names from a scene file are; not shortened below
/// the longest path a system takes.
pub fn shown_path(path: &std::path::Path) -> String {
    shown_within(&path.to_string_lossy(), 4096)
}

/// `path` made absolute against the working folder, `.` taken out and `..` applied to
/// the folders as written (links are not followed).
pub fn absolute_as_written(path: &std::path::Path) -> std::path::PathBuf {
    use std::path::Component;
    let absolute = std::env::current_dir().unwrap_or_default().join(path);
    let mut clean = std::path::PathBuf::new();
    for part in absolute.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir => {
                clean.pop();
            }
            other => clean.push(other),
        }
    }
    clean
}

/// Where the file system looked for `path` when it differs from what was written
/// ([`absolute_as_written`]). Said for a file not found, so that a user sees which folder
/// a relative path was taken in.
pub fn looked_for(path: &std::path::Path) -> Option<String> {
    let clean = absolute_as_written(path);
    (clean != path).then(|| shown_path(&clean))
}

/// The cause of a failed read of `path`, and for a file not found where it was looked for.
pub fn read_failure(path: &std::path::Path, e: &std::io::Error) -> String {
    let cause = io_message(e);
    match looked_for(path).filter(|_| e.kind() == std::io::ErrorKind::NotFound) {
        Some(place) => format!("{cause}; looked for {place}"),
        None => cause,
    }
}

/// A number as a person writes it: plainly in the usual range, in exponent form when huge
/// or tiny (2e19, not 20000000000000000000).
pub fn number(v: f32) -> String {
    plain_or_exponent(v, v.abs() as f64)
}

/// A field that breaks a rule, and what is wrong with it, in the scene file's words (the
/// message names the field). The rules a model's values follow (`Material::check`,
/// `Light::check`) return it; the file places it at the field's line, an edit names the
/// object or light.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct FieldProblem {
    /// The field at fault, as the scene file spells it.
    pub field: &'static str,
    /// What is wrong with it.
    pub message: String,
}

impl FieldProblem {
    /// `field` refused for `message`.
    pub fn new(field: &'static str, message: impl Into<String>) -> Self {
        Self {
            field,
            message: message.into(),
        }
    }

    /// Number `v` of `field` within `range` ([`outside_range`]).
    pub fn check_range(
        field: &'static str,
        v: f32,
        range: &std::ops::RangeInclusive<f32>,
    ) -> Result<(), FieldProblem> {
        match outside_range(field, v, range) {
            Some(message) => Err(Self::new(field, message)),
            None => Ok(()),
        }
    }

    /// Length `v` of `field` ([`outside_length`]).
    pub fn check_length(field: &'static str, v: f32) -> Result<(), FieldProblem> {
        match outside_length(field, v) {
            Some(message) => Err(Self::new(field, message)),
            None => Ok(()),
        }
    }

    /// Colour `c` of `field` in [0, hi] per channel ([`outside_color_range`]).
    pub fn check_color(
        field: &'static str,
        c: [f32; 3],
        hi: f32,
        why: &str,
    ) -> Result<(), FieldProblem> {
        match outside_color_range(field, c, hi, why) {
            Some(message) => Err(Self::new(field, message)),
            None => Ok(()),
        }
    }
}

/// Why length `v` of `field` (a radius, a height, a pattern's size) is refused: not finite,
/// not positive, or outside `limits::LENGTH`; None when it is taken.
pub fn outside_length(field: &str, v: f32) -> Option<String> {
    use crate::limits::{LENGTH, MAX_COORDINATE, MIN_LENGTH};
    let problem = if !v.is_finite() {
        return outside_range(field, v, &LENGTH);
    } else if v <= 0.0 {
        "be greater than zero"
    } else if v < *LENGTH.start() {
        &format!("be at least {MIN_LENGTH:e}")
    } else if v > *LENGTH.end() {
        &format!("be at most {MAX_COORDINATE:e}")
    } else {
        return None;
    };
    Some(format!("`{field}` must {problem}, got {}", number(v)))
}

/// Why number `v` of `field` is refused: not finite, or outside `range`; None when it is
/// taken. The one wording for every range a scene file or an edit checks.
pub fn outside_range(field: &str, v: f32, range: &std::ops::RangeInclusive<f32>) -> Option<String> {
    if !v.is_finite() {
        Some(format!(
            "`{field}` must be a finite number, got {}",
            number(v)
        ))
    } else if !range.contains(&v) {
        Some(format!(
            "`{field}` must lie in [{}, {}], got {}",
            number(*range.start()),
            number(*range.end()),
            number(v)
        ))
    } else {
        None
    }
}

/// Why colour `c` of `field` is refused: not finite, negative, or above `hi` in a channel
/// (`why` says why `hi` is the bound); None when it is taken.
pub fn outside_color_range(field: &str, c: [f32; 3], hi: f32, why: &str) -> Option<String> {
    if !c.iter().all(|v| v.is_finite()) {
        Some(format!("`{field}` must hold finite numbers, got {c:?}"))
    } else if c.iter().any(|&v| v < 0.0) {
        Some(format!("`{field}` must not be negative, got {c:?}"))
    } else if c.iter().any(|&v| v > hi) {
        Some(format!(
            "`{field}` must lie in [0, {hi}] per channel ({why}), got {c:?}"
        ))
    } else {
        None
    }
}

/// [`number`] for a number read as f64 (a frame, a rate).
pub fn number64(v: f64) -> String {
    plain_or_exponent(v, v.abs())
}

/// `v` (of magnitude `a`) plainly in the usual range, else in exponent form.
fn plain_or_exponent<T: std::fmt::Display + std::fmt::LowerExp>(v: T, a: f64) -> String {
    if a == 0.0 || (1e-4..1e7).contains(&a) || !a.is_finite() {
        v.to_string()
    } else {
        format!("{v:e}")
    }
}

/// The f64 an f32 reads as when written with the fewest digits that read back as it (0.1f32
/// is 0.1, not 0.10000000149011612): what a saved file says.
pub fn shortest(v: f32) -> f64 {
    format!("{v:?}").parse::<f64>().unwrap_or(v as f64)
}

/// `text` shown, in double quotes.
pub fn quoted(text: &str) -> String {
    format!("\"{}\"", shown(text))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped_and_long_names_cut() {
        assert_eq!(shown("ball"), "ball");
        assert_eq!(shown("a\u{1b}[31mred\nx"), "a\\u{1b}[31mred\\nx");
        let long = "é".repeat(5_000_000);
        let s = shown(&long);
        assert_eq!(s.chars().count(), MAX_NAME_CHARS + 1);
        assert!(s.ends_with('…'));
        assert_eq!(quoted("x\ty"), "\"x\\ty\"");
    }

    #[test]
    fn near_names_are_suggested() {
        let known = ["position", "radius", "material", "name"];
        assert_eq!(closest("raduis", known), Some("radius"));
        assert_eq!(closest("Material", known), Some("material"));
        assert_eq!(closest("zzz", known), None);
        assert_eq!(
            did_you_mean("matreial", known),
            "; did you mean \"material\"?"
        );
        assert_eq!(did_you_mean("radius", known), "");
        assert_eq!(
            did_you_mean("colour", ["color", "width"]),
            "; did you mean \"color\"?"
        );
    }

    #[test]
    fn serde_words_become_the_formats_words() {
        assert_eq!(
            plain_type_words("invalid type: string \"x\", expected f32"),
            "invalid type: string \"x\", expected a number"
        );
        assert_eq!(
            plain_type_words("invalid length 5, expected an array of 3"),
            "this array has 5 values; it must have exactly 3"
        );
        assert_eq!(
            plain_type_words("unknown field `raduis`, expected one of `center`, `radius`"),
            "unknown field `raduis`, expected one of `center`, `radius`; did you mean \"radius\"?"
        );
        assert_eq!(
            plain_type_words("invalid type: integer `5`, expected a sequence"),
            "invalid type: integer `5`, expected a list"
        );
    }

    #[test]
    fn paths_are_escaped_whole() {
        let p = std::path::Path::new("out/\u{1b}]0;title\u{7}x.png");
        assert_eq!(shown_path(p), "out/\\u{1b}]0;title\\u{7}x.png");
        let long = "d/".repeat(1000) + "f.png";
        assert_eq!(shown_path(std::path::Path::new(&long)), long);
    }

    #[test]
    fn numbers_read_as_written() {
        assert_eq!(number(-1.0), "-1");
        assert_eq!(number(1.43), "1.43");
        assert_eq!(number(2e19), "2e19");
        assert_eq!(number(f32::MAX), "3.4028235e38");
        assert_eq!(number(1e-9), "1e-9");
        assert_eq!(number(f32::NAN), "NaN");
    }

    #[test]
    fn io_messages_name_the_cause_once() {
        let e = std::io::Error::from_raw_os_error(2);
        assert_eq!(io_message(&e), "No such file or directory (os error 2)");
        let wrapped = std::io::Error::new(e.kind(), "at path /tmp/.x.tmp");
        assert_eq!(io_message(&wrapped), "at path /tmp/.x.tmp");
    }
}
