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
        // FLIP of the final image (the quick run's 128² output) against the quick reference
        // final image (level 0 of a 128² map, 256² photons), at the default pixels per degree.
        let flip = metric(cell, "FLIP").unwrap_or(f64::NAN);
        assert!(flip > 0.0 && flip < 0.2, "{}: FLIP {flip}", cell["cell"]);
        let f = &cell["final_flip"];
        assert_eq!(f["mean"].as_f64(), Some(flip), "{}", cell["cell"]);
        assert_eq!((f["width"].as_u64(), f["height"].as_u64()), (Some(128), Some(128)), "{f}");
        assert!((f["ppd"].as_f64().unwrap_or(0.0) - 67.02).abs() < 0.01, "{f}");
        let r = &f["reference"];
        assert_eq!(
            (r["level"].as_u64(), r["caustic_map_resolution"].as_u64(), r["photons"].as_u64()),
            (Some(0), Some(128), Some(256)),
            "{f}"
        );
    }
}

#[test]
fn quick_quality_wd2006_compares_every_wyman_davis_technique_with_the_reference() {
    let (_, r) = quick_run("quality_wd2006.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 3 * 13 * 2, "3 scenes x 13 technique columns x 2 photon counts");
    for cell in cells {
        let rmse = metric(cell, "rel. RMSE").unwrap_or(f64::NAN);
        let flux = metric(cell, "flux ratio").unwrap_or(f64::NAN);
        assert!(rmse.is_finite() && rmse > 0.0, "{}: rel. RMSE {rmse}", cell["cell"]);
        // The paper's polygon quads land hit-or-miss under a pixel: their flux is what the table
        // measures (0.5-3.1 in the quick run). Everything else is within 40% at the quick run's
        // 64²-128² photons (gather eye on ring_cardioid with Eq. 10: 0.65).
        let label = cell["cell"]["technique_label"].as_str().unwrap_or_default();
        if label.ends_with("polygons") {
            assert!(flux.is_finite() && flux > 0.0, "{}: flux ratio {flux}", cell["cell"]);
        } else {
            assert!((0.6..1.4).contains(&flux), "{}: flux ratio {flux}", cell["cell"]);
        }
    }
    let flux = |scene: &str, label: &str, photons: u64| -> f64 {
        metric(cell_in(&r, scene, label, photons), "flux ratio").expect("flux ratio")
    };
    for scene in ["sphere_on_plane.toml", "sphere_oblique.toml"] {
        for photons in [64, 128] {
            // The paper's lighting (Eq. 10, Eq. 3) re-lights each photon by cos(photon) /
            // cos(direct), less than 1 where the sphere bends the light: it keeps less flux than
            // the light's direction (Eq. 11, Eq. 4) does.
            for (paper, direct) in [
                ("eye points Eq. 10", "eye points Eq. 11"),
                ("quads eye Eq. 3", "quads eye Eq. 4"),
                ("quads light Eq. 3", "quads light Eq. 4"),
                ("gather eye Eq. 10", "gather eye Eq. 11"),
                ("gather light Eq. 10", "gather light Eq. 11"),
            ] {
                let (p, d) = (flux(scene, paper, photons), flux(scene, direct, photons));
                assert!(d > 1.05 * p, "{scene} {photons}²: {paper} keeps {p}, {direct} {d}");
            }
            // The polygons are not the exact variant's points and lines.
            for space in ["eye", "light"] {
                let (exact, polygons) = (format!("quads {space} Eq. 3"), format!("quads {space} Eq. 3 polygons"));
                let (e, p) = (flux(scene, &exact, photons), flux(scene, &polygons, photons));
                assert!((e - p).abs() > 1e-3, "{scene} {photons}²: {polygons} keeps {p}, as {exact} does");
            }
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

#[test]
fn quick_quality_faithful_scores_every_paper_default_on_four_scenes() {
    // Q4: every technique with its paper's defaults and the faithful variants, on the sphere
    // scenes, the coffee-cup caustic and the underwater pool: every cell has an error, a flux
    // ratio and a peak; the tutorial's Shah (its path, and its path and lookup) and the polygon
    // quads are cells of their own.
    let (_, r) = quick_run("quality_faithful.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 4 * 14, "4 scenes x 14 technique rows at the quick run's one photon count");
    for cell in cells {
        let get = |m: &str| metric(cell, m).unwrap_or(f64::NAN);
        let (rmse, flux, peak, offset) = (get("rel. RMSE"), get("flux ratio"), get("peak ratio"), get("peak offset"));
        assert!(rmse.is_finite() && rmse > 0.0, "{}: rel. RMSE {rmse}", cell["cell"]);
        assert!(flux.is_finite() && flux > 0.0, "{}: flux ratio {flux}", cell["cell"]);
        assert!(peak.is_finite() && peak > 0.0, "{}: peak ratio {peak}", cell["cell"]);
        assert!(offset.is_finite() && offset >= 0.0, "{}: peak offset {offset}", cell["cell"]);
    }
    let scenes: std::collections::BTreeSet<&str> =
        cells.iter().filter_map(|c| c["cell"]["scene"].as_str()).map(|s| s.rsplit('/').next().unwrap_or(s)).collect();
    assert_eq!(
        scenes.into_iter().collect::<Vec<_>>(),
        ["ring_cardioid.toml", "sphere_oblique.toml", "sphere_on_plane.toml", "underwater.toml"]
    );
}

#[test]
fn quick_front_places_every_cell_and_names_the_cheapest_per_error_level() {
    // F1: every cell has a caustic-stage time, a frame time and an error; the table's front
    // sections (one per time) list, per scene, the cheapest cell for each error level, and that
    // cell is, among those at or below the level, the one with the least time (checked here
    // from the JSON).
    let (dir, r) = quick_run("front.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 3 * 17, "3 scenes x 17 techniques at the quick run's one photon count");
    for cell in cells {
        let get = |m: &str| metric(cell, m).unwrap_or(f64::NAN);
        let (stages, ms, rmse) = (get("Caustic map"), get("Frame"), get("rel. RMSE"));
        assert!(
            stages > 0.0 && ms > 0.0 && rmse > 0.0,
            "{}: Caustic map {stages} ms, Frame {ms} ms, rel. RMSE {rmse}",
            cell["cell"]
        );
    }
    let md = std::fs::read_to_string(dir.join("front.md")).expect("front.md");
    // Beside the receiver map's error, the final image's FLIP: a section per time metric.
    for x in ["Caustic map", "Frame"] {
        assert!(md.contains(&format!("## FLIP against {x}\n")), "no FLIP front against {x}");
    }
    assert!(md.contains("- **FLIP:** the mean HDR-FLIP"), "no FLIP line in the header");
    // Alone in its results folder, the front draws none of T4's curves, and says why.
    assert!(
        md.contains("No progressive curves drawn: no table `photon_trace_progressive` in this results folder."),
        "{md}"
    );
    for x in ["Caustic map", "Frame"] {
        let section = md.split(&format!("## rel. RMSE against {x}\n")).nth(1).unwrap_or_else(|| panic!("no {x} front"));
        let section = section.split("\n## ").next().unwrap_or_default();
        cheapest_rows_match(cells, section, x);
    }
}

/// In a front's `section` along time metric `x`, each scene's row for level 0.5 names the
/// cheapest cell at or below it.
fn cheapest_rows_match(cells: &[serde_json::Value], section: &str, x: &str) {
    for scene in ["sphere_on_plane", "ring_cardioid", "bunny_in_room"] {
        let of_scene: Vec<&serde_json::Value> = cells.iter().filter(|c| in_scene(c, scene)).collect();
        let level = 0.5;
        let best = of_scene
            .iter()
            .filter(|c| metric(c, "rel. RMSE").is_some_and(|e| e <= level))
            .min_by(|a, b| metric(a, x).unwrap_or(f64::INFINITY).total_cmp(&metric(b, x).unwrap_or(f64::INFINITY)));
        let of = section.split(&format!("**{scene}**")).nth(1).expect("a section per scene");
        let row = of.lines().find(|l| l.starts_with(&format!("| {level} |"))).expect("a row per level");
        match best {
            Some(c) => {
                let label = c["cell"]["technique_label"].as_str().expect("label");
                let photons = c["cell"]["photons"].as_u64().expect("photons");
                assert!(
                    row.contains(&format!("| {label} | {photons}² |")),
                    "{scene}, {x}: expected {label} {photons}² in {row}"
                );
            }
            None => assert!(row.contains("none reaches it"), "{scene}: {row}"),
        }
    }
}

#[test]
fn quick_wyman_davis2006_fig10_measures_the_metal_and_glass_octahedron() {
    // Fig. 10: both octahedra, four techniques, each cell's error, flux and peak against the
    // exact reference; the metal one's caustic is reflected light, and every technique finds
    // some of it.
    let (_, r) = quick_run("wyman_davis2006_fig10.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 2 * 4 * 2, "2 scenes x 4 techniques x 2 photon counts");
    for c in cells {
        let label = format!("{} {}", c["cell"]["scene"], c["cell"]["technique_label"]);
        for m in ["rel. RMSE", "flux ratio", "peak ratio"] {
            assert!(metric(c, m).is_some_and(|v| v.is_finite() && v > 0.0), "{label}: {m}");
        }
    }
}

#[test]
fn quick_wyman_davis2006_fig8_measures_the_filter_along_a_moving_light() {
    // Fig. 8: the gathers with the temporal filter off and on, the light orbiting; 3 measured
    // frames per cell after the 3 warm-up frames that fill the filter's history.
    let (_, r) = quick_run("wyman_davis2006_fig8.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 4 * 2, "4 techniques x 2 photon counts");
    for c in cells {
        let label = format!("{} {}", c["cell"]["technique_label"], c["cell"]["photons"]);
        let changes = c["temporal_changes"].as_array().expect("temporal_changes");
        assert_eq!(changes.len(), 2, "{label}: one change per pair of the 3 measured frames");
        // The light moves, so every frame's caustic differs from the last one's.
        let change = metric(c, "frame-to-frame change").unwrap_or(f64::NAN);
        assert!(change.is_finite() && change > 1e-3, "{label}: frame-to-frame change {change}");
        for m in ["rel. RMSE", "flux ratio"] {
            assert!(metric(c, m).is_some_and(|v| v.is_finite() && v > 0.0), "{label}: {m}");
        }
    }
    for space in ["eye", "light"] {
        for photons in [64, 128] {
            let change =
                |label: &str| metric(cell_in(&r, "beethoven_standin", label, photons), "frame-to-frame change");
            let (off, on) = (change(&format!("gather {space}")), change(&format!("gather {space}, filtered")));
            // The filter averages four frames' counts: it must change what the frames show.
            assert!(
                off.zip(on).is_some_and(|(a, b)| (a - b).abs() > 1e-4),
                "{space} {photons}²: off {off:?}, on {on:?}"
            );
        }
    }
}

#[test]
fn quick_wyman2008_fig7_measures_four_splat_sizes_against_the_reference() {
    // Fig. 7: constant, thin-lens, interpolated and Sec. 3.3's splats on two scenes; every cell's
    // error, flux and peak against the exact reference, and the splat passes' host time.
    let (_, r) = quick_run("wyman2008_fig7.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 2 * 4, "2 scenes x 4 techniques at the quick run's one photon count");
    for c in cells {
        let label = format!("{} {} {}", c["cell"]["scene"], c["cell"]["technique_label"], c["cell"]["photons"]);
        for m in ["rel. RMSE", "flux ratio", "peak ratio", "splat"] {
            assert!(metric(c, m).is_some_and(|v| v.is_finite() && v > 0.0), "{label}: {m}");
        }
        // Every splat deposits its photon's power in each of its layers: the caustic's flux
        // stays near the reference's (measured 0.96-1.11 in the quick run).
        let flux = metric(c, "flux ratio").unwrap_or(f64::NAN);
        assert!((0.8..1.25).contains(&flux), "{label}: flux ratio {flux}");
    }
    // The interpolated splats draw four radii: four splat passes per light where the others
    // have one.
    let passes = |label: &str| -> Vec<String> {
        cell_in(&r, "sphere_on_plane", label, 64)["passes"]
            .as_array()
            .expect("passes")
            .iter()
            .filter_map(|p| p["name"].as_str().filter(|n| n.starts_with("splat.")).map(str::to_string))
            .collect()
    };
    assert_eq!(passes("constant"), ["splat.light0"]);
    assert_eq!(
        passes("interpolated"),
        ["splat.level0.light0", "splat.level1.light0", "splat.level2.light0", "splat.level3.light0"]
    );
}
