//! Progressive accumulation's curve (`photon-trace --progressive`, Knaus & Zwicker 2011): after
//! a cell's frames, its renderer starts its means again and renders frame after frame, each
//! timed on the host, the receiver map compared with the exact CPU reference after every frame
//! (outside the time). The curve is the (frames, accumulated ms, rel. RMSE) of every frame; its
//! metrics read it:
//!
//! - `progressive_rel_rmse` with `frames = N`: the relative RMSE after N frames; with
//!   `after_ms = T`: after the first frame whose accumulated time reaches T ms;
//! - `progressive_ms` with `frames = N`: the accumulated time of the first N frames;
//! - `progressive_frames` with `after_ms = T`: the frames it took to reach T ms.
//!
//! The time of a frame is the host time of the passes matching the metrics' `passes` (each pass
//! submitted and waited for alone, as `pass_host_ms` times them), or its host wall time where
//! they name none. Under `--quick` a curve stops at [`QUICK_FRAMES`]. A technique that does not accumulate renders the same frame every time: its
//! curve is flat, which is what an eye gets from it.

use crate::config::MetricSpec;
use crate::metrics::glob;
use serde::{Deserialize, Serialize};

/// The most frames a curve may take (a config's `frames` and `after_ms` are checked against it:
/// past it, a cell would run for hours on lavapipe).
pub const MAX_FRAMES: u32 = 4096;

/// The most frames a curve takes under `--quick` (a smoke test: its later points read n/a).
pub const QUICK_FRAMES: u32 = 8;

/// One frame of the curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// Frames accumulated (this one included).
    pub frames: u32,
    /// Their time, ms.
    pub ms: f64,
    /// The receiver map's relative RMSE against the exact reference after this frame.
    pub rel_rmse: f64,
}

/// Whether metric `kind` reads the progressive curve.
pub fn is_progressive_metric(kind: &str) -> bool {
    matches!(kind, "progressive_rel_rmse" | "progressive_ms" | "progressive_frames")
}

/// What the curve must reach for `metrics`: (frames, ms).
pub fn targets(metrics: &[MetricSpec]) -> (u32, f64) {
    let progressive = metrics.iter().filter(|m| is_progressive_metric(&m.kind));
    let frames = progressive.clone().filter_map(|m| m.frames).max().unwrap_or(1);
    let ms = progressive.filter_map(|m| m.after_ms).fold(0.0, f64::max);
    (frames, ms)
}

/// The passes a frame's time sums (the progressive metrics share them: validated), none for
/// the wall time.
pub fn timed_passes(metrics: &[MetricSpec]) -> Vec<String> {
    metrics.iter().find(|m| is_progressive_metric(&m.kind)).map(|m| m.passes.clone()).unwrap_or_default()
}

/// A frame's time: the host times of its passes matching `passes` summed, or `wall` without
/// any pattern. None where patterns match no pass with a host time.
pub fn frame_time(passes: &[String], report: &vkcore::FrameReport, wall: f64) -> Option<f64> {
    if passes.is_empty() {
        return Some(wall);
    }
    let times: Vec<f64> = report
        .passes
        .iter()
        .filter(|p| passes.iter().any(|pat| glob(pat, &p.name)))
        .filter_map(|p| p.host_ms)
        .collect();
    (!times.is_empty()).then(|| times.iter().sum())
}

/// Whether the curve so far reaches `targets`, or has `cap` frames.
pub fn reached(curve: &[Point], targets: (u32, f64), cap: u32) -> bool {
    curve.last().is_some_and(|p| p.frames >= targets.0 && p.ms >= targets.1) || curve.len() >= cap as usize
}

/// The value of progressive metric `m` on `curve` (None where the curve does not reach it).
pub fn evaluate(m: &MetricSpec, curve: &[Point]) -> Option<f64> {
    let at = match (m.frames, m.after_ms) {
        (Some(n), _) => curve.iter().find(|p| p.frames == n)?,
        (None, Some(t)) => curve.iter().find(|p| p.ms >= t)?,
        (None, None) => return None,
    };
    match m.kind.as_str() {
        "progressive_rel_rmse" => Some(at.rel_rmse),
        "progressive_ms" => Some(at.ms),
        "progressive_frames" => Some(f64::from(at.frames)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(kind: &str, frames: Option<u32>, after_ms: Option<f64>) -> MetricSpec {
        let mut m: MetricSpec = toml::from_str(&format!("label = \"{kind}\"\nkind = \"{kind}\"")).expect("a metric");
        m.frames = frames;
        m.after_ms = after_ms;
        m
    }

    #[test]
    fn metrics_read_the_curve_at_a_frame_or_at_a_time() {
        let curve: Vec<Point> =
            (1..=8u32).map(|i| Point { frames: i, ms: 10.0 * f64::from(i), rel_rmse: 1.0 / f64::from(i) }).collect();
        assert_eq!(evaluate(&spec("progressive_rel_rmse", Some(4), None), &curve), Some(0.25));
        assert_eq!(evaluate(&spec("progressive_ms", Some(4), None), &curve), Some(40.0));
        // 35 ms is first reached by frame 4 (40 ms).
        assert_eq!(evaluate(&spec("progressive_rel_rmse", None, Some(35.0)), &curve), Some(0.25));
        assert_eq!(evaluate(&spec("progressive_frames", None, Some(35.0)), &curve), Some(4.0));
        assert_eq!(evaluate(&spec("progressive_frames", None, Some(80.0)), &curve), Some(8.0));
        // Beyond the curve: no value, never the last point's.
        assert_eq!(evaluate(&spec("progressive_rel_rmse", Some(9), None), &curve), None);
        assert_eq!(evaluate(&spec("progressive_frames", None, Some(80.5)), &curve), None);
        let metrics = [spec("progressive_rel_rmse", Some(16), None), spec("progressive_frames", None, Some(500.0))];
        assert_eq!(targets(&metrics), (16, 500.0));
        assert!(!reached(&curve, (16, 0.0), MAX_FRAMES) && !reached(&curve, (8, 81.0), MAX_FRAMES));
        assert!(reached(&curve, (8, 80.0), MAX_FRAMES) && reached(&curve, (16, 0.0), 8));
    }

    #[test]
    fn a_frames_time_is_its_matching_passes_or_its_wall_time() {
        let pass = |name: &str, host: Option<f64>| vkcore::PassTiming {
            name: name.into(),
            gpu_ms: None,
            host_ms: host,
            stats: None,
        };
        let report = vkcore::FrameReport {
            passes: vec![
                pass("photon_trace.light0", Some(3.0)),
                pass("splat.light0", Some(1.5)),
                pass("composite", Some(9.0)),
            ],
            ..Default::default()
        };
        assert_eq!(frame_time(&[], &report, 20.0), Some(20.0));
        let caustics = ["photon_trace*".to_string(), "splat*".to_string()];
        assert_eq!(frame_time(&caustics, &report, 20.0), Some(4.5));
        assert_eq!(frame_time(&["hierarchy*".to_string()], &report, 20.0), None);
    }
}
