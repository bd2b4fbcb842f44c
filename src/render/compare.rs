//! Comparing rendered images: what the stress tests, the window test and the bench measure.

/// The share of pixels in which some channel differs by more than `levels` 8-bit steps.
pub fn fraction_differing(a: &image::RgbImage, b: &image::RgbImage, levels: u8) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions(), "images of different sizes");
    let n = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > levels))
        .count();
    n as f64 / (a.width() as f64 * a.height() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_pixels_beyond_the_tolerance() {
        let a = image::RgbImage::from_pixel(2, 2, image::Rgb([100, 100, 100]));
        let mut b = a.clone();
        b.put_pixel(0, 0, image::Rgb([103, 100, 100]));
        b.put_pixel(1, 0, image::Rgb([100, 101, 100]));
        assert_eq!(fraction_differing(&a, &b, 2), 0.25);
        assert_eq!(fraction_differing(&a, &b, 0), 0.5);
        assert_eq!(fraction_differing(&a, &a, 0), 0.0);
    }
}
