//! Photon batching under a memory limit (Wyman & Nichols 2009 Sec. 4.3): "We adaptively
//! generate photons breadth-first until we exceed a user-defined memory limit. We then split
//! photons into independent batches. Batches are processed one at a time, refining photons and
//! splatting them into the caustic map before continuing."
//!
//! Nothing is read back between steps, so the split is planned when the buffers are made, for
//! the worst case (every cluster touching the refractor): the traversal goes breadth-first down
//! to the deepest level B whose lists, with those one batch needs below it, fit in the limit;
//! the pending clusters of level B are then taken S at a time, each batch refined down to the
//! last level and splatted before the next. A batch beyond the clusters that are actually
//! pending is empty (its dispatches and draws find no work). The photon storage is every
//! buffer whose size follows from the photon count: the lists of pending clusters, a batch's
//! input, the cluster hits (xfb, max-error) and the output photons, with their counters; it is
//! all allocated at once, so its total is its peak.

use super::photon::{CLUSTER_BYTES, HITS_BYTES, PHOTON_BYTES};
use crate::techniques::wyman_nichols2009::settings::{tests_convergence, Metric, TOP_PHOTONS};
use vkcore::compaction::COUNTER_BYTES;

/// Passes of a frame left to the rest of it (the eye render, shadow maps, and per light its
/// receiver positions, geometry buffers, up to four refractors' own and about a dozen coverage
/// levels: under 20 per light, at most 4 lights): the batches of every light share what remains
/// of `vkcore::MAX_PASSES`.
pub const OTHER_PASSES: u32 = 160;

/// Passes one light's traversal records with breadth-first levels 0..B (exclusive) and
/// `batches` batches of levels B..=L: at most four per step (xfb max-error: three kernels and
/// the counts; compute: the kernel, the counter's finalize and the counts), and per batch its
/// input, reset, the photons' finalize and the splat (up to three passes).
fn passes(finest: u32, b: u32, batches: u32) -> u64 {
    let per_batch = 6 + 4 * (finest - b + 1) as u64;
    2 + 4 * b as u64 + 6 + batches as u64 * per_batch
}

/// How a traversal is split, and the capacities of its buffers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BatchPlan {
    /// B: the last level traversed breadth-first for all clusters at once.
    pub breadth: u32,
    /// S: the clusters of level B per batch.
    pub batch: u32,
    /// Batches (1: no batching; then B is the last level and one batch is all of it).
    pub batches: u32,
    /// Capacity of each level's list of pending clusters (levels 0 to L).
    pub clusters: Vec<u32>,
    /// Capacity of the cluster hits (0: none; xfb path with max-error only).
    pub hits: u32,
    /// Capacity of the output photons.
    pub photons: u32,
}

/// The clusters of level k: (32 × 2^k)².
fn clusters_at(k: u32) -> u64 {
    let side = ((TOP_PHOTONS / 2) as u64) << k;
    side * side
}

/// Bytes of a stream of `capacity` elements of `bytes` and its counter, as vkcore allocates
/// them (each buffer rounded up to 16 bytes).
pub fn stream_bytes(capacity: u32, bytes: u64) -> u64 {
    let buffer = |b: u64| b.max(16).div_ceil(16) * 16;
    buffer(capacity.max(1) as u64 * bytes) + buffer(COUNTER_BYTES)
}

impl BatchPlan {
    /// The most passes this plan's traversal records for one light (levels, batches and their
    /// splats; what [`plan`] counts against each light's share of `vkcore::MAX_PASSES`).
    pub fn traversal_passes(&self) -> u64 {
        passes(self.clusters.len() as u32 - 1, self.breadth, self.batches)
    }

    /// Whether the traversal is split into batches.
    pub fn batched(&self) -> bool {
        self.batches > 1
    }

    /// The photon storage the plan allocates, bytes: every list, the batch input, the hits and
    /// the photons, with their counters (and the unused output of the last step).
    pub fn storage_bytes(&self) -> u64 {
        let lists: u64 = self.clusters.iter().map(|&c| stream_bytes(c, CLUSTER_BYTES)).sum();
        let batch_input = if self.batched() { stream_bytes(self.batch, CLUSTER_BYTES) } else { 0 };
        let hits = if self.hits > 0 { stream_bytes(self.hits, HITS_BYTES) } else { 0 };
        lists + batch_input + hits + stream_bytes(self.photons, PHOTON_BYTES) + stream_bytes(1, CLUSTER_BYTES)
    }
}

/// The plan without a limit: everything breadth-first, one batch.
pub fn unbatched(finest: u32, metric: Metric, xfb: bool) -> BatchPlan {
    let converging = (0..=finest).any(|k| tests_convergence(metric, k));
    let last = clusters_at(finest) as u32;
    BatchPlan {
        breadth: finest,
        batch: last,
        batches: 1,
        clusters: (0..=finest).map(|k| clusters_at(k) as u32).collect(),
        hits: if xfb && converging { last } else { 0 },
        photons: 4 * last,
    }
}

/// The plan with breadth-first levels 0..=B and batches of S clusters of level B.
fn with_batches(finest: u32, metric: Metric, xfb: bool, b: u32, s: u32) -> BatchPlan {
    let converging = |k: u32| tests_convergence(metric, k);
    let below = |k: u32| 1u64 << (2 * (k - b));
    let mut clusters: Vec<u32> = (0..=b).map(|k| clusters_at(k) as u32).collect();
    clusters.extend((b + 1..=finest).map(|k| (s as u64 * below(k)) as u32));
    // The breadth-first steps may emit converged clusters (into the photons, splatted before
    // the first batch) and need hits for them; a batch's steps B..L need their own.
    let breadth_emits: u64 = (0..b).filter(|&k| converging(k)).map(clusters_at).sum();
    let batch_photons = s as u64 * below(finest) * 4;
    let hits = if xfb && (0..=finest).any(converging) {
        let breadth = (0..b).filter(|&k| converging(k)).map(clusters_at).max().unwrap_or(0);
        breadth.max(s as u64 * below(finest))
    } else {
        0
    };
    BatchPlan {
        breadth: b,
        batch: s,
        batches: clusters_at(b).div_ceil(s as u64) as u32,
        clusters,
        hits: hits as u32,
        photons: batch_photons.max(breadth_emits) as u32,
    }
}

pub use crate::techniques::wyman_nichols2009::settings::MAX_BATCHES;

/// The plan for photon storage of at most `limit` bytes (None: no limit) in at least
/// `least_batches` batches (`photon_batches`, Fig. 8) for `lights` lights: the deepest
/// breadth-first level that leaves room for batches of at least one cluster, with the largest
/// batch that fits and gives at least `least_batches` batches, in no more batches than one frame
/// can record (each light's share of `vkcore::MAX_PASSES`). An error (naming what it would
/// take) when no plan fits.
pub fn plan(
    finest: u32,
    metric: Metric,
    xfb: bool,
    limit: Option<u64>,
    least_batches: u32,
    lights: u32,
) -> Result<BatchPlan, String> {
    let budget = (vkcore::MAX_PASSES - OTHER_PASSES) as u64 / lights.max(1) as u64;
    let whole = unbatched(finest, metric, xfb);
    let least = least_batches.max(1);
    if least == 1 && limit.is_none_or(|limit| whole.storage_bytes() <= limit) {
        return Ok(whole);
    }
    let limit_or_max = limit.unwrap_or(u64::MAX);
    let mut smallest = u64::MAX;
    for b in (0..=finest).rev() {
        let fits = |s: u32| with_batches(finest, metric, xfb, b, s).storage_bytes() <= limit_or_max;
        smallest = smallest.min(with_batches(finest, metric, xfb, b, 1).storage_bytes());
        if !fits(1) {
            continue;
        }
        // The largest batch that fits (storage grows with the batch) and gives at least `least`
        // batches, as even as can be: C / n clusters each (rounded up), or, where that rounding
        // leaves fewer than n batches (n beyond about the square root of C), the largest s with
        // ceil(C / s) >= n, which is s <= (C - 1) / (n - 1).
        let c = clusters_at(b);
        let n = least as u64;
        let even = c.div_ceil(n);
        let most = if n == 1 || c.div_ceil(even) >= n { even } else { ((c - 1) / (n - 1)).max(1) };
        let (mut lo, mut hi) = (1u32, most.min(u32::MAX as u64) as u32);
        while lo < hi {
            let mid = lo + (hi - lo).div_ceil(2);
            if fits(mid) {
                lo = mid;
            } else {
                hi = mid - 1;
            }
        }
        let p = with_batches(finest, metric, xfb, b, lo);
        if p.batches >= least && passes(finest, b, p.batches) <= budget {
            return Ok(p);
        }
    }
    let what = match limit {
        Some(limit) => format!(
            "{:.3} MiB cannot hold the traversal of {}² photons in at least {least} batch(es): batches of one cluster \
             need at least {:.3} MiB, and",
            limit as f64 / MIB,
            TOP_PHOTONS << finest,
            smallest as f64 / MIB,
        ),
        None => format!("{least} batches cannot split the traversal of {}² photons:", TOP_PHOTONS << finest),
    };
    Err(format!(
        "{what} the worst case ({:.1} MiB unbatched) must fit in the batches one frame can record ({budget} passes \
         per light)",
        whole.storage_bytes() as f64 / MIB
    ))
}

const MIB: f64 = 1024.0 * 1024.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plans_fit_their_limit_and_cover_every_cluster() {
        // A limit too small is refused (`a_limit_too_small_...`); count the plans checked.
        let (mut checked, mut refused) = (0, 0);
        for finest in [0u32, 2, 3, 5, 8] {
            for metric in Metric::ALL {
                for xfb in [false, true] {
                    let whole = unbatched(finest, *metric, xfb);
                    assert_eq!(whole.photons as u64, (64u64 << finest).pow(2), "every photon of the last level");
                    assert_eq!(plan(finest, *metric, xfb, None, 1, 1), Ok(whole.clone()));
                    assert_eq!(plan(finest, *metric, xfb, Some(whole.storage_bytes()), 1, 1), Ok(whole.clone()));
                    for divisor in [2u64, 3, 7, 50, 1000] {
                        let limit = whole.storage_bytes() / divisor;
                        let Ok(p) = plan(finest, *metric, xfb, Some(limit), 1, 2) else {
                            refused += 1;
                            continue;
                        };
                        checked += 1;
                        let label = format!("L {finest} {metric} xfb {xfb} limit {limit}");
                        assert!(p.storage_bytes() <= limit, "{label}: {p:?} needs {}", p.storage_bytes());
                        assert!(p.batched(), "{label}: not batched");
                        assert!(passes(finest, p.breadth, p.batches) <= (vkcore::MAX_PASSES - OTHER_PASSES) as u64 / 2);
                        assert!(p.batch as u64 * p.batches as u64 >= clusters_at(p.breadth), "{label}: {p:?}");
                        assert!(
                            (p.batches as u64 - 1) * (p.batch as u64) < clusters_at(p.breadth),
                            "{label}: idle batch"
                        );
                        // A batch's subtree fits its lists: 4 children per cluster per level.
                        for k in p.breadth + 1..=finest {
                            assert_eq!(p.clusters[k as usize] as u64, p.batch as u64 * 4u64.pow(k - p.breadth));
                        }
                        assert!(p.photons as u64 >= p.batch as u64 * 4u64.pow(finest - p.breadth + 1));
                    }
                }
            }
        }
        assert!(checked > refused, "{checked} plans checked, {refused} limits refused");
    }

    #[test]
    fn least_batches_give_that_many_batches_of_every_cluster() {
        let mut limited = 0;
        for finest in [0u32, 2, 4, 6] {
            for metric in Metric::ALL {
                for xfb in [false, true] {
                    let whole = unbatched(finest, *metric, xfb);
                    for n in [1u32, 2, 3, 4, 8, 16, 17] {
                        let label = format!("L {finest} {metric} xfb {xfb} {n} batches");
                        let p = plan(finest, *metric, xfb, None, n, 1).expect(&label);
                        // Exactly n: 32² clusters and more at level B, n ≤ 32 (n² < clusters + n).
                        assert_eq!(p.batches, n, "{label}: {p:?}");
                        assert_eq!(p.breadth, finest, "{label}: batches split the last level's clusters");
                        let pending = (32u64 << p.breadth).pow(2);
                        assert!(p.batch as u64 * n as u64 >= pending, "{label}: clusters left out");
                        assert!((n as u64 - 1) * (p.batch as u64) < pending, "{label}: idle batch");
                        // Under a limit that needs more, more.
                        let limit = whole.storage_bytes() / 8;
                        if let Ok(q) = plan(finest, *metric, xfb, Some(limit), n, 1) {
                            assert!(q.batches >= n && q.storage_bytes() <= limit, "{label} under {limit} B: {q:?}");
                            limited += 1;
                        }
                    }
                }
            }
        }
        assert!(limited > 0, "no plan under a limit was checked");
        // More batches than the square root of the clusters: at least n, none idle.
        for n in [33u32, 100, 200, 256] {
            let p = plan(0, Metric::MaxTraversal, false, None, n, 1).unwrap_or_else(|e| panic!("{n} batches: {e}"));
            assert!(p.batches >= n && (p.batches as u64 - 1) * (p.batch as u64) < 1024, "{n} batches: {p:?}");
            assert!(p.batch as u64 * p.batches as u64 >= 1024, "{n} batches: clusters left out: {p:?}");
        }
        let err = plan(0, Metric::MaxTraversal, false, None, 4096, 1).unwrap_err();
        assert!(err.contains("4096 batches"), "{err}");
    }

    #[test]
    fn a_limit_too_small_is_an_error_naming_what_it_takes() {
        let err = plan(8, Metric::MaxTraversal, false, Some(1024), 1, 1).unwrap_err();
        assert!(err.contains("16384²") && err.contains("at least"), "{err}");
        // 16384² photons (8 GiB unbatched) within 64 MiB, batched (planned for the worst case:
        // the paper's 16 MiB held its data-dependent batches, Fig. 8).
        let p = plan(8, Metric::MaxError, false, Some(64 << 20), 1, 1).expect("a plan");
        assert!(p.batched() && p.storage_bytes() <= 64 << 20, "{p:?}");
        assert!(plan(8, Metric::MaxError, false, Some(16 << 20), 1, 1).is_err(), "16 MiB: too many worst-case batches");
    }

    /// The batch count need not grow with the photons (plausibility rule g marks it in
    /// `wyman_nichols2009_adaptive`): under 96 MiB the compute path's max-traversal plan
    /// batches 8192² from level 7 (198 batches), but at 16384² batches of level 7 fit the 3,936
    /// passes a light may record only with 60,350 clusters or more each (278 batches), which
    /// 96 MiB cannot hold, so it batches from level 6: 115 batches, each refined two levels.
    #[test]
    fn the_pass_budget_moves_16384s_batches_up_a_level_so_there_are_fewer() {
        let limit = 96 * 1024 * 1024;
        let at_8192 = plan(7, Metric::MaxTraversal, false, Some(limit), 1, 1).unwrap();
        let at_16384 = plan(8, Metric::MaxTraversal, false, Some(limit), 1, 1).unwrap();
        assert_eq!((at_8192.breadth, at_8192.batches), (7, 198));
        assert_eq!((at_16384.breadth, at_16384.batches), (6, 115));
        let budget = (vkcore::MAX_PASSES - OTHER_PASSES) as u64;
        assert_eq!(budget, 3_936);
        // Level 7 of 16384² (32 x 2^7 = 4096² clusters) in batches of s: 278 batches fit the
        // budget, 279 do not; s = 60,350 is the smallest that gives 278.
        let level7 = clusters_at(7);
        assert_eq!(level7.div_ceil(60_350), 278);
        assert!(passes(8, 7, 278) <= budget && passes(8, 7, 279) > budget);
        assert_eq!(level7.div_ceil(60_349), 279);
        let fewest = with_batches(8, Metric::MaxTraversal, false, 7, 60_350);
        assert!(fewest.storage_bytes() > limit, "{} MiB", fewest.storage_bytes() / (1 << 20));
    }
}
