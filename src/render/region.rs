//! Part of a frame rendered on its own (a region, or one tile of a split), and the margin
//! around it that adaptive sampling needs so that the part equals the same pixels of the
//! full frame.
//!
//! Every pixel's subsamples depend only on its own position and the pass index, so without
//! adaptive sampling a region needs nothing around it. Adaptive sampling decides whether a
//! pixel goes on by looking at its eight neighbours, whose own decisions looked at theirs:
//! after k such looks a pixel depends on pixels up to k away. A region rendered with that
//! many pixels more on each side (where the frame has them) decides its own pixels exactly
//! as the full frame does.

use super::settings::RenderSettings;
use thiserror::Error;

/// A rectangle of pixels: columns `x0..x1` and rows `y0..y1` (the ends excluded), in the
/// frame's pixel coordinates (origin at the top left).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PixelRect {
    /// The first column.
    pub x0: u32,
    /// The first row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

/// A region or tile that cannot be rendered, or a placement that cannot be read.
#[derive(Debug, Error, PartialEq)]
pub enum RegionError {
    /// Not four whole numbers.
    #[error("region \"{0}\": expected X0,Y0,X1,Y1 (four whole numbers of pixels, ends excluded)")]
    Syntax(String),
    /// A start at or past its end (never "all but" or a wrap-around).
    #[error(
        "region {x0},{y0},{x1},{y1}: each end must be greater than its start \
         (X0 < X1 and Y0 < Y1; the ends are excluded)"
    )]
    Reversed {
        /// The first column.
        x0: u32,
        /// The first row.
        y0: u32,
        /// One past the last column.
        x1: u32,
        /// One past the last row.
        y1: u32,
    },
    /// Not inside the frame.
    #[error("region {x0},{y0},{x1},{y1} does not fit in the {width}×{height} image")]
    Outside {
        /// The first column.
        x0: u32,
        /// The first row.
        y0: u32,
        /// One past the last column.
        x1: u32,
        /// One past the last row.
        y1: u32,
        /// The frame's width.
        width: u32,
        /// The frame's height.
        height: u32,
    },
    /// `--tile I/N` not of that form.
    #[error("tile \"{0}\": expected I/N, tile I (counted from 0) of N")]
    TileSyntax(String),
    /// A tile index or count out of range.
    #[error(
        "tile {index}/{count}: the index counts from 0 to N−1 and the {height}-row image \
         splits into 1 to {height} tiles"
    )]
    TileRange {
        /// The index asked for.
        index: u32,
        /// The count asked for.
        count: u32,
        /// The frame's height.
        height: u32,
    },
    /// A placement record that does not read as one.
    #[error("placement \"{0}\": expected \"X0,Y0,X1,Y1 of WIDTHxHEIGHT\"")]
    Placement(String),
}

impl PixelRect {
    /// The whole of a `width` × `height` frame.
    pub fn full(width: u32, height: u32) -> Self {
        Self {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        }
    }

    /// Reads `X0,Y0,X1,Y1` (the command line's `--region`): four whole numbers, ends excluded.
    pub fn parse(text: &str) -> Result<Self, RegionError> {
        let numbers: Vec<u32> = text
            .split(',')
            .map(|n| n.trim().parse::<u32>())
            .collect::<Result<_, _>>()
            .map_err(|_| RegionError::Syntax(text.to_string()))?;
        let [x0, y0, x1, y1] = numbers[..] else {
            return Err(RegionError::Syntax(text.to_string()));
        };
        let rect = Self { x0, y0, x1, y1 };
        if x0 >= x1 || y0 >= y1 {
            return Err(RegionError::Reversed { x0, y0, x1, y1 });
        }
        Ok(rect)
    }

    /// Tile `index` (from 0) of a split of the frame into `count` bands of whole rows, as
    /// even as whole rows allow (their heights differ by at most one).
    pub fn tile(index: u32, count: u32, width: u32, height: u32) -> Result<Self, RegionError> {
        if count == 0 || count > height || index >= count {
            return Err(RegionError::TileRange {
                index,
                count,
                height,
            });
        }
        let row = |i: u32| (i as u64 * height as u64 / count as u64) as u32;
        Ok(Self {
            x0: 0,
            y0: row(index),
            x1: width,
            y1: row(index + 1),
        })
    }

    /// Reads `I/N` (the command line's `--tile`) as (index, count).
    pub fn parse_tile(text: &str) -> Result<(u32, u32), RegionError> {
        let syntax = || RegionError::TileSyntax(text.to_string());
        let (i, n) = text.split_once('/').ok_or_else(syntax)?;
        let i = i.trim().parse().map_err(|_| syntax())?;
        let n = n.trim().parse().map_err(|_| syntax())?;
        Ok((i, n))
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }

    /// Pixels inside.
    pub fn area(&self) -> u64 {
        self.width() as u64 * self.height() as u64
    }

    /// Whether it is the whole `width` × `height` frame.
    pub fn is_full(&self, width: u32, height: u32) -> bool {
        *self == Self::full(width, height)
    }

    /// Refuses a rectangle that is empty, reversed or not inside the frame.
    pub fn check_within(&self, width: u32, height: u32) -> Result<(), RegionError> {
        let Self { x0, y0, x1, y1 } = *self;
        if x0 >= x1 || y0 >= y1 {
            return Err(RegionError::Reversed { x0, y0, x1, y1 });
        }
        if x1 > width || y1 > height {
            return Err(RegionError::Outside {
                x0,
                y0,
                x1,
                y1,
                width,
                height,
            });
        }
        Ok(())
    }

    /// This rectangle with `margin` more pixels on each side, cut to the frame.
    pub fn grown(&self, margin: u32, width: u32, height: u32) -> Self {
        Self {
            x0: self.x0.saturating_sub(margin),
            y0: self.y0.saturating_sub(margin),
            x1: self.x1.saturating_add(margin).min(width),
            y1: self.y1.saturating_add(margin).min(height),
        }
    }

    /// Whether `other` lies wholly inside.
    pub fn contains(&self, other: &Self) -> bool {
        other.x0 >= self.x0 && other.y0 >= self.y0 && other.x1 <= self.x1 && other.y1 <= self.y1
    }

    /// Its place inside `outer`, which contains it, in `outer`'s own coordinates.
    pub fn relative_to(&self, outer: PixelRect) -> PixelRect {
        debug_assert!(outer.contains(self));
        PixelRect {
            x0: self.x0 - outer.x0,
            y0: self.y0 - outer.y0,
            x1: self.x1 - outer.x0,
            y1: self.y1 - outer.y0,
        }
    }

    /// Whether the two share a pixel.
    pub fn overlaps(&self, other: &Self) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    /// Its place in a `width` × `height` frame as text, `X0,Y0,X1,Y1 of WIDTHxHEIGHT`: what a
    /// tile's file records (a PNG text chunk, or a sidecar) for `prism stitch`.
    pub fn placement(&self, width: u32, height: u32) -> String {
        format!(
            "{},{},{},{} of {width}x{height}",
            self.x0, self.y0, self.x1, self.y1
        )
    }

    /// Reads `placement`'s text back: the rectangle and the frame's width and height.
    pub fn parse_placement(text: &str) -> Result<(Self, u32, u32), RegionError> {
        let bad = || RegionError::Placement(text.to_string());
        let (rect, frame) = text.trim().split_once(" of ").ok_or_else(bad)?;
        let rect = Self::parse(rect).map_err(|_| bad())?;
        let (w, h) = frame.split_once('x').ok_or_else(bad)?;
        let (w, h) = (w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?);
        rect.check_within(w, h).map_err(|_| bad())?;
        Ok((rect, w, h))
    }
}

impl std::fmt::Display for PixelRect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{},{},{},{}", self.x0, self.y0, self.x1, self.y1)
    }
}

/// How many pixels around a region its render must include to decide the region's pixels
/// as the full frame does: one per adaptive check that looks at neighbours (those at
/// power-of-two pass counts from the minimum up to, not including, the last pass; in a
/// render that is not `stochastic`, only those before `edge_samples`). None without
/// adaptive sampling.
pub fn adaptive_margin(settings: &RenderSettings, stochastic: bool) -> u32 {
    let Some(adaptive) = settings.adaptive else {
        return 0;
    };
    let first = adaptive.min_samples.max(2);
    // A check after the last pass changes nothing; a noisy render's pools its neighbours'
    // noise at every check.
    let last = if stochastic {
        settings.total_passes()
    } else {
        adaptive.edge_samples.min(settings.total_passes())
    };
    (1..32)
        .map(|k| 1u32 << k)
        .filter(|&n| n >= first && n < last)
        .count() as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::AdaptiveSettings;

    #[test]
    fn regions_parse_and_refuse_reversed_bounds() {
        let r = PixelRect::parse("10, 20,30,40").unwrap();
        assert_eq!((r.x0, r.y0, r.x1, r.y1), (10, 20, 30, 40));
        assert_eq!((r.width(), r.height(), r.area()), (20, 20, 400));
        for bad in ["", "1,2,3", "1,2,3,4,5", "a,b,c,d", "-1,0,4,4", "1.5,0,4,4"] {
            assert!(
                matches!(PixelRect::parse(bad), Err(RegionError::Syntax(_))),
                "{bad}"
            );
        }
        // Reversed and empty bounds are refused, never rendered as "nothing" or looped on.
        for bad in ["30,0,10,4", "0,4,4,4", "5,5,5,6"] {
            let e = PixelRect::parse(bad).unwrap_err();
            assert!(matches!(e, RegionError::Reversed { .. }), "{bad}: {e}");
        }
        let e = r.check_within(25, 100).unwrap_err();
        assert!(e.to_string().contains("25×100"), "{e}");
        assert!(r.check_within(30, 40).is_ok());
    }

    #[test]
    fn tiles_cover_the_frame_once_in_bands_of_rows() {
        for (height, count) in [(600, 4), (7, 7), (601, 6), (1, 1), (10, 3)] {
            let mut next_row = 0;
            for i in 0..count {
                let t = PixelRect::tile(i, count, 800, height).unwrap();
                assert_eq!((t.x0, t.x1), (0, 800));
                assert_eq!(t.y0, next_row, "tiles are contiguous");
                assert!(t.height() >= height / count && t.height() <= height / count + 1);
                next_row = t.y1;
            }
            assert_eq!(next_row, height);
        }
        for (i, n) in [(4, 4), (0, 0), (0, 601)] {
            assert!(PixelRect::tile(i, n, 800, 600).is_err(), "{i}/{n}");
        }
        assert_eq!(PixelRect::parse_tile("2/8"), Ok((2, 8)));
        assert!(PixelRect::parse_tile("2").is_err());
        assert!(PixelRect::parse_tile("a/b").is_err());
    }

    #[test]
    fn placements_read_back() {
        let r = PixelRect::parse("0,150,800,300").unwrap();
        let text = r.placement(800, 600);
        assert_eq!(text, "0,150,800,300 of 800x600");
        assert_eq!(PixelRect::parse_placement(&text), Ok((r, 800, 600)));
        for bad in ["0,0,1,1", "0,0,1,1 of 1", "0,0,9,9 of 4x4", "x of 4x4"] {
            assert!(PixelRect::parse_placement(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn growing_stops_at_the_frame() {
        let r = PixelRect::parse("1,10,5,20").unwrap();
        assert_eq!(r.grown(3, 6, 100), PixelRect::parse("0,7,6,23").unwrap());
        assert!(r.grown(3, 6, 100).contains(&r));
        let outer = r.grown(3, 6, 100);
        assert_eq!(r.relative_to(outer), PixelRect::parse("1,3,5,13").unwrap());
        assert!(r.overlaps(&PixelRect::parse("4,19,9,30").unwrap()));
        assert!(!r.overlaps(&PixelRect::parse("5,10,9,20").unwrap()));
    }

    #[test]
    fn the_margin_counts_the_checks_that_look_at_neighbours() {
        let mut s = RenderSettings::new(10, 10, 4);
        assert_eq!(
            adaptive_margin(&s, true),
            0,
            "no adaptive sampling, no margin"
        );
        s.adaptive = Some(AdaptiveSettings::default());
        // min 4, edge 8 of 16 passes: only the check at 4 looks at neighbours, unless the
        // render is noisy, when the one at 8 pools its neighbours' noise too.
        assert_eq!(adaptive_margin(&s, false), 1);
        assert_eq!(adaptive_margin(&s, true), 2);
        s.adaptive = Some(AdaptiveSettings {
            min_samples: 1,
            edge_samples: 64,
            ..AdaptiveSettings::default()
        });
        // Checks at 2, 4 and 8 (the one after the 16th and last pass changes nothing).
        assert_eq!(adaptive_margin(&s, false), 3);
        s.samples = Some(1000);
        assert_eq!(adaptive_margin(&s, false), 5, "2..32");
        assert_eq!(adaptive_margin(&s, true), 9, "2..512, of 1000 passes");
    }
}
