//! The faithful path's fixed-point arithmetic (Sec. 3.2): every function stored between passes is
//! an 8-bit UNORM value, "adjusted" by a scale and bias into [0, 1] (f~ = alpha f + beta, here
//! written f~ = (f - lo) / span), and every non-linear function of one variable is a 256-entry
//! 8-bit lookup table indexed by the 8-bit code of its argument, nearest entry, as the OpenGL 1.2
//! colour tables are (Sec. 4.1; the normal's is a 256 x 256 pixel texture).
//!
//! The scale and bias of each function come from bounds known beforehand (Sec. 3.2: "proper
//! scaling and biasing requires one to know the approximate bounds of computation"): the pool's
//! `height_range` and `slope_range`, pushed through Eq. 1, the Fresnel T and the kernels. A
//! product of an adjusted function f~ and an unadjusted g in [0, 1] keeps f's encoding,
//! (fg)~ = g f~ + (1 - g) beta, so the encodings of such f contain 0 (Sec. 3.2, Products).
//!
//! What the OpenGL 1.2 pipeline did with fixed functions between two 8-bit stores (scale and
//! bias, the colour matrix, colour-table lookups, the convolution, blending) the fragment
//! shaders do in float within one pass; what makes the path faithful is that every function
//! crosses from one pass to the next as an 8-bit code, and every non-linear function is an
//! 8-bit table indexed by an 8-bit code. The height field is evaluated per texel and stored once
//! (the paper's distance texture and per-impulse colour tables are not emulated).

use super::kernels::{basis, interface, Kernels};
use crate::scene::PoolSpec;
use glam::DVec3;

/// The 8-bit path stores E in [0, IRRADIANCE_RANGE x the largest flat-water E]: caustics focus
/// light to a few times flat water's irradiance (the float path's peaks: 1.3 to 1.6).
pub const IRRADIANCE_RANGE: f64 = 3.0;

/// f~ = (f - lo) / span.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Encoding {
    pub lo: f64,
    pub span: f64,
}

impl Encoding {
    /// The unadjusted encoding: f~ = f, for functions already in [0, 1].
    pub const UNADJUSTED: Encoding = Encoding { lo: 0.0, span: 1.0 };

    /// [lo, hi] widened by 1% of the span on each side.
    pub fn range(lo: f64, hi: f64) -> Encoding {
        let pad = 0.01 * (hi - lo).max(1e-12);
        Encoding { lo: lo - pad, span: hi - lo + 2.0 * pad }
    }

    /// [-m, m]: a signed function whose adjusted form can be multiplied by an unadjusted one.
    pub fn symmetric(m: f64) -> Encoding {
        Encoding::range(-m.abs().max(1e-12), m.abs().max(1e-12))
    }

    /// f~, clamped to [0, 1] as the pipeline clamps.
    pub fn encode(&self, v: f64) -> f64 {
        ((v - self.lo) / self.span).clamp(0.0, 1.0)
    }

    /// The 8-bit code of f (round to nearest).
    pub fn code(&self, v: f64) -> u8 {
        (self.encode(v) * 255.0).round() as u8
    }

    /// f from its 8-bit code.
    pub fn decode(&self, code: u8) -> f64 {
        self.lo + self.span * code as f64 / 255.0
    }

    /// The value a table entry `k` of 256 stands for.
    pub fn entry(&self, k: usize) -> f64 {
        self.lo + self.span * k as f64 / 255.0
    }
}

/// The scale and bias of every function the faithful path stores or looks up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adjustments {
    /// The height field (0.5 is the surface at rest, Sec. 4.1).
    pub height: Encoding,
    /// The discrete partial derivatives that index the normals' pixel texture.
    pub slope: Encoding,
    /// Pass 1: N (world x, y, z).
    pub normal: [Encoding; 3],
    /// cos(theta_i): the index of the Gamma and cos T tables.
    pub cos_i: Encoding,
    /// Pass 2: Gamma N (world x, y, z).
    pub gamma_n: [Encoding; 3],
    /// L_t in the expansion basis; its z indexes the (L_tz)^(n-1) table.
    pub lt: [Encoding; 3],
    /// Passes 4 and 5: L_t (L_tz)^(n-1) and F (x, y adjusted, z unadjusted).
    pub direction: [Encoding; 3],
    /// Pass 6: E_x, E_y, E_z and E.
    pub convolution: [Encoding; 4],
}

/// What flat water and every slope within `slope_range` give, for the bounds.
struct Sample {
    normal: DVec3,
    cos_i: f64,
    gamma_n: DVec3,
    lt: DVec3,
    direction: DVec3,
}

fn sample(pool: &PoolSpec, sx: f64, sz: f64) -> Sample {
    let it = interface(pool);
    let b = basis(pool);
    let normal = DVec3::new(-sx, 1.0, -sz).normalize();
    let cos_i = -pool.light_direction.dot(normal);
    let gamma_n = it.gamma(cos_i) * normal;
    let lt = b.coords(it.eta() * pool.light_direction + gamma_n);
    let w = if lt.z > 0.0 { ((pool.exponent - 1.0) * lt.z.ln()).exp() } else { 0.0 };
    Sample { normal, cos_i, gamma_n, lt, direction: lt * w }
}

/// Per component, [min, max] over `values`.
fn bounds(values: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    values.fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), v| (lo.min(v), hi.max(v)))
}

/// The encodings for `pool` with the Pass 6 kernels `k`: the bounds of each function over
/// every slope in [-slope_range, slope_range]^2.
pub fn adjustments(pool: &PoolSpec, k: &Kernels) -> Adjustments {
    let s = pool.slope_range;
    let steps = 64;
    let mut samples = vec![];
    for a in 0..=steps {
        for b in 0..=steps {
            let f = |t: usize| -s + 2.0 * s * t as f64 / steps as f64;
            samples.push(sample(pool, f(a), f(b)));
        }
    }
    let (nlo, nhi) = bounds(samples.iter().map(|x| x.normal));
    let (clo, chi) =
        samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| (l.min(x.cos_i), h.max(x.cos_i)));
    let (glo, ghi) = bounds(samples.iter().map(|x| x.gamma_n));
    let (llo, lhi) = bounds(samples.iter().map(|x| x.lt));
    let (dlo, dhi) = bounds(samples.iter().map(|x| x.direction));
    let sym = |lo: f64, hi: f64| Encoding::symmetric(lo.abs().max(hi.abs()));
    let direction = [sym(dlo.x, dhi.x), sym(dlo.y, dhi.y), Encoding::UNADJUSTED];
    // Pass 6: |E_j| <= max |F_j| sum |K_j|, F_j = L_s cos T (in [0, 1]) times the direction.
    let ksum = |c: usize| k.taps.iter().map(|t| t[c].abs()).sum::<f64>();
    let fmax = [direction[0].lo.abs(), direction[1].lo.abs(), 1.0];
    let (ex, ey, ez) = (fmax[0] * ksum(0), fmax[1] * ksum(1), fmax[2] * ksum(2));
    Adjustments {
        height: Encoding::symmetric(pool.height_range),
        slope: Encoding::symmetric(s),
        normal: [sym(nlo.x, nhi.x), Encoding::range(nlo.y, nhi.y), sym(nlo.z, nhi.z)],
        cos_i: Encoding::range(clo, chi.min(1.0)),
        gamma_n: [sym(glo.x, ghi.x), Encoding::range(glo.y, ghi.y), sym(glo.z, ghi.z)],
        lt: [Encoding::range(llo.x, lhi.x), Encoding::range(llo.y, lhi.y), Encoding::range(llo.z, lhi.z.min(1.0))],
        direction,
        // E itself is an irradiance: from 0 to a few times flat water's (whose E is at most
        // sum K_z); the dipole terms E_x, E_y are large but mostly cancel in the sum.
        convolution: [
            Encoding::symmetric(ex),
            Encoding::symmetric(ey),
            Encoding::range(0.0, ez),
            Encoding::range(0.0, IRRADIANCE_RANGE * ez),
        ],
    }
}

/// The normals' pixel texture (Pass 1): 256 x 256 RGBA8, texel (x code, z code) of the two
/// partial derivatives holding N~ (RGB).
pub fn pixel_texture(adj: &Adjustments) -> Vec<u8> {
    let mut out = Vec::with_capacity(256 * 256 * 4);
    for kz in 0..256 {
        for kx in 0..256 {
            let n = DVec3::new(-adj.slope.entry(kx), 1.0, -adj.slope.entry(kz)).normalize();
            out.extend_from_slice(&[adj.normal[0].code(n.x), adj.normal[1].code(n.y), adj.normal[2].code(n.z), 255]);
        }
    }
    out
}

/// The colour tables, 256 x 1 RGBA8: R = -Gamma and G = cos(theta_i) T(cos(theta_i)), indexed by
/// the code of cos(theta_i) (Passes 2-3); B = (L_tz)^(n-1), indexed by the code of L_tz
/// (Pass 4). All three are unadjusted functions in [0, 1].
pub fn colour_tables(pool: &PoolSpec, adj: &Adjustments) -> Vec<u8> {
    let it = interface(pool);
    let q = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let mut out = Vec::with_capacity(256 * 4);
    for k in 0..256 {
        let c = adj.cos_i.entry(k).clamp(0.0, 1.0);
        let z = adj.lt[2].entry(k);
        let w = if z > 0.0 { ((pool.exponent - 1.0) * z.min(1.0).ln()).exp() } else { 0.0 };
        out.extend_from_slice(&[q(-it.gamma(c)), q(c * it.transmittance(c)), q(w), 255]);
    }
    out
}
