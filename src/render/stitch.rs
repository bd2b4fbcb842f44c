//! Assembling a frame from tiles rendered apart (`prism stitch`): each tile records its
//! place in the frame, and the tiles must cover the frame once, with one pixel type.

use super::image_file::Placement;
use super::image_read::{ImageInfo, PixelType, ReadImage};
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
    #[error("{name} holds {theirs}, {first} {ours}: stitch tiles written alike")]
    PixelMismatch {
        /// The tile that differs.
        name: String,
        /// Its pixel type and format.
        theirs: String,
        /// The first tile.
        first: String,
        /// The first tile's pixel type and format.
        ours: String,
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
    /// A frame larger than any prism renders.
    #[error("{name} is a tile of a {width}×{height} frame: at most {max_side} pixels a side")]
    FrameTooLarge {
        /// The tile that says so.
        name: String,
        /// The frame's width.
        width: u32,
        /// The frame's height.
        height: u32,
        /// The largest side.
        max_side: u32,
    },
    /// A tile whose pixels are not what its header said (it changed while being read).
    #[error("{0}: its pixels are not what its header said (did it change while stitching?)")]
    Changed(String),
    /// A float tile holding a NaN or infinite value.
    #[error(
        "{name}: pixel ({x}, {y}) of the frame is not a finite number; a render writes none, \
         so the tile is damaged"
    )]
    NotFinite {
        /// The tile.
        name: String,
        /// The pixel's column in the frame.
        x: u32,
        /// Its row.
        y: u32,
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

/// How tiles make a frame, decided from their headers alone (no pixel is decoded before
/// the set is known to cover the frame once): the frame's size and pixel type and each
/// tile's place, in the order given.
#[derive(Clone, Debug, PartialEq)]
pub struct StitchPlan {
    /// The whole frame: its rectangle and size.
    pub frame: Placement,
    /// The pixel type every tile holds.
    pub pixels: PixelType,
    /// Where each tile goes, in the order given.
    pub rects: Vec<PixelRect>,
}

/// The plan by which `tiles` (each with the name it is known by) make a frame of at most
/// `max_side` pixels a side: refused if any tile is unplaced or of the wrong size, if the
/// tiles disagree on the frame or the pixel type, overlap, or leave a pixel uncovered.
pub fn plan_stitch(
    tiles: &[(String, ImageInfo)],
    max_side: u32,
) -> Result<StitchPlan, StitchError> {
    let (first_name, first) = tiles.first().ok_or(StitchError::Empty)?;
    let frame_of = |name: &str, tile: &ImageInfo| {
        tile.placement
            .ok_or_else(|| StitchError::Unplaced(name.to_string()))
    };
    let frame = frame_of(first_name, first)?;
    let (fw, fh) = (frame.frame_width, frame.frame_height);
    if fw > max_side || fh > max_side {
        return Err(StitchError::FrameTooLarge {
            name: first_name.clone(),
            width: fw,
            height: fh,
            max_side,
        });
    }
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
        if tile.pixels != first.pixels || tile.format != first.format {
            return Err(StitchError::PixelMismatch {
                name: name.clone(),
                theirs: pixels_in(tile),
                first: first_name.clone(),
                ours: pixels_in(first),
            });
        }
        if (tile.width, tile.height) != (p.rect.width(), p.rect.height()) {
            return Err(StitchError::WrongSize {
                name: name.clone(),
                width: tile.width,
                height: tile.height,
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
    Ok(StitchPlan {
        frame: Placement {
            rect: PixelRect::full(fw, fh),
            frame_width: fw,
            frame_height: fh,
        },
        pixels: first.pixels,
        rects: placed.into_iter().map(|(_, r)| r).collect(),
    })
}

impl StitchPlan {
    /// The frame, black, to paste the tiles into.
    pub fn blank(&self) -> DynamicImage {
        self.pixels
            .blank(self.frame.frame_width, self.frame.frame_height)
    }

    /// Copies tile `index` (known as `name`), decoded, into its place in `frame`; a tile
    /// that is not as its header said, or that holds a NaN or infinite value (which no
    /// render writes), is refused.
    pub fn paste(
        &self,
        frame: &mut DynamicImage,
        index: usize,
        name: &str,
        tile: &DynamicImage,
    ) -> Result<(), StitchError> {
        let rect = self.rects[index];
        if PixelType::of(tile) != Some(self.pixels)
            || (tile.width(), tile.height()) != (rect.width(), rect.height())
        {
            return Err(StitchError::Changed(name.to_string()));
        }
        if let DynamicImage::ImageRgb32F(t) = tile
            && let Some((x, y, _)) = t
                .enumerate_pixels()
                .find(|(_, _, p)| p.0.iter().any(|v| !v.is_finite()))
        {
            return Err(StitchError::NotFinite {
                name: name.to_string(),
                x: rect.x0 + x,
                y: rect.y0 + y,
            });
        }
        copy_into(frame, tile, rect.x0, rect.y0);
        Ok(())
    }
}

/// The frame that decoded `tiles` make (each with the name it is known by): `plan_stitch`
/// and `StitchPlan::paste` for images already in memory.
pub fn stitch(tiles: &[(String, ReadImage)]) -> Result<(DynamicImage, Placement), StitchError> {
    let infos: Vec<(String, ImageInfo)> = tiles
        .iter()
        .map(|(name, t)| {
            let info = ImageInfo {
                width: t.image.width(),
                height: t.image.height(),
                pixels: PixelType::of(&t.image).unwrap_or(PixelType::Rgb8),
                format: t.format,
                placement: t.placement,
            };
            (name.clone(), info)
        })
        .collect();
    let plan = plan_stitch(&infos, u32::MAX)?;
    let mut frame = plan.blank();
    for (i, (name, tile)) in tiles.iter().enumerate() {
        plan.paste(&mut frame, i, name, &tile.image)?;
    }
    Ok((frame, plan.frame))
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

/// A tile's pixels as a message names them: their type and the file's format (two float
/// formats hold the same pixels).
fn pixels_in(tile: &ImageInfo) -> String {
    format!("{} pixels in {}", tile.pixels.name(), tile.format.name())
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

        let mut nan = tile("0,3,8,6");
        let mut float = nan.1.image.to_rgb32f();
        float.get_pixel_mut(2, 1).0[1] = f32::INFINITY;
        nan.1.image = DynamicImage::ImageRgb32F(float);
        let mut top = tile("0,0,8,3");
        top.1.image = DynamicImage::ImageRgb32F(top.1.image.to_rgb32f());
        let e = stitch(&[top, nan]).unwrap_err();
        assert_eq!(
            e,
            StitchError::NotFinite {
                name: "tile 0,3,8,6".into(),
                x: 2,
                y: 4
            }
        );

        let (name, big) = tile("0,0,8,6");
        let info = ImageInfo {
            width: 8,
            height: 6,
            pixels: PixelType::Rgb8,
            format: big.format,
            placement: Some(Placement {
                rect: PixelRect::parse("0,0,8,6").unwrap(),
                frame_width: 16384,
                frame_height: 16385,
            }),
        };
        let e = plan_stitch(&[(name, info)], 16384).unwrap_err();
        assert!(matches!(e, StitchError::FrameTooLarge { .. }), "{e}");

        let mut unplaced = tile("0,3,8,6");
        unplaced.1.placement = None;
        let e = stitch(&[unplaced]).unwrap_err();
        assert!(e.to_string().contains("--tile"), "{e}");
        assert_eq!(stitch(&[]).unwrap_err(), StitchError::Empty);
    }
}
