//! Saving what the viewer shows: the accumulated image only (no panel), at its own
//! resolution, named by date, time and samples per pixel.

use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

/// Writes `rgba` (width × height RGBA8) as a PNG in `dir`; returns the path.
pub fn save(dir: &Path, rgba: &[u8], width: u32, height: u32, spp: f64) -> Result<PathBuf> {
    let rgb: Vec<u8> = rgba
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let image = image::RgbImage::from_raw(width, height, rgb).context("no image to save yet")?;
    let path = dir.join(file_name(SystemTime::now(), spp));
    Ok(prism::render::write_png(&path, &image)?)
}

/// `prism-YYYY-MM-DD_HH-MM-SS.mmmZ-<spp>spp.png`, in UTC so names sort by time.
pub fn file_name(at: SystemTime, spp: f64) -> String {
    let since = at.duration_since(UNIX_EPOCH).unwrap_or_default();
    let secs = since.as_secs();
    let (y, m, d) = civil_from_days((secs / 86_400) as i64);
    let rem = secs % 86_400;
    let spp = if (spp - spp.round()).abs() < 0.005 {
        format!("{}", spp.round() as u64)
    } else {
        format!("{spp:.2}")
    };
    format!(
        "prism-{y:04}-{m:02}-{d:02}_{:02}-{:02}-{:02}.{:03}Z-{spp}spp.png",
        rem / 3600,
        rem / 60 % 60,
        rem % 60,
        since.subsec_millis()
    )
}

/// Days since 1970-01-01 to a proleptic Gregorian (year, month, day) (H. Hinnant's algorithm).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + (m <= 2) as i64;
    (y, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn names_carry_date_time_and_samples() {
        // 2026-11-22 20:41:05.250 UTC.
        let at = UNIX_EPOCH + Duration::from_millis(1_795_380_065_250);
        assert_eq!(
            file_name(at, 16.0),
            "prism-2026-11-22_20-41-05.250Z-16spp.png"
        );
        assert_eq!(
            file_name(at, 5.5),
            "prism-2026-11-22_20-41-05.250Z-5.50spp.png"
        );
    }

    #[test]
    fn calendar_edges() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
        assert_eq!(civil_from_days(-1), (1969, 12, 31));
    }

    #[test]
    fn saves_rgb_without_alpha_and_reports_failures() {
        let dir = tempfile::tempdir().unwrap();
        let rgba = [10, 20, 30, 255, 40, 50, 60, 255];
        let path = save(dir.path(), &rgba, 2, 1, 4.0).unwrap();
        let back = image::open(&path).unwrap().into_rgb8();
        assert_eq!(back.as_raw(), &vec![10, 20, 30, 40, 50, 60]);
        let missing = dir.path().join("nope");
        let err = save(&missing, &rgba, 2, 1, 4.0).unwrap_err();
        assert!(format!("{err:#}").contains("nope"));
    }
}
