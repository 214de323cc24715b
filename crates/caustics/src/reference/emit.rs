//! Photon emission: a small seedable PCG32, bounding spheres of the specular objects and
//! uniform sampling of the cone of directions from a light that subtends such a sphere.

use glam::DVec3;

/// SplitMix64 finaliser, used to derive independent seeds.
#[inline]
pub fn splitmix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = x;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// PCG32 (XSH-RR, O'Neill 2014): 64-bit state, 32-bit output, selectable stream.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

impl Pcg32 {
    const MUL: u64 = 6364136223846793005;

    pub fn new(seed: u64, stream: u64) -> Pcg32 {
        let mut rng = Pcg32 { state: 0, inc: (stream << 1) | 1 };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(seed);
        rng.next_u32();
        rng
    }

    /// The stream for one chunk of photons: a pure function of `(seed, keys)`, so results
    /// do not depend on which thread runs the chunk.
    pub fn for_chunk(seed: u64, keys: &[u64]) -> Pcg32 {
        let mut h = splitmix64(seed);
        for &k in keys {
            h = splitmix64(h ^ k);
        }
        Pcg32::new(h, splitmix64(h ^ 0xC0FF_EE00_D15E_A5E5))
    }

    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(Self::MUL).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in [0, 1) with 53 random bits.
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        let hi = (self.next_u32() >> 5) as u64; // 27 bits
        let lo = (self.next_u32() >> 6) as u64; // 26 bits
        ((hi << 26) | lo) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// A cone of directions from a light position towards a sphere (or the full sphere of
/// directions when the light is inside it).
#[derive(Clone, Copy, Debug)]
pub struct Cone {
    pub axis: DVec3,
    /// Cosine of the half-angle; -1 = all directions.
    pub cos_half: f64,
    tangent: DVec3,
    bitangent: DVec3,
}

impl Cone {
    /// The cone from `apex` subtending the sphere (`centre`, `radius`): half-angle
    /// `asin(R/d)`; the whole sphere of directions when `d <= R`.
    pub fn towards_sphere(apex: DVec3, centre: DVec3, radius: f64) -> Cone {
        let to = centre - apex;
        let d = to.length();
        let (axis, cos_half) = if d <= radius || d == 0.0 {
            (DVec3::Y, -1.0)
        } else {
            let s = radius / d;
            (to / d, (1.0 - s * s).max(0.0).sqrt())
        };
        let (tangent, bitangent) = axis.any_orthonormal_pair();
        Cone { axis, cos_half, tangent, bitangent }
    }

    /// Solid angle `2π(1 − cos α)`.
    pub fn solid_angle(&self) -> f64 {
        2.0 * std::f64::consts::PI * (1.0 - self.cos_half)
    }

    /// Whether `dir` (unit) lies inside the cone.
    #[inline]
    pub fn contains(&self, dir: DVec3) -> bool {
        dir.dot(self.axis) >= self.cos_half
    }

    /// A direction uniformly distributed (in solid angle) over the cone.
    #[inline]
    pub fn sample(&self, rng: &mut Pcg32) -> DVec3 {
        let u1 = rng.next_f64();
        let u2 = rng.next_f64();
        let cos_t = 1.0 - u1 * (1.0 - self.cos_half);
        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
        let phi = 2.0 * std::f64::consts::PI * u2;
        (self.tangent * (sin_t * phi.cos()) + self.bitangent * (sin_t * phi.sin()) + self.axis * cos_t).normalize()
    }
}

/// Bounding sphere of a point set: centre of the bounding box, radius to the farthest
/// point (in `f64`).
pub fn bounding_sphere(points: &[glam::Vec3]) -> (DVec3, f64) {
    if points.is_empty() {
        return (DVec3::ZERO, 0.0);
    }
    let (lo, hi) = points.iter().fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
        (lo.min(p.as_dvec3()), hi.max(p.as_dvec3()))
    });
    let c = 0.5 * (lo + hi);
    let r = points.iter().map(|p| (p.as_dvec3() - c).length()).fold(0.0, f64::max);
    (c, r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rng_is_deterministic_uniform_and_stream_dependent() {
        let mut a = Pcg32::for_chunk(7, &[1, 2]);
        let mut b = Pcg32::for_chunk(7, &[1, 2]);
        let mut c = Pcg32::for_chunk(7, &[1, 3]);
        let va: Vec<u32> = (0..16).map(|_| a.next_u32()).collect();
        let vb: Vec<u32> = (0..16).map(|_| b.next_u32()).collect();
        let vc: Vec<u32> = (0..16).map(|_| c.next_u32()).collect();
        assert_eq!(va, vb);
        assert_ne!(va, vc);
        let mut r = Pcg32::new(42, 54);
        let n = 200_000;
        let (mut sum, mut sum2) = (0.0, 0.0);
        for _ in 0..n {
            let x = r.next_f64();
            assert!((0.0..1.0).contains(&x));
            sum += x;
            sum2 += x * x;
        }
        assert!((sum / n as f64 - 0.5).abs() < 0.005);
        assert!((sum2 / n as f64 - 1.0 / 3.0).abs() < 0.005);
    }

    #[test]
    fn cone_samples_stay_inside_and_are_uniform_in_solid_angle() {
        let apex = DVec3::new(0.0, 6.0, 0.0);
        let cone = Cone::towards_sphere(apex, DVec3::new(0.3, 1.0, -0.2), 0.5);
        let mut rng = Pcg32::new(1, 1);
        let n = 100_000;
        let mut inner = 0;
        // Inner cone of half the solid angle: cos = 1 - (1 - cos_half)/2.
        let cos_mid = 1.0 - 0.5 * (1.0 - cone.cos_half);
        for _ in 0..n {
            let d = cone.sample(&mut rng);
            assert!((d.length() - 1.0).abs() < 1e-12);
            assert!(d.dot(cone.axis) >= cone.cos_half - 1e-12);
            if d.dot(cone.axis) >= cos_mid {
                inner += 1;
            }
        }
        let frac = inner as f64 / n as f64;
        assert!((frac - 0.5).abs() < 0.01, "{frac}");
        let inside = Cone::towards_sphere(DVec3::ZERO, DVec3::X * 0.1, 1.0);
        assert!((inside.solid_angle() - 4.0 * std::f64::consts::PI).abs() < 1e-12);
    }
}
