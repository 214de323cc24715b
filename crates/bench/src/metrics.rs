//! Turns one cell's frames into the values of the config's metrics.
//!
//! Times: `pass_ms` sums the GPU timestamps of the matching passes within each frame, then
//! takes the median over the measured frames (quartiles, min and max and every sample kept);
//! `pass_host_ms` sums the host times of the matching passes where each pass was submitted and
//! waited for alone (for drivers whose timestamps miss some work);
//! `pass_fps` is 1000 / that sum, per frame (a rate of some passes alone: Trendall & Stewart
//! 2000 Table 1 times the caustic passes without the height field or the display);
//! `gpu_frame_ms` does so over every pass; `frame_ms` is the host's wall time per frame
//! (record, submit, wait), which also covers work a driver's timestamps miss; `fps` is 1000 /
//! mean `frame_ms` (the papers' average over an animation), its samples and quartiles the
//! per-frame rates. Counts are exact
//! per frame. `rel_rmse` and `flux_ratio` are `causticlab compare`'s relative RMSE and caustic
//! flux ratio of the receiver map against the CPU reference; `flip` the mean HDR-FLIP of the
//! final image against the reference final image (`crate::final_flip`).

use crate::config::MetricSpec;
use crate::measure::CellRun;
use crate::results::Value;
use std::collections::BTreeMap;

/// `*` matches any run of characters; everything else literally.
pub fn glob(pattern: &str, name: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    if parts.len() == 1 {
        return pattern == name;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !name.starts_with(first) || !name[first.len()..].ends_with(last) || name.len() < first.len() + last.len() {
        return false;
    }
    let mut rest = &name[first.len()..name.len() - last.len()];
    for p in &parts[1..parts.len() - 1] {
        match rest.find(p) {
            Some(i) => rest = &rest[i + p.len()..],
            None => return false,
        }
    }
    true
}

fn of_samples(kind: &str, samples: Vec<f64>) -> Value {
    let finite = samples.iter().copied().filter(|x| x.is_finite());
    let q = crate::stats::quartiles(&samples);
    Value {
        kind: kind.into(),
        value: q.map(|(_, m, _)| m),
        min: finite.clone().reduce(f64::min),
        max: finite.reduce(f64::max),
        q1: q.map(|(a, _, _)| a),
        q3: q.map(|(_, _, c)| c),
        samples,
    }
}

fn exact(kind: &str, v: Option<f64>) -> Value {
    Value { kind: kind.into(), value: v, min: v, max: v, q1: None, q3: None, samples: vec![] }
}

/// Per measured frame: the summed GPU time of the passes matching any of `patterns`; None when
/// the device has no timestamps or no pass matched.
fn pass_samples(run: &CellRun, patterns: &[String]) -> Vec<f64> {
    summed_passes(run, patterns, |p| p.gpu_ms)
}

/// Per measured frame: the host times of the passes matching `patterns` (each pass submitted
/// and waited for alone: `FrameStep::host_pass_times`), summed.
fn pass_host_samples(run: &CellRun, patterns: &[String]) -> Vec<f64> {
    summed_passes(run, patterns, |p| p.host_ms)
}

/// Per measured frame with any: the sum of `time` over the passes matching `patterns`.
fn summed_passes(run: &CellRun, patterns: &[String], time: fn(&vkcore::PassTiming) -> Option<f64>) -> Vec<f64> {
    run.frames
        .iter()
        .filter_map(|f| {
            let times: Vec<f64> =
                f.passes.iter().filter(|p| patterns.iter().any(|pat| glob(pat, &p.name))).filter_map(time).collect();
            (!times.is_empty()).then(|| times.iter().sum())
        })
        .collect()
}

/// Millions of the frame's emitted photons per second of each of `ms`.
fn mphotons(run: &CellRun, ms: Vec<f64>) -> Vec<f64> {
    ms.iter().map(|ms| run.photons_emitted as f64 / ms / 1000.0).collect()
}

/// Per measured frame: its host wall time less the GPU time of the passes matching `exclude`.
fn wall_ms(run: &CellRun, exclude: &[String]) -> Vec<f64> {
    run.frames
        .iter()
        .zip(&run.wall_ms)
        .map(|(f, wall)| {
            let excluded: f64 =
                f.passes.iter().filter(|p| exclude.iter().any(|pat| glob(pat, &p.name))).filter_map(|p| p.gpu_ms).sum();
            wall - excluded
        })
        .collect()
}

/// Photons (points) a frame pushes through the pipeline after the photon buffer: every texel
/// for the dense techniques; for `hcm` every entry each traversal level reads plus the splatted
/// list, for `adaptive` every pending cluster of every level plus the splatted photons (Wyman &
/// Nichols 2009 Table 1 counts the splatted ones: `splats_drawn`).
fn photons_processed(run: &CellRun) -> u64 {
    match &run.hierarchy_sizes {
        Some(lights) => lights.iter().flatten().sum(),
        None => run.splats_drawn,
    }
}

/// The mean of a count over `counters` (`None` without any).
fn mean_count(counters: &[vkcore::Counters], count: impl Fn(&vkcore::Counters) -> u64) -> Option<f64> {
    (!counters.is_empty()).then(|| counters.iter().map(|c| count(c) as f64).sum::<f64>() / counters.len() as f64)
}

/// A throughput metric: from the timed blocks (host) or each frame's timestamp pair (GPU). fps
/// is the median of the blocks' rates, its spread theirs.
fn throughput(k: &str, run: &CellRun) -> Value {
    let Some(t) = &run.throughput else { return exact(k, None) };
    match k {
        "fps" => of_samples(k, t.block_ms.iter().map(|ms| 1000.0 / ms).collect()),
        "frame_ms" => of_samples(k, t.block_ms.clone()),
        "gpu_frame_ms" => of_samples(k, t.gpu_frame_ms.clone()),
        _ => exact(k, None),
    }
}

pub fn evaluate(specs: &[MetricSpec], run: &CellRun) -> BTreeMap<String, Value> {
    let mut out = BTreeMap::new();
    for m in specs {
        let k = m.kind.as_str();
        if m.throughput() {
            out.insert(m.label.clone(), throughput(k, run));
            continue;
        }
        let v = match k {
            "pass_ms" => of_samples(k, pass_samples(run, &m.passes)),
            "pass_host_ms" => of_samples(k, pass_host_samples(run, &m.passes)),
            "pass_fps" => of_samples(k, pass_samples(run, &m.passes).iter().map(|ms| 1000.0 / ms).collect()),
            // Millions of the frame's emitted photons per second of the passes.
            "pass_mphotons" => of_samples(k, mphotons(run, pass_samples(run, &m.passes))),
            // The same over the passes' host times (each submitted alone): the rate of a pass
            // whose device timestamps miss its work.
            "pass_host_mphotons" => of_samples(k, mphotons(run, pass_host_samples(run, &m.passes))),
            "gpu_frame_ms" => of_samples(k, pass_samples(run, &["*".to_string()])),
            "frame_ms" => of_samples(k, wall_ms(run, &m.exclude)),
            // Millions of the frame's emitted photons per second of its host wall time.
            "frame_mphotons" => of_samples(k, mphotons(run, wall_ms(run, &m.exclude))),
            "fps" => {
                let wall = wall_ms(run, &m.exclude);
                let mean = wall.iter().sum::<f64>() / wall.len().max(1) as f64;
                let fps: Vec<f64> = wall.iter().map(|ms| 1000.0 / ms).collect();
                let mut v = of_samples(k, fps);
                v.value = (mean > 0.0).then(|| 1000.0 / mean);
                v
            }
            // The pose updates before the measured frames, timed on the host (outside `frame_ms`).
            "pose_ms" => of_samples(k, run.pose_ms.clone()),
            // Acceleration structures built per pose update before a measured frame.
            "blas_builds" => exact(k, mean_count(&run.pose_counters, |c| c.blas_builds)),
            "tlas_builds" => exact(k, mean_count(&run.pose_counters, |c| c.tlas_builds)),
            "blas_refits" => exact(k, mean_count(&run.pose_counters, |c| c.blas_refits)),
            "photons_emitted" => exact(k, Some(run.photons_emitted as f64)),
            "splats_drawn" => exact(k, Some(run.splats_drawn as f64)),
            "photons_processed" => exact(k, Some(photons_processed(run) as f64)),
            "valid_photons" => exact(k, run.valid_photons.map(|v| v as f64)),
            // Valid photons per photon-buffer texel (N^2 per light).
            "valid_fraction" => exact(
                k,
                run.valid_photons.map(|v| v as f64 / (run.caustics.photons as f64).powi(2) / run.lights.max(1) as f64),
            ),
            "rel_rmse" => exact(k, run.quality.as_ref().map(|q| q.rel_rmse)),
            "temporal_change" => exact(k, run.temporal_change()),
            "photon_storage" => exact(k, run.photon_storage.map(|b| b as f64 / (1024.0 * 1024.0))),
            "photon_batches" => exact(k, run.photon_batches.map(f64::from)),
            "depth_complexity_mean" => exact(k, run.depth_complexity.as_ref().and_then(|d| d.mean())),
            "depth_complexity_p50" => exact(k, run.depth_complexity.as_ref().and_then(|d| d.percentile(0.5))),
            "depth_complexity_p90" => exact(k, run.depth_complexity.as_ref().and_then(|d| d.percentile(0.9))),
            "depth_complexity_p99" => exact(k, run.depth_complexity.as_ref().and_then(|d| d.percentile(0.99))),
            "depth_complexity_max" => {
                exact(k, run.depth_complexity.as_ref().and_then(|d| d.covered.last().map(|&c| c as f64)))
            }
            "quad_coverage" => exact(k, run.depth_complexity.as_ref().and_then(|d| d.coverage())),
            "flux_ratio" => exact(k, run.quality.as_ref().map(|q| q.caustic_flux_ratio)),
            "peak_ratio" => exact(k, run.quality.as_ref().map(|q| q.peak_ratio)),
            "peak_offset" => exact(k, run.quality.as_ref().map(|q| q.peak_offset_texels)),
            "flip" => exact(k, run.final_flip.as_ref().map(|f| f.mean)),
            k if crate::progressive::is_progressive_metric(k) => {
                exact(k, crate::progressive::evaluate(m, &run.progressive))
            }
            _ => exact(k, None),
        };
        out.insert(m.label.clone(), v);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pose_updates_are_timed_and_their_structures_counted_apart_from_the_frames() {
        let c = |blas_builds, tlas_builds| vkcore::Counters {
            blas_builds,
            tlas_builds,
            blas_refits: 2 * blas_builds,
            ..Default::default()
        };
        let run = CellRun {
            pose_ms: vec![2.0, 4.0, 3.0],
            // The frames' own counters hold their pose updates' builds too, and more.
            counters: vec![c(5, 5); 3],
            pose_counters: vec![c(1, 1), c(0, 1), c(0, 1)],
            ..CellRun::default()
        };
        let spec = |kind: &str| -> MetricSpec {
            toml::from_str(&format!("label = \"{kind}\"\nkind = \"{kind}\"")).expect("a metric")
        };
        let out = evaluate(&[spec("pose_ms"), spec("blas_builds"), spec("tlas_builds"), spec("blas_refits")], &run);
        assert_eq!(out["pose_ms"].value, Some(3.0));
        assert_eq!(out["pose_ms"].samples, vec![2.0, 4.0, 3.0]);
        assert_eq!(out["blas_builds"].value, Some(1.0 / 3.0));
        assert_eq!(out["tlas_builds"].value, Some(1.0));
        assert_eq!(out["blas_refits"].value, Some(2.0 / 3.0));
        let still = CellRun { counters: vec![c(0, 0)], ..CellRun::default() };
        let out = evaluate(&[spec("pose_ms"), spec("blas_builds")], &still);
        assert_eq!((out["pose_ms"].value, out["blas_builds"].value), (None, None), "no pose update, no number");
    }

    #[test]
    fn globs() {
        assert!(glob("splat.*", "splat.light0"));
        assert!(glob("*", "anything"));
        assert!(glob("photon_buffer.light*", "photon_buffer.light1"));
        assert!(!glob("photon_buffer.light*", "photon_buffer.to_16bit.light0"));
        assert!(glob("*light0", "splat.light0"));
        assert!(glob("a*b*c", "aXXbYYc"));
        assert!(!glob("a*b*c", "aXXcYYb"));
        assert!(!glob("ab*ba", "aba"));
        assert!(glob("exact", "exact"));
        assert!(!glob("exact", "exact.light0"));
    }
}
