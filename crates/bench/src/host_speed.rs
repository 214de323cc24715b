//! How fast the host's CPU ran when each cell started: a fixed single-threaded loop (integer
//! hashing and a dependent floating-point chain, the same work every time) timed before the
//! cell's frames, the best of three tries.
//!
//! A virtual machine's speed can drift by tens of percent over minutes with no steal and no
//! other process to show for it (a neighbour on the physical host, frequency scaling). On a
//! software rasteriser such as lavapipe every pass slows with it, so two cells measured far apart
//! may differ for no reason of their own; the table's header gives the fastest and slowest probe
//! so that a reader can tell (`crate::report`).

use std::hint::black_box;
use std::time::Instant;

/// Iterations of the loop: about 13 ms on the 2-core Xeon VM of the lavapipe tables.
const ITERATIONS: u64 = 4_000_000;

/// Milliseconds of the fixed loop, best of three.
pub fn probe_ms() -> f64 {
    (0..3).map(|_| once_ms()).fold(f64::INFINITY, f64::min)
}

fn once_ms() -> f64 {
    let t = Instant::now();
    let mut h: u64 = black_box(0x9e37_79b9_7f4a_7c15);
    let mut x: f64 = black_box(1.0);
    for i in 0..ITERATIONS {
        h ^= h << 13;
        h ^= h >> 7;
        h ^= h << 17;
        x = x * 0.999_999_9 + (h & 0xff) as f64 * 1e-9 + i as f64 * 1e-15;
    }
    black_box((h, x));
    t.elapsed().as_secs_f64() * 1e3
}

/// (fastest, median, slowest) of the probes, where there are any.
pub fn summary(probes: &[f64]) -> Option<(f64, f64, f64)> {
    let mut v: Vec<f64> = probes.iter().copied().filter(|p| p.is_finite() && *p > 0.0).collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    Some((v[0], v[v.len() / 2], v[v.len() - 1]))
}

/// The slowest probe over the fastest beyond which the header warns.
pub const DRIFT_WARNING: f64 = 1.15;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_probe_times_its_work_and_the_summary_orders_it() {
        let p = probe_ms();
        assert!(p.is_finite() && p > 0.0, "{p}");
        assert_eq!(summary(&[3.0, 1.0, 2.0, f64::NAN]), Some((1.0, 2.0, 3.0)));
        assert_eq!(summary(&[]), None);
    }
}
