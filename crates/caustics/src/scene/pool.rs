//! `[pool]`: the square pool of Trendall & Stewart 2000 (Sec. 4): its water surface driven by
//! impulses (Sec. 4.3), the distant light, and the water's scattering and extinction (Eq. 2).
//! A pool scene has no `[[objects]]` or `[[lights]]`; it is rendered by technique
//! `pool-convolution` alone. See `scenes/README.md`.

use super::load::Ctx;
use crate::input_error;
use glam::{DVec2, DVec3};
use serde::Deserialize;
use std::path::PathBuf;

/// Most impulses a pool holds (each adds four reflections; the GPU keeps them in one buffer).
pub const MAX_IMPULSES: usize = 48;

/// `[pool]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoolDef {
    pub side: f64,
    pub depth: f64,
    pub albedo: f64,
    pub ior: f64,
    pub ior_air: Option<f64>,
    pub time: Option<f64>,
    pub time_step: Option<f64>,
    pub light_direction: [f64; 3],
    pub light_radiance: Option<f64>,
    pub light_texture: Option<String>,
    pub scattering: f64,
    pub exponent: Option<f64>,
    pub extinction: f64,
    pub wall_reflections: Option<bool>,
    pub height_range: Option<f64>,
    pub slope_range: Option<f64>,
    pub wave: WaveDef,
    #[serde(default)]
    pub impulses: Vec<ImpulseDef>,
}

/// `[pool.wave]`: h(t, d) = A exp(-beta (f(t) - d)) exp(-alpha t) sin(K d - omega t), Sec. 4.3.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WaveDef {
    pub amplitude: f64,
    pub wavelength: f64,
    pub frequency: f64,
    pub time_damping: f64,
    pub distance_damping: f64,
}

/// `[[pool.impulses]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImpulseDef {
    pub position: [f64; 2],
    pub start: Option<f64>,
}

/// The wave an impulse sends out (Sec. 4.3), in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wave {
    /// A, m.
    pub amplitude: f64,
    /// K = 2 pi / wavelength, 1/m.
    pub wave_number: f64,
    /// omega = 2 pi frequency, 1/s.
    pub angular_frequency: f64,
    /// alpha, 1/s: damping with time.
    pub time_damping: f64,
    /// beta, 1/m: damping with distance behind the wavefront.
    pub distance_damping: f64,
}

/// A pebble dropped at `position` (x, z) at time `start`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impulse {
    pub position: DVec2,
    pub start: f64,
}

/// A loaded, validated `[pool]`. The pool spans x, z in [-side/2, side/2]; the water is at rest
/// at y = 0 and the bottom is at y = -depth.
#[derive(Debug, Clone, PartialEq)]
pub struct PoolSpec {
    pub side: f64,
    pub depth: f64,
    /// Diffuse albedo of the bottom and walls.
    pub albedo: f64,
    /// n_t (water).
    pub ior: f64,
    /// n_i (air).
    pub ior_air: f64,
    /// The time the height field is evaluated at, s.
    pub time: f64,
    /// Seconds per frame of the animation (bench `object_path = "orbit"`).
    pub time_step: f64,
    /// Direction the light travels in (normalised, downwards): L_i of Eq. 1.
    pub light_direction: DVec3,
    /// L_s of the distant light, in [0, 1].
    pub light_radiance: f64,
    /// Footnote 1's projected texture: L_s varies over the surface (a PNG over the pool).
    pub light_texture: Option<PathBuf>,
    /// a, the forward-scattering coefficient of the Gaussian lobe.
    pub scattering: f64,
    /// n, the exponent of the exponentiated cosine (2a unless given).
    pub exponent: f64,
    /// epsilon, the extinction coefficient, 1/m.
    pub extinction: f64,
    /// Each impulse's four reflections through the walls (Sec. 4.3).
    pub wall_reflections: bool,
    /// The faithful path's scale and bias: |h| up to this, m (Sec. 3.2, 4.1).
    pub height_range: f64,
    /// The faithful path's scale and bias: surface slopes up to this.
    pub slope_range: f64,
    pub wave: Wave,
    pub impulses: Vec<Impulse>,
}

impl PoolSpec {
    /// Half the side: the pool spans [-half, half] in x and z.
    pub fn half(&self) -> f64 {
        0.5 * self.side
    }

    /// The scene at time `t` (same pool, other time).
    pub fn at_time(&self, t: f64) -> PoolSpec {
        PoolSpec { time: t, ..self.clone() }
    }
}

pub(super) fn build_pool(ctx: &Ctx, p: &PoolDef) -> anyhow::Result<PoolSpec> {
    let key = |k: &str| format!("pool.{k}");
    let positive = |k: &str, v: f64| -> anyhow::Result<f64> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(ctx.err(&key(k), format!("must be a finite number > 0, got {v}")))
        }
    };
    let non_negative = |k: &str, v: f64| -> anyhow::Result<f64> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(ctx.err(&key(k), format!("must be a finite number >= 0, got {v}")))
        }
    };
    // Finite is not enough: a pool of 1e300 m, or a wave of it, renders NaN. The bounds are
    // far beyond any pool and keep every product in range.
    let at_most = |k: &str, v: f64, max: f64| -> anyhow::Result<f64> {
        if v <= max {
            Ok(v)
        } else {
            Err(ctx.err(&key(k), format!("must be at most {max}, got {v}")))
        }
    };
    let side = at_most("side", positive("side", p.side)?, 1e4)?;
    let depth = at_most("depth", positive("depth", p.depth)?, 1e4)?;
    if !(0.0..=1.0).contains(&p.albedo) {
        return Err(ctx.err(&key("albedo"), format!("must be between 0 and 1, got {}", p.albedo)));
    }
    let ior_air = p.ior_air.unwrap_or(1.0);
    if !(1.0..=4.0).contains(&ior_air) {
        return Err(ctx.err(&key("ior_air"), format!("must be between 1.0 and 4.0, got {ior_air}")));
    }
    if !(p.ior.is_finite() && p.ior > ior_air && p.ior <= 4.0) {
        return Err(ctx.err(
            &key("ior"),
            format!("must be above ior_air ({ior_air}) and at most 4.0 (light enters a denser medium), got {}", p.ior),
        ));
    }
    let time = p.time.unwrap_or(0.0);
    if !(time.is_finite() && time.abs() <= 1e6) {
        return Err(ctx.err(&key("time"), format!("must be within ±1e6 s, got {time}")));
    }
    let time_step = non_negative("time_step", p.time_step.unwrap_or(1.0 / 30.0))?;
    let d = DVec3::from_array(p.light_direction);
    if !(d.is_finite() && d.length() > 0.0 && d.y < -1e-3 * d.length()) {
        return Err(ctx.err(
            &key("light_direction"),
            format!("must be a finite direction travelling downwards (y < 0), got {:?}", p.light_direction),
        ));
    }
    let light_direction = d.normalize();
    // Grazing light would need kernels far wider than the pool; 80 degrees is plenty.
    if light_direction.y > -(80f64.to_radians().cos()) {
        return Err(ctx.err(&key("light_direction"), "must be within 80 degrees of straight down"));
    }
    // Light refracted by flat water lands on the bottom at most one pool side from where it
    // entered: further (a deep pool under oblique light), its caustic leaves the pool and Pass
    // 6's kernels sit more than the whole grid away from their receiver texel.
    let sin_t = (1.0 - light_direction.y * light_direction.y).max(0.0).sqrt() * ior_air / p.ior;
    let shift = depth * sin_t / (1.0 - sin_t * sin_t).sqrt();
    if shift > side {
        return Err(ctx.err(
            &key("depth"),
            format!(
                "the refracted light lands {shift:.3} m from where it enters, more than the pool's side ({side} m): \
                 make the pool shallower or the light steeper"
            ),
        ));
    }
    let light_radiance = p.light_radiance.unwrap_or(1.0);
    if !(0.0..=1.0).contains(&light_radiance) {
        return Err(ctx.err(
            &key("light_radiance"),
            format!("must be between 0 and 1 (L_s is an unadjusted function, Sec. 4.2), got {light_radiance}"),
        ));
    }
    let light_texture = match &p.light_texture {
        None => None,
        Some(t) => Some(ctx.beside(&key("light_texture"), t, "texture file")?),
    };
    let scattering = at_most("scattering", positive("scattering", p.scattering)?, 1e6)?;
    let exponent = p.exponent.unwrap_or(2.0 * scattering);
    if !(exponent.is_finite() && (1.0..=2e6).contains(&exponent)) {
        return Err(ctx.err(&key("exponent"), format!("must be a number from 1 to 2e6, got {exponent}")));
    }
    let extinction = non_negative("extinction", p.extinction)?;
    let w = &p.wave;
    let wk = |k: &str| format!("wave.{k}");
    let wave = Wave {
        amplitude: at_most(&wk("amplitude"), non_negative(&wk("amplitude"), w.amplitude)?, depth)?,
        wave_number: std::f64::consts::TAU
            / at_most(&wk("wavelength"), positive(&wk("wavelength"), w.wavelength)?, 1e4)?,
        angular_frequency: std::f64::consts::TAU
            * at_most(&wk("frequency"), positive(&wk("frequency"), w.frequency)?, 1e4)?,
        time_damping: non_negative(&wk("time_damping"), w.time_damping)?,
        distance_damping: non_negative(&wk("distance_damping"), w.distance_damping)?,
    };
    if p.impulses.len() > MAX_IMPULSES {
        return Err(ctx.err(&key("impulses"), format!("at most {MAX_IMPULSES} impulses, got {}", p.impulses.len())));
    }
    let half = 0.5 * side;
    let impulses = p
        .impulses
        .iter()
        .enumerate()
        .map(|(i, imp)| {
            let pos = DVec2::from_array(imp.position);
            if !(pos.is_finite() && pos.x.abs() <= half && pos.y.abs() <= half) {
                return Err(ctx.err(
                    &key(&format!("impulses[{i}].position")),
                    format!("must be [x, z] inside the pool (|x|, |z| <= {half}), got {:?}", imp.position),
                ));
            }
            let start = imp.start.unwrap_or(0.0);
            if !start.is_finite() {
                return Err(ctx.err(&key(&format!("impulses[{i}].start")), format!("must be finite, got {start}")));
            }
            Ok(Impulse { position: pos, start })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    // Bounds the faithful path scales and biases by (Sec. 3.2): by default the largest height
    // and slope one impulse's wave can have.
    let height_range = positive("height_range", p.height_range.unwrap_or(wave.amplitude.max(1e-6)))?;
    let slope_bound = wave.amplitude * (wave.wave_number + wave.distance_damping);
    let slope_range = positive("slope_range", p.slope_range.unwrap_or(slope_bound.clamp(1e-3, 1.0)))?;
    Ok(PoolSpec {
        side,
        depth,
        albedo: p.albedo,
        ior: p.ior,
        ior_air,
        time,
        time_step,
        light_direction,
        light_radiance,
        light_texture,
        scattering,
        exponent,
        extinction,
        wall_reflections: p.wall_reflections.unwrap_or(true),
        height_range,
        slope_range,
        wave,
        impulses,
    })
}

/// A pool scene describes its light and surfaces in `[pool]`: meshes, point lights and a
/// receiver rectangle of the mesh renderer would be ignored, so they are refused.
pub(super) fn check_pool_scene(ctx: &Ctx, def: &super::schema::SceneFile) -> anyhow::Result<()> {
    let refuse = |present: bool, k: &str| -> anyhow::Result<()> {
        if present {
            return Err(anyhow::Error::new(input_error!(
                "{}: key `{k}`: a pool scene ([pool]) has no {k}: its light is pool.light_direction, its surfaces \
                 the pool, and its receiver map the pool bottom on the height-field grid",
                ctx.file.display()
            )));
        }
        Ok(())
    };
    refuse(!def.lights.is_empty(), "lights")?;
    refuse(!def.objects.is_empty(), "objects")?;
    refuse(!def.materials.is_empty(), "materials")?;
    refuse(def.receiver_map.is_some(), "receiver_map")
}
