//! What surfaces and lights look like: materials, textures, lights, the background. Kept
//! apart from geometry so that an edit changes a table in place and rebuilds nothing.

mod background;
mod environment;
mod fog;
mod light;
mod material;
mod pattern;
mod relief;
mod texture;

pub use background::Background;
pub use environment::EnvironmentDistribution;
pub use fog::{Fog, FogKind};
pub use light::{AreaShape, Falloff, Light, LightKind, MAX_FALLOFF_GAIN, SpotCone};
pub use material::{Material, fresnel_reflectance, reflect, refract, schlick_reflectance};
pub use pattern::{ColorMap, MAX_COLOR_STOPS, MAX_OCTAVES, MAX_TURBULENCE, Pattern, PatternKind};
pub use relief::Relief;
pub use texture::{ImageTexture, Texture, TextureError, UvTransform};

use glam::{Vec3, Vec3A};

/// The appearance of a prepared scene: one material per object, the lights, the ambient
/// light and the background, and what they imply for shadow rays.
#[derive(Clone, Debug)]
pub struct Appearance {
    materials: Vec<Material>,
    shadow: ShadowFilters,
    /// The same for the path tracer's shadow rays.
    path_shadow: ShadowFilters,
    lights: Vec<Light>,
    /// Read at every hit and miss, so kept in the hot path's SIMD form.
    ambient: Vec3A,
    background: Background,
    /// The background image's light, for drawing directions toward it: built on first use
    /// (Whitted's renders never ask), anew after the background changes.
    environment: std::sync::OnceLock<Option<std::sync::Arc<EnvironmentDistribution>>>,
    max_depth: u32,
    fog: Option<Fog>,
    /// Whether some light shows its surface to rays (`Light::emitter`).
    any_emitter: bool,
}

/// What one crossing of each object's surface lets through to a shadow ray.
#[derive(Clone, Debug)]
pub struct ShadowFilters {
    /// Which integrator's meaning of a transparent surface the filters follow.
    rule: ShadowRule,
    per_object: Vec<Vec3A>,
    /// Whether each object blocks light at all (false: it lets everything through).
    casts_shadow: Vec<bool>,
    /// Whether any surface lets light through; when none does, a shadow ray may stop at
    /// the first occluder without looking at materials.
    any_transmission: bool,
}

/// What a transparent surface lets through to a shadow ray (a closed set).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowRule {
    /// Whitted's: a transparent surface passes light tinted by its colour
    /// (`Material::shadow_filter`), glass that bends light included.
    Whitted,
    /// The path tracer's: light through a surface that bends it cannot reach the light
    /// along a straight shadow ray (the path's bounces carry it), so such a surface blocks;
    /// one that lets light on unbent passes its `transparency`, as a path through it does.
    Path,
}

impl ShadowFilters {
    fn new(materials: &[Material], casts_shadow: Vec<bool>, rule: ShadowRule) -> Self {
        let mut filters = Self {
            rule,
            per_object: Vec::with_capacity(materials.len()),
            casts_shadow,
            any_transmission: false,
        };
        for (object, material) in materials.iter().enumerate() {
            let filter = filters.filter(object, material);
            filters.per_object.push(filter);
        }
        filters.update_any(materials);
        filters
    }

    /// What object `object`, of `material`, lets through.
    fn filter(&self, object: usize, material: &Material) -> Vec3A {
        if !self.casts_shadow[object] {
            return Vec3A::ONE;
        }
        match self.rule {
            ShadowRule::Whitted => material.shadow_filter().into(),
            ShadowRule::Path if material.bends() => Vec3A::ZERO,
            ShadowRule::Path => Vec3A::splat(material.transparency),
        }
    }

    fn update_any(&mut self, materials: &[Material]) {
        let passes = |m: &Material| match self.rule {
            ShadowRule::Whitted => m.transparency > 0.0,
            ShadowRule::Path => m.transparency > 0.0 && !m.bends(),
        };
        self.any_transmission =
            materials.iter().any(passes) || self.casts_shadow.iter().any(|&casts| !casts);
    }

    /// What a crossing of `object`'s surface lets through.
    #[inline]
    pub fn of(&self, object: u32) -> Vec3A {
        self.per_object[object as usize]
    }

    /// Whether any surface transmits light.
    #[inline]
    pub fn any_transmission(&self) -> bool {
        self.any_transmission
    }
}

impl Appearance {
    /// One material per object (in the objects' order) and whether each object casts a
    /// shadow, the lights, the ambient light, the background and the most bounces along one
    /// path.
    ///
    /// # Panics
    /// If `casts_shadow` does not have one entry per material.
    pub fn new(
        materials: Vec<Material>,
        casts_shadow: Vec<bool>,
        lights: Vec<Light>,
        ambient: Vec3,
        background: Background,
        max_depth: u32,
    ) -> Self {
        Self {
            shadow: {
                assert_eq!(casts_shadow.len(), materials.len(), "one flag per object");
                ShadowFilters::new(&materials, casts_shadow.clone(), ShadowRule::Whitted)
            },
            path_shadow: ShadowFilters::new(&materials, casts_shadow, ShadowRule::Path),
            materials,
            any_emitter: lights.iter().any(|l| l.emitter().is_some()),
            lights,
            ambient: ambient.into(),
            background,
            environment: std::sync::OnceLock::new(),
            max_depth,
            fog: None,
        }
    }

    /// The same appearance with `members`' materials numbered after the objects' own: the
    /// CSG members that give materials of their own (`Scene::member_materials`).
    pub fn with_member_materials(mut self, members: Vec<Material>) -> Self {
        self.materials.extend(members);
        self.shadow.update_any(&self.materials);
        self.path_shadow.update_any(&self.materials);
        self
    }

    /// The same appearance with fog (or none).
    pub fn with_fog(mut self, fog: Option<Fog>) -> Self {
        self.fog = fog;
        self
    }

    /// Material `slot`: object `slot`'s own, or past the objects, a CSG member's
    /// (`Accelerator::material_slot` gives a hit's).
    #[inline]
    pub fn material(&self, slot: u32) -> &Material {
        &self.materials[slot as usize]
    }

    /// Replaces object `object`'s material (already validated, as the scene loader and
    /// `Scene`'s edits do). Costs one pass over the objects' filters, no rebuild.
    ///
    /// # Panics
    /// If there is no such object.
    pub fn set_material(&mut self, object: usize, material: Material) {
        for filters in [&mut self.shadow, &mut self.path_shadow] {
            filters.per_object[object] = filters.filter(object, &material);
        }
        self.materials[object] = material;
        self.shadow.update_any(&self.materials);
        self.path_shadow.update_any(&self.materials);
    }

    /// Sets light `light`'s colour (intensity per channel, already validated). Its position
    /// is geometry: the acceleration layer's light buffers are built for it.
    ///
    /// # Panics
    /// If there is no such light.
    pub fn set_light_color(&mut self, light: usize, color: Vec3) {
        self.lights[light].color = color;
    }

    /// Replaces light `light` by one with the same shadow-ray end point (`Light::position`:
    /// what the light buffers were built around): a colour, a cone, an area light's surface.
    ///
    /// # Panics
    /// If there is no such light, or the new one moves the point.
    pub fn set_light(&mut self, light: usize, new: Light) {
        assert_eq!(
            self.lights[light].position(),
            new.position(),
            "light {light} moved"
        );
        self.lights[light] = new;
        self.any_emitter = self.lights.iter().any(|l| l.emitter().is_some());
    }

    /// Sets the fog (None: clear air).
    pub fn set_fog(&mut self, fog: Option<Fog>) {
        self.fog = fog;
    }

    /// The fog, if any.
    #[inline]
    pub fn fog(&self) -> Option<&Fog> {
        self.fog.as_ref()
    }

    /// Whether shading draws random numbers: a light with soft shadows or a glossy
    /// material. Its pixels are then noisy as well as edged, which adaptive sampling must
    /// allow for.
    pub fn is_stochastic(&self) -> bool {
        self.lights.iter().any(Light::is_soft) || self.materials.iter().any(|m| m.roughness > 0.0)
    }

    /// Whether some light shows its surface to rays.
    #[inline]
    pub fn any_emitter(&self) -> bool {
        self.any_emitter
    }

    /// Sets the ambient light.
    pub fn set_ambient(&mut self, ambient: Vec3) {
        self.ambient = ambient.into();
    }

    /// Sets what a ray that leaves the scene sees.
    pub fn set_background(&mut self, background: Background) {
        self.background = background;
        self.environment = std::sync::OnceLock::new();
    }

    /// How to draw directions toward the background in proportion to its light, when it is
    /// an image.
    pub fn environment(&self) -> Option<&EnvironmentDistribution> {
        self.environment
            .get_or_init(|| match &self.background {
                Background::Image(image) => {
                    Some(std::sync::Arc::new(EnvironmentDistribution::new(image)))
                }
                _ => None,
            })
            .as_deref()
    }

    /// Sets the most bounces along one path.
    pub fn set_max_depth(&mut self, max_depth: u32) {
        self.max_depth = max_depth;
    }

    /// What shadow rays see of each surface.
    #[inline]
    pub fn shadow_filters(&self) -> &ShadowFilters {
        &self.shadow
    }

    /// What the path tracer's shadow rays see of each surface ([`ShadowRule::Path`]).
    #[inline]
    pub fn path_shadow_filters(&self) -> &ShadowFilters {
        &self.path_shadow
    }

    /// The lights.
    #[inline]
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// Light that falls on every surface from everywhere.
    #[inline]
    pub fn ambient(&self) -> Vec3A {
        self.ambient
    }

    /// What a ray that leaves the scene sees.
    #[inline]
    pub fn background(&self) -> &Background {
        &self.background
    }

    /// The most bounces along one path.
    #[inline]
    pub fn max_depth(&self) -> u32 {
        self.max_depth
    }
}
