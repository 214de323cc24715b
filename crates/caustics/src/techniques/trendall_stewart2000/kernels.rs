//! The Pass 6 convolution kernels (Sec. 4.1), computed at Init.
//!
//! Eq. 2 integrates, over the water surface, T cos(theta_i) P_down exp(-a (1 - (L_t . P)^2))
//! exp(-epsilon |P|), P from the surface point to the bottom point. With d >> h the vector P
//! depends on the offset x0 - x only, and the Gaussian is replaced by the exponentiated cosine
//! (L_t . P)^n, kept to first order in the components of L_t across the expansion axis:
//!
//!   (L_t . P)^n ~ (L_tz P_z)^(n-1) (L_tz P_z + n L_tx P_x + n L_ty P_y),
//!
//! a sum of three separable products, so E is a sum of three convolutions of F_j = L_s cos(theta_i)
//! T L_tz^(n-1) L_tj (Passes 3-5) with the kernels K_z = P_z^n P_down exp(-epsilon |P|) and
//! K_x, K_y = n P_z^(n-1) P_x,y P_down exp(-epsilon |P|) (times the texel area).
//!
//! The paper expands about the vertical, which suits light from overhead ("most accurate for
//! L_tz >> L_tx, L_ty"). Here the axis z is the direction light takes through flat water: the
//! vertical for overhead light, and for oblique light the same expansion about the refracted
//! direction (expanded about the vertical, L_tz^n would vanish for n = 4000). The kernel window
//! is then centred where that direction meets the bottom.

use super::fresnel::Interface;
use crate::scene::PoolSpec;
use glam::DVec3;

/// The expansion axes: `z` the direction light takes through flat water, `x` and `y` across it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Basis {
    pub x: DVec3,
    pub y: DVec3,
    pub z: DVec3,
}

impl Basis {
    /// The components of `v` along x, y, z.
    pub fn coords(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }
}

/// The interface of the pool's air and water.
pub fn interface(pool: &PoolSpec) -> Interface {
    Interface { n_i: pool.ior_air, n_t: pool.ior }
}

/// The expansion basis of `pool`: z along the light's direction in flat water.
pub fn basis(pool: &PoolSpec) -> Basis {
    let (z, _) = interface(pool).transmitted(pool.light_direction, DVec3::Y);
    let z = z.normalize();
    let x = (DVec3::X - z * z.x).normalize();
    Basis { x, y: z.cross(x), z }
}

/// The kernels of Pass 6 on an `n` x `n` grid: `side` x `side` taps centred `offset` texels
/// (x, z) from the receiver texel. Tap (a, b) holds the kernels for the surface texel at
/// (i - (a - r + offset.x), j - (b - r + offset.z)) of receiver texel (i, j), r = side / 2:
/// E(i, j) = sum over taps of F(surface texel) . K(tap).
#[derive(Debug, Clone, PartialEq)]
pub struct Kernels {
    pub side: usize,
    pub offset: [i32; 2],
    /// (K_x, K_y, K_z) per tap, row-major (b then a), in m^2 (the texel area is folded in).
    pub taps: Vec<[f64; 3]>,
}

impl Kernels {
    /// The (x, z) texel offset from the receiver texel to the surface texel of tap (a, b).
    pub fn tap_offset(&self, a: usize, b: usize) -> (i32, i32) {
        let r = (self.side / 2) as i32;
        (a as i32 - r + self.offset[0], b as i32 - r + self.offset[1])
    }
}

/// Where light through flat water lands, in texels from its surface texel (x, z).
pub fn landing_offset(pool: &PoolSpec, n: usize) -> [i32; 2] {
    let z = basis(pool).z;
    let texel = pool.side / n as f64;
    let along = pool.depth / -z.y;
    [(z.x * along / texel).round() as i32, (z.z * along / texel).round() as i32]
}

/// The kernels K_x, K_y, K_z for an `n` x `n` height field and `side` x `side` taps.
pub fn kernels(pool: &PoolSpec, n: usize, side: usize) -> Kernels {
    let b = basis(pool);
    let texel = pool.side / n as f64;
    let offset = landing_offset(pool, n);
    let r = (side / 2) as i32;
    let nexp = pool.exponent;
    let mut taps = Vec::with_capacity(side * side);
    for bj in 0..side {
        for ai in 0..side {
            // The surface point is at -offset from the receiver: P goes from it to the receiver.
            let dx = (ai as i32 - r + offset[0]) as f64 * texel;
            let dz = (bj as i32 - r + offset[1]) as f64 * texel;
            let p = DVec3::new(dx, -pool.depth, dz);
            let len = p.length();
            let c = b.coords(p / len);
            let down = pool.depth / len;
            let common = down * (-pool.extinction * len).exp() * texel * texel;
            if c.z <= 0.0 {
                taps.push([0.0; 3]);
                continue;
            }
            let pz_n1 = ((nexp - 1.0) * c.z.ln()).exp();
            taps.push([nexp * pz_n1 * c.x * common, nexp * pz_n1 * c.y * common, pz_n1 * c.z * common]);
        }
    }
    Kernels { side, offset, taps }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_basis_is_orthonormal_and_follows_snell() {
        let mut pool = crate::techniques::trendall_stewart2000::tests::canonical_pool();
        pool.light_direction = DVec3::new(0.5, -0.8660254037844386, 0.0);
        let b = basis(&pool);
        for (u, v) in [(b.x, b.y), (b.y, b.z), (b.z, b.x)] {
            assert!(u.dot(v).abs() < 1e-12 && (u.length() - 1.0).abs() < 1e-12);
        }
        // sin(theta_t) = sin(30 deg) / 1.333.
        assert!((b.z.x - 0.5 / 1.333).abs() < 1e-12 && b.z.y < 0.0);
        // 0.3 m down at that angle: 0.3 tan(theta_t) / (1/256) texels.
        let st: f64 = 0.5 / 1.333;
        let want = (0.3 * st / (1.0 - st * st).sqrt() * 256.0).round() as i32;
        assert_eq!(landing_offset(&pool, 256), [want, 0]);
        assert_eq!(want, 31);
    }

    #[test]
    fn overhead_kernels_are_symmetric_and_hold_the_lobe() {
        let pool = crate::techniques::trendall_stewart2000::tests::canonical_pool();
        let k = kernels(&pool, 256, 7);
        assert_eq!(k.offset, [0, 0]);
        let at = |a: usize, b: usize| k.taps[b * 7 + a];
        // K_z is even in both directions; K_x odd in x, even in z.
        assert!((at(1, 3)[2] - at(5, 3)[2]).abs() < 1e-18 && (at(3, 1)[2] - at(3, 5)[2]).abs() < 1e-18);
        assert!((at(1, 3)[0] + at(5, 3)[0]).abs() < 1e-18 && at(3, 3)[0] == 0.0);
        // The 7 x 7 kernel holds the lobe down to about 5% (the choice of a and n).
        let edge = at(6, 3)[2] / at(3, 3)[2];
        assert!((0.03..0.08).contains(&edge), "{edge}");
    }
}
