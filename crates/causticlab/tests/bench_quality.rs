//! `causticlab bench --quick` of the quality configs: every technique against the exact
//! reference, with an error and a flux ratio per cell.

mod common;

use common::bench::*;

#[test]
fn quick_quality_compares_with_the_reference() {
    let (_, r) = quick_run("quality.toml");
    for cell in r["cells"].as_array().expect("cells") {
        let rmse = metric(cell, "rel. RMSE").unwrap_or(f64::NAN);
        let flux = metric(cell, "flux ratio").unwrap_or(f64::NAN);
        assert!(rmse.is_finite() && rmse > 0.0 && rmse < 1.0, "{}: rel. RMSE {rmse}", cell["cell"]);
        assert!((0.7..1.3).contains(&flux), "{}: flux ratio {flux}", cell["cell"]);
    }
}

#[test]
fn quick_quality_wd2006_compares_every_wyman_davis_technique_with_the_reference() {
    let (_, r) = quick_run("quality_wd2006.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 3 * 6 * 2, "3 scenes x 6 techniques x 2 photon counts");
    for cell in cells {
        let rmse = metric(cell, "rel. RMSE").unwrap_or(f64::NAN);
        let flux = metric(cell, "flux ratio").unwrap_or(f64::NAN);
        assert!(rmse.is_finite() && rmse > 0.0, "{}: rel. RMSE {rmse}", cell["cell"]);
        // Eye-space quads on ring_cardioid are off by up to 3x in flux (an open issue, see
        // results/quality/wyman_davis2006.md); everything else is within 40% at
        // the quick run's 64² photons (gather eye on ring_cardioid: 0.72).
        let scene = cell["cell"]["scene"].as_str().unwrap_or_default();
        let ring_quads = scene.ends_with("ring_cardioid.toml") && cell["cell"]["technique_label"] == "quads eye";
        if !ring_quads {
            assert!((0.6..1.4).contains(&flux), "{}: flux ratio {flux}", cell["cell"]);
        }
    }
}

#[test]
fn quick_quality_adaptive_compares_every_technique_with_the_reference() {
    // Q3: adaptive caustic maps (max-error, fixed and varying multi-res splats) and the dense
    // buffer against the exact reference: every cell has an error and a flux ratio, the metric
    // splats fewer photons than the dense buffer, and varying splats the same photons.
    let (_, r) = quick_run("quality_adaptive.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 2 * 3 * 2, "2 scenes x 3 techniques x 2 photon counts");
    for c in cells {
        let label = c["cell"]["technique_label"].as_str().unwrap_or_default();
        let rmse = metric(c, "rel. RMSE").unwrap_or(-1.0);
        let flux = metric(c, "flux ratio").unwrap_or(-1.0);
        assert!(rmse > 0.0 && rmse < 0.5, "{label}: relative RMSE {rmse}");
        assert!((0.8..1.2).contains(&flux), "{label}: flux ratio {flux}");
    }
    for photons in [128u64, 256] {
        let splats = |t: &str| metric(cell(&r, t, photons), "splatted").expect("splatted");
        assert!(splats("max-error") < splats("wd-points"), "{photons}: adaptive splats every texel");
        assert_eq!(splats("max-error"), splats("max-error · varying multi-res"), "{photons}");
    }
}
