//! The CPU reference: passes 1-6 of Sec. 4.2 in f64, with the same approximations as the
//! hardware (finite-difference normals, d >> h, the exponentiated cosine kept to first order,
//! the kernels of `kernels.rs`) but none of its precision limits: the paper's "software
//! implementation" (Sec. 5), which is also `--precision f64` and `causticlab reference`.
//! One thread, as the paper's software was.

use super::kernels::{basis, interface, Kernels};
use crate::scene::PoolSpec;
use glam::DVec3;
use std::time::Instant;

/// Every pass's function on the `n` x `n` grid, row-major (row j at z_j).
#[derive(Debug, Clone)]
pub struct CpuPasses {
    pub n: usize,
    /// h, m.
    pub height: Vec<f64>,
    /// Pass 1: N, the unit normal.
    pub normals: Vec<DVec3>,
    /// Pass 2: Gamma N (world axes).
    pub gamma_n: Vec<DVec3>,
    /// Pass 3: L_s cos(theta_i) T(cos(theta_i)).
    pub transmitted: Vec<f64>,
    /// Pass 4: L_t (L_tz)^(n-1), in the expansion basis (x, y, z).
    pub direction: Vec<DVec3>,
    /// Pass 5: F, the product of Passes 3 and 4 (basis axes).
    pub integrand: Vec<DVec3>,
    /// Pass 6: the three convolutions E_x, E_y, E_z and their sum E.
    pub convolutions: Vec<[f64; 4]>,
    /// (pass name, host ms) of passes 1-6.
    pub timings: Vec<(&'static str, f64)>,
}

impl CpuPasses {
    /// E per texel.
    pub fn irradiance(&self) -> Vec<f64> {
        self.convolutions.iter().map(|c| c[3]).collect()
    }
}

/// Pass 1: the normal to the plane through h(i, j), h(i+1, j) and h(i, j+1) (Sec. 4.1); the last
/// column and row use the texel before instead.
pub fn pass1_normals(pool: &PoolSpec, n: usize, h: &[f64]) -> Vec<DVec3> {
    let texel = pool.side / n as f64;
    let at = |i: usize, j: usize| h[j * n + i];
    let mut out = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let dx = if i + 1 < n { at(i + 1, j) - at(i, j) } else { at(i, j) - at(i - 1, j) };
            let dz = if j + 1 < n { at(i, j + 1) - at(i, j) } else { at(i, j) - at(i, j - 1) };
            out.push(DVec3::new(-dx / texel, 1.0, -dz / texel).normalize());
        }
    }
    out
}

/// Pass 2: Gamma N (Eq. 1).
pub fn pass2_gamma_n(pool: &PoolSpec, normals: &[DVec3]) -> Vec<DVec3> {
    let it = interface(pool);
    normals.iter().map(|&nrm| it.gamma(-pool.light_direction.dot(nrm)) * nrm).collect()
}

/// Pass 3: L_s cos(theta_i) T(cos(theta_i)).
pub fn pass3_transmitted(pool: &PoolSpec, normals: &[DVec3], light_radiance: &[f64]) -> Vec<f64> {
    let it = interface(pool);
    normals
        .iter()
        .zip(light_radiance)
        .map(|(&nrm, &ls)| {
            let ci = -pool.light_direction.dot(nrm);
            ls * ci * it.transmittance(ci)
        })
        .collect()
}

/// Pass 4: L_t (L_tz)^(n-1) in the expansion basis, L_t = (n_i/n_t) L_i + Gamma N (Eq. 1).
pub fn pass4_direction(pool: &PoolSpec, gamma_n: &[DVec3]) -> Vec<DVec3> {
    let b = basis(pool);
    let eta_li = interface(pool).eta() * pool.light_direction;
    gamma_n
        .iter()
        .map(|&g| {
            let lt = b.coords(eta_li + g);
            if lt.z <= 0.0 {
                return DVec3::ZERO;
            }
            lt * ((pool.exponent - 1.0) * lt.z.ln()).exp()
        })
        .collect()
}

/// Pass 5: F = (Pass 3) (Pass 4).
pub fn pass5_integrand(transmitted: &[f64], direction: &[DVec3]) -> Vec<DVec3> {
    transmitted.iter().zip(direction).map(|(&t, &d)| t * d).collect()
}

/// Pass 6: E_j(i, j) = sum over taps of F_j(surface texel) K_j(tap), and E = E_x + E_y + E_z.
/// Surface texels outside the pool hold no water: they add nothing.
pub fn pass6_convolve(n: usize, k: &Kernels, f: &[DVec3]) -> Vec<[f64; 4]> {
    let mut out = vec![[0.0; 4]; n * n];
    for b in 0..k.side {
        for a in 0..k.side {
            let [kx, ky, kz] = k.taps[b * k.side + a];
            if kx == 0.0 && ky == 0.0 && kz == 0.0 {
                continue;
            }
            let (di, dj) = k.tap_offset(a, b);
            for j in 0..n {
                let sj = j as i64 - dj as i64;
                if sj < 0 || sj >= n as i64 {
                    continue;
                }
                for i in 0..n {
                    let si = i as i64 - di as i64;
                    if si < 0 || si >= n as i64 {
                        continue;
                    }
                    let fs = f[sj as usize * n + si as usize];
                    let e = &mut out[j * n + i];
                    e[0] += fs.x * kx;
                    e[1] += fs.y * ky;
                    e[2] += fs.z * kz;
                }
            }
        }
    }
    for e in &mut out {
        e[3] = e[0] + e[1] + e[2];
    }
    out
}

/// Passes 1-6 on the height field `height` (n x n) with L_s per texel, each pass timed.
pub fn run(pool: &PoolSpec, n: usize, k: &Kernels, height: Vec<f64>, light_radiance: &[f64]) -> CpuPasses {
    let mut timings = vec![];
    let mut timed = |name: &'static str, start: Instant| timings.push((name, start.elapsed().as_secs_f64() * 1e3));
    let t = Instant::now();
    let normals = pass1_normals(pool, n, &height);
    timed("pool.pass1_normals", t);
    let t = Instant::now();
    let gamma_n = pass2_gamma_n(pool, &normals);
    timed("pool.pass2_gamma_n", t);
    let t = Instant::now();
    let transmitted = pass3_transmitted(pool, &normals, light_radiance);
    timed("pool.pass3_transmitted", t);
    let t = Instant::now();
    let direction = pass4_direction(pool, &gamma_n);
    timed("pool.pass4_direction", t);
    let t = Instant::now();
    let integrand = pass5_integrand(&transmitted, &direction);
    timed("pool.pass5_integrand", t);
    let t = Instant::now();
    let convolutions = pass6_convolve(n, k, &integrand);
    timed("pool.pass6_convolution", t);
    CpuPasses { n, height, normals, gamma_n, transmitted, direction, integrand, convolutions, timings }
}
