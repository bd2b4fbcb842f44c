//! Every bound an input may take, in one place: the scene file's validator, the command
//! line, the viewer and the renderer all read these, so a value one of them accepts is one
//! the others accept too. docs/testing.md lists them with what a user sees at each.
//!
//! The numeric bounds exist so that every quantity the tracer derives from valid input
//! stays finite in f32: a product of two coordinates (a cross product, a squared distance)
//! of at most `MAX_COORDINATE` each is far below f32's largest value, and so is a colour
//! after any number of bounces.

use std::ops::RangeInclusive;

/// The largest scene file read, in bytes: far beyond any hand-written scene, small enough
/// that a wrong path (a disk image, /dev/zero) is refused at once.
pub const MAX_SCENE_FILE_BYTES: u64 = 16 << 20;

/// The largest image file read as a texture, in bytes.
pub const MAX_TEXTURE_FILE_BYTES: u64 = 256 << 20;

/// The largest mesh (OBJ) or material library (MTL) file read, in bytes: a mesh of tens
/// of millions of triangles.
pub const MAX_MESH_FILE_BYTES: u64 = 1 << 30;

/// The most triangles the meshes of one scene may have together (each file counted once,
/// however many objects place it): about 1.5 GiB of mesh and hierarchy.
pub const MAX_SCENE_TRIANGLES: usize = 1 << 24;

/// The factors an object's `scale` may have on each axis: enough to turn a unit model
/// into anything from a grain to a planet, and no further, so a scaled shape's lengths
/// stay within `MIN_LENGTH` and `MAX_COORDINATE` of sensible models.
pub const SCALE: RangeInclusive<f64> = 1.0e-6..=1.0e6;

/// The most texels one image texture may have (8192 × 8192; stored as 3 bytes each).
pub const MAX_TEXTURE_TEXELS: u64 = 1 << 26;

/// The most texels all the image textures of one scene may have together.
pub const MAX_SCENE_TEXELS: u64 = 1 << 27;

/// How far from the camera any position may lie, and the longest length (radius, height,
/// pattern size), in scene units. Squares and cross products of such values stay below
/// 10²⁵, far inside f32's range, and f64 checks in the validator see no overflow either.
pub const MAX_COORDINATE: f64 = 1.0e12;

/// How far from its own origin a mesh file's vertex may lie: as far as the smallest scale
/// can bring within `MAX_COORDINATE`. Cross products of such coordinates stay finite in f32.
pub const MAX_MESH_COORDINATE: f64 = MAX_COORDINATE / *SCALE.start();

/// The shortest length a radius, height or pattern size may have, in scene units. Its
/// square is still a normal f32 number.
pub const MIN_LENGTH: f64 = 1.0e-12;

/// The lengths an f32 value may have (radii, heights, sizes, the focus distance): from
/// `MIN_LENGTH` to `MAX_COORDINATE`, both included as the file writes them. The bounds are
/// rounded to f32 as a typed value is, so `radius = 1e-12` is at the minimum, not below it.
pub const LENGTH: RangeInclusive<f32> = (MIN_LENGTH as f32)..=(MAX_COORDINATE as f32);

/// The smallest extent a box side or a cone's or cylinder's height may have, as a fraction
/// of its distance from the camera: 2⁻²⁰, eight steps of f32 at that distance. Thinner,
/// single precision cannot tell its two faces apart from rounding, and hits on it are noise.
pub const MIN_RELATIVE_EXTENT: f32 = 1.0 / (1u32 << 20) as f32;

/// An infinite plane is traced as a disc this many times wider than the scene's extent from
/// the eye: its rim then lies below the horizon by at most 1/PLANE_REACH radians, far less
/// than a pixel.
pub const PLANE_REACH: f32 = 1.0e4;

/// Indices of refraction: real materials lie between about 1 and 4; values below 1 model
/// a less dense inside (a bubble). Beyond this range the ratios and their squares that
/// Snell's law takes would stop being meaningful long before they overflow.
pub const ETA: RangeInclusive<f32> = 0.1..=10.0;

/// The camera's vertical field of view, in degrees (file, panel, scroll zoom).
pub const VFOV: RangeInclusive<f32> = 0.01..=179.0;

/// How far the camera may pitch above or below the plane perpendicular to `up`, in
/// degrees: short of straight up or down, where yaw would lose its meaning.
pub const MAX_PITCH: f32 = 89.0;

/// The camera's pitch, in degrees (file, panel, mouse look).
pub const PITCH: RangeInclusive<f32> = -MAX_PITCH..=MAX_PITCH;

/// Fractions of light: a material's reflectivity and transparency.
pub const FRACTION: RangeInclusive<f32> = 0.0..=1.0;

/// Reflectances (a material's colour, a texture's colours, a texel): a surface returns
/// at most the light it receives.
pub const REFLECTANCE: RangeInclusive<f32> = 0.0..=1.0;

/// Why a reflectance stops at 1, as messages say it.
pub const REFLECTANCE_BOUND: &str = "a surface reflects at most all the light";

/// Radiance-like colours (a light's colour, the background, the ambient light) may be
/// brighter than white (high dynamic range), up to this per channel.
pub const MAX_RADIANCE: f32 = 1.0e4;

/// Why a radiance may pass 1, as messages say it.
pub const RADIANCE_BOUND: &str = "light may be brighter than white, up to this";

/// An inverse-square light's intensity (its colour's multiplier one scene unit away): enough
/// for a light 10¹² units off (the farthest position) to light a surface, and the gain near
/// the light is capped (`appearance::MAX_FALLOFF_GAIN`), so every product stays finite.
pub const MAX_LIGHT_INTENSITY: f32 = 1.0e30;

/// The largest `uv_scale` and `uv_offset` of an image texture: a picture repeated a million
/// times across a surface is already finer than any pixel.
pub const MAX_UV_TRANSFORM: f32 = 1.0e6;

/// Phong's ambient, diffuse and specular factors: above 1 brightens a surface on purpose
/// (a glowing lamp), but not without bound.
pub const MAX_PHONG_FACTOR: f32 = 1.0e3;

/// The Phong exponent; past this the highlight is narrower than f32 can resolve.
pub const MAX_SHININESS: f32 = 1.0e4;

/// Reflection or refraction bounces along one path (the scene file's `max_depth`,
/// `--max-depth`).
pub const DEPTH: RangeInclusive<u32> = 0..=64;

/// The most secondary rays (reflected, refracted, passed straight through) one camera ray
/// may spawn, shared evenly between the branches of its tree (integrator.rs). A surface
/// that both reflects and transmits doubles the tree at each bounce; the budget keeps a
/// sample's cost, and the recursion's stack depth, bounded whatever the depth limit.
pub const RAY_BUDGET: u32 = 1024;

/// How many transparent objects, one inside another, a ray keeps track of: the medium it
/// travels in, and the one it returns to on leaving, for Snell's law and absorption (a
/// glass of water in a fish tank needs three). Deeper nesting is treated as this deep.
pub const MAX_NESTED_MEDIA: usize = 4;

/// The stack of every thread that traces rays (`render::thread_pool`): a sample's ray tree
/// recurses once per ray of its budget, and a level of it takes a few KiB.
pub const RENDER_STACK_BYTES: usize = 32 << 20;

/// How many lists (light-buffer cells, first-hit tiles) each primitive may appear in on
/// average, beyond the lists' own capacity, before an accelerator gives up listing and
/// leaves every ray to the BVH: crowds of overlapping primitives would otherwise cost time
/// and memory that grow with their square.
pub const LISTINGS_PER_PRIMITIVE: u64 = 64;

/// Anti-aliasing levels N (N × N subsamples per pixel): file, flags, panel.
pub const AA: RangeInclusive<u32> = 1..=8;

/// Subsamples per pixel when a scene or a flag asks for a count other than the N×N grid
/// (`samples`): enough for the noisiest soft shadow, within the 2^16 indices each sample
/// dimension stratifies (sampler.rs).
pub const SAMPLES: RangeInclusive<u32> = 1..=65536;

/// A glossy material's roughness: 0 is a mirror, 1 nearly diffuse.
pub const ROUGHNESS: RangeInclusive<f32> = 0.0..=1.0;

/// The most solids one CSG combination holds, nested ones included: a ray tests them all,
/// and a hit on one tests whether the point is inside the others. (A union at the top of
/// an entry is traced as its members, each counted apart.)
pub const MAX_CSG_MEMBERS: usize = 256;

/// How deep CSG combinations may nest.
pub const MAX_CSG_DEPTH: usize = 32;

/// How deep groups may nest (a group in a group in a group …).
pub const MAX_GROUP_DEPTH: usize = 32;

/// How far a bump map's white stands above its black, in scene units (0: flat).
pub const BUMP_DEPTH: RangeInclusive<f32> = 0.0..=(MAX_COORDINATE as f32);

/// What a normal map's tilt is multiplied by (0: flat, 1: the picture's own).
pub const NORMAL_STRENGTH: RangeInclusive<f32> = 0.0..=16.0;

/// A spotlight's half-angle, in degrees, from a pencil beam to every direction.
pub const SPOT_ANGLE: RangeInclusive<f32> = 0.01..=180.0;

/// Absorption (per scene unit) of a medium, and fog's density: the inverse of the shortest
/// length, beyond which everything is opaque anyway.
pub const MAX_EXTINCTION: f32 = 1.0e12;

/// An image's width or height, in pixels: file, flags, settings.
pub const IMAGE_SIDE: RangeInclusive<u32> = 1..=16384;

/// Adaptive sampling's tolerance: the estimated error of a pixel's mean luminance at which
/// it stops, on the 0..1 scale (flags, panel). Below the lower end no pixel would stop
/// before the grid is full; above the upper, an image would stop at its first samples.
pub const ADAPTIVE_TOLERANCE: RangeInclusive<f32> = 1e-4..=0.5;

/// Adaptive sampling's least edge contrast worth refining beside (0..1, any channel).
pub const EDGE_CONTRAST: RangeInclusive<f32> = 0.0..=1.0;

/// The largest window side the viewer opens (image plus panel); graphics drivers commonly
/// refuse surfaces beyond it.
pub const MAX_WINDOW_SIDE: u32 = 8192;

/// Worker threads a render may use (`--threads`).
pub const THREADS: RangeInclusive<u16> = 1..=256;

/// Names from a scene file are shown in messages at most this many characters long.
pub const MAX_NAME_CHARS: usize = 60;

/// Exposure, in stops (a factor of two each), for the colour a file stores (`--exposure`,
/// `[render] exposure`): from a millionth to a million times as bright.
pub const EXPOSURE: RangeInclusive<f32> = -20.0..=20.0;

/// JPEG quality (`--quality`): 1 (smallest) to 100 (best).
pub const JPEG_QUALITY: RangeInclusive<u8> = 1..=100;

/// The most tiles `prism stitch` assembles in one go.
pub const MAX_TILES: usize = 1 << 16;

/// The most corners one face of a mesh file may have: a face becomes a fan of triangles
/// that all meet at its first corner, and a ray near it tests each of them.
pub const MAX_FACE_CORNERS: usize = 4096;

/// The most surfaces (a scene's primitives, or one mesh's triangles) that may share one
/// centre: no hierarchy can part them, so a ray near them tests each.
pub const MAX_COINCIDENT: usize = 4096;

/// The most frames an animation may have (and so one render command may render): over
/// nine hours at 30 frames a second.
pub const MAX_FRAMES: u32 = 1_000_000;

/// The most keyframes an animation may have, over all its tracks (each frame's scene is
/// the file with every track's value written in: its cost grows with them).
pub const MAX_KEYS: usize = 100_000;

/// The most elements an array in a scene file may have: the longest list a field takes
/// (a track's keys). Longer is refused before the parser reads it.
pub const MAX_ARRAY_ELEMENTS: usize = MAX_KEYS;
