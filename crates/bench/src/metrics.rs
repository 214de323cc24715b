//! Turns one cell's frames into the values of the config's metrics.
//!
//! Times: `pass_ms` sums the GPU timestamps of the matching passes within each frame, then
//! takes the median over the measured frames (min and max kept); `pass_fps` is 1000 / that sum,
//! per frame (a rate of some passes alone: Trendall & Stewart 2000 Table 1 times the caustic
//! passes without the height field or the display); `gpu_frame_ms` does so over
//! every pass; `frame_ms` is the host's wall time per frame (record, submit, wait), which also
//! covers work a driver's timestamps miss; `fps` is 1000 / mean `frame_ms`. Counts are exact
//! per frame. `rel_rmse` and `flux_ratio` are `causticlab compare`'s relative RMSE and caustic
//! flux ratio of the receiver map against the CPU reference.

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

fn median(v: &[f64]) -> Option<f64> {
    let mut s: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    if s.is_empty() {
        return None;
    }
    s.sort_by(f64::total_cmp);
    let n = s.len();
    Some(if n % 2 == 1 { s[n / 2] } else { 0.5 * (s[n / 2 - 1] + s[n / 2]) })
}

fn of_samples(kind: &str, samples: Vec<f64>) -> Value {
    let finite = samples.iter().copied().filter(|x| x.is_finite());
    Value {
        kind: kind.into(),
        value: median(&samples),
        min: finite.clone().reduce(f64::min),
        max: finite.reduce(f64::max),
        samples,
    }
}

fn exact(kind: &str, v: Option<f64>) -> Value {
    Value { kind: kind.into(), value: v, min: v, max: v, samples: vec![] }
}

/// Per measured frame: the summed GPU time of the passes matching any of `patterns`; None when
/// the device has no timestamps or no pass matched.
fn pass_samples(run: &CellRun, patterns: &[String]) -> Vec<f64> {
    run.frames
        .iter()
        .filter_map(|f| {
            let times: Vec<f64> = f
                .passes
                .iter()
                .filter(|p| patterns.iter().any(|pat| glob(pat, &p.name)))
                .filter_map(|p| p.gpu_ms)
                .collect();
            (!times.is_empty()).then(|| times.iter().sum())
        })
        .collect()
}

/// Photons (points) a frame pushes through the pipeline after the photon buffer: every texel
/// for the dense techniques; for `hcm` every entry each traversal level reads plus the splatted
/// list (Wyman & Nichols 2009 Table 1 counts the splatted ones: `splats_drawn`).
fn photons_processed(run: &CellRun) -> u64 {
    match &run.hierarchy_sizes {
        Some(lights) => lights.iter().flatten().sum(),
        None => run.splats_drawn,
    }
}

pub fn evaluate(specs: &[MetricSpec], run: &CellRun) -> BTreeMap<String, Value> {
    let mut out = BTreeMap::new();
    for m in specs {
        let k = m.kind.as_str();
        let v = match k {
            "pass_ms" => of_samples(k, pass_samples(run, &m.passes)),
            "pass_fps" => of_samples(k, pass_samples(run, &m.passes).iter().map(|ms| 1000.0 / ms).collect()),
            "gpu_frame_ms" => of_samples(k, pass_samples(run, &["*".to_string()])),
            "frame_ms" => of_samples(k, run.wall_ms.clone()),
            "fps" => {
                let mean = run.wall_ms.iter().sum::<f64>() / run.wall_ms.len().max(1) as f64;
                let fps: Vec<f64> = run.wall_ms.iter().map(|ms| 1000.0 / ms).collect();
                let mut v = of_samples(k, fps);
                v.value = (mean > 0.0).then(|| 1000.0 / mean);
                v
            }
            "photons_emitted" => exact(k, Some(run.photons_emitted as f64)),
            "splats_drawn" => exact(k, Some(run.splats_drawn as f64)),
            "photons_processed" => exact(k, Some(photons_processed(run) as f64)),
            "rel_rmse" => exact(k, run.quality.as_ref().map(|q| q.rel_rmse)),
            "flux_ratio" => exact(k, run.quality.as_ref().map(|q| q.caustic_flux_ratio)),
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

    #[test]
    fn medians() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), Some(2.5));
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[f64::NAN, 5.0]), Some(5.0));
    }
}
