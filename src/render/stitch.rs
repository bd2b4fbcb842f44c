//! Assembling a frame from tiles rendered apart (`prism stitch`): each tile records its
//! place in the frame, and the tiles must cover the frame once, with one pixel type.

use super::image_file::{Placement, ReadImage};
use super::region::PixelRect;
use image::DynamicImage;
use thiserror::Error;

/// Why tiles cannot make a frame. Each names the tiles by the names given to `stitch`.
#[derive(Debug, Error, PartialEq)]
pub enum StitchError {
    /// No tiles at all.
    #[error("no tiles to stitch")]
    Empty,
    /// A tile with no placement (an image not written as a part of a frame).
    #[error(
        "{0}: records no place in a frame (no \"prism placement\" text chunk or sidecar); \
         was it rendered with --region or --tile?"
    )]
    Unplaced(String),
    /// A tile whose image is not the size its placement says.
    #[error("{name}: its image is {width}×{height} but its placement {rect} is {}×{}", rect.width(), rect.height())]
    WrongSize {
        /// The tile.
        name: String,
        /// The image's width.
        width: u32,
        /// The image's height.
        height: u32,
        /// Its placement.
        rect: PixelRect,
    },
    /// Tiles of frames of different sizes.
    #[error("{name} is a tile of a {}×{} frame, {first} of a {}×{} one", theirs.0, theirs.1, ours.0, ours.1)]
    FrameMismatch {
        /// The tile that differs.
        name: String,
        /// Its frame size.
        theirs: (u32, u32),
        /// The first tile.
        first: String,
        /// The first tile's frame size.
        ours: (u32, u32),
    },
    /// Tiles of different pixel types or formats.
    #[error("{name} holds {theirs} pixels, {first} {ours}: stitch tiles written alike")]
    PixelMismatch {
        /// The tile that differs.
        name: String,
        /// Its pixel type.
        theirs: &'static str,
        /// The first tile.
        first: String,
        /// The first tile's pixel type.
        ours: &'static str,
    },
    /// Two tiles that share pixels.
    #[error("{a} ({ra}) and {b} ({rb}) overlap")]
    Overlap {
        /// One tile.
        a: String,
        /// Its placement.
        ra: PixelRect,
        /// The other.
        b: String,
        /// Its placement.
        rb: PixelRect,
    },
    /// Pixels no tile covers.
    #[error(
        "the tiles cover {covered} of the frame's {total} pixels: nothing covers row {row} \
         from column {x0} to {x1} (end excluded); is a tile missing?"
    )]
    Missing {
        /// Pixels covered.
        covered: u64,
        /// Pixels in the frame.
        total: u64,
        /// The first row with a gap.
        row: u32,
        /// Where the gap starts.
        x0: u32,
        /// Where it ends.
        x1: u32,
    },
}

/// The name of an image's pixel type, in messages.
fn pixel_type(image: &DynamicImage) -> &'static str {
    match image {
        DynamicImage::ImageRgb8(_) => "8-bit RGB",
        DynamicImage::ImageRgb16(_) => "16-bit RGB",
        DynamicImage::ImageRgb32F(_) => "32-bit float RGB",
        _ => "other",
    }
}

/// The frame that `tiles` (each with the name it is known by) make, and its size: refused
/// if any tile is unplaced or of the wrong size, if the tiles disagree on the frame or the
/// pixel type, overlap, or leave a pixel uncovered.
pub fn stitch(tiles: &[(String, ReadImage)]) -> Result<(DynamicImage, Placement), StitchError> {
    let (first_name, first) = tiles.first().ok_or(StitchError::Empty)?;
    let frame_of = |name: &str, tile: &ReadImage| {
        tile.placement
            .ok_or_else(|| StitchError::Unplaced(name.to_string()))
    };
    let frame = frame_of(first_name, first)?;
    let (fw, fh) = (frame.frame_width, frame.frame_height);
    let mut placed: Vec<(&str, PixelRect)> = Vec::with_capacity(tiles.len());
    for (name, tile) in tiles {
        let p = frame_of(name, tile)?;
        if (p.frame_width, p.frame_height) != (fw, fh) {
            return Err(StitchError::FrameMismatch {
                name: name.clone(),
                theirs: (p.frame_width, p.frame_height),
                first: first_name.clone(),
                ours: (fw, fh),
            });
        }
        let (theirs, ours) = (pixel_type(&tile.image), pixel_type(&first.image));
        if theirs != ours || tile.format != first.format {
            return Err(StitchError::PixelMismatch {
                name: name.clone(),
                theirs,
                first: first_name.clone(),
                ours,
            });
        }
        let (w, h) = (tile.image.width(), tile.image.height());
        if (w, h) != (p.rect.width(), p.rect.height()) {
            return Err(StitchError::WrongSize {
                name: name.clone(),
                width: w,
                height: h,
                rect: p.rect,
            });
        }
        placed.push((name, p.rect));
    }
    // Sorted by their first row, so only tiles that start before one ends can overlap it.
    let mut order: Vec<usize> = (0..placed.len()).collect();
    order.sort_by_key(|&i| (placed[i].1.y0, placed[i].1.x0));
    for (k, &i) in order.iter().enumerate() {
        let (a, ra) = placed[i];
        for &j in &order[k + 1..] {
            let (b, rb) = placed[j];
            if rb.y0 >= ra.y1 {
                break;
            }
            if ra.overlaps(&rb) {
                return Err(StitchError::Overlap {
                    a: a.to_string(),
                    ra,
                    b: b.to_string(),
                    rb,
                });
            }
        }
    }
    let total = fw as u64 * fh as u64;
    let covered: u64 = placed.iter().map(|(_, r)| r.area()).sum();
    if covered < total {
        let (row, x0, x1) = first_gap(&placed, fw, fh);
        return Err(StitchError::Missing {
            covered,
            total,
            row,
            x0,
            x1,
        });
    }
    let mut out = match &first.image {
        DynamicImage::ImageRgb16(_) => DynamicImage::new_rgb16(fw, fh),
        DynamicImage::ImageRgb32F(_) => DynamicImage::new_rgb32f(fw, fh),
        _ => DynamicImage::new_rgb8(fw, fh),
    };
    for ((_, tile), (_, rect)) in tiles.iter().zip(&placed) {
        copy_into(&mut out, &tile.image, rect.x0, rect.y0);
    }
    Ok((
        out,
        Placement {
            rect: PixelRect::full(fw, fh),
            frame_width: fw,
            frame_height: fh,
        },
    ))
}

/// Copies `tile` into `frame` with its top left at (x, y); both of one pixel type.
fn copy_into(frame: &mut DynamicImage, tile: &DynamicImage, x: u32, y: u32) {
    use image::GenericImage;
    match (frame, tile) {
        (DynamicImage::ImageRgb8(f), DynamicImage::ImageRgb8(t)) => f.copy_from(t, x, y),
        (DynamicImage::ImageRgb16(f), DynamicImage::ImageRgb16(t)) => f.copy_from(t, x, y),
        (DynamicImage::ImageRgb32F(f), DynamicImage::ImageRgb32F(t)) => f.copy_from(t, x, y),
        _ => unreachable!("pixel types were checked alike"),
    }
    .expect("placements were checked inside the frame");
}

/// The first row, top down, with pixels no tile covers, and the first such run in it.
fn first_gap(placed: &[(&str, PixelRect)], width: u32, height: u32) -> (u32, u32, u32) {
    for row in 0..height {
        let mut spans: Vec<(u32, u32)> = placed
            .iter()
            .filter(|(_, r)| r.y0 <= row && row < r.y1)
            .map(|(_, r)| (r.x0, r.x1))
            .collect();
        spans.sort_unstable();
        let mut x = 0;
        for (x0, x1) in spans {
            if x0 > x {
                return (row, x, x0);
            }
            x = x.max(x1);
        }
        if x < width {
            return (row, x, width);
        }
    }
    unreachable!("called only when some pixel is uncovered")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::ImageFormat;

    /// A tile of an 8×6 frame whose pixels hold their own frame coordinates.
    fn tile(rect: &str) -> (String, ReadImage) {
        let rect = PixelRect::parse(rect).unwrap();
        let image = image::RgbImage::from_fn(rect.width(), rect.height(), |x, y| {
            image::Rgb([(rect.x0 + x) as u8, (rect.y0 + y) as u8, 7])
        });
        (
            format!("tile {rect}"),
            ReadImage {
                image: DynamicImage::ImageRgb8(image),
                format: ImageFormat::Png,
                placement: Some(Placement {
                    rect,
                    frame_width: 8,
                    frame_height: 6,
                }),
            },
        )
    }

    #[test]
    fn tiles_in_any_order_make_the_frame() {
        let tiles = [tile("0,3,8,6"), tile("0,0,5,3"), tile("5,0,8,3")];
        let (frame, p) = stitch(&tiles).unwrap();
        assert_eq!(p.rect, PixelRect::full(8, 6));
        let frame = frame.into_rgb8();
        for (x, y, px) in frame.enumerate_pixels() {
            assert_eq!(px.0, [x as u8, y as u8, 7]);
        }
    }

    #[test]
    fn missing_overlapping_and_mismatched_tiles_are_refused() {
        let e = stitch(&[tile("0,0,8,3"), tile("0,4,8,6")]).unwrap_err();
        assert_eq!(
            e,
            StitchError::Missing {
                covered: 40,
                total: 48,
                row: 3,
                x0: 0,
                x1: 8
            }
        );
        let e = stitch(&[tile("0,0,8,4"), tile("0,3,8,6")]).unwrap_err();
        assert!(matches!(e, StitchError::Overlap { .. }), "{e}");
        assert!(e.to_string().contains("0,0,8,4") && e.to_string().contains("0,3,8,6"));
        // The same rectangle twice is an overlap, not a cover.
        let e = stitch(&[tile("0,0,8,6"), tile("0,0,8,6")]).unwrap_err();
        assert!(matches!(e, StitchError::Overlap { .. }), "{e}");

        let mut other_frame = tile("0,3,8,6");
        other_frame.1.placement.as_mut().unwrap().frame_height = 7;
        let e = stitch(&[tile("0,0,8,3"), other_frame]).unwrap_err();
        assert!(e.to_string().contains("8×7"), "{e}");

        let mut deeper = tile("0,3,8,6");
        deeper.1.image = DynamicImage::ImageRgb16(deeper.1.image.to_rgb16());
        let e = stitch(&[tile("0,0,8,3"), deeper]).unwrap_err();
        assert!(e.to_string().contains("16-bit"), "{e}");

        let mut wrong = tile("0,3,8,6");
        wrong.1.placement.as_mut().unwrap().rect = PixelRect::parse("0,2,8,6").unwrap();
        let e = stitch(&[tile("0,0,8,2"), wrong]).unwrap_err();
        assert!(matches!(e, StitchError::WrongSize { .. }), "{e}");

        let mut unplaced = tile("0,3,8,6");
        unplaced.1.placement = None;
        let e = stitch(&[unplaced]).unwrap_err();
        assert!(e.to_string().contains("--tile"), "{e}");
        assert_eq!(stitch(&[]).unwrap_err(), StitchError::Empty);
    }
}
