//! Which frames of an animation a render command renders, and the file each goes to: an
//! output template such as `frames/seed_{frame:04}.png`.

use super::render_args::{BadOption, RenderArgs};
use anyhow::{Result, bail};
use prism::scene_file::Animation;
use std::path::PathBuf;

/// The frames the flags ask for.
#[derive(Clone, Debug, PartialEq)]
pub enum FrameChoice {
    /// No flag: frame 0 (the scene as a still, or the first frame of an animation).
    First,
    /// `--frame N`, or the number `--frame-from-env` read.
    One(u32),
    /// `--frames A..B`: A up to B, excluded.
    Range(u32, u32),
    /// `--frames all`.
    All,
}

impl FrameChoice {
    /// The choice `args` make; `--frame-from-env` reads its variable here.
    pub fn from_args(args: &RenderArgs) -> Result<Self> {
        if let Some(n) = args.frame {
            return Ok(FrameChoice::One(n));
        }
        if let Some(var) = &args.frame_from_env {
            let value = std::env::var(var).map_err(|e| match e {
                std::env::VarError::NotPresent => BadOption(format!(
                    "--frame-from-env {var}: the environment has no {var} (is this a job \
                     array task?)"
                )),
                std::env::VarError::NotUnicode(value) => BadOption(format!(
                    "--frame-from-env {var}: {var}={} is not text, so not a frame number",
                    prism::messages::shown(&value.to_string_lossy())
                )),
            })?;
            let n = value.trim().parse().map_err(|_| {
                BadOption(format!(
                    "--frame-from-env {var}: {var}={value:?} is not a frame number"
                ))
            })?;
            return Ok(FrameChoice::One(n));
        }
        match &args.frames {
            None => Ok(FrameChoice::First),
            Some(text) => Ok(Self::parse_range(text)?),
        }
    }

    /// Reads `A..B` (B excluded), `A..=B` (B included) or `all`.
    pub fn parse_range(text: &str) -> Result<Self, BadOption> {
        let bad = || {
            BadOption(format!(
                "--frames {text:?}: expected A..B (B excluded), A..=B (B included) or all"
            ))
        };
        if text.trim() == "all" {
            return Ok(FrameChoice::All);
        }
        let (a, b, inclusive) = match text.split_once("..=") {
            Some((a, b)) => (a, b, true),
            None => {
                let (a, b) = text.split_once("..").ok_or_else(bad)?;
                (a, b, false)
            }
        };
        // Read wide, so that a number past the last frame is called that, not a bad form.
        let a: u64 = a.trim().parse().map_err(|_| bad())?;
        let b: u64 = b.trim().parse().map_err(|_| bad())?;
        let end = if inclusive { b.saturating_add(1) } else { b };
        let most = prism::limits::MAX_FRAMES;
        if end > most as u64 {
            return Err(BadOption(format!(
                "--frames {text}: an animation has at most {most} frames, 0 to {}",
                most - 1
            )));
        }
        let (a, end) = (a as u32, end as u32);
        if end <= a {
            return Err(BadOption(format!(
                "--frames {text}: the range holds no frame (its end must come after its start)"
            )));
        }
        Ok(FrameChoice::Range(a, end))
    }

    /// The frame numbers to render, in order, checked against the scene's animation.
    pub fn frames(&self, animation: Option<&Animation>) -> Result<Vec<u32>> {
        let count = animation.map_or(1, |a| a.frames);
        let (start, end) = match *self {
            FrameChoice::First => (0, 1),
            FrameChoice::One(n) => (n, n.saturating_add(1)),
            FrameChoice::Range(a, b) => (a, b),
            FrameChoice::All => (0, count),
        };
        if end > count {
            match animation {
                None => bail!(BadOption(format!(
                    "frame {}: the scene has no [animation], so its only frame is 0",
                    end - 1
                ))),
                Some(_) => bail!(BadOption(format!(
                    "frame {}: the scene's animation has {count} frames, 0 to {}",
                    end - 1,
                    count - 1
                ))),
            }
        }
        if end - start > prism::limits::MAX_FRAMES {
            bail!(BadOption(format!(
                "{} frames in one command: at most {} (split the range)",
                end - start,
                prism::limits::MAX_FRAMES
            )));
        }
        Ok((start..end).collect())
    }
}

/// One piece of an output template.
#[derive(Clone, Debug, PartialEq)]
enum Piece {
    Text(String),
    /// `{frame}` or `{frame:0N}`: the frame number, zero-padded to `width` digits.
    Frame {
        width: usize,
    },
    /// `{tile}` or `{tile:0N}`: the tile's index.
    Tile {
        width: usize,
    },
}

/// A file name with placeholders: `{frame}`, `{frame:04}`, `{tile}`, `{tile:03}`; `{{` and
/// `}}` stand for braces.
#[derive(Clone, Debug, PartialEq)]
pub struct OutputTemplate {
    pieces: Vec<Piece>,
}

impl OutputTemplate {
    /// Reads the template `text` given to `flag`.
    pub fn parse(flag: &str, text: &str) -> Result<Self, BadOption> {
        let mut pieces = Vec::new();
        let mut literal = String::new();
        let mut rest = text;
        while let Some(c) = rest.chars().next() {
            if rest.starts_with("{{") || rest.starts_with("}}") {
                literal.push(c);
                rest = &rest[2..];
                continue;
            }
            if c == '}' {
                return Err(BadOption(format!(
                    "{flag} {text}: a lone \"}}\" (write \"}}}}\" for a brace)"
                )));
            }
            if c != '{' {
                literal.push(c);
                rest = &rest[c.len_utf8()..];
                continue;
            }
            let Some(end) = rest.find('}') else {
                return Err(BadOption(format!(
                    "{flag} {text}: a \"{{\" that is not closed (write \"{{{{\" for a brace)"
                )));
            };
            let field = &rest[1..end];
            let (name, spec) = field.split_once(':').unwrap_or((field, ""));
            let width = match spec {
                "" => 0,
                _ => spec
                    .strip_prefix('0')
                    .and_then(|w| w.parse::<usize>().ok())
                    .filter(|w| (1..=10).contains(w))
                    .ok_or_else(|| {
                        BadOption(format!(
                            "{flag} {text}: {{{field}}}: the width is written :0N, N from 1 \
                             to 10, as in {{{name}:04}}"
                        ))
                    })?,
            };
            let piece = match name {
                "frame" => Piece::Frame { width },
                "tile" => Piece::Tile { width },
                _ => {
                    return Err(BadOption(format!(
                        "{flag} {text}: unknown placeholder {{{field}}}; the placeholders are \
                         {{frame}} and {{tile}} (with a width: {{frame:04}})"
                    )));
                }
            };
            if !literal.is_empty() {
                pieces.push(Piece::Text(std::mem::take(&mut literal)));
            }
            pieces.push(piece);
            rest = &rest[end + 1..];
        }
        if !literal.is_empty() {
            pieces.push(Piece::Text(literal));
        }
        Ok(Self { pieces })
    }

    /// Refuses a template without `{frame}` for `count` frames, which would write them all
    /// to one file.
    pub fn require_frame(&self, flag: &str, count: usize) -> Result<(), BadOption> {
        if count <= 1 || self.pieces.iter().any(|p| matches!(p, Piece::Frame { .. })) {
            return Ok(());
        }
        Err(BadOption(format!(
            "{flag}: {count} frames would all be written to one file; put {{frame}} in the \
             name (e.g. frames/shot_{{frame:04}}.png)"
        )))
    }

    /// Refuses `{tile}` in a template when no tile is rendered: it would be left empty.
    pub fn require_tile(&self, flag: &str, tile: bool) -> Result<(), BadOption> {
        if tile || !self.pieces.iter().any(|p| matches!(p, Piece::Tile { .. })) {
            return Ok(());
        }
        Err(BadOption(format!(
            "{flag}: {{tile}} stands for the tile's index, which --tile I/N gives; without \
             --tile there is none (write the name without it)"
        )))
    }

    /// The path for `frame` (and `tile`, when rendering one; else `{tile}` is left empty).
    pub fn path(&self, frame: u32, tile: Option<u32>) -> PathBuf {
        let mut out = String::new();
        for piece in &self.pieces {
            match piece {
                Piece::Text(t) => out.push_str(t),
                Piece::Frame { width } => out.push_str(&format!("{frame:0width$}")),
                Piece::Tile { width } => {
                    if let Some(tile) = tile {
                        out.push_str(&format!("{tile:0width$}"));
                    }
                }
            }
        }
        PathBuf::from(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn templates_fill_in_frames_and_tiles() {
        let t = OutputTemplate::parse("--out", "frames/seed_{frame:04}.png").unwrap();
        assert_eq!(t.path(7, None), PathBuf::from("frames/seed_0007.png"));
        assert_eq!(t.path(12345, None), PathBuf::from("frames/seed_12345.png"));
        let t = OutputTemplate::parse("--out", "t{tile:02}_f{frame}.exr").unwrap();
        assert_eq!(t.path(3, Some(4)), PathBuf::from("t04_f3.exr"));
        let t = OutputTemplate::parse("--out", "{{literal}}.png").unwrap();
        assert_eq!(t.path(0, None), PathBuf::from("{literal}.png"));
        assert!(t.require_frame("--out", 2).is_err());
        assert!(t.require_frame("--out", 1).is_ok());
        let t = OutputTemplate::parse("--out", "x_{tile}.png").unwrap();
        assert!(t.require_tile("--out", true).is_ok());
        let e = t.require_tile("--out", false).unwrap_err();
        assert!(e.to_string().contains("--tile"), "{e}");
        for bad in [
            "{frames}.png",
            "{frame:4}.png",
            "{frame.png",
            "a}.png",
            "{frame:0}.png",
        ] {
            assert!(OutputTemplate::parse("--out", bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn ranges_read_both_ways_and_refuse_empty_ones() {
        assert_eq!(
            FrameChoice::parse_range("0..24").unwrap(),
            FrameChoice::Range(0, 24)
        );
        assert_eq!(
            FrameChoice::parse_range("1..=24").unwrap(),
            FrameChoice::Range(1, 25)
        );
        assert_eq!(FrameChoice::parse_range("all").unwrap(), FrameChoice::All);
        for bad in ["5..5", "6..2", "1-24", "..3", "a..b"] {
            assert!(FrameChoice::parse_range(bad).is_err(), "{bad}");
        }
        // A still scene has frame 0 only.
        assert_eq!(FrameChoice::First.frames(None).unwrap(), vec![0]);
        let e = FrameChoice::One(3).frames(None).unwrap_err();
        assert!(e.to_string().contains("no [animation]"), "{e}");
    }
}
