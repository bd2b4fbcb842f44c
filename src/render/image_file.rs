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
use image::{DynamicImage, ImageBuffer};
use std::io::{BufWriter, Write};
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
            let raw: Vec<u8> = means.flat_map(super::accumulator::to_8bit).collect();
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
                ImageFormat::Png => {
                    encode_png(&mut writer, image, options.encoding.transfer, placement)?
                }
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

/// Writes `image` to `path` as a PNG, atomically; the path must name a PNG.
pub fn write_png(path: &Path, image: &image::RgbImage) -> Result<PathBuf, OutputError> {
    ImageFormat::from_path(path)?;
    PendingFile::create(path)?.finish_png(image)
}

/// An image crate error in plain words (an I/O cause said once).
pub(super) fn image_message(e: image::ImageError) -> String {
    match e {
        image::ImageError::IoError(e) => io_message(&e),
        other => other.to_string(),
    }
}

/// A PNG of the image's own depth, tagged with its transfer curve (so that viewers show a
/// linear file as linear, not as sRGB), with the placement as a text chunk.
fn encode_png(
    writer: &mut impl Write,
    image: &DynamicImage,
    transfer: Transfer,
    placement: Option<Placement>,
) -> Result<(), String> {
    let (w, h) = (image.width(), image.height());
    let mut encoder = png::Encoder::new(writer, w, h);
    encoder.set_color(png::ColorType::Rgb);
    // fdeflate, tuned for images: the default (zlib's level) costs as much as a few
    // percent of a whole render of the seed, for a file about 15% smaller.
    encoder.set_compression(png::Compression::Fast);
    match transfer {
        // gAMA 1.0: the stored values are proportional to light.
        Transfer::Linear => encoder.set_source_gamma(png::ScaledFloat::new(1.0)),
        // The sRGB chunk, with the gAMA it implies for readers that know only that.
        Transfer::Srgb => {
            encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            encoder.set_source_gamma(png::ScaledFloat::from_scaled(45455));
        }
    }
    // An 8-bit image is written from its own bytes, without a copy of the frame.
    let data: std::borrow::Cow<[u8]> = match image {
        DynamicImage::ImageRgb16(buffer) => {
            encoder.set_depth(png::BitDepth::Sixteen);
            let bytes = buffer.as_raw().iter().flat_map(|v| v.to_be_bytes());
            std::borrow::Cow::Owned(bytes.collect())
        }
        DynamicImage::ImageRgb8(buffer) => {
            encoder.set_depth(png::BitDepth::Eight);
            std::borrow::Cow::Borrowed(buffer.as_raw())
        }
        other => {
            encoder.set_depth(png::BitDepth::Eight);
            std::borrow::Cow::Owned(other.to_rgb8().into_raw())
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::read_image;
    use glam::Vec3;
    use std::io::BufReader;

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
        // A PNG says which curve its values follow.
        let info = |name: &str| {
            let file = std::fs::File::open(dir.path().join(name)).unwrap();
            let reader = png::Decoder::new(BufReader::new(file)).read_info().unwrap();
            (reader.info().gama_chunk, reader.info().srgb)
        };
        assert_eq!(info("a.png"), (Some(png::ScaledFloat::new(1.0)), None));
        let srgb = OutputOptions {
            encoding: Encoding {
                transfer: Transfer::Srgb,
                exposure: 0.0,
            },
            ..OutputOptions::default()
        };
        let path = dir.path().join("s.png");
        PendingFile::create(&path)
            .unwrap()
            .finish_image(
                &encode(&acc, ImageFormat::Png, &srgb),
                ImageFormat::Png,
                &srgb,
                None,
            )
            .unwrap();
        assert_eq!(
            info("s.png"),
            (
                Some(png::ScaledFloat::from_scaled(45455)),
                Some(png::SrgbRenderingIntent::Perceptual)
            )
        );
        // Too large for the caller's limit: refused before decoding.
        let e = read_image(&dir.path().join("a.png"), 2).err().unwrap();
        assert!(e.to_string().contains("3×2"), "{e}");
    }
}
