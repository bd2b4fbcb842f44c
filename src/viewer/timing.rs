//! `prism view --log-timing`: a line on stderr for every frame drawn and for every change's
//! first image on screen, for tests/window/responsiveness.sh to summarise.
//!
//! ```text
//! prism-timing: frame MS_SINCE_START MS_SINCE_LAST_FRAME MS_TO_DRAW BYTES_OF_IMAGE_UPLOADED
//! prism-timing: shown KIND LATENCY_MS coarse|full
//! ```

use std::time::Instant;

pub struct Timing {
    start: Instant,
    last_frame: Option<Instant>,
    /// Changes sent and not yet seen: their generation, when sent, and what they were.
    pending: Vec<(u64, Instant, &'static str)>,
}

impl Timing {
    pub fn new() -> Self {
        Self {
            start: Instant::now(),
            last_frame: None,
            pending: Vec::new(),
        }
    }

    /// A change of `kind` went to the render thread as generation `generation`.
    pub fn sent(&mut self, generation: u64, kind: &'static str) {
        self.pending.push((generation, Instant::now(), kind));
    }

    /// A frame begun at `began` was drawn showing an image of generation `shown`
    /// (`preview`: a coarse one), uploading `uploaded` bytes of image. The line gives when,
    /// the time since the frame before, how long this one took to draw, and the bytes.
    pub fn frame(&mut self, shown: u64, preview: bool, began: Instant, uploaded: usize) {
        let now = Instant::now();
        let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
        let interval = self.last_frame.map_or(0.0, |l| ms(l, now));
        eprintln!(
            "prism-timing: frame {:.1} {interval:.2} {:.2} {uploaded}",
            ms(self.start, now),
            ms(began, now)
        );
        self.last_frame = Some(now);
        let quality = if preview { "coarse" } else { "full" };
        self.pending.retain(|&(generation, sent, kind)| {
            let seen = shown >= generation;
            if seen {
                eprintln!("prism-timing: shown {kind} {:.1} {quality}", ms(sent, now));
            }
            !seen
        });
    }
}
