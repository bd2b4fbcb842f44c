//! `prism stitch TILES… -o OUT`: the frame that tiles rendered apart make, written as one
//! image; refused, with the tiles named, when they are missing, overlap or disagree.

use super::render::BadOption;
use anyhow::{Result, bail};
use image::DynamicImage;
use prism::render::{ImageFormat, OutputOptions, PendingFile, read_image, stitch};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
#[command(after_help = super::EXIT_STATUS_HELP)]
pub struct StitchArgs {
    /// The tiles: images written by `prism render --tile` or `--region`, in any order.
    #[arg(required = true, value_name = "TILES")]
    pub tiles: Vec<PathBuf>,
    /// The whole frame's image. Its format must hold the tiles' pixels: 8-bit tiles make a
    /// PNG or JPEG, 16-bit ones a PNG, float ones (EXR, PFM) an EXR or PFM.
    #[arg(long, short)]
    pub out: PathBuf,
    /// JPEG quality, 1..100, when OUT is a JPEG.
    #[arg(long, value_parser = super::within(prism::limits::JPEG_QUALITY))]
    pub quality: Option<u8>,
    /// No summary line.
    #[arg(long, short)]
    pub quiet: bool,
}

pub fn run(args: StitchArgs) -> Result<()> {
    if args.tiles.len() > prism::limits::MAX_TILES {
        bail!(BadOption(format!(
            "{} tiles: at most {} at once",
            args.tiles.len(),
            prism::limits::MAX_TILES
        )));
    }
    let format = ImageFormat::from_path(&args.out)?;
    let options = OutputOptions {
        jpeg_quality: args
            .quality
            .unwrap_or(OutputOptions::default().jpeg_quality),
        ..OutputOptions::default()
    };
    format.check(&args.out, &options)?;
    // Claimed first: an unwritable output fails before the tiles are read.
    let pending = PendingFile::create(&args.out)?;
    let max_side = *prism::limits::IMAGE_SIDE.end();
    let mut tiles = Vec::with_capacity(args.tiles.len());
    for path in &args.tiles {
        tiles.push((path.display().to_string(), read_image(path, max_side)?));
    }
    let (frame, _) = stitch(&tiles)?;
    let fits = match &frame {
        DynamicImage::ImageRgb32F(_) => format.is_hdr(),
        DynamicImage::ImageRgb16(_) => format == ImageFormat::Png,
        _ => !format.is_hdr(),
    };
    if !fits {
        bail!(BadOption(format!(
            "{}: a {} file cannot hold the tiles' {} pixels unchanged; name a {}",
            args.out.display(),
            format.name(),
            match &frame {
                DynamicImage::ImageRgb32F(_) => "float",
                DynamicImage::ImageRgb16(_) => "16-bit",
                _ => "8-bit",
            },
            match &frame {
                DynamicImage::ImageRgb32F(_) => ".exr or .pfm file",
                DynamicImage::ImageRgb16(_) => ".png file",
                _ => ".png or .jpg file",
            }
        )));
    }
    let (w, h) = (frame.width(), frame.height());
    let path = pending.finish_image(&frame, format, &options, None)?;
    if !args.quiet {
        eprintln!(
            "stitched {} tiles into {} ({w}×{h})",
            tiles.len(),
            path.display()
        );
    }
    Ok(())
}
