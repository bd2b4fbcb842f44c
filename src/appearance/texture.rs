//! Surface colour as a function of position: solid colours, the seed's procedural patterns,
//! and bilinearly filtered images.

use super::pattern::Pattern;
use glam::{Vec3, Vec3A};
use std::path::Path;
use std::sync::Arc;

/// An RGB image held as 8-bit texels, looked up with bilinear filtering.
#[derive(Debug, PartialEq)]
pub struct ImageTexture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Three bytes per texel, rows top to bottom: the decoder's own buffer, kept as it is.
    texels: Vec<u8>,
    /// The average colour, taken once: every appearance made from the scene asks for it.
    mean: Vec3,
}

/// Why an image file cannot be a texture.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    /// The file cannot be read (the cause, in words).
    #[error("{0}")]
    Io(String),
    /// A directory, a FIFO or a device.
    #[error("it is not a regular file")]
    NotAFile,
    #[error(
        "the file holds {bytes} bytes, more than the {} a texture may have",
        crate::limits::MAX_TEXTURE_FILE_BYTES
    )]
    /// Larger than a texture file may be.
    FileTooLarge {
        /// Its size in bytes.
        bytes: u64,
    },
    #[error(
        "it is {width}×{height} texels, more than the {} (8192×8192) a texture may have",
        crate::limits::MAX_TEXTURE_TEXELS
    )]
    /// More texels than a texture may have.
    TooManyTexels {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// No texels at all.
    #[error("it is {width}×{height} texels; an image needs at least one")]
    Empty {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// A JPEG stream without its end marker.
    #[error("the JPEG data ends early (the file is truncated)")]
    Truncated,
    /// The decoder refused the data (its message).
    #[error("{0}")]
    Decode(String),
}

impl ImageTexture {
    /// The width and height an image file declares, read from its header alone (no more of
    /// the file is read), after checking that it is a regular file of a size a texture may
    /// have.
    pub fn probe(path: &Path) -> Result<(u32, u32), TextureError> {
        check_file(path)?;
        let reader = image::ImageReader::open(path)
            .and_then(|r| r.with_guessed_format())
            .map_err(io_error)?;
        let (width, height) = reader
            .into_dimensions()
            .map_err(|e| TextureError::Decode(e.to_string()))?;
        check_size(width, height)?;
        Ok((width, height))
    }

    /// Reads an image file, refusing anything but a regular file within the limits: the
    /// size is read from the header before any texel is decoded.
    pub fn load(path: &Path) -> Result<Self, TextureError> {
        check_file(path)?;
        let bytes = std::fs::read(path).map_err(io_error)?;
        Self::decode(&bytes)
    }

    /// The width and height that image data (a whole file's bytes) declares.
    pub fn probe_bytes(bytes: &[u8]) -> Result<(u32, u32), TextureError> {
        check_bytes(bytes)?;
        let (width, height) = reader(bytes)?
            .into_dimensions()
            .map_err(|e| TextureError::Decode(e.to_string()))?;
        check_size(width, height)?;
        Ok((width, height))
    }

    /// Decodes image data (a whole file's bytes), within the limits: the size is read from
    /// the header before any texel is decoded.
    pub fn decode(bytes: &[u8]) -> Result<Self, TextureError> {
        use crate::limits::MAX_TEXTURE_TEXELS;
        check_bytes(bytes)?;
        let header = reader(bytes)?;
        let format = header.format();
        let (width, height) = header
            .into_dimensions()
            .map_err(|e| TextureError::Decode(e.to_string()))?;
        check_size(width, height)?;
        // JPEG decoders fill a truncated stream with grey rather than fail; a complete
        // stream ends with the end-of-image marker (trailing padding aside).
        if format == Some(image::ImageFormat::Jpeg) && !ends_with_jpeg_eoi(bytes) {
            return Err(TextureError::Truncated);
        }
        let mut decoder = reader(bytes)?;
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(width);
        limits.max_image_height = Some(height);
        // The decoded image in its widest form (16-bit RGBA), and the RGB copy made from it.
        limits.max_alloc = Some(MAX_TEXTURE_TEXELS * 8 + MAX_TEXTURE_TEXELS * 3);
        decoder.limits(limits);
        let img = decoder
            .decode()
            .map_err(|e| TextureError::Decode(e.to_string()))?;
        let rgb = img.into_rgb8();
        Ok(Self::from_rgb8(rgb.width(), rgb.height(), rgb.into_raw()))
    }

    /// An image of `width` × `height` texels from RGB bytes, rows top to bottom.
    ///
    /// # Panics
    /// If `raw` does not hold exactly three bytes per texel.
    pub fn from_rgb8(width: u32, height: u32, raw: Vec<u8>) -> Self {
        assert_eq!(
            raw.len() as u64,
            width as u64 * height as u64 * 3,
            "texel count"
        );
        let mean = mean_of(&raw);
        Self {
            width,
            height,
            texels: raw,
            mean,
        }
    }

    /// How many texels the image holds.
    pub fn texel_count(&self) -> u64 {
        self.width as u64 * self.height as u64
    }

    #[inline]
    fn texel(&self, x: u32, y: u32) -> Vec3A {
        let i = (y as usize * self.width as usize + x as usize) * 3;
        let [r, g, b] = [self.texels[i], self.texels[i + 1], self.texels[i + 2]];
        Vec3A::new(r as f32, g as f32, b as f32) * (1.0 / 255.0)
    }

    /// Bilinear lookup at (u, v), u wrapping around (longitude), v clamped (latitude);
    /// texel (i, j) has its centre at ((i + ½) / width, (j + ½) / height).
    pub fn sample(&self, u: f32, v: f32) -> Vec3A {
        let x = (u - floor_to_int(u) as f32) * self.width as f32 - 0.5;
        let y = v.clamp(0.0, 1.0) * self.height as f32 - 0.5;
        let (x0, y0) = (floor_to_int(x), floor_to_int(y));
        let (fx, fy) = (x - x0 as f32, y - y0 as f32);
        let w = self.width as i64;
        let h = self.height as i64;
        // x lies in [−½, width − ½): one step of wrapping at most.
        let x0 = if x0 < 0 { x0 + w } else { x0 };
        let x1 = if x0 + 1 >= w { 0 } else { x0 + 1 } as u32;
        let x0 = x0 as u32;
        let y1 = (y0 + 1).clamp(0, h - 1) as u32;
        let y0 = y0.clamp(0, h - 1) as u32;
        let top = self.texel(x0, y0).lerp(self.texel(x1, y0), fx);
        let bottom = self.texel(x0, y1).lerp(self.texel(x1, y1), fx);
        top.lerp(bottom, fy)
    }

    /// The brightness (the mean of red, green and blue, 0 to 1) at (u, v) and its slope
    /// per unit of u and of v: central differences half a texel either way across the
    /// bilinear lookup, which measure the slope between neighbouring texels exactly.
    pub fn brightness_slope(&self, u: f32, v: f32) -> (f32, f32) {
        let brightness = |u: f32, v: f32| {
            let c = self.sample(u, v);
            (c.x + c.y + c.z) * (1.0 / 3.0)
        };
        let (du, dv) = (0.5 / self.width as f32, 0.5 / self.height as f32);
        (
            (brightness(u + du, v) - brightness(u - du, v)) / (2.0 * du),
            (brightness(u, v + dv) - brightness(u, v - dv)) / (2.0 * dv),
        )
    }

    /// The average colour of the image (used to tint light passing through it).
    pub fn mean(&self) -> Vec3 {
        self.mean
    }
}

/// The average colour of RGB texels: the sums are whole numbers, exact in u64 (a long f32
/// sum would drift), divided once in f64.
fn mean_of(texels: &[u8]) -> Vec3 {
    // Byte i of a run of `SPAN` bytes (sixteen texels) belongs to channel i % 3. Summed
    // position by position in u32 lanes, the loop vectorises; a block of `BLOCK` runs
    // cannot overflow them (255 × BLOCK < 2³²) before they are added into the u64 sums.
    const SPAN: usize = 48;
    const BLOCK: usize = 1 << 16;
    let mut sum = [0u64; 3];
    let whole = texels.len() / SPAN * SPAN;
    for block in texels[..whole].chunks(SPAN * BLOCK) {
        let mut lanes = [0u32; SPAN];
        for run in block.as_chunks::<SPAN>().0 {
            // Indexed: the zipped form of this loop is not vectorised.
            #[allow(clippy::needless_range_loop)]
            for i in 0..SPAN {
                lanes[i] += run[i] as u32;
            }
        }
        for (i, lane) in lanes.iter().enumerate() {
            sum[i % 3] += *lane as u64;
        }
    }
    for t in texels[whole..].chunks_exact(3) {
        for (s, &v) in sum.iter_mut().zip(t) {
            *s += v as u64;
        }
    }
    let count = (texels.len() / 3).max(1) as f64;
    (glam::DVec3::from(sum.map(|s| s as f64)) / (255.0 * count)).as_vec3()
}

fn io_error(e: std::io::Error) -> TextureError {
    TextureError::Io(crate::messages::io_message(&e))
}

/// That `path` is a regular file (a FIFO would block, a device might never end) of a size
/// a texture may have.
fn check_file(path: &Path) -> Result<(), TextureError> {
    let meta = std::fs::metadata(path)
        .map_err(|e| TextureError::Io(crate::messages::read_failure(path, &e)))?;
    if !meta.is_file() {
        return Err(TextureError::NotAFile);
    }
    if meta.len() > crate::limits::MAX_TEXTURE_FILE_BYTES {
        return Err(TextureError::FileTooLarge { bytes: meta.len() });
    }
    Ok(())
}

/// A reader of in-memory image data, its format guessed from its first bytes.
fn reader(bytes: &[u8]) -> Result<image::ImageReader<std::io::Cursor<&[u8]>>, TextureError> {
    image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(io_error)
}

/// That in-memory image data is of a size a texture file may have.
fn check_bytes(bytes: &[u8]) -> Result<(), TextureError> {
    let len = bytes.len() as u64;
    if len > crate::limits::MAX_TEXTURE_FILE_BYTES {
        return Err(TextureError::FileTooLarge { bytes: len });
    }
    Ok(())
}

/// That a declared image size is one a texture may have.
fn check_size(width: u32, height: u32) -> Result<(), TextureError> {
    if width == 0 || height == 0 {
        return Err(TextureError::Empty { width, height });
    }
    if width as u64 * height as u64 > crate::limits::MAX_TEXTURE_TEXELS {
        return Err(TextureError::TooManyTexels { width, height });
    }
    Ok(())
}

/// Whether JPEG data ends with the end-of-image marker, allowing for zero or 0xFF padding
/// after it.
fn ends_with_jpeg_eoi(bytes: &[u8]) -> bool {
    let end = bytes
        .iter()
        .rposition(|&b| b != 0 && b != 0xFF)
        .map_or(0, |i| i + 1);
    // The marker is 0xFF 0xD9: its 0xD9 is the last byte that is not padding.
    end >= 2 && bytes[end - 1] == 0xD9 && bytes[end - 2] == 0xFF
}

/// ⌊x⌋ as an integer, without a call into libm (`f32::floor` is one on the x86-64
/// baseline, which lacks SSE4.1's `roundss`). Exact for every finite x whose floor fits in
/// an i64; beyond that the pattern has no meaning left anyway (NaN gives 0).
#[inline]
fn floor_to_int(x: f32) -> i64 {
    let truncated = x as i64;
    truncated.saturating_sub(((truncated as f32) > x) as i64)
}

/// What colours a surface. Procedural patterns are evaluated on the object-local point
/// (relative to the object's own origin, turned and scaled back by its placement: they
/// move with the object and keep their precision far from the world origin); images on the
/// shape's (u, v).
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// One colour everywhere.
    Solid(Vec3),
    /// Cells of edge `size` alternating between two colours; only the axes whose mask
    /// component is 1 take part (a floor uses x and z, so rounding in y cannot flip a cell).
    Checker {
        /// The two colours, alternating.
        colors: [Vec3; 2],
        /// The edge of a cell, in scene units.
        size: f32,
        /// 1 for each axis that takes part, else 0.
        axes: Vec3,
    },
    /// Bands of width `width` across the unit `direction`.
    Stripes {
        /// The two colours, alternating.
        colors: [Vec3; 2],
        /// The width of a band, in scene units.
        width: f32,
        /// The unit direction across the bands.
        direction: Vec3,
    },
    /// A procedural pattern (noise, marble, wood, …) in the object's own space.
    Pattern(Arc<Pattern>),
    /// An image, looked up at the shape's (u, v).
    Image {
        /// The texels.
        image: Arc<ImageTexture>,
        /// How the shape's (u, v) map onto the image.
        uv: UvTransform,
    },
}

/// How a shape's (u, v) map onto an image: rotated about the image's centre by `rotate`
/// degrees (counter-clockwise as the picture is seen), then scaled about the centre (2
/// shows the picture twice across and twice down), then moved by `offset` (in picture
/// widths and heights). A transformed picture repeats in both directions; untransformed,
/// v stops at the image's top and bottom rows (a sphere's poles).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    /// The rotation and the scale as one matrix, row by row.
    matrix: [f32; 4],
    offset: [f32; 2],
    identity: bool,
}

impl UvTransform {
    /// (u, v) as the shape gives them.
    pub const IDENTITY: UvTransform = UvTransform {
        matrix: [1.0, 0.0, 0.0, 1.0],
        offset: [0.0, 0.0],
        identity: true,
    };

    /// Rotate by `rotate` degrees, scale by `scale`, then move by `offset`.
    pub fn new(scale: [f32; 2], offset: [f32; 2], rotate: f32) -> UvTransform {
        if scale == [1.0, 1.0] && offset == [0.0, 0.0] && rotate == 0.0 {
            return Self::IDENTITY;
        }
        // The matrix takes a surface's (u, v) to the picture's; with v running down the
        // picture, this turn of the lookup shows the picture turned counter-clockwise.
        let (s, c) = rotate.to_radians().sin_cos();
        UvTransform {
            matrix: [scale[0] * c, -scale[0] * s, scale[1] * s, scale[1] * c],
            offset,
            identity: false,
        }
    }

    /// How the picture's coordinates change with the surface's: the matrix (row by row)
    /// of ∂(picture u, v)/∂(u, v).
    #[inline]
    pub fn jacobian(&self) -> [f32; 4] {
        self.matrix
    }

    /// Where (u, v) lands in the picture.
    #[inline]
    pub fn apply(&self, (u, v): (f32, f32)) -> (f32, f32) {
        if self.identity {
            return (u, v);
        }
        let [a, b, c, d] = self.matrix;
        let (x, y) = (u - 0.5, v - 0.5);
        let v = c * x + d * y + 0.5 + self.offset[1];
        (
            a * x + b * y + 0.5 + self.offset[0],
            // u wraps in the lookup; v is wrapped here, so the picture repeats down too.
            v - floor_to_int(v) as f32,
        )
    }
}

impl Texture {
    /// The colour at texture coordinates `uv` (images) or at `local`, the object-local point
    /// (patterns).
    #[inline]
    pub fn eval(&self, uv: (f32, f32), local: Vec3A) -> Vec3A {
        match self {
            Texture::Solid(c) => (*c).into(),
            Texture::Checker { colors, size, axes } => {
                let cell = local * Vec3A::from(*axes) / *size;
                let sum = floor_to_int(cell.x) + floor_to_int(cell.y) + floor_to_int(cell.z);
                colors[(sum & 1) as usize].into()
            }
            Texture::Stripes {
                colors,
                width,
                direction,
            } => {
                let band = floor_to_int(local.dot((*direction).into()) / *width);
                colors[(band & 1) as usize].into()
            }
            Texture::Pattern(pattern) => pattern.eval(local),
            Texture::Image {
                image,
                uv: transform,
            } => {
                let (u, v) = transform.apply(uv);
                image.sample(u, v)
            }
        }
    }

    /// Whether `eval` reads the surface (u, v).
    pub fn needs_uv(&self) -> bool {
        matches!(self, Texture::Image { .. })
    }

    /// A representative colour (the mean over the pattern).
    pub fn mean(&self) -> Vec3 {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker { colors, .. } | Texture::Stripes { colors, .. } => {
                (colors[0] + colors[1]) * 0.5
            }
            Texture::Pattern(pattern) => pattern.map.mean(),
            Texture::Image { image, .. } => image.mean(),
        }
    }

    /// Scales the pattern's lengths with the scene (for scale-invariance tests).
    pub fn scaled(&self, factor: f32) -> Texture {
        match self {
            Texture::Checker { colors, size, axes } => Texture::Checker {
                colors: *colors,
                size: size * factor,
                axes: *axes,
            },
            Texture::Stripes {
                colors,
                width,
                direction,
            } => Texture::Stripes {
                colors: *colors,
                width: width * factor,
                direction: *direction,
            },
            Texture::Pattern(pattern) => Texture::Pattern(Arc::new(pattern.scaled(factor))),
            other => other.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn four_texels() -> ImageTexture {
        // 2×2: red, green / blue, white.
        ImageTexture::from_rgb8(2, 2, vec![255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255])
    }

    #[test]
    fn the_mean_is_the_texels_average() {
        // Red, green, blue and white: each channel is full in two of the four.
        assert_eq!(four_texels().mean(), Vec3::splat(0.5));
        let grey = ImageTexture::from_rgb8(3, 1, vec![51; 9]);
        assert_eq!(grey.mean(), Vec3::splat(0.2));
    }

    #[test]
    fn the_mean_is_that_of_a_plain_sum() {
        // Small and large sizes, against a plain f64 sum.
        // (1 << 20) + 7 texels run past the first block of sums.
        for texels in [
            1usize,
            2,
            3,
            5,
            16,
            17,
            1 << 18,
            (1 << 18) + 5,
            (1 << 20) + 7,
        ] {
            let raw: Vec<u8> = (0..texels * 3).map(|i| (i * 37 % 251) as u8).collect();
            let mut plain = glam::DVec3::ZERO;
            for t in raw.chunks_exact(3) {
                plain += glam::DVec3::new(t[0] as f64, t[1] as f64, t[2] as f64);
            }
            let expected = (plain / (255.0 * texels as f64)).as_vec3();
            let image = ImageTexture::from_rgb8(texels as u32, 1, raw);
            assert_eq!(image.mean(), expected, "{texels} texels");
        }
    }

    #[test]
    fn the_mean_of_white_is_one_across_blocks() {
        // Three blocks of sums and a remainder, at the largest byte.
        let texels = (3 << 20) + 1;
        let image = ImageTexture::from_rgb8(texels, 1, vec![255; texels as usize * 3]);
        assert_eq!(image.mean(), Vec3::ONE);
    }

    #[test]
    fn texel_centres_return_their_colour() {
        let t = four_texels();
        assert_eq!(t.sample(0.25, 0.25), Vec3A::X);
        assert_eq!(t.sample(0.75, 0.25), Vec3A::Y);
        assert_eq!(t.sample(0.25, 0.75), Vec3A::Z);
        assert_eq!(t.sample(0.75, 0.75), Vec3A::ONE);
    }

    #[test]
    fn bilinear_blends_and_wraps_in_u() {
        let t = four_texels();
        let mid = t.sample(0.5, 0.25);
        assert!((mid - Vec3A::new(0.5, 0.5, 0.0)).length() < 1e-6);
        // u = 0 lies halfway between the last column and the first.
        let seam = t.sample(0.0, 0.25);
        assert!((seam - Vec3A::new(0.5, 0.5, 0.0)).length() < 1e-6);
        // v is clamped at the poles.
        assert_eq!(t.sample(0.25, 0.0), Vec3A::X);
        assert_eq!(t.sample(0.25, 1.0), Vec3A::Z);
    }

    #[test]
    fn checker_alternates_on_masked_axes_only() {
        let c = Texture::Checker {
            colors: [Vec3::ZERO, Vec3::ONE],
            size: 5.0,
            axes: Vec3::new(1.0, 0.0, 1.0),
        };
        assert_eq!(c.eval((0.0, 0.0), Vec3A::new(1.0, 0.0, 1.0)), Vec3A::ZERO);
        assert_eq!(c.eval((0.0, 0.0), Vec3A::new(6.0, 0.0, 1.0)), Vec3A::ONE);
        assert_eq!(c.eval((0.0, 0.0), Vec3A::new(6.0, 0.0, 6.0)), Vec3A::ZERO);
        assert_eq!(c.eval((0.0, 0.0), Vec3A::new(-1.0, 0.0, 1.0)), Vec3A::ONE);
        // y does not take part: a point just below the floor keeps its cell.
        assert_eq!(c.eval((0.0, 0.0), Vec3A::new(1.0, -1e-7, 1.0)), Vec3A::ZERO);
    }

    #[test]
    fn floor_to_int_matches_floor() {
        let mut x = 1.0e-6f32;
        while x < 3.0e9 {
            for v in [x, -x, x * 1e-9, -x * 1e-9, x.fract(), -(x.fract())] {
                assert_eq!(floor_to_int(v), v.floor() as i64, "{v}");
            }
            x = x * 1.37 + 0.731;
        }
        for v in [
            0.0,
            -0.0,
            -1e-30,
            1e-30,
            -0.5,
            0.5,
            -1.0,
            1.0,
            16777215.5,
            -16777215.5,
        ] {
            assert_eq!(floor_to_int(v), v.floor() as i64, "{v}");
        }
    }

    #[test]
    fn stripes_follow_their_direction() {
        let s = Texture::Stripes {
            colors: [Vec3::X, Vec3::Y],
            width: 2.0,
            direction: Vec3::X,
        };
        assert_eq!(s.eval((0.0, 0.0), Vec3A::new(1.0, 50.0, -3.0)), Vec3A::X);
        assert_eq!(s.eval((0.0, 0.0), Vec3A::new(3.0, -7.0, 9.0)), Vec3A::Y);
        assert_eq!(s.eval((0.0, 0.0), Vec3A::new(-1.0, 0.0, 0.0)), Vec3A::Y);
    }
}
