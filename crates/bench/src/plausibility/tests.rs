//! The rules' boundaries, each with a twin just inside and just outside (the mutation tests of
//! `scripts/mutants.sh` found these unheld: results/mutants/plausibility.md).

use super::*;

/// (q1, median, q3) of a time: lower is faster.
fn t(x: f64) -> (f64, f64, f64) {
    (x, x, x)
}

#[test]
fn a_time_is_clearly_faster_only_beyond_the_margin() {
    // b's slowest quartile, with the 1% margin, must be under a's fastest.
    let a = 1.5;
    assert!(clearly_faster("pass_ms", t(a), t(1.0)), "1.0 ms x 1.01 is under 1.5 ms");
    // Exactly on the margin is not beyond it.
    let b = 1.0;
    let on = b * (1.0 + MARGIN);
    assert!(!clearly_faster("pass_ms", t(on), t(b)), "on the margin");
    assert!(clearly_faster("pass_ms", t(on * 1.001), t(b)), "just beyond it");
    assert!(!clearly_faster("pass_ms", t(a), t(a)), "equal times");
    assert!(!clearly_faster("pass_ms", t(1.0), t(0.995)), "within the margin: 0.995 x 1.01 > 1.0");
    assert!(clearly_faster("pass_ms", t(1.0), t(0.98)), "beyond it: 0.98 x 1.01 < 1.0");
    // The quartiles, not the medians: b's q3 against a's q1.
    assert!(!clearly_faster("pass_ms", (0.9, 1.0, 1.1), (0.5, 0.8, 0.95)), "overlapping spreads");
}

#[test]
fn a_frame_rate_is_clearly_faster_when_higher_beyond_the_margin() {
    // For fps (Wyman & Davis Table 1) and photon rates higher is faster: b's lowest quartile
    // must be over a's highest, with the margin.
    for kind in ["fps", "pass_fps", "pass_mphotons", "frame_mphotons", "pass_host_mphotons"] {
        assert!(clearly_faster(kind, t(100.0), t(101.5)), "{kind}: 101.5 > 100 x 1.01");
        assert!(!clearly_faster(kind, t(100.0), t(100.5)), "{kind}: 100.5 is within 1% of 100");
        assert!(clearly_faster(kind, t(100.0), t(101.005)), "{kind}: 101.005 > 101");
        assert!(!clearly_faster(kind, t(100.0), t(99.0)), "{kind}: lower is slower");
        let edge = 100.0 * (1.0 + MARGIN);
        assert!(!clearly_faster(kind, t(100.0), t(edge)), "{kind}: on the margin");
        assert!(!clearly_faster(kind, (90.0, 100.0, 110.0), (105.0, 120.0, 130.0)), "{kind}: overlapping spreads");
        // A time's direction is the other one.
        assert!(!clearly_faster("pass_ms", t(100.0), t(101.5)));
    }
}

#[test]
fn a_copy_of_64_mib_or_more_is_held_to_the_bandwidth_itself() {
    let gbs = 20.0;
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b;
    let bound = gbs * (1.0 + RULE_C_MARGIN);
    assert!(close(copy_bound_gbs(RULE_C_MIN_BYTES, gbs), bound), "exactly 64 MiB: no cache allowance");
    assert!(close(copy_bound_gbs(RULE_C_MIN_BYTES - 1.0, gbs), bound * RULE_C_CACHE_FACTOR), "under 64 MiB");
    assert!(close(copy_bound_gbs(2.0 * RULE_C_MIN_BYTES, gbs), bound));
}

#[test]
fn bytes_per_photon_is_read_for_times_and_photon_rates_only() {
    for kind in
        ["pass_ms", "pass_host_ms", "gpu_frame_ms", "frame_ms", "pass_mphotons", "pass_host_mphotons", "frame_mphotons"]
    {
        assert!(takes_bytes_per_photon(kind), "{kind}");
    }
    for kind in ["fps", "pass_fps", "rel_rmse", "photons_emitted", "photon_batches", "valid_fraction"] {
        assert!(!takes_bytes_per_photon(kind), "{kind}");
    }
}

fn cell_with(metric: &str, value: serde_json::Value) -> CellResult {
    let cell = serde_json::json!({
        "cell": {"index": 0, "scene": "s.toml", "technique": 0, "technique_label": "t", "photons": 1024,
                 "lights": 0, "resolution": [0, 0], "lighting": "dynamic"},
        "caustics": null, "photon_copy": "", "triangles": 0,
        "metrics": {metric: value},
        "wall_ms": [], "passes": []
    });
    serde_json::from_value(cell).expect("a cell result")
}

#[test]
fn a_spread_is_the_recorded_quartiles_when_the_results_have_them() {
    // Quartiles recorded with the value win over the samples' (a merged or rounded table keeps
    // them); the samples give them when absent; a value alone is its own spread.
    let recorded = cell_with(
        "m",
        serde_json::json!({"kind": "pass_ms", "value": 2.0, "min": 1.0, "max": 3.0, "q1": 1.5, "q3": 2.5,
                           "samples": [2.0, 2.0, 2.0, 2.0, 2.0]}),
    );
    assert_eq!(spread(&recorded, "m"), Some((1.5, 2.0, 2.5)));
    let samples = cell_with(
        "m",
        serde_json::json!({"kind": "pass_ms", "value": 2.0, "min": 1.0, "max": 3.0, "samples": [1.0, 1.5, 2.0, 2.5, 3.0]}),
    );
    let (q1, m, q3) = spread(&samples, "m").expect("a spread from the samples");
    assert_eq!(m, 2.0);
    assert!(q1 < 2.0 && q3 > 2.0, "{q1} {q3}");
    let alone =
        cell_with("m", serde_json::json!({"kind": "pass_ms", "value": 2.0, "min": null, "max": null, "samples": []}));
    assert_eq!(spread(&alone, "m"), Some((2.0, 2.0, 2.0)));
    assert_eq!(spread(&alone, "other"), None);
}
