//! What a render will hold in memory, worked out before anything is allocated, and what
//! the machine can give: so that a frame too large for it is refused with the figures and
//! a way out (tiles), rather than aborting part-way when an allocation fails.

use super::accumulator::PixelSum;
use super::adaptive::PixelNoise;
use super::image_file::{BitDepth, ImageFormat};
use super::region::PixelRect;

/// The memory a headless render of a region holds at its peak, by part, in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderMemory {
    /// The pixel sums of the rendered window (the region and its adaptive margin).
    pub film: u64,
    /// The per-pixel state of the progressive render's adaptive sampling (whether active,
    /// and its noise).
    pub flags: u64,
    /// The region's sums cut from a larger window (none for a whole frame).
    pub crop: u64,
    /// The encoded image, and the copies its file format's encoder makes.
    pub image: u64,
}

impl RenderMemory {
    /// The figures for rendering `region` through `window` to a file of `format`.
    pub fn of(window: PixelRect, region: PixelRect, format: ImageFormat, depth: BitDepth) -> Self {
        let sum = std::mem::size_of::<PixelSum>() as u64;
        let (window_px, region_px) = (window.area(), region.area());
        let (bytes, copies) = match (format, depth) {
            // The float formats: the image, and the encoder's own float copy.
            (ImageFormat::Exr | ImageFormat::Pfm, _) => (12, 2),
            (ImageFormat::Png, BitDepth::Sixteen) => (6, 2),
            // 8-bit PNG is written from the image itself; JPEG converts once.
            (ImageFormat::Png, BitDepth::Eight) => (3, 1),
            (ImageFormat::Jpeg, _) => (3, 2),
        };
        Self {
            film: window_px * sum,
            flags: window_px * (1 + std::mem::size_of::<PixelNoise>() as u64),
            crop: if window == region { 0 } else { region_px * sum },
            image: region_px * bytes * copies,
        }
    }

    /// All of it together.
    pub fn total(&self) -> u64 {
        self.film + self.flags + self.crop + self.image
    }
}

/// Where a memory figure comes from, for messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MemorySource {
    /// The system's estimate of memory available without swapping (MemAvailable).
    System,
    /// The process's address-space limit (`ulimit -v`), less what it maps already.
    AddressSpaceLimit,
    /// The control group's memory limit (a container or a job's allocation).
    ControlGroup,
}

impl MemorySource {
    /// Its name in messages.
    pub fn name(self) -> &'static str {
        match self {
            MemorySource::System => "available on this machine",
            MemorySource::AddressSpaceLimit => "left under this process's address-space limit",
            MemorySource::ControlGroup => "left under this job's memory limit",
        }
    }
}

/// The memory this process can still take, and the tightest bound that says so; None
/// where nothing can be read (not Linux).
pub fn available_memory() -> Option<(u64, MemorySource)> {
    let mut bounds = Vec::new();
    if let Some(kib) = proc_field("/proc/meminfo", "MemAvailable:") {
        bounds.push((kib * 1024, MemorySource::System));
    }
    if let Some(limit) = address_space_limit() {
        let used = proc_field("/proc/self/status", "VmSize:").map_or(0, |k| k * 1024);
        bounds.push((limit.saturating_sub(used), MemorySource::AddressSpaceLimit));
    }
    let cgroup = |name: &str| {
        let text = std::fs::read_to_string(format!("/sys/fs/cgroup/{name}")).ok()?;
        text.trim().parse::<u64>().ok()
    };
    if let Some(max) = cgroup("memory.max") {
        let current = cgroup("memory.current").unwrap_or(0);
        bounds.push((max.saturating_sub(current), MemorySource::ControlGroup));
    }
    bounds.into_iter().min_by_key(|(bytes, _)| *bytes)
}

/// The number after `key` in a /proc file of `key value kB` lines.
fn proc_field(file: &str, key: &str) -> Option<u64> {
    let text = std::fs::read_to_string(file).ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The soft address-space limit, from /proc/self/limits (None when unlimited).
fn address_space_limit() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    let soft = line["Max address space".len()..]
        .split_whitespace()
        .next()?;
    soft.parse().ok()
}

/// Bytes in GiB with one decimal, for messages.
pub fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_frame_holds_what_its_parts_say() {
        let full = PixelRect::full(16384, 16384);
        let m = RenderMemory::of(full, full, ImageFormat::Png, BitDepth::Eight);
        let pixels = 16384u64 * 16384;
        assert_eq!(m.film, pixels * std::mem::size_of::<PixelSum>() as u64);
        assert_eq!(m.crop, 0);
        assert_eq!(m.image, pixels * 3);
        assert!(m.total() > 9 << 30, "{}", gib(m.total()));
        // A tile holds its window and its own crop, a fraction of the frame.
        let tile = PixelRect::tile(0, 8, 16384, 16384).unwrap();
        let window = tile.grown(1, 16384, 16384);
        let t = RenderMemory::of(window, tile, ImageFormat::Exr, BitDepth::Eight);
        assert!(t.total() < m.total() / 2);
        assert_eq!(t.image, tile.area() * 24);
    }

    #[test]
    fn available_memory_is_read_on_linux() {
        if std::path::Path::new("/proc/meminfo").exists() {
            let (bytes, _) = available_memory().unwrap();
            assert!(bytes > 1 << 20);
        }
    }
}
