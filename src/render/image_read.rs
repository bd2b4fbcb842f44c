//! Reading back the images prism writes (for `prism stitch`): first what a file's header
//! says (its size, pixel type and placement), which costs no pixel memory, then its pixels.
//! Only regular files are opened: a FIFO would block, a device might never end.

use super::image_file::{ImageFormat, PLACEMENT_KEY, Placement, image_message, sidecar_path};
use super::output::OutputError;
use super::region::PixelRect;
use crate::messages::{io_message, shown_path};
use image::{DynamicImage, ImageBuffer, Rgb};
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

/// The longest placement sidecar read: one line of a few numbers, with room to spare.
const MAX_SIDECAR_BYTES: u64 = 1024;

/// The pixel types prism writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelType {
    /// 8 bits per channel (PNG, JPEG).
    Rgb8,
    /// 16 bits per channel (PNG).
    Rgb16,
    /// 32-bit float per channel (OpenEXR, PFM).
    Rgb32F,
}

impl PixelType {
    /// Its name in messages.
    pub fn name(self) -> &'static str {
        match self {
            PixelType::Rgb8 => "8-bit RGB",
            PixelType::Rgb16 => "16-bit RGB",
            PixelType::Rgb32F => "32-bit float RGB",
        }
    }

    /// Bytes per pixel in memory.
    pub fn bytes(self) -> u64 {
        match self {
            PixelType::Rgb8 => 3,
            PixelType::Rgb16 => 6,
            PixelType::Rgb32F => 12,
        }
    }

    /// The pixel type of a decoded image (one prism reads back).
    pub fn of(image: &DynamicImage) -> Option<Self> {
        match image {
            DynamicImage::ImageRgb8(_) => Some(PixelType::Rgb8),
            DynamicImage::ImageRgb16(_) => Some(PixelType::Rgb16),
            DynamicImage::ImageRgb32F(_) => Some(PixelType::Rgb32F),
            _ => None,
        }
    }

    /// A black image of this type.
    pub fn blank(self, width: u32, height: u32) -> DynamicImage {
        match self {
            PixelType::Rgb8 => DynamicImage::new_rgb8(width, height),
            PixelType::Rgb16 => DynamicImage::new_rgb16(width, height),
            PixelType::Rgb32F => DynamicImage::new_rgb32f(width, height),
        }
    }
}

/// What an image file's header says, read without decoding its pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ImageInfo {
    /// Its width in pixels.
    pub width: u32,
    /// Its height in pixels.
    pub height: u32,
    /// Its pixel type.
    pub pixels: PixelType,
    /// Its format.
    pub format: ImageFormat,
    /// Where it lies in its frame, from its text chunk or its sidecar.
    pub placement: Option<Placement>,
}

/// An image file read back, with its placement if it records one.
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
#[error("{}: {reason}", shown_path(path))]
pub struct ReadError {
    /// The file.
    pub path: PathBuf,
    /// Why, in words.
    pub reason: String,
}

/// Opens `path` for reading if it is a regular file, saying what it is otherwise.
fn open_regular(path: &Path) -> Result<std::fs::File, String> {
    let meta = std::fs::metadata(path).map_err(|e| io_message(&e))?;
    if meta.is_dir() {
        return Err("it is a directory".into());
    }
    if !meta.is_file() {
        return Err("it is not a regular file (a FIFO or a device)".into());
    }
    std::fs::File::open(path).map_err(|e| io_message(&e))
}

/// Reads the header of an image that prism wrote (PNG of 8 or 16 bits, JPEG, OpenEXR,
/// PFM) and its placement, refusing one larger than `max_side` on a side.
pub fn read_image_info(path: &Path, max_side: u32) -> Result<ImageInfo, ReadError> {
    let fail = |reason: String| ReadError {
        path: path.to_path_buf(),
        reason,
    };
    let format = image_format(path).map_err(fail)?;
    let file = open_regular(path).map_err(fail)?;
    let mut placement_text = None;
    let (width, height, pixels) = match format {
        ImageFormat::Png => {
            let mut decoder = png::Decoder::new(BufReader::new(file));
            decoder.set_transformations(png::Transformations::IDENTITY);
            let reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
            let info = reader.info();
            let mut texts = info
                .uncompressed_latin1_text
                .iter()
                .filter(|t| t.keyword == PLACEMENT_KEY);
            placement_text = texts.next().map(|t| t.text.clone());
            if texts.next().is_some() {
                return Err(fail(format!(
                    "it has more than one \"{PLACEMENT_KEY}\" text chunk: which one holds?"
                )));
            }
            if info.color_type != png::ColorType::Rgb {
                return Err(fail(format!(
                    "a {:?} PNG; prism writes RGB PNGs",
                    info.color_type
                )));
            }
            let pixels = match info.bit_depth {
                png::BitDepth::Eight => PixelType::Rgb8,
                png::BitDepth::Sixteen => PixelType::Rgb16,
                other => return Err(fail(format!("a {other:?}-bit PNG; prism writes 8 or 16"))),
            };
            (info.width, info.height, pixels)
        }
        ImageFormat::Pfm => {
            let (w, h, _) = read_pfm_header(&mut BufReader::new(file)).map_err(fail)?;
            (w, h, PixelType::Rgb32F)
        }
        ImageFormat::Jpeg | ImageFormat::Exr => {
            let (w, h) = reader(file, format)
                .into_dimensions()
                .map_err(|e| fail(image_message(e)))?;
            let pixels = match format {
                ImageFormat::Jpeg => PixelType::Rgb8,
                _ => PixelType::Rgb32F,
            };
            (w, h, pixels)
        }
    };
    if width > max_side || height > max_side {
        return Err(fail(format!(
            "{width}×{height} is larger than the {max_side} pixels a side a frame may have"
        )));
    }
    // A PNG records its placement in itself; only the other formats have sidecars.
    if format != ImageFormat::Png {
        placement_text = read_sidecar(path).map_err(fail)?;
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
    Ok(ImageInfo {
        width,
        height,
        pixels,
        format,
        placement,
    })
}

/// Reads an image that prism wrote, with its placement, refusing one larger than
/// `max_side` on a side before its pixels are decoded.
pub fn read_image(path: &Path, max_side: u32) -> Result<ReadImage, ReadError> {
    let info = read_image_info(path, max_side)?;
    let image = read_pixels(path, &info)?;
    Ok(ReadImage {
        image,
        format: info.format,
        placement: info.placement,
    })
}

/// Decodes the pixels of the image whose header said `info`, refusing a file that no
/// longer matches it.
pub fn read_pixels(path: &Path, info: &ImageInfo) -> Result<DynamicImage, ReadError> {
    let fail = |reason: String| ReadError {
        path: path.to_path_buf(),
        reason,
    };
    let file = open_regular(path).map_err(fail)?;
    let image = match info.format {
        ImageFormat::Png => {
            let mut decoder = png::Decoder::new(BufReader::new(file));
            decoder.set_transformations(png::Transformations::IDENTITY);
            let mut reader = decoder.read_info().map_err(|e| fail(e.to_string()))?;
            let (w, h) = (reader.info().width, reader.info().height);
            let depth = reader.info().bit_depth;
            if (w, h) != (info.width, info.height) {
                return Err(fail("the file changed while it was read".into()));
            }
            let size = reader
                .output_buffer_size()
                .ok_or_else(|| fail("too large".into()))?;
            let mut data = vec![0; size];
            reader
                .next_frame(&mut data)
                .map_err(|e| fail(e.to_string()))?;
            match depth {
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
                _ => DynamicImage::ImageRgb8(
                    ImageBuffer::from_raw(w, h, data).ok_or_else(|| fail("short data".into()))?,
                ),
            }
        }
        ImageFormat::Pfm => DynamicImage::ImageRgb32F(read_pfm(file).map_err(fail)?),
        ImageFormat::Jpeg | ImageFormat::Exr => {
            let mut reader = reader(file, info.format);
            let mut limits = image::Limits::default();
            limits.max_image_width = Some(info.width);
            limits.max_image_height = Some(info.height);
            reader.limits(limits);
            let image = reader.decode().map_err(|e| fail(image_message(e)))?;
            match info.format {
                ImageFormat::Jpeg => DynamicImage::ImageRgb8(image.into_rgb8()),
                _ => DynamicImage::ImageRgb32F(image.into_rgb32f()),
            }
        }
    };
    if (image.width(), image.height()) != (info.width, info.height)
        || PixelType::of(&image) != Some(info.pixels)
    {
        return Err(fail("the file changed while it was read".into()));
    }
    Ok(image)
}

/// The format a read path names, in a reader's words.
fn image_format(path: &Path) -> Result<ImageFormat, String> {
    ImageFormat::from_path(path).map_err(|e| match e {
        OutputError::Format { .. } => "not a PNG, JPEG, EXR or PFM file name".into(),
        other => other.to_string(),
    })
}

/// A decoder of a JPEG or OpenEXR file.
fn reader(
    file: std::fs::File,
    format: ImageFormat,
) -> image::ImageReader<BufReader<std::fs::File>> {
    let mut reader = image::ImageReader::new(BufReader::new(file));
    reader.set_format(match format {
        ImageFormat::Jpeg => image::ImageFormat::Jpeg,
        _ => image::ImageFormat::OpenExr,
    });
    reader
}

/// The placement text a sidecar records, if the image has a sidecar: one line
/// `prism placement: …`; a sidecar that is not a regular file, is larger than a line or
/// records more than one placement is refused.
fn read_sidecar(image: &Path) -> Result<Option<String>, String> {
    let sidecar = sidecar_path(image);
    let about = |what: &str| format!("its sidecar {} {what}", shown_path(&sidecar));
    match std::fs::symlink_metadata(&sidecar) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        _ => {}
    }
    let file = open_regular(&sidecar).map_err(|e| about(&format!("cannot be read: {e}")))?;
    let mut bytes = Vec::new();
    file.take(MAX_SIDECAR_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| about(&format!("cannot be read: {}", io_message(&e))))?;
    if bytes.len() as u64 > MAX_SIDECAR_BYTES {
        return Err(about(&format!(
            "is longer than the {MAX_SIDECAR_BYTES} bytes of a placement line"
        )));
    }
    let text = String::from_utf8(bytes).map_err(|_| about("is not text"))?;
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let line = lines.next().unwrap_or_default();
    if lines.next().is_some() {
        return Err(about("records more than one placement: which one holds?"));
    }
    line.strip_prefix(PLACEMENT_KEY)
        .and_then(|rest| rest.strip_prefix(':'))
        .map(|t| Some(t.trim().to_string()))
        .ok_or_else(|| about(&format!("does not begin \"{PLACEMENT_KEY}:\"")))
}

/// A PFM header: width, height and scale (negative for little-endian values).
fn read_pfm_header(reader: &mut impl BufRead) -> Result<(u32, u32, f32), String> {
    let mut words = Vec::new();
    // The header is three whitespace-separated words after "PF": width, height, scale.
    while words.len() < 4 {
        let mut line = String::new();
        // At most a short line: a file of one endless line must not fill memory.
        let read = reader
            .by_ref()
            .take(257)
            .read_line(&mut line)
            .map_err(|e| io_message(&e))?;
        if read == 0 || line.len() > 256 {
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
    Ok((w, h, scale))
}

/// A Portable Float Map (RGB, either byte order), as an image from the top row down.
fn read_pfm(file: std::fs::File) -> Result<image::Rgb32FImage, String> {
    let mut reader = BufReader::new(file);
    let (w, h, scale) = read_pfm_header(&mut reader)?;
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

    #[test]
    fn only_regular_files_are_opened() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_image_info(dir.path(), 100).err().unwrap();
        assert!(e.to_string().contains("not a PNG"), "{e}");
        let folder = dir.path().join("d.png");
        std::fs::create_dir(&folder).unwrap();
        let e = read_image_info(&folder, 100).err().unwrap();
        assert!(e.to_string().contains("directory"), "{e}");
        #[cfg(unix)]
        {
            // A FIFO is refused at once rather than waited on.
            let fifo = dir.path().join("f.png");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            if made.is_ok_and(|s| s.success()) {
                let e = read_image_info(&fifo, 100).err().unwrap();
                assert!(e.to_string().contains("not a regular file"), "{e}");
            }
            // A sidecar linked to an endless device is refused, not read.
            let pfm = dir.path().join("t.pfm");
            std::fs::write(&pfm, b"PF\n1 1\n-1.0\n\0\0\0\0\0\0\0\0\0\0\0\0").unwrap();
            std::os::unix::fs::symlink("/dev/zero", sidecar_path(&pfm)).unwrap();
            let e = read_image_info(&pfm, 100).err().unwrap();
            assert!(e.to_string().contains("not a regular file"), "{e}");
        }
    }

    #[test]
    fn sidecars_hold_one_placement() {
        let dir = tempfile::tempdir().unwrap();
        let pfm = dir.path().join("t.pfm");
        std::fs::write(&pfm, b"PF\n1 1\n-1.0\n\0\0\0\0\0\0\0\0\0\0\0\0").unwrap();
        let sidecar = sidecar_path(&pfm);
        std::fs::write(&sidecar, "prism placement: 0,0,1,1 of 2x1\n").unwrap();
        let info = read_image_info(&pfm, 100).unwrap();
        assert_eq!(info.placement.unwrap().frame_width, 2);
        assert_eq!(
            (info.width, info.height, info.pixels),
            (1, 1, PixelType::Rgb32F)
        );
        std::fs::write(
            &sidecar,
            "prism placement: 0,0,1,1 of 2x1\nprism placement: 1,0,2,1 of 2x1\n",
        )
        .unwrap();
        let e = read_image_info(&pfm, 100).err().unwrap();
        assert!(e.to_string().contains("more than one placement"), "{e}");
        std::fs::write(&sidecar, "x".repeat(5000)).unwrap();
        let e = read_image_info(&pfm, 100).err().unwrap();
        assert!(e.to_string().contains("longer than"), "{e}");
    }

    #[test]
    fn a_png_with_two_placements_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("two.png");
        let file = std::fs::File::create(&path).unwrap();
        let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), 1, 1);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        for text in ["0,0,1,1 of 2x1", "1,0,2,1 of 2x1"] {
            encoder
                .add_text_chunk(PLACEMENT_KEY.to_string(), text.to_string())
                .unwrap();
        }
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(&[1, 2, 3]).unwrap();
        writer.finish().unwrap();
        let e = read_image_info(&path, 100).err().unwrap();
        assert!(e.to_string().contains("more than one"), "{e}");
    }
}
