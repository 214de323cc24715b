//! Trendall & Stewart, "General calculations using graphics hardware, with application to
//! interactive caustics" (EGWR 2000): technique `pool-convolution`. No photons: the irradiance
//! on the bottom of a pool under a time-varying water surface (Eq. 2: Fresnel transmission,
//! forward scattering as a Gaussian about the refracted direction, extinction) is evaluated as
//! three convolutions of functions computed per height-field texel (Sec. 4.1-4.2).
//!
//! | stage | paper | module |
//! |---|---|---|
//! | water surface: impulses and their wall reflections | Sec. 4.3 | [`water_surface`] |
//! | Snell (Eq. 1), Fresnel T | Sec. 4 | [`fresnel`] |
//! | Pass 6 kernels, the expansion axis | Sec. 4.1 | [`kernels`] |
//! | passes 1-6 in f64 (the software implementation) | Sec. 4.2, 5 | [`cpu`] |
//! | Eq. 2 itself, without the convolution's approximations | Eq. 2 | [`direct`] |
//! | scale-and-bias ("adjusted") encodings and lookup tables of the 8-bit path | Sec. 3.2, 4.1 | [`adjusted`] |
//! | the GPU passes (8-bit UNORM or float fragment passes) | Sec. 4.2 | [`gpu_passes`], [`pipelines`], [`targets`] |
//! | the pool seen from above, the receiver map, dumps | Fig. 2 | [`view`], [`dumps`] |
//! | a frame: height field, passes, view | | [`renderer`] |
//!
//! The receiver map is E / E_flat per texel of the bottom, E_flat the same computation for a
//! flat surface (computed once, at Init, by the same path).

pub mod adjusted;
pub mod cpu;
pub mod direct;
pub mod dumps;
pub mod fresnel;
pub mod gpu_passes;
pub mod kernels;
pub mod pipelines;
pub mod renderer;
pub mod settings;
pub mod targets;
pub mod uniforms;
pub mod view;
// The height field lives with the scene (`shape = "water"` builds its mesh from it too).
pub use crate::scene::water_surface;

pub use renderer::PoolRenderer;
pub use settings::{Precision, DUMPS, PAPER};

use crate::scene::{PoolSpec, Scene};
use anyhow::{Context as _, Result};

/// The pool of `scene`, or an input error naming the file: `pool-convolution` renders pool
/// scenes only.
pub fn pool_of(scene: &Scene) -> Result<&PoolSpec> {
    scene.pool.as_ref().ok_or_else(|| {
        crate::input_error!(
            "{}: technique `pool-convolution` needs a pool scene (a [pool] table, e.g. scenes/pool.toml)",
            scene.path.display()
        )
        .into()
    })
}

/// L_s per texel of the `n` x `n` grid: the light's radiance, times footnote 1's projected
/// texture where there is one (its mean RGB, the PNG stretched over the pool, first row at
/// z = -side/2, sampled at the texel centres).
pub fn light_radiance(pool: &PoolSpec, n: usize) -> Result<Vec<f64>> {
    let Some(path) = &pool.light_texture else {
        return Ok(vec![pool.light_radiance; n * n]);
    };
    let (w, h, rgba) =
        crate::image_io::read_png_rgba(path).with_context(|| format!("pool.light_texture {}", path.display()))?;
    let mut out = Vec::with_capacity(n * n);
    for j in 0..n {
        let sy = ((j * 2 + 1) * h as usize / (2 * n)).min(h as usize - 1);
        for i in 0..n {
            let sx = ((i * 2 + 1) * w as usize / (2 * n)).min(w as usize - 1);
            let p = &rgba[(sy * w as usize + sx) * 4..][..3];
            out.push(pool.light_radiance * (p[0] + p[1] + p[2]) as f64 / 3.0);
        }
    }
    Ok(out)
}

/// The f64 passes of `pool` on an `n` x `n` grid with `kernel` x `kernel` taps: the surface at
/// the pool's time, and the same for a flat surface (E_flat).
pub fn reference(pool: &PoolSpec, n: usize, kernel: usize) -> Result<(cpu::CpuPasses, cpu::CpuPasses)> {
    let k = kernels::kernels(pool, n, kernel);
    let ls = light_radiance(pool, n)?;
    let wavy = cpu::run(pool, n, &k, water_surface::height_field(pool, n), &ls);
    let flat = cpu::run(pool, n, &k, vec![0.0; n * n], &ls);
    Ok((wavy, flat))
}

/// What Init computes once (Sec. 4.2: "Calculate lookup tables, convolution kernels"), for a
/// pool at a grid side and kernel size, on one path.
#[derive(Debug, Clone)]
pub struct Init {
    pub pool: PoolSpec,
    /// The grid side n (the height field's, the receiver map's).
    pub n: usize,
    pub precision: Precision,
    pub kernels: kernels::Kernels,
    /// The 8-bit path's scales and biases (computed on every path; used by the faithful one).
    pub adjustments: adjusted::Adjustments,
    /// L_s per texel.
    pub light_radiance: Vec<f64>,
}

impl Init {
    /// Init for `pool` with the technique settings `settings` (`photons` is the grid side).
    pub fn new(pool: &PoolSpec, settings: &crate::scene::CausticSettings) -> Result<Init> {
        let n = settings.photons as usize;
        let kernels = kernels::kernels(pool, n, settings.kernel as usize);
        Ok(Init {
            adjustments: adjusted::adjustments(pool, &kernels),
            light_radiance: light_radiance(pool, n)?,
            pool: pool.clone(),
            n,
            precision: settings.precision,
            kernels,
        })
    }
}

/// E / E_flat per texel; 0 where E_flat is 0 (no light reaches the texel through flat water).
pub fn relative(e: &[f64], e_flat: &[f64]) -> Vec<f64> {
    e.iter().zip(e_flat).map(|(&a, &b)| if b > 0.0 { a / b } else { 0.0 }).collect()
}

/// The relative RMS error of Sec. 5.2: sqrt(sum (a - b)^2 / sum b^2), b the reference.
pub fn relative_rms(a: &[f64], b: &[f64]) -> f64 {
    let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    let den: f64 = b.iter().map(|y| y * y).sum();
    if den > 0.0 {
        (num / den).sqrt()
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
pub(crate) mod tests;
