//! What `prism render` reports when it finishes, as POV-Ray does: where the time went
//! (loading the scene, building its acceleration structures, tracing), the rays by kind,
//! the samples per pixel and the peak memory; on stderr for people and, with
//! `--stats-json FILE`, as JSON for scripts and farms.

use serde::Serialize;

/// One finished render.
#[derive(Debug, Serialize)]
pub struct RenderStats {
    /// The scene file, or "seed" for the built-in scene.
    pub scene: String,
    /// The image written.
    pub output: String,
    /// The animation's frame, for an animated scene.
    pub frame: Option<u32>,
    /// The pixels rendered, X0,Y0,X1,Y1, when not the whole frame.
    pub region: Option<String>,
    pub width: u32,
    pub height: u32,
    pub threads: usize,
    pub seconds: Seconds,
    pub samples_per_pixel: f64,
    pub passes: u32,
    pub rays: Rays,
    /// Rays traced per second of tracing.
    pub rays_per_second: f64,
    /// The most memory the process held at once (its resident set's high-water mark), in
    /// bytes; None where the system does not say (only Linux's /proc is read).
    pub peak_memory_bytes: Option<u64>,
    /// False when a signal stopped the render and `--write-partial` wrote what it had.
    pub complete: bool,
}

/// Wall-clock seconds of each stage.
#[derive(Debug, Serialize)]
pub struct Seconds {
    /// Reading and validating the scene file, with its textures and meshes.
    pub load: f64,
    /// Preparing the scene: the BVH, light buffers and other acceleration structures.
    pub build: f64,
    /// The passes, to convergence.
    pub trace: f64,
    /// From start to the image written.
    pub total: f64,
}

/// Rays traced, by kind.
#[derive(Debug, Serialize)]
pub struct Rays {
    pub primary: u64,
    pub shadow: u64,
    pub secondary: u64,
    pub total: u64,
}

impl RenderStats {
    /// The lines printed after a render, under its one-line summary.
    pub fn lines(&self) -> String {
        let s = &self.seconds;
        let memory = match self.peak_memory_bytes {
            Some(b) => format!("{:.1} MiB", b as f64 / (1u64 << 20) as f64),
            None => "not known here".into(),
        };
        format!(
            "time: {:.3} s loading, {:.3} s building, {:.3} s tracing, {:.3} s in all\n\
             peak memory: {memory}",
            s.load, s.build, s.trace, s.total
        )
    }

    /// The statistics as pretty-printed JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("plain numbers and strings serialise") + "\n"
    }
}

/// The process's peak resident memory, from /proc/self/status's VmHWM (Linux).
pub fn peak_memory_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example() -> RenderStats {
        RenderStats {
            scene: "seed".into(),
            output: "out.png".into(),
            frame: None,
            region: None,
            width: 8,
            height: 6,
            threads: 2,
            seconds: Seconds {
                load: 0.25,
                build: 0.5,
                trace: 1.0,
                total: 1.875,
            },
            samples_per_pixel: 4.0,
            passes: 4,
            rays: Rays {
                primary: 192,
                shadow: 100,
                secondary: 8,
                total: 300,
            },
            rays_per_second: 300.0,
            peak_memory_bytes: Some(3 << 20),
            complete: true,
        }
    }

    #[test]
    fn json_holds_every_figure_and_reads_back() {
        let json: serde_json::Value = serde_json::from_str(&example().to_json()).unwrap();
        assert_eq!(json["seconds"]["trace"], 1.0);
        assert_eq!(json["rays"]["total"], 300);
        assert_eq!(json["peak_memory_bytes"], 3 << 20);
        assert_eq!(json["scene"], "seed");
        let lines = example().lines();
        assert!(
            lines.contains("0.250 s loading, 0.500 s building, 1.000 s tracing"),
            "{lines}"
        );
        assert!(lines.contains("peak memory: 3.0 MiB"), "{lines}");
    }

    #[test]
    fn peak_memory_is_read_on_linux() {
        if cfg!(target_os = "linux") {
            let bytes = peak_memory_bytes().expect("VmHWM is in /proc/self/status");
            assert!(bytes > 1 << 20, "{bytes}");
        }
    }
}
