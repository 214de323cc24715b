//! Eq. 2 evaluated directly (`causticlab reference --direct`), without the approximations that
//! make it a convolution: the Gaussian lobe exp(-a (1 - (L_t . P)^2)) itself rather than the
//! exponentiated cosine kept to first order, and P from the surface point (x, h, z) rather than
//! from (x, 0, z) (no d >> h). It integrates over the same discrete surface (the height field's
//! texels with Pass 1's normals, midpoint rule over texel areas), so that what differs from the
//! convolution is the convolution's approximations alone.

use super::cpu::pass1_normals;
use super::kernels::{basis, interface};
use crate::scene::PoolSpec;
use glam::DVec3;

/// Below exp(-LOBE_CUTOFF) of its peak the lobe is left out.
const LOBE_CUTOFF: f64 = 32.0;

/// The half-width, in texels, of the window around the flat-water landing point that holds
/// every receiver a surface texel's lobe reaches (above exp(-LOBE_CUTOFF)).
fn window(pool: &PoolSpec, n: usize, lt: &[DVec3], height: &[f64]) -> i64 {
    let b = basis(pool);
    let tilt = lt.iter().map(|l| l.normalize().dot(b.z).clamp(-1.0, 1.0).acos()).fold(0.0, f64::max);
    let lobe = (LOBE_CUTOFF / pool.scattering).min(1.0).sqrt().asin();
    let cone = (tilt + lobe).min(1.5);
    let depth = pool.depth + height.iter().fold(0.0f64, |m, h| m.max(h.abs()));
    let texel = pool.side / n as f64;
    let land = |d: DVec3| DVec3::new(d.x, 0.0, d.z) * (depth / -d.y);
    let centre = land(b.z);
    let mut reach = 0.0f64;
    for k in 0..64 {
        let phi = std::f64::consts::TAU * k as f64 / 64.0;
        let d = b.z * cone.cos() + (b.x * phi.cos() + b.y * phi.sin()) * cone.sin();
        if d.y >= -1e-3 {
            return n as i64;
        }
        reach = reach.max((land(d) - centre).length());
    }
    // No wider than the grid: a source's light that lands further is off it anyway.
    (reach / texel).ceil().min(n as f64) as i64 + 2
}

/// E of Eq. 2 at every receiver texel of the `n` x `n` grid over the bottom, for the height
/// field `height` and L_s per texel.
pub fn direct_irradiance(pool: &PoolSpec, n: usize, height: &[f64], light_radiance: &[f64]) -> Vec<f64> {
    let it = interface(pool);
    let texel = pool.side / n as f64;
    let normals = pass1_normals(pool, n, height);
    let mut lt = Vec::with_capacity(n * n);
    let mut flux = Vec::with_capacity(n * n);
    for (s, &nrm) in normals.iter().enumerate() {
        let (t, ci) = it.transmitted(pool.light_direction, nrm);
        lt.push(t);
        flux.push(light_radiance[s] * ci * it.transmittance(ci));
    }
    let w = window(pool, n, &lt, height);
    let o = super::kernels::landing_offset(pool, n);
    let mut e = vec![0.0; n * n];
    for sj in 0..n {
        for si in 0..n {
            let s = sj * n + si;
            if flux[s] == 0.0 {
                continue;
            }
            let below = -pool.depth - height[s];
            for dj in -w..=w {
                let rj = sj as i64 + o[1] as i64 + dj;
                if rj < 0 || rj >= n as i64 {
                    continue;
                }
                for di in -w..=w {
                    let ri = si as i64 + o[0] as i64 + di;
                    if ri < 0 || ri >= n as i64 {
                        continue;
                    }
                    let p = DVec3::new((ri - si as i64) as f64 * texel, below, (rj - sj as i64) as f64 * texel);
                    let len = p.length();
                    let c = lt[s].dot(p) / len;
                    if c <= 0.0 {
                        continue;
                    }
                    let lobe = -pool.scattering * (1.0 - c * c);
                    if lobe < -LOBE_CUTOFF {
                        continue;
                    }
                    let down = -below / len;
                    e[rj as usize * n + ri as usize] +=
                        flux[s] * down * (lobe - pool.extinction * len).exp() * texel * texel;
                }
            }
        }
    }
    e
}
