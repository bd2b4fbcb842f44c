//! Errors of loading a scene, each naming the file, the place in it, and the problem.

use super::brackets::scan_brackets;
use super::spans::entry_at;
use std::ops::Range;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a scene file cannot be loaded, with where in the file.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The file cannot be read: missing, not a regular file, too large, not UTF-8 text.
    #[error(
        "{}: cannot read the scene file: {reason}",
        crate::messages::shown_path(path)
    )]
    Read {
        /// The file.
        path: PathBuf,
        /// Why, in words.
        reason: String,
    },
    /// TOML syntax, an unknown or missing field, a value of the wrong type.
    #[error("{}:{line}:{column}: {message}", crate::messages::shown_path(path))]
    Syntax {
        /// The scene file.
        path: PathBuf,
        /// The line, counted from 1.
        line: usize,
        /// The column, counted from 1.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A well-formed value that makes no sense: a negative radius, an eta of zero, …
    #[error("{}:{line}: {item}: {message}", crate::messages::shown_path(path))]
    Invalid {
        /// The scene file.
        path: PathBuf,
        /// The line, counted from 1.
        line: usize,
        /// The table the value is in (`spheres[2]`, `camera`).
        item: String,
        /// What is wrong.
        message: String,
    },
    /// A problem at a line of a file the scene reads: a mesh or its material library.
    #[error("{}:{line}: {message}", crate::messages::shown_path(path))]
    Asset {
        /// The mesh or material file.
        path: PathBuf,
        /// The line, counted from 1.
        line: usize,
        /// What is wrong, and which of the scene's tables reads the file.
        message: String,
    },
    /// A frame of an animated scene that does not validate: the animation's values at that
    /// frame put a field out of its bounds (a line is the field's, in the scene file).
    #[error("frame {frame}: {error}")]
    Frame {
        /// The frame, from 0.
        frame: u32,
        /// What is wrong at it.
        error: Box<SceneError>,
    },
}

impl SceneError {
    /// The 1-based line the error points at, if any.
    pub fn line(&self) -> Option<usize> {
        match self {
            SceneError::Read { .. } => None,
            SceneError::Syntax { line, .. }
            | SceneError::Invalid { line, .. }
            | SceneError::Asset { line, .. } => Some(*line),
            SceneError::Frame { error, .. } => error.line(),
        }
    }
}

/// 1-based line and column of byte `offset` in `source`.
pub(crate) fn line_column(source: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(source.len());
    let before = &source[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.rfind('\n').map_or(offset, |nl| offset - nl - 1) + 1;
    (line, column)
}

/// The parser's error `message` about `source` (the file `path`) at `span`, in the
/// format's words, with the entry it lies in named (`spheres[0] "glass ball": …`). Where a
/// bracket opened before that place is never closed, the error is that bracket's, at its
/// line: the parser stops only where the text no longer fits, often lines later.
pub(super) fn syntax_error(
    source: &str,
    path: &Path,
    span: Option<Range<usize>>,
    message: &str,
) -> SceneError {
    let offset = span.as_ref().map_or(0, |s| s.start);
    let plain = crate::messages::plain_type_words(message.trim());
    // The parser may quote the file (an unknown key of any length, say).
    let text = crate::messages::shown_within(&plain, 400);
    let unclosed = scan_brackets(source, usize::MAX)
        .unclosed
        .filter(|&at| at < offset && line_column(source, at).0 < line_column(source, offset).0);
    if let Some(at) = unclosed {
        let (line, column) = line_column(source, at);
        let bracket = &source[at..at + 1];
        return SceneError::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            message: format!(
                "this `{bracket}` is never closed (the parser stopped at line {}: {text})",
                line_column(source, offset).0
            ),
        };
    }
    // A field missing from the file as a whole has an empty span at its start (an
    // entry's spans its header): no entry to name.
    let whole = span.as_ref().is_some_and(|s| s.is_empty());
    let entry = span
        .filter(|_| !whole)
        .and_then(|s| entry_at(source, s.start));
    let (line, column) = line_column(source, offset);
    SceneError::Syntax {
        path: path.to_path_buf(),
        line,
        column,
        message: match entry {
            Some(entry) => format!("{entry}: {text}"),
            None => text,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_of_offsets() {
        let src = "a = 1\nbb = 2\n";
        assert_eq!(line_column(src, 0), (1, 1));
        assert_eq!(line_column(src, 6), (2, 1));
        assert_eq!(line_column(src, 8), (2, 3));
    }
}
