//! How values and labels print: photon counts as N², times with three significant digits,
//! counts with thousands separators, the paper's values as the paper prints them.

/// `items` without repeats, each where it first appears (the order a table or a legend lists
/// scenes, papers, row groups in).
pub fn first_seen<T: PartialEq>(items: impl IntoIterator<Item = T>) -> Vec<T> {
    let mut out = vec![];
    for x in items {
        if !out.contains(&x) {
            out.push(x);
        }
    }
    out
}

/// A label as the papers print it: photon counts as N².
pub fn display(axis: &str, key: &str) -> String {
    match axis {
        // A data file may write its photon counts with the square already.
        "photons" if key.ends_with('²') => key.to_string(),
        "photons" => format!("{key}²"),
        "lights" if key != "scene" => format!("{key} light{}", if key == "1" { "" } else { "s" }),
        _ => key.to_string(),
    }
}

/// A value formatted for its metric kind.
pub fn format_value(kind: &str, v: Option<f64>) -> String {
    let Some(v) = v else { return "–".into() };
    if !v.is_finite() {
        return "n/a".into();
    }
    match kind {
        "pass_ms" | "pass_host_ms" | "gpu_frame_ms" | "frame_ms" | "pose_ms" | "fps" | "pass_fps" | "pass_mphotons"
        | "pass_host_mphotons" | "frame_mphotons" => significant(v),
        // A mean per pose update: 1 where each builds one.
        "blas_builds" | "tlas_builds" | "blas_refits" => format!("{v:.2}"),
        "photons_emitted" | "splats_drawn" | "photons_processed" | "valid_photons" | "photon_batches" => {
            thousands(v.round() as u64)
        }
        // A share of the photon buffer, as a percentage with three significant digits.
        "valid_fraction" => format!("{}%", significant(100.0 * v)),
        "rel_rmse" | "flux_ratio" | "peak_ratio" | "temporal_change" | "progressive_rel_rmse" => format!("{v:.4}"),
        "progressive_ms" => significant(v),
        "progressive_frames" => format!("{v:.0}"),
        "peak_offset" => format!("{v:.1}"),
        // HDR-FLIP's mean, three significant digits (0.00947, 0.0304).
        "flip" => significant(v),
        "photon_storage" => significant(v),
        "depth_complexity_mean" => format!("{v:.2}"),
        "depth_complexity_p50" | "depth_complexity_p90" | "depth_complexity_p99" | "depth_complexity_max" => {
            format!("{v:.0}")
        }
        "quad_coverage" => format!("{}%", significant(100.0 * v)),
        _ => format!("{v}"),
    }
}

/// A time or a rate with at least three significant digits and at most one decimal above 10, so
/// that lavapipe's 0.013 fps and a GPU's 0.024 ms passes do not print as 0.0.
pub fn significant(v: f64) -> String {
    let a = v.abs();
    if a >= 10.0 || a == 0.0 {
        return format!("{v:.1}");
    }
    // Digits before the decimal point are 1 for a ≥ 1; below 1, leading zeros add decimals.
    let decimals = (2.0 - a.log10().floor()).max(2.0) as usize;
    format!("{v:.decimals$}")
}

fn thousands(n: u64) -> String {
    let digits: Vec<char> = n.to_string().chars().collect();
    let head = digits.len() % 3;
    let mut groups: Vec<String> = vec![];
    if head > 0 {
        groups.push(digits[..head].iter().collect());
    }
    groups.extend(digits[head..].chunks(3).map(|c| c.iter().collect::<String>()));
    groups.join(",")
}

/// The unit of a metric kind, for headers and plot axes.
pub fn unit(kind: &str) -> &'static str {
    match kind {
        "pass_ms" | "pass_host_ms" | "gpu_frame_ms" | "frame_ms" | "pose_ms" => "ms",
        "blas_builds" | "tlas_builds" => "builds per pose update",
        "blas_refits" => "refits per pose update",
        "fps" | "pass_fps" => "fps",
        "pass_mphotons" | "pass_host_mphotons" | "frame_mphotons" => "M photons/s",
        "photons_emitted" => "photons",
        "splats_drawn" | "photons_processed" => "points",
        "valid_photons" => "photons",
        "photon_storage" => "MiB",
        "photon_batches" => "batches",
        k if k.starts_with("depth_complexity_") => "fragments per pixel",
        _ => "",
    }
}

/// A paper's value as the paper prints it (the config holds it verbatim): 3.6 stays 3.6, 8.0 stays
/// 8.0 (TOML keeps no trailing zeros beyond that).
/// Counts keep their thousands separators.
pub fn paper_value(kind: &str, v: Option<f64>) -> String {
    match (kind, v) {
        ("photons_emitted" | "splats_drawn" | "photons_processed", _) | (_, None) => format_value(kind, v),
        (_, Some(v)) if v.fract() == 0.0 => format!("{v:.1}"),
        (_, Some(v)) => format!("{v}"),
    }
}

/// A ratio: two decimals from 0.1 to 100, whole numbers above, two significant digits below
/// (0.012), so that a 50x speed-up and a 0.02 cost share both read.
pub fn ratio(v: f64) -> String {
    let a = v.abs();
    if !v.is_finite() {
        "n/a".into()
    } else if a >= 100.0 {
        format!("{v:.0}")
    } else if a >= 0.1 || a == 0.0 {
        format!("{v:.2}")
    } else {
        let decimals = (1.0 - a.log10().floor()) as usize;
        format!("{v:.decimals$}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_values_print_as_the_paper_prints_them() {
        assert_eq!(paper_value("fps", Some(3.6)), "3.6");
        assert_eq!(paper_value("pass_ms", Some(861.0)), "861.0");
        assert_eq!(paper_value("pass_ms", Some(0.02)), "0.02");
        assert_eq!(paper_value("photons_processed", Some(262144.0)), "262,144");
        assert_eq!(paper_value("fps", None), "–");
    }

    #[test]
    fn ratios() {
        assert_eq!(ratio(0.3812), "0.38");
        assert_eq!(ratio(52.346), "52.35");
        assert_eq!(ratio(158.6), "159");
        assert_eq!(ratio(0.01234), "0.012");
        assert_eq!(ratio(0.05), "0.050");
    }

    #[test]
    fn formatting() {
        assert_eq!(thousands(16777216), "16,777,216");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(format_value("pass_ms", Some(4.256)), "4.26");
        assert_eq!(format_value("pass_ms", Some(861.54)), "861.5");
        assert_eq!(format_value("fps", None), "–");
        assert_eq!(format_value("fps", Some(32.44)), "32.4");
        assert_eq!(format_value("fps", Some(3.456)), "3.46");
        assert_eq!(format_value("fps", Some(0.01234)), "0.0123");
        assert_eq!(format_value("pass_ms", Some(0.5)), "0.500");
        assert_eq!(format_value("fps", Some(0.0)), "0.0");
        assert_eq!(format_value("valid_fraction", Some(0.5928440093994141)), "59.3%");
        assert_eq!(format_value("valid_fraction", Some(0.0062103271484375)), "0.621%");
        assert_eq!(format_value("valid_photons", Some(8216.0)), "8,216");
        assert_eq!(format_value("flip", Some(0.009472)), "0.00947");
        assert_eq!(first_seen(["b", "a", "b", "c", "a"]), ["b", "a", "c"]);
        assert_eq!(format_value("flip", Some(0.03041)), "0.0304");
        assert_eq!(display("photons", "256"), "256²");
        assert_eq!(display("photons", "512²"), "512²");
        assert_eq!(display("lights", "2"), "2 lights");
    }
}
