//! Which light transport a render computes: Whitted's (direct light, mirrors and glass) or
//! path tracing (light that bounces off every surface).

/// The integrators (a closed set).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum IntegratorKind {
    /// Phong shading from the lights, an ambient term, and mirror and refraction rays: the
    /// seed's look, and every scene's unless it asks for another.
    #[default]
    Whitted,
    /// Unidirectional path tracing with next-event estimation and multiple importance
    /// sampling: light bounces between diffuse surfaces (docs/effects.md, "Path tracing").
    Path,
}

impl IntegratorKind {
    /// Every kind, in the order menus list them.
    pub const ALL: [IntegratorKind; 2] = [IntegratorKind::Whitted, IntegratorKind::Path];

    /// The name a scene file and the command line use.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::Whitted => "whitted",
            IntegratorKind::Path => "path",
        }
    }

    /// The kind of that name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for kind in IntegratorKind::ALL {
            assert_eq!(IntegratorKind::from_name(kind.name()), Some(kind));
        }
        assert_eq!(IntegratorKind::from_name("Path"), None);
        assert_eq!(IntegratorKind::default(), IntegratorKind::Whitted);
    }
}
