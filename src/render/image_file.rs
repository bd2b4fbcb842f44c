//! Image files: which format a path names, turning the film's linear means into a file's
//! pixels, and writing and reading them with the placement of a tile in its frame.
//!
//! PNG (8 or 16 bits) and JPEG hold display values in 0..1; OpenEXR and PFM hold linear
//! floating-point values, brighter than white where the scene is, for compositing and for
//! HDR viewers. A tile's place in its frame goes in a PNG text chunk, and beside the image
//! in a sidecar file (`NAME.placement`) for the formats that have no such chunk.

use super::accumulator::Accumulator;
use super::output::{OutputError, PendingFile};
use super::region::PixelRect;
use crate::color::{Encoding, Transfer};
use crate::messages::{io_message, shown};
use image::{DynamicImage, ImageBuffer, Rgb};
use std::io::{BufRead, BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

/// The keyword of the PNG text chunk (and the first word of a sidecar's line) that records
/// where a tile lies in its frame.
pub const PLACEMENT_KEY: &str = "prism placement";

/// The image formats prism writes, chosen by a path's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    /// Portable Network Graphics, 8 or 16 bits per channel (`.png`).
    Png,
    /// JPEG, 8 bits, lossy (`.jpg`, `.jpeg`).
    Jpeg,
    /// OpenEXR, 32-bit float, linear (`.exr`).
    Exr,
    /// Portable Float Map, 32-bit float, linear (`.pfm`).
    Pfm,
}

/// Bits per channel of a PNG.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BitDepth {
    /// 0..255.
    #[default]
    Eight,
    /// 0..65535.
    Sixteen,
}

/// How a film becomes a file: the encoding of its colours and the format's own options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputOptions {
    /// Exposure and curve (linear HDR formats take the exposure and no curve).
    pub encoding: Encoding,
    /// A PNG's bits per channel.
    pub depth: BitDepth,
    /// A JPEG's quality, 1..100.
    pub jpeg_quality: u8,
}

impl Default for OutputOptions {
    fn default() -> Self {
        Self {
            encoding: Encoding::default(),
            depth: BitDepth::Eight,
            jpeg_quality: 90,
        }
    }
}

impl ImageFormat {
    /// The format `path` names by its extension; an unknown or missing one is refused, so
    /// `out.tiff` never receives PNG bytes. A device or FIFO (`/dev/stdout`, a pipe) has no
    /// extension to read and receives PNG.
    pub fn from_path(path: &Path) -> Result<Self, OutputError> {
        if std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
            return Ok(ImageFormat::Png);
        }
        let extension = path.extension().map(|e| e.to_string_lossy().into_owned());
        match extension.as_deref().map(str::to_ascii_lowercase).as_deref() {
            Some("png") => Ok(ImageFormat::Png),
            Some("jpg" | "jpeg") => Ok(ImageFormat::Jpeg),
            Some("exr") => Ok(ImageFormat::Exr),
            Some("pfm") => Ok(ImageFormat::Pfm),
            _ => Err(OutputError::Format {
                path: path.to_path_buf(),
                extension: extension.map(|e| shown(&e)),
            }),
        }
    }

    /// Whether it stores linear floating-point values (unbounded, no curve).
    pub fn is_hdr(self) -> bool {
        matches!(self, ImageFormat::Exr | ImageFormat::Pfm)
    }

    /// Its name in messages.
    pub fn name(self) -> &'static str {
        match self {
            ImageFormat::Png => "PNG",
            ImageFormat::Jpeg => "JPEG",
            ImageFormat::Exr => "OpenEXR",
            ImageFormat::Pfm => "PFM",
        }
    }

    /// Refuses options the format cannot honour, naming the file.
    pub fn check(self, path: &Path, options: &OutputOptions) -> Result<(), OutputError> {
        let refuse = |reason: String| {
            Err(OutputError::Options {
                path: path.to_path_buf(),
                reason,
            })
        };
        if options.depth == BitDepth::Sixteen && self != ImageFormat::Png {
            return refuse(format!(
                "16 bits per channel is a PNG option; {} is not PNG",
                self.name()
            ));
        }
        if self.is_hdr() && options.encoding.transfer != Transfer::Linear {
            return refuse(format!(
                "{} holds linear values: the sRGB curve is for PNG and JPEG",
                self.name()
            ));
        }
        if !crate::limits::JPEG_QUALITY.contains(&options.jpeg_quality) {
            return refuse(format!(
                "JPEG quality {} must be {} to {}",
                options.jpeg_quality,
                crate::limits::JPEG_QUALITY.start(),
                crate::limits::JPEG_QUALITY.end()
            ));
        }
        Ok(())
    }
}

/// The film's pixel means as `format`'s pixels: 8 or 16 bits per channel for PNG and JPEG
/// (clamped to 0..1 after the encoding), 32-bit floats for EXR and PFM. At the default
/// options an 8-bit image equals `Accumulator::to_rgb8`.
pub fn encode(acc: &Accumulator, format: ImageFormat, options: &OutputOptions) -> DynamicImage {
    let (w, h) = (acc.width, acc.height);
    let means = acc.pixels.iter().map(|p| options.encoding.apply(p.mean()));
    if format.is_hdr() {
        let raw: Vec<f32> = means.flat_map(|c| c.to_array()).collect();
        return DynamicImage::ImageRgb32F(ImageBuffer::from_raw(w, h, raw).expect("size"));
    }
    match (format, options.depth) {
        (ImageFormat::Png, BitDepth::Sixteen) => {
            let q = |v: f32| (v.clamp(0.0, 1.0) * 65535.0 + 0.5) as u16;
            let raw: Vec<u16> = means.flat_map(|c| [q(c.x), q(c.y), q(c.z)]).collect();
            DynamicImage::ImageRgb16(ImageBuffer::from_raw(w, h, raw).expect("size"))
        }
        _ => {
            let raw: Vec<u8> = means.flat_map(super::to_8bit).collect();
            DynamicImage::ImageRgb8(ImageBuffer::from_raw(w, h, raw).expect("size"))
        }
    }
}

/// Where a tile lies in its frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placement {
    /// Its pixels in the frame.
    pub rect: PixelRect,
    /// The frame's width.
    pub frame_width: u32,
    /// The frame's height.
    pub frame_height: u32,
}

impl Placement {
    /// The text a file records (see `PixelRect::placement`).
    pub fn text(&self) -> String {
        self.rect.placement(self.frame_width, self.frame_height)
    }
}

/// The sidecar file that records the placement of an image in a format with no text chunk.
pub fn sidecar_path(image: &Path) -> PathBuf {
    let mut name = image.as_os_str().to_os_string();
    name.push(".placement");
    PathBuf::from(name)
}

impl PendingFile {
    /// Writes `image` in `format`, with `placement` recorded when it is a part of a frame,
    /// then puts the finished file in place. A sidecar, for a format without text chunks,
    /// is written (atomically too) before the image, so an image never lacks its record.
    pub fn finish_image(
        self,
        image: &DynamicImage,
        format: ImageFormat,
        options: &OutputOptions,
        placement: Option<Placement>,
    ) -> Result<PathBuf, OutputError> {
        let sidecar = sidecar_path(self.path());
        if let Some(p) = placement
            && format != ImageFormat::Png
        {
            let line = format!("{PLACEMENT_KEY}: {}\n", p.text());
            super::output::write_bytes(&sidecar, line.as_bytes())?;
        }
        let quality = options.jpeg_quality;
        let written = self.commit(|file| {
            let mut writer = BufWriter::new(file);
            match format {
                ImageFormat::Png => write_png(&mut writer, image, placement)?,
                ImageFormat::Jpeg => {
                    let encoder =
                        image::codecs::jpeg::JpegEncoder::new_with_quality(&mut writer, quality);
                    image
                        .to_rgb8()
                        .write_with_encoder(encoder)
                        .map_err(image_message)?;
                }
                ImageFormat::Exr => {
                    DynamicImage::ImageRgb32F(image.to_rgb32f())
                        .write_to(&mut writer, image::ImageFormat::OpenExr)
                        .map_err(image_message)?;
                }
                ImageFormat::Pfm => write_pfm(&mut writer, &image.to_rgb32f())?,
            }
            writer.flush().map_err(|e| io_message(&e))
        })?;
        // A sidecar left by an earlier tile of the same name would misplace this image.
        if placement.is_none() || format == ImageFormat::Png {
            let _ = std::fs::remove_file(&sidecar);
        }
        Ok(written)
    }
}

fn image_message(e: image::ImageError) -> String {
    match e {
        image::ImageError::IoError(e) => io_message(&e),
        other => other.to_string(),
    }
}

/// A PNG of the image's own depth, with the placement as a text chunk.
fn write_png(
    writer: &mut impl Write,
    image: &DynamicImage,
    placement: Option<Placement>,
) -> Result<(), String> {
    let (w, h) = (image.width(), image.height());
    let mut encoder = png::Encoder::new(writer, w, h);
    encoder.set_color(png::ColorType::Rgb);
    let data: Vec<u8> = match image {
        DynamicImage::ImageRgb16(buffer) => {
            encoder.set_depth(png::BitDepth::Sixteen);
            buffer
                .as_raw()
                .iter()
                .flat_map(|v| v.to_be_bytes())
                .collect()
        }
        other => {
            encoder.set_depth(png::BitDepth::Eight);
            other.to_rgb8().into_raw()
        }
    };
    if let Some(p) = placement {
        encoder
            .add_text_chunk(PLACEMENT_KEY.to_string(), p.text())
            .map_err(|e| e.to_string())?;
    }
    let png_message = |e: png::EncodingError| match e {
        png::EncodingError::IoError(e) => io_message(&e),
        other => other.to_string(),
    };
    let mut png = encoder.write_header().map_err(png_message)?;
    png.write_image_data(&data).map_err(png_message)?;
    png.finish().map_err(png_message)
}

/// A Portable Float Map: a text header, then rows from the bottom up of little-endian f32
/// RGB (the negative scale says little-endian).
fn write_pfm(writer: &mut impl Write, image: &image::Rgb32FImage) -> Result<(), String> {
    let (w, h) = image.dimensions();
    let io = |e: std::io::Error| io_message(&e);
    write!(writer, "PF\n{w} {h}\n-1.0\n").map_err(io)?;
    let row = w as usize * 3;
    for y in (0..h as usize).rev() {
        let values = &image.as_raw()[y * row..(y + 1) * row];
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        writer.write_all(&bytes).map_err(io)?;
    }
    Ok(())
}

/// An image file read back (by `prism stitch`), with its placement if it records one.
pub struct ReadImage {
    /// The pixels: RGB 8 or 16 bits, or 32-bit float.
    pub image: DynamicImage,
    /// Its format.
    pub format: ImageFormat,
    /// Where it lies in its frame, from its text chunk or its sidecar.
    pub placement: Option<Placement>,
}

/// Why an image file cannot be read back.
#[derive(Debug, thiserror::Error)]
#[error("{}: {reason}", path.display())]
pub struct ReadError {
    /// The file.
    pub path: PathBuf,
    /// Why, in words.
    pub reason: String,
}

/// Reads an image that prism wrote (PNG of 8 or 16 bits, JPEG, OpenEXR, PFM), refusing
/// one larger than `max_side` on a side before its pixels are decoded.
pub fn read_image(path: &Path, max_side: u32) -> Result<ReadImage, ReadError> {
    let fail = |reason: String| ReadError {
        path: path.to_path_buf(),
        reason,
    };
    let format = ImageFormat::from_path(path).map_err(|e| match e {
        OutputError::Format { .. } => fail("not a PNG, JPEG, EXR or PFM file name".into()),
        other => fail(other.to_string()),
    })?;
    let file = std::fs::File::open(path).map_err(|e| fail(io_message(&e)))?;
    let too_large = |w: u32, h: u32| {
        fail(format!(
            "{w}×{h} is larger than the {max_side} pixels a side a frame may have"
        ))
    };
    let mut placement_text = None;
    let image = match format {
        ImageFormat::Png => {
            let mut decoder = png::Decoder::new(BufReader::new(file));
            decoder.set_transformations(png::Transformations::IDENTITY);
            let mut reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
            let info = reader.info();
            let (w, h) = (info.width, info.height);
            if w > max_side || h > max_side {
                return Err(too_large(w, h));
            }
            placement_text = info
                .uncompressed_latin1_text
                .iter()
                .find(|t| t.keyword == PLACEMENT_KEY)
                .map(|t| t.text.clone());
            if info.color_type != png::ColorType::Rgb {
                return Err(fail(format!(
                    "a {:?} PNG; prism writes RGB PNGs",
                    info.color_type
                )));
            }
            let depth = info.bit_depth;
            let mut data = vec![0; reader.output_buffer_size().ok_or_else(|| too_large(w, h))?];
            reader
                .next_frame(&mut data)
                .map_err(|e| fail(e.to_string()))?;
            match depth {
                png::BitDepth::Eight => DynamicImage::ImageRgb8(
                    ImageBuffer::from_raw(w, h, data).ok_or_else(|| fail("short data".into()))?,
                ),
                png::BitDepth::Sixteen => {
                    let values = data
                        .chunks_exact(2)
                        .map(|b| u16::from_be_bytes([b[0], b[1]]))
                        .collect();
                    DynamicImage::ImageRgb16(
                        ImageBuffer::from_raw(w, h, values)
                            .ok_or_else(|| fail("short data".into()))?,
                    )
                }
                other => return Err(fail(format!("a {other:?}-bit PNG; prism writes 8 or 16"))),
            }
        }
        ImageFormat::Pfm => DynamicImage::ImageRgb32F(read_pfm(file, max_side).map_err(fail)?),
        ImageFormat::Jpeg | ImageFormat::Exr => {
            let mut reader = image::ImageReader::new(BufReader::new(file));
            reader.set_format(match format {
                ImageFormat::Jpeg => image::ImageFormat::Jpeg,
                _ => image::ImageFormat::OpenExr,
            });
            let mut limits = image::Limits::default();
            limits.max_image_width = Some(max_side);
            limits.max_image_height = Some(max_side);
            reader.limits(limits);
            let image = reader.decode().map_err(|e| fail(image_message(e)))?;
            match format {
                ImageFormat::Jpeg => DynamicImage::ImageRgb8(image.into_rgb8()),
                _ => DynamicImage::ImageRgb32F(image.into_rgb32f()),
            }
        }
    };
    // A PNG records its placement in itself; only the other formats have sidecars.
    if placement_text.is_none() && format != ImageFormat::Png {
        let sidecar = sidecar_path(path);
        if let Ok(text) = std::fs::read_to_string(&sidecar) {
            let line = text.lines().next().unwrap_or_default();
            placement_text = Some(
                line.strip_prefix(PLACEMENT_KEY)
                    .and_then(|rest| rest.strip_prefix(':'))
                    .map(|t| t.trim().to_string())
                    .ok_or_else(|| {
                        fail(format!(
                            "its sidecar {} does not begin \"{PLACEMENT_KEY}:\"",
                            sidecar.display()
                        ))
                    })?,
            );
        }
    }
    let placement = match placement_text {
        None => None,
        Some(text) => {
            let (rect, frame_width, frame_height) =
                PixelRect::parse_placement(&text).map_err(|e| fail(e.to_string()))?;
            Some(Placement {
                rect,
                frame_width,
                frame_height,
            })
        }
    };
    Ok(ReadImage {
        image,
        format,
        placement,
    })
}

/// A Portable Float Map (RGB, either byte order), as an image from the top row down.
fn read_pfm(file: std::fs::File, max_side: u32) -> Result<image::Rgb32FImage, String> {
    let mut reader = BufReader::new(file);
    let mut words = Vec::new();
    // The header is three whitespace-separated words after "PF": width, height, scale.
    while words.len() < 4 {
        let mut line = String::new();
        if reader.read_line(&mut line).map_err(|e| io_message(&e))? == 0 || line.len() > 256 {
            return Err("not a PFM file (its header ends early)".into());
        }
        words.extend(line.split_whitespace().map(str::to_string));
    }
    if words[0] != "PF" {
        return Err("not an RGB PFM file (it does not begin \"PF\")".into());
    }
    let bad = || "a PFM header with a bad width, height or scale".to_string();
    let w: u32 = words[1].parse().map_err(|_| bad())?;
    let h: u32 = words[2].parse().map_err(|_| bad())?;
    let scale: f32 = words[3].parse().map_err(|_| bad())?;
    if w == 0 || h == 0 || !scale.is_finite() || scale == 0.0 {
        return Err(bad());
    }
    if w > max_side || h > max_side {
        return Err(format!("{w}×{h} is larger than {max_side} pixels a side"));
    }
    let row = w as usize * 3;
    let mut bytes = vec![0u8; row * 4 * h as usize];
    reader
        .read_exact(&mut bytes)
        .map_err(|_| "the PFM file is shorter than its header says".to_string())?;
    let value = |b: &[u8]| {
        let b = [b[0], b[1], b[2], b[3]];
        if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        }
    };
    let mut raw = vec![0f32; row * h as usize];
    for (y, src) in bytes.chunks_exact(row * 4).enumerate() {
        let dst = &mut raw[(h as usize - 1 - y) * row..][..row];
        for (d, s) in dst.iter_mut().zip(src.chunks_exact(4)) {
            *d = value(s);
        }
    }
    Ok(ImageBuffer::<Rgb<f32>, _>::from_raw(w, h, raw).expect("size"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A 3×2 film with one subsample per pixel, one of them brighter than white.
    fn film() -> Accumulator {
        let mut acc = Accumulator::new(3, 2);
        let colors = [0.0, 0.25, 0.5, 0.75, 1.0, 3.5];
        for (p, c) in acc.pixels.iter_mut().zip(colors) {
            p.add(Vec3::new(c, c * 0.5, 0.1), 0);
        }
        acc
    }

    #[test]
    fn formats_follow_the_extension() {
        for (name, format) in [
            ("a.png", ImageFormat::Png),
            ("a.JPG", ImageFormat::Jpeg),
            ("a.jpeg", ImageFormat::Jpeg),
            ("a.exr", ImageFormat::Exr),
            ("a.pfm", ImageFormat::Pfm),
        ] {
            assert_eq!(ImageFormat::from_path(Path::new(name)).unwrap(), format);
        }
        for name in ["a.tiff", "a", "a.png.tmp"] {
            assert!(ImageFormat::from_path(Path::new(name)).is_err(), "{name}");
        }
        let sixteen = OutputOptions {
            depth: BitDepth::Sixteen,
            ..OutputOptions::default()
        };
        assert!(ImageFormat::Png.check(Path::new("a.png"), &sixteen).is_ok());
        let e = ImageFormat::Jpeg
            .check(Path::new("a.jpg"), &sixteen)
            .unwrap_err();
        assert!(
            e.to_string().contains("a.jpg") && e.to_string().contains("16"),
            "{e}"
        );
        let srgb = OutputOptions {
            encoding: Encoding {
                transfer: Transfer::Srgb,
                exposure: 0.0,
            },
            ..OutputOptions::default()
        };
        assert!(ImageFormat::Exr.check(Path::new("a.exr"), &srgb).is_err());
        assert!(ImageFormat::Jpeg.check(Path::new("a.jpg"), &srgb).is_ok());
    }

    #[test]
    fn eight_bits_by_default_equal_the_film_as_shown() {
        let acc = film();
        let image = encode(&acc, ImageFormat::Png, &OutputOptions::default());
        assert_eq!(image.to_rgb8(), acc.to_rgb8());
    }

    /// Every format written reads back with its values: PNG exactly (8 and 16 bits), the
    /// float formats exactly and unclamped, JPEG within its loss; a placement comes back
    /// from the PNG chunk and from the sidecar.
    #[test]
    fn every_format_reads_back() {
        let dir = tempfile::tempdir().unwrap();
        let acc = film();
        let placement = Placement {
            rect: PixelRect::parse("2,5,5,7").unwrap(),
            frame_width: 10,
            frame_height: 9,
        };
        for (name, depth) in [
            ("a.png", BitDepth::Eight),
            ("b.png", BitDepth::Sixteen),
            ("c.jpg", BitDepth::Eight),
            ("d.exr", BitDepth::Eight),
            ("e.pfm", BitDepth::Eight),
        ] {
            let path = dir.path().join(name);
            let format = ImageFormat::from_path(&path).unwrap();
            let options = OutputOptions {
                depth,
                jpeg_quality: 100,
                ..OutputOptions::default()
            };
            let image = encode(&acc, format, &options);
            PendingFile::create(&path)
                .unwrap()
                .finish_image(&image, format, &options, Some(placement))
                .unwrap();
            let back = read_image(&path, 100).unwrap();
            assert_eq!(back.placement, Some(placement), "{name}");
            assert_eq!(back.format, format);
            match format {
                ImageFormat::Jpeg => {
                    let (a, b) = (image.to_rgb8(), back.image.to_rgb8());
                    let worst = a.iter().zip(b.iter()).map(|(x, y)| x.abs_diff(*y)).max();
                    assert!(worst.unwrap() <= 12, "{worst:?}");
                }
                _ => assert_eq!(back.image, image, "{name}"),
            }
            assert_eq!(sidecar_path(&path).exists(), format != ImageFormat::Png);
        }
        // A whole frame written where a tile was leaves no stale sidecar to misplace it.
        let path = dir.path().join("e.pfm");
        let image = encode(&acc, ImageFormat::Pfm, &OutputOptions::default());
        PendingFile::create(&path)
            .unwrap()
            .finish_image(&image, ImageFormat::Pfm, &OutputOptions::default(), None)
            .unwrap();
        assert!(!sidecar_path(&path).exists());
        assert_eq!(read_image(&path, 100).unwrap().placement, None);
        // The float formats keep values above white, linear.
        let back = read_image(&dir.path().join("e.pfm"), 100).unwrap();
        assert_eq!(back.image.to_rgb32f().get_pixel(2, 1).0, [3.5, 1.75, 0.1]);
        let sixteen = read_image(&dir.path().join("b.png"), 100).unwrap();
        assert_eq!(
            sixteen.image.as_rgb16().unwrap().get_pixel(1, 0).0[0],
            16384
        );
        // Too large for the caller's limit: refused before decoding.
        let e = read_image(&dir.path().join("a.png"), 2).err().unwrap();
        assert!(e.to_string().contains("3×2"), "{e}");
    }
}
