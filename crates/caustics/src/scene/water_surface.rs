//! The water surface of Sec. 4.3: a height field on the square pool, the sum of the waves of
//! impulses ("dropping a pebble"), each with its four reflections through the pool walls.
//!
//! h(t, d) = A exp(-beta (f(t) - d)) exp(-alpha t) sin(K d - omega t) behind the wavefront
//! (d < f(t) = (omega / K) t) and 0 ahead of it, t the time since the impulse and d the distance
//! from it. The paper evaluates it with a distance texture T and a colour table holding one row
//! of h; the GPU pass (`height_field.frag`) evaluates the same function per texel.

use super::{PoolSpec, Wave};
use glam::DVec2;

/// One source of waves: an impulse, or its mirror image through a wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveSource {
    pub position: DVec2,
    /// Time since the impulse, s (> 0).
    pub age: f64,
}

/// h(t, d) of Sec. 4.3: the height a wave of age `t` has at distance `d` from its impulse.
pub fn wave_height(w: &Wave, t: f64, d: f64) -> f64 {
    let front = w.angular_frequency / w.wave_number * t;
    if t <= 0.0 || d >= front {
        return 0.0;
    }
    w.amplitude
        * (-w.distance_damping * (front - d)).exp()
        * (-w.time_damping * t).exp()
        * (w.wave_number * d - w.angular_frequency * t).sin()
}

/// The impulse at `p` mirrored through each wall of a pool of side `side` centred on the origin:
/// +x, -x, +z, -z.
pub fn reflections(p: DVec2, side: f64) -> [DVec2; 4] {
    [
        DVec2::new(side - p.x, p.y),
        DVec2::new(-side - p.x, p.y),
        DVec2::new(p.x, side - p.y),
        DVec2::new(p.x, -side - p.y),
    ]
}

/// The wave sources at the pool's time: every impulse that has happened (and, with
/// `wall_reflections`, its four reflections), in scene order, each impulse before its images.
pub fn sources(pool: &PoolSpec) -> Vec<WaveSource> {
    let mut out = vec![];
    for imp in &pool.impulses {
        let age = pool.time - imp.start;
        if age <= 0.0 {
            continue;
        }
        out.push(WaveSource { position: imp.position, age });
        if pool.wall_reflections {
            for r in reflections(imp.position, pool.side) {
                out.push(WaveSource { position: r, age });
            }
        }
    }
    out
}

/// The surface height at (x, z), m.
pub fn height_at(w: &Wave, sources: &[WaveSource], x: f64, z: f64) -> f64 {
    let p = DVec2::new(x, z);
    sources.iter().map(|s| wave_height(w, s.age, p.distance(s.position))).sum()
}

/// The centre of texel `i` of an `n`-texel side across the pool: -side/2 + (i + 0.5) side / n.
pub fn texel_centre(pool: &PoolSpec, n: usize, i: usize) -> f64 {
    -pool.half() + (i as f64 + 0.5) * pool.side / n as f64
}

/// The height field at the pool's time on an `n` x `n` grid over the pool, texel (i, j) at
/// (x_i, z_j), row-major (row j at z_j, row 0 at z = -side/2).
pub fn height_field(pool: &PoolSpec, n: usize) -> Vec<f64> {
    let src = sources(pool);
    let mut h = vec![0.0; n * n];
    for j in 0..n {
        let z = texel_centre(pool, n, j);
        for i in 0..n {
            h[j * n + i] = height_at(&pool.wave, &src, texel_centre(pool, n, i), z);
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wave() -> Wave {
        Wave {
            amplitude: 0.005,
            wave_number: std::f64::consts::TAU / 0.1,
            angular_frequency: std::f64::consts::TAU * 1.25,
            time_damping: 0.3,
            distance_damping: 10.0,
        }
    }

    #[test]
    fn zero_ahead_of_the_front_and_continuous_at_it() {
        let w = wave();
        let t = 2.4;
        let front = w.angular_frequency / w.wave_number * t;
        assert!((front - 0.3).abs() < 1e-12);
        assert_eq!(wave_height(&w, t, front + 1e-9), 0.0);
        assert!(wave_height(&w, t, front - 1e-9).abs() < 1e-9);
        assert_eq!(wave_height(&w, 0.0, 0.0), 0.0);
        // A quarter wavelength behind the front: the sine is -1 there.
        let d = front - 0.025;
        let want = -0.005 * (-10.0f64 * 0.025).exp() * (-0.3f64 * t).exp();
        assert!((wave_height(&w, t, d) - want).abs() < 1e-15);
    }

    #[test]
    fn reflections_are_the_mirror_images_through_the_walls() {
        let r = reflections(DVec2::new(0.3, 0.1), 1.0);
        assert_eq!(r, [DVec2::new(0.7, 0.1), DVec2::new(-1.3, 0.1), DVec2::new(0.3, 0.9), DVec2::new(0.3, -1.1)]);
        // Each image is as far from its wall as the impulse.
        assert!(((r[0].x - 0.5) - (0.5 - 0.3)).abs() < 1e-12);
        assert!(((-0.5 - r[1].x) - (0.3 + 0.5)).abs() < 1e-12);
    }
}
