//! The CPU side of Trendall & Stewart 2000 against closed forms written out here: a flat surface,
//! and the convolution against Eq. 2 evaluated directly as the exponent n grows.

use super::*;
use crate::scene::Scene;
use glam::DVec3;
use std::path::PathBuf;

fn scene(name: &str) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.toml"));
    Scene::load(&p).expect("shipped scene")
}

/// `scenes/pool_overhead.toml`'s pool.
pub(crate) fn canonical_pool() -> PoolSpec {
    scene("pool_overhead").pool.expect("a pool scene")
}

/// The textbook Fresnel transmittance, 1 - (R_s + R_p) / 2, and cos(theta_t).
fn textbook(n1: f64, n2: f64, ci: f64) -> (f64, f64) {
    let ct = (1.0 - (n1 / n2).powi(2) * (1.0 - ci * ci)).sqrt();
    let rs = ((n1 * ci - n2 * ct) / (n1 * ci + n2 * ct)).powi(2);
    let rp = ((n2 * ci - n1 * ct) / (n2 * ci + n1 * ct)).powi(2);
    (1.0 - 0.5 * (rs + rp), ct)
}

/// The refracted direction through flat water, written out: in the plane of incidence,
/// sin(theta_t) = sin(theta_i) n1 / n2.
fn refracted(pool: &PoolSpec) -> DVec3 {
    let l = pool.light_direction;
    let horizontal = DVec3::new(l.x, 0.0, l.z);
    let st = horizontal.length() * pool.ior_air / pool.ior;
    let dir = if horizontal.length() > 0.0 { horizontal.normalize() } else { DVec3::X };
    dir * st - DVec3::Y * (1.0 - st * st).sqrt()
}

/// E of flat water away from the walls, from Eq. 2 with the exponentiated cosine, summed over
/// the kernel window written out independently: L_s cos T sum (L_t . P)^n P_down e^(-eps |P|) dA.
fn flat_closed_form(pool: &PoolSpec, n: usize, side: usize) -> f64 {
    let ci = -pool.light_direction.y;
    let (t, _) = textbook(pool.ior_air, pool.ior, ci);
    let lt = refracted(pool);
    let texel = pool.side / n as f64;
    let centre =
        [(lt.x * pool.depth / -lt.y / texel).round() as i64, (lt.z * pool.depth / -lt.y / texel).round() as i64];
    let r = (side / 2) as i64;
    let mut sum = 0.0;
    for b in -r..=r {
        for a in -r..=r {
            let p = DVec3::new((centre[0] + a) as f64 * texel, -pool.depth, (centre[1] + b) as f64 * texel);
            let c = lt.dot(p.normalize());
            sum += c.powf(pool.exponent) * (pool.depth / p.length()) * (-pool.extinction * p.length()).exp();
        }
    }
    pool.light_radiance * ci * t * sum * texel * texel
}

/// Texels whose kernel window and direct lobe lie inside the pool (`margin` texels from every
/// wall, around where light from them lands).
fn interior(n: usize, margin: usize, offset: [i32; 2]) -> Vec<usize> {
    let mut out = vec![];
    for j in 0..n {
        for i in 0..n {
            let (si, sj) = (i as i64 - offset[0] as i64, j as i64 - offset[1] as i64);
            let m = margin as i64;
            if si >= m
                && sj >= m
                && si < n as i64 - m
                && sj < n as i64 - m
                && i >= margin
                && j >= margin
                && i < n - margin
                && j < n - margin
            {
                out.push(j * n + i);
            }
        }
    }
    out
}

#[test]
fn a_flat_surface_gives_the_closed_form_and_a_ratio_of_one() {
    for name in ["pool_overhead", "pool_oblique"] {
        let mut pool = scene(name).pool.expect("pool");
        pool.impulses.clear();
        let n = 64;
        let (wavy, flat) = reference(&pool, n, 7).expect("reference");
        let want = flat_closed_form(&pool, n, 7);
        let k = kernels::kernels(&pool, n, 7);
        let e = flat.irradiance();
        for &i in &interior(n, 4, k.offset) {
            assert!((e[i] / want - 1.0).abs() < 1e-9, "{name}: texel {i}: {} vs {want}", e[i]);
        }
        let ratio = relative(&wavy.irradiance(), &e);
        assert!(ratio.iter().zip(&e).all(|(&r, &f)| f == 0.0 || (r - 1.0).abs() < 1e-12), "{name}");
    }
}

/// The direct evaluation and the convolution (with kernels that hold the whole lobe) on flat
/// water: what differs is the Gaussian against the exponentiated cosine (relative ~1/a) and P's
/// direction over the lobe; both vanish as n = 2a grows.
#[test]
fn direct_and_convolution_agree_better_as_n_grows_on_flat_water() {
    for name in ["pool_overhead", "pool_oblique"] {
        let mut pool = scene(name).pool.expect("pool");
        pool.impulses.clear();
        let n = 96;
        let mut last = f64::INFINITY;
        for a in [500.0, 2000.0, 8000.0] {
            pool.scattering = a;
            pool.exponent = 2.0 * a;
            // The lobe's sigma at the bottom, in texels; the kernel holds 6 sigma each way.
            let sigma = pool.depth / (2.0 * a).sqrt() / (pool.side / n as f64);
            let side = 2 * (6.0 * sigma / (-refracted(&pool).y).powi(2)).ceil() as usize + 1;
            let (_, flat) = reference(&pool, n, side).expect("reference");
            let ls = light_radiance(&pool, n).expect("L_s");
            let direct = direct::direct_irradiance(&pool, n, &vec![0.0; n * n], &ls);
            let k = kernels::kernels(&pool, n, side);
            let conv = flat.irradiance();
            let worst = interior(n, side / 2 + 2, k.offset)
                .iter()
                .map(|&i| (conv[i] / direct[i] - 1.0).abs())
                .fold(0.0, f64::max);
            // Stated: within 1.5 / a (measured: about 1 / a at a = 500 and 2000 in both scenes).
            println!("{name}: a = {a}: kernel {side}, |conv / direct - 1| <= {worst:.2e} (bound {:.1e})", 1.5 / a);
            assert!(worst < 1.5 / a, "{name}: a = {a}: {worst}");
            assert!(worst < last, "{name}: the error did not shrink as n grew");
            last = worst;
        }
    }
}

/// On the canonical wave the convolution's first-order expansion is the main error: the
/// exponentiated cosine's tilt term n L_tx P_x is not small where the waves tilt L_t by more
/// than the lobe's width (n tau^2 ~ 3 at the wavefront), so the convolution dims the steep
/// slopes by L_tz^n and misplaces their light (see results/trendall_stewart2000/README.md).
/// Stated: the measured relative RMS (0.167 overhead, 0.157 oblique) with about 20% margin.
#[test]
fn the_convolution_against_eq_2_on_the_canonical_waves() {
    for (name, stated) in [("pool_overhead", 0.2), ("pool_oblique", 0.2)] {
        let s = scene(name);
        let pool = s.pool.expect("pool");
        let n = 256;
        let (wavy, flat) = reference(&pool, n, 7).expect("reference");
        let ls = light_radiance(&pool, n).expect("L_s");
        let h = water_surface::height_field(&pool, n);
        let direct = direct::direct_irradiance(&pool, n, &h, &ls);
        let direct_flat = direct::direct_irradiance(&pool, n, &vec![0.0; n * n], &ls);
        let a = relative(&wavy.irradiance(), &flat.irradiance());
        let b = relative(&direct, &direct_flat);
        // Where flat water lights the bottom in both (as `causticlab compare --region lit`).
        let (ef, df) = (flat.irradiance(), &direct_flat);
        let keep: Vec<usize> = (0..n * n).filter(|&i| ef[i] > 0.0 && df[i] > 0.0).collect();
        let pick = |v: &[f64]| keep.iter().map(|&i| v[i]).collect::<Vec<_>>();
        let rms = relative_rms(&pick(&a), &pick(&b));
        let flux = |v: &[f64]| v.iter().sum::<f64>();
        println!(
            "{name}: relative RMS of E / E_flat, convolution vs Eq. 2: {rms:.4}; flux vs flat water: convolution {:.4}, Eq. 2 {:.4}",
            flux(&wavy.irradiance()) / flux(&flat.irradiance()),
            flux(&direct) / flux(&direct_flat)
        );
        assert!(rms < stated, "{name}: {rms}");
        // Eq. 2 moves light about but keeps it (up to Fresnel on tilted facets): the flux stays.
        assert!((flux(&direct) / flux(&direct_flat) - 1.0).abs() < 0.01, "{name}");
    }
}
