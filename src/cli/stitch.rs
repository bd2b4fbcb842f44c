//! `prism stitch TILES… -o OUT`: the frame that tiles rendered apart make, written as one
//! image; refused, with the tiles named, when they are missing, overlap or disagree.

use super::render_args::BadOption;
use anyhow::{Result, bail};
use prism::messages::shown_path;
use prism::render::{ImageFormat, OutputOptions, PendingFile, PixelType};
use prism::render::{plan_stitch, read_image_info, read_pixels};
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
    // The headers first: a set that cannot make a frame is refused before any pixel is
    // decoded, and memory holds the frame and one tile at a time.
    let mut infos = Vec::with_capacity(args.tiles.len());
    for path in &args.tiles {
        infos.push((shown_path(path), read_image_info(path, max_side)?));
    }
    let plan = plan_stitch(&infos, max_side)?;
    let fits = match plan.pixels {
        PixelType::Rgb32F => format.is_hdr(),
        PixelType::Rgb16 => format == ImageFormat::Png,
        PixelType::Rgb8 => !format.is_hdr(),
    };
    if !fits {
        bail!(BadOption(format!(
            "{}: a {} file cannot hold the tiles' {} pixels unchanged; name a {}",
            shown_path(&args.out),
            format.name(),
            match plan.pixels {
                PixelType::Rgb32F => "float",
                PixelType::Rgb16 => "16-bit",
                PixelType::Rgb8 => "8-bit",
            },
            match plan.pixels {
                PixelType::Rgb32F => ".exr or .pfm file",
                PixelType::Rgb16 => ".png file",
                PixelType::Rgb8 => ".png or .jpg file",
            }
        )));
    }
    let mut frame = plan.blank();
    for (i, (path, (name, info))) in args.tiles.iter().zip(&infos).enumerate() {
        let tile = read_pixels(path, info)?;
        plan.paste(&mut frame, i, name, &tile)?;
    }
    let (w, h) = (frame.width(), frame.height());
    let path = pending.finish_image(&frame, format, &options, None)?;
    if !args.quiet {
        eprintln!(
            "stitched {} tiles into {} ({w}×{h})",
            infos.len(),
            shown_path(&path)
        );
    }
    Ok(())
}
