//! Overrides of [`CausticSettings`]: the scene's `[caustics]` table, a bench config's
//! `[[technique]]` entry and the `render` command's flags all set some of the settings and leave
//! the rest; each becomes a [`CausticOverrides`] applied over the defaults or the scene's.

use super::CausticSettings;
use serde::Deserialize;

/// Each `Some` replaces the setting of the same name (see [`CausticSettings`] for what they mean).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CausticOverrides {
    pub technique: Option<String>,
    pub photons: Option<u32>,
    pub splat_radius: Option<f32>,
    pub splat_kernel: Option<String>,
    pub caustic_map_resolution: Option<u32>,
    pub iterations: Option<u32>,
    pub fresnel: Option<bool>,
    pub back_face_iterations: Option<u32>,
    pub intersect: Option<String>,
    pub path: Option<String>,
    pub cluster: Option<String>,
    pub splat: Option<String>,
    pub varying_radius: Option<String>,
    pub splat_path: Option<String>,
    pub instance_vertices: Option<u32>,
}

impl CausticOverrides {
    /// Writes every set override over `s` (not checked: see [`CausticSettings::validate`]).
    pub fn apply(&self, s: &mut CausticSettings) {
        fn set<T: Clone>(to: &mut T, from: &Option<T>) {
            if let Some(v) = from {
                *to = v.clone();
            }
        }
        set(&mut s.technique, &self.technique);
        set(&mut s.photons, &self.photons);
        set(&mut s.splat_radius, &self.splat_radius);
        set(&mut s.splat_kernel, &self.splat_kernel);
        set(&mut s.caustic_map_resolution, &self.caustic_map_resolution);
        set(&mut s.iterations, &self.iterations);
        set(&mut s.fresnel, &self.fresnel);
        set(&mut s.back_face_iterations, &self.back_face_iterations);
        if self.intersect.is_some() {
            s.intersect = self.intersect.clone();
        }
        set(&mut s.path, &self.path);
        set(&mut s.cluster, &self.cluster);
        set(&mut s.splat, &self.splat);
        set(&mut s.varying_radius, &self.varying_radius);
        set(&mut s.splat_path, &self.splat_path);
        set(&mut s.instance_vertices, &self.instance_vertices);
    }
}
