//! What a render is asked to do, checked before any work starts.

use crate::integrator::{IntegratorKind, SelfIntersection};
use crate::sampler::SampleLayout;
use thiserror::Error;

use crate::limits::{AA, ADAPTIVE_TOLERANCE, EDGE_CONTRAST, IMAGE_SIDE, SAMPLES};

/// What a render is asked to do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Anti-aliasing level N: N×N subsamples per pixel, one per pass.
    pub aa: u32,
    /// Subsamples per pixel, when not N×N: more for the noise of soft shadows, lenses and
    /// glossy lobes (past N², the grid's cells are visited again at new places).
    pub samples: Option<u32>,
    /// Where in each pixel the subsamples lie.
    pub layout: SampleLayout,
    /// Secondary rays weighted below this are skipped (0 traces all).
    pub min_weight: f32,
    /// Stop refining pixels whose subsamples agree (None: every pixel gets all N×N).
    pub adaptive: Option<AdaptiveSettings>,
    /// How secondary rays avoid re-hitting their own surface.
    pub self_intersection: SelfIntersection,
    /// Keep subsamples brighter than white, for a linear HDR file (EXR, PFM); off, each is
    /// clamped to the 0..1 a display shows before it is summed, as the seed does.
    pub high_dynamic_range: bool,
    /// Which light transport is computed.
    pub integrator: IntegratorKind,
}

/// Stop refining a pixel once its subsamples agree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveSettings {
    /// A pixel stops when the estimated error of its mean luminance falls below this
    /// (on the 0..1 scale; 1/255 is one 8-bit step). In a noisy render (adaptive.rs) this
    /// is the error at 16 subsamples; a pixel that needs n stops at this × √(n/16).
    pub tolerance: f32,
    /// Every pixel gets at least this many subsamples before it may stop.
    pub min_samples: u32,
    /// A pixel beside an edge (a neighbour met other surfaces, shadows or pattern cells)
    /// gets at least this many, so that an edge its first few subsamples missed is found.
    pub edge_samples: u32,
    /// An edge counts only where the pixels on either side of it differ by more than this
    /// in some channel (0..1 scale): a faint edge cannot hide enough to be worth the search.
    pub edge_contrast: f32,
}

impl Default for AdaptiveSettings {
    fn default() -> Self {
        // Measured on the seed scene (docs/benchmarks/README.md): these reach the full 4×4
        // grid's FLIP error soonest; fewer edge samples never get there.
        Self {
            tolerance: 1.0 / 256.0,
            min_samples: 4,
            edge_samples: 8,
            edge_contrast: 0.04,
        }
    }
}

/// The skip threshold that can never change an 8-bit pixel beyond rounding.
pub const DEFAULT_MIN_WEIGHT: f32 = 1.0 / 512.0;

impl RenderSettings {
    /// A render of `width` × `height` pixels at anti-aliasing level `aa`, with every other setting at its default.
    pub fn new(width: u32, height: u32, aa: u32) -> Self {
        Self {
            width,
            height,
            aa,
            samples: None,
            layout: SampleLayout::Stratified,
            min_weight: DEFAULT_MIN_WEIGHT,
            adaptive: None,
            self_intersection: SelfIntersection::ErrorBound,
            high_dynamic_range: false,
            integrator: IntegratorKind::Whitted,
        }
    }

    /// Checks every setting against its bounds (limits.rs).
    pub fn validate(&self) -> Result<(), SettingsError> {
        if self.width < *IMAGE_SIDE.start() || self.height < *IMAGE_SIDE.start() {
            return Err(SettingsError::ZeroSize {
                width: self.width,
                height: self.height,
            });
        }
        if !(IMAGE_SIDE.contains(&self.width) && IMAGE_SIDE.contains(&self.height)) {
            return Err(SettingsError::TooLarge {
                width: self.width,
                height: self.height,
            });
        }
        if !AA.contains(&self.aa) {
            return Err(SettingsError::Aa(self.aa));
        }
        if let Some(n) = self.samples
            && !SAMPLES.contains(&n)
        {
            return Err(SettingsError::Samples(n));
        }
        if !(self.min_weight.is_finite() && (0.0..1.0).contains(&self.min_weight)) {
            return Err(SettingsError::MinWeight(self.min_weight));
        }
        if let SelfIntersection::FixedEpsilon(e) = self.self_intersection
            && !(e.is_finite() && e >= 0.0)
        {
            return Err(SettingsError::Epsilon(e));
        }
        if let Some(a) = self.adaptive {
            if !ADAPTIVE_TOLERANCE.contains(&a.tolerance) {
                return Err(SettingsError::Tolerance(a.tolerance));
            }
            if a.min_samples == 0 {
                return Err(SettingsError::MinSamples);
            }
            if !EDGE_CONTRAST.contains(&a.edge_contrast) {
                return Err(SettingsError::EdgeContrast(a.edge_contrast));
            }
        }
        Ok(())
    }

    /// The settings of a render of `scene`: its image size and anti-aliasing level unless
    /// `width`, `height` or `aa` override them (as the command line and the viewer's
    /// options do), checked.
    pub fn for_scene(
        defaults: &crate::scene::RenderDefaults,
        width: Option<u32>,
        height: Option<u32>,
        aa: Option<u32>,
    ) -> Result<Self, SettingsError> {
        let settings = Self {
            samples: defaults.samples,
            integrator: defaults.integrator,
            ..Self::new(
                width.unwrap_or(defaults.width),
                height.unwrap_or(defaults.height),
                aa.unwrap_or(defaults.aa),
            )
        };
        settings.validate()?;
        Ok(settings)
    }

    /// Passes to convergence: one per subsample (`samples`, else the N×N grid's).
    pub fn total_passes(&self) -> u32 {
        self.samples.unwrap_or(self.aa * self.aa)
    }
}

/// A setting outside its bounds.
#[derive(Debug, Error, PartialEq)]
pub enum SettingsError {
    /// A side of zero pixels.
    #[error("image size {width}×{height}: width and height must be at least 1")]
    ZeroSize {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// A side beyond the largest image.
    #[error("image size {width}×{height}: width and height must be at most {}", IMAGE_SIDE.end())]
    TooLarge {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// An anti-aliasing level out of range.
    #[error("anti-aliasing level {level}: must be {} to {} (N×N subsamples per pixel)", AA.start(), AA.end(), level = .0)]
    Aa(u32),
    /// A lens (`--aperture`, `--focus-distance`) out of range.
    #[error("camera lens: {0}")]
    Lens(String),
    /// A subsample count out of range.
    #[error("samples {n}: must be {} to {} subsamples per pixel", SAMPLES.start(), SAMPLES.end(), n = .0)]
    Samples(u32),
    /// A faint-ray threshold out of range.
    #[error("minimum ray weight {0}: must be a number in [0, 1)")]
    MinWeight(f32),
    #[error(
        "adaptive tolerance {value}: must be a number from {} to {}",
        ADAPTIVE_TOLERANCE.start(),
        ADAPTIVE_TOLERANCE.end(),
        value = .0
    )]
    /// An adaptive tolerance out of range.
    Tolerance(f32),
    /// A negative or non-finite self-intersection offset.
    #[error("self-intersection epsilon {0}: must be a finite number ≥ 0")]
    Epsilon(f32),
    /// Adaptive sampling with a minimum of no samples.
    #[error("adaptive minimum samples must be at least 1")]
    MinSamples,
    #[error(
        "adaptive edge contrast {value}: must be a number from {} to {}",
        EDGE_CONTRAST.start(),
        EDGE_CONTRAST.end(),
        value = .0
    )]
    /// An edge contrast out of range.
    EdgeContrast(f32),
    /// The viewer's window (image beside the panel) is larger than it opens.
    #[error(
        "a {width}×{height} image beside the {panel}-pixel panel makes a window larger than \
         the {} pixels a side the viewer opens; choose a smaller --width/--height, or use \
         `prism render` for large images",
        crate::limits::MAX_WINDOW_SIDE
    )]
    /// A viewer window larger than it may open.
    Window {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
        /// The panel's width, in pixels.
        panel: u32,
    },
}
