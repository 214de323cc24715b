//! `causticlab bench --quick` of every shipped paper config (validation on, zero messages):
//! each table's cells are all there, counted and timed by their own passes.

mod common;

use common::bench::*;
use common::workspace;
use serde_json::Value;

#[test]
fn quick_wyman2008_table1_times_every_phase_and_copies_only_on_the_copy_path() {
    let (dir, r) = quick_run("wyman2008_table1.toml");
    for cell in r["cells"].as_array().expect("cells") {
        let technique = cell["cell"]["technique_label"].as_str().unwrap_or_default();
        for m in ["Render Photon Buffer", "Splat Photons", "Eye Render"] {
            let v = metric(cell, m).unwrap_or(-1.0);
            assert!(v > 0.0, "{technique}: {m} = {v}");
        }
        // The copy pass exists exactly where the technique copies the photon buffer.
        let copy = metric(cell, "Copy to Vertex Array");
        assert_eq!(copy.is_some(), technique == "W&D copy", "{technique}: copy = {copy:?}");
        let samples = cell["passes"][0]["samples_ms"].as_array().map(|s| s.len()).unwrap_or(0);
        assert_eq!(samples, 2, "raw samples of the 2 measured quick frames are kept");
    }
    let md = std::fs::read_to_string(dir.join("wyman2008_table1.md")).expect("md");
    assert!(md.contains("Costs for the caustic mapping phases") && md.contains("| 64² "), "{md}");
    // On Linux each cell records how much CPU the hypervisor took while it ran, and the table says so.
    if cfg!(target_os = "linux") {
        for cell in r["cells"].as_array().expect("cells") {
            let steal = cell["cpu_steal"].as_f64().unwrap_or(-1.0);
            assert!((0.0..=1.0).contains(&steal), "cpu_steal {steal} in {}", cell["cell"]);
        }
        assert!(md.contains("**Host CPU steal**"), "{md}");
    }
}

#[test]
fn quick_wyman2008_table2_copies_each_data_type() {
    let (_, r) = quick_run("wyman2008_table2.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 6, "3 copy types x 2 photon counts");
    for cell in cells {
        assert!(metric(cell, "copy").unwrap_or(-1.0) > 0.0, "{}", cell["cell"]);
    }
}

#[test]
fn quick_wyman_davis2006_table1_runs_static_and_dynamic_lighting() {
    let (_, r) = quick_run("wyman_davis2006_table1.toml");
    let cells = r["cells"].as_array().expect("cells");
    let passes = |c: &Value| c["frame_counters"]["throughput"]["passes"].as_f64().expect("throughput passes per frame");
    for cell in cells {
        let lighting = cell["cell"]["lighting"].as_str().unwrap_or_default();
        assert!(metric(cell, "fps").unwrap_or(-1.0) > 0.0);
        // fps is measured in throughput frames: warm ones make no Vulkan object, submit once.
        let t = &cell["frame_counters"]["throughput"];
        assert_eq!(t["most_objects"].as_u64(), Some(0), "{}: {t}", cell["cell"]);
        assert_eq!(t["submits"].as_f64(), Some(1.0), "{}: {t}", cell["cell"]);
        assert!(cell["block_ms"].as_array().is_some_and(|b| b.len() >= 2), "{}", cell["cell"]);
        // Static lighting renders its photon buffer once before the timed frames and reuses it:
        // its frames record fewer passes than the dynamic twin's.
        if lighting == "dynamic" {
            let twin = cells
                .iter()
                .find(|c| {
                    c["cell"]["lighting"] == "static"
                        && ["scene", "technique", "photons"].iter().all(|k| c["cell"][k] == cell["cell"][k])
                })
                .expect("a static twin");
            assert!(
                passes(twin) < passes(cell),
                "{}: static {} passes, dynamic {}",
                cell["cell"],
                passes(twin),
                passes(cell)
            );
        }
    }
}

#[test]
fn quick_hierarchical_tables_count_and_time_every_cell() {
    // Wyman 2008 Tables 3-5: every timed column has a value in every cell.
    for config in ["wyman2008_table3.toml", "wyman2008_table4.toml", "wyman2008_table5.toml"] {
        let (dir, r) = quick_run(config);
        // Laid out like the paper's: its columns (Table 3: photons and ten more), each line
        // of the table within a 120-column terminal.
        let md = std::fs::read_to_string(dir.join(config.replace(".toml", ".md"))).expect("md");
        // The header lines of the value table (wrapped into blocks), before the ratio grid.
        let values = &md[..md.find("## Ratios").unwrap_or(md.len())];
        let headers: std::collections::BTreeSet<&str> = values
            .lines()
            .filter(|l| l.starts_with("| photons") || l.starts_with("| scene"))
            .flat_map(|l| l.split('|').map(str::trim).filter(|c| !c.is_empty()))
            .collect();
        assert!(md.lines().filter(|l| l.starts_with('|')).all(|l| l.chars().count() <= 120), "{md}");
        let paper_columns = match config {
            "wyman2008_table3.toml" => 11,
            "wyman2008_table4.toml" => 7,
            _ => 3, // Table 5: scene and the quick run's two photon counts
        };
        assert_eq!(headers.len(), paper_columns, "{config}: {headers:?}");
        if config == "wyman2008_table3.toml" {
            for h in ["Render Photon Buffer", "W&D 2006 Gather", "Varying, Single Map", "Final Render, Multi-Res"] {
                assert!(headers.contains(h), "{config}: no column `{h}` in {headers:?}");
            }
        }
        for cell in r["cells"].as_array().expect("cells") {
            for (label, v) in cell["metrics"].as_object().expect("metrics") {
                let x = v["value"].as_f64().unwrap_or(-1.0);
                // W&D + Sec. 4 has no copy; every other column is a time or a rate.
                assert!(x > 0.0, "{config}: {} {label} = {x}", cell["cell"]);
            }
        }
    }
    // Wyman & Nichols 2009 Table 1: the hierarchy splats only valid photons, clustering fewer.
    let (_, r) = quick_run("wyman_nichols2009_table1.toml");
    for scene in ["bunny_in_room", "sphere_in_room"] {
        for photons in [64u64, 128] {
            let find = |t: &str| cell_in(&r, scene, t, photons);
            let (dense, hier, last) = (find("Caustic Maps"), find("Hier. Caustic Maps"), find("combine last"));
            let s = |c: &Value, m: &str| metric(c, m).unwrap_or(f64::NAN);
            assert_eq!(s(dense, "splatted"), (photons * photons) as f64, "{scene} {photons}");
            assert!(s(hier, "splatted") > 0.0 && s(hier, "splatted") < s(dense, "splatted"), "{scene} {photons}");
            assert!(s(hier, "processed") > s(hier, "splatted"), "{scene} {photons}: traversal entries not counted");
            assert!(s(last, "splatted") <= s(hier, "splatted"), "{scene} {photons}: clustering splatted more");
        }
    }
}

#[test]
fn quick_adaptive_table_counts_both_metrics_and_keeps_each_levels_list() {
    // Wyman & Nichols 2009 Table 1's adaptive columns and Fig. 7: max-traversal splats what the
    // hierarchy would (the valid photons, up to the geometry buffers' interpolation), max-error
    // fewer once it tests convergence (512²), the same below; every cell keeps its per-level
    // list sizes, whose last entry is the splatted count.
    let (dir, r) = quick_run("wyman_nichols2009_adaptive.toml");
    let md = std::fs::read_to_string(dir.join("wyman_nichols2009_adaptive.md")).expect("md");
    assert!(md.contains("## Ratios"), "no Fig. 7 ratio grid:\n{md}");
    for scene in ["bunny_in_room", "sphere_in_room"] {
        for photons in [128u64, 512] {
            let find = |t: &str| cell_in(&r, scene, t, photons);
            let (hier, traversal, error) =
                (find("Hier. Caustic Maps"), find("Adaptive Max Traversal"), find("Adaptive Max Error"));
            let s = |c: &Value| metric(c, "splatted").unwrap_or(f64::NAN);
            assert!(s(traversal) > 0.0, "{scene} {photons}: nothing splatted");
            assert!((s(traversal) / s(hier) - 1.0).abs() < 0.1, "{scene} {photons}: {} vs {}", s(traversal), s(hier));
            if photons < 512 {
                assert_eq!(s(error), s(traversal), "{scene} {photons}: max-error clustered above 512²");
            } else {
                assert!(s(error) < s(traversal), "{scene} {photons}: max-error splatted no fewer");
            }
            for c in [traversal, error] {
                let sizes = c["list_sizes"][0].as_array().expect("list sizes");
                let levels = (photons / 64).trailing_zeros() as usize + 1;
                assert_eq!(sizes.len(), levels + 1, "{scene} {photons}: {sizes:?}");
                assert_eq!(sizes[0].as_u64(), Some(32 * 32), "{scene} {photons}: the coarse grid's clusters");
                assert_eq!(sizes[levels].as_f64(), Some(s(c)), "{scene} {photons}: the splatted count");
            }
        }
    }
}

#[test]
fn quick_photon_view_times_every_view_and_the_fitted_one_wastes_least() {
    // V1: every view is timed, and the fitted view spends the largest share of its photons on
    // the object.
    let (_, r) = quick_run("photon_view.toml");
    let cells = r["cells"].as_array().expect("cells");
    for c in cells {
        for m in ["Render Photon Buffer", "Gather"] {
            assert!(metric(c, m).unwrap_or(-1.0) > 0.0, "{}: {m} not timed", c["cell"]);
        }
        let valid = metric(c, "valid").unwrap_or(-1.0);
        assert!((0.0..=1.0).contains(&valid), "{}: valid share {valid}", c["cell"]);
    }
    for c in cells.iter().filter(|c| c["cell"]["technique_label"] == "W&D 90°") {
        let fitted = cell(&r, "W&D fitted", c["cell"]["photons"].as_u64().unwrap_or(0));
        assert!(metric(fitted, "valid") > metric(c, "valid"), "{}", c["cell"]);
    }
}

#[test]
fn quick_fig9_times_each_refraction_by_its_own_passes() {
    // Wyman & Nichols 2009 Fig. 9: forward and deferred refraction, each metric timed from the
    // refraction's own passes, on every model.
    let (_, r) = quick_run("wyman_nichols2009_fig9.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 16);
    for c in cells {
        let refraction = c["caustics"]["refraction"].as_str().unwrap_or_default();
        assert_eq!(c["cell"]["technique_label"].as_str(), Some(refraction));
        for m in ["refraction", "geometry", "shading", "eye"] {
            assert!(metric(c, m).unwrap_or(-1.0) > 0.0, "{} {refraction}: {m} not timed", c["cell"]);
        }
        let passes: Vec<&str> =
            c["passes"].as_array().expect("passes").iter().filter_map(|p| p["name"].as_str()).collect();
        let deferred = passes.contains(&"refractor_geometry.layer0") && passes.contains(&"deferred_refraction.layer0");
        let forward = passes.contains(&"refractor_back_faces") && passes.contains(&"composite");
        assert_eq!((forward, deferred), (refraction == "forward", refraction == "deferred"), "{passes:?}");
    }
}

#[test]
fn quick_fig8_splits_into_the_batches_asked_for_and_splats_the_same_photons() {
    // Wyman & Nichols 2009 Fig. 8: each column's batch count is the one its label asks for (the
    // plan's, as recorded), more batches allocate less, and every cell splats the same photons.
    let (_, r) = quick_run("wyman_nichols2009_fig8.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 10);
    for photons in [128u64, 256] {
        let mut storage = f64::INFINITY;
        let one = cell(&r, "1 batch", photons);
        for n in [1u32, 2, 4, 8, 16] {
            let label = if n == 1 { "1 batch".to_string() } else { format!("{n} batches") };
            let c = cell(&r, &label, photons);
            assert_eq!(metric(c, "batches"), Some(n as f64), "{label} {photons}");
            assert!(metric(c, "caustic map").unwrap_or(-1.0) > 0.0, "{label} {photons}: not timed");
            let s = metric(c, "storage").expect("storage");
            assert!(s < storage, "{label} {photons}: {s} MiB, not less than with fewer batches");
            storage = s;
            assert_eq!(c["list_sizes"], one["list_sizes"], "{label} {photons}: other photons than 1 batch");
            let splats = c["passes"]
                .as_array()
                .expect("passes")
                .iter()
                .filter(|p| p["name"].as_str().is_some_and(|n| n.starts_with("splat.batch")));
            assert_eq!(splats.count(), if n == 1 { 0 } else { n as usize }, "{label} {photons}: splats");
        }
    }
}

#[test]
fn quick_fig8_at_the_batched_sizes_keeps_the_memory_limit_and_the_photons() {
    // The Fig. 8 configs for the sizes only batches reach (lavapipe's and the GPU suite's): each
    // cell runs at least the batches its label asks for, stays within its 96 MiB limit, is
    // timed, and splats the photons the 2-batch cell splats.
    for config in ["wyman_nichols2009_fig8_batched.toml", "wyman_nichols2009_fig8_16384.toml"] {
        let (_, r) = quick_run(config);
        assert_eq!(
            r["cells"].as_array().expect("cells").len(),
            4,
            "{config}: 4 batch counts at the quick run's one photon count"
        );
        let photons = 128u64;
        let two = cell(&r, "2 batches", photons);
        for n in [2u32, 4, 8, 16] {
            let label = format!("{n} batches");
            let c = cell(&r, &label, photons);
            assert!(metric(c, "batches").is_some_and(|b| b >= n as f64), "{config} {label} {photons}");
            assert!(metric(c, "caustic map").unwrap_or(-1.0) > 0.0, "{config} {label} {photons}: not timed");
            let s = metric(c, "storage").expect("storage");
            assert!(s <= 96.0, "{config} {label} {photons}: {s} MiB over the limit");
            assert_eq!(c["list_sizes"], two["list_sizes"], "{config} {label} {photons}: other photons");
        }
    }
}

#[test]
fn quick_fig11_times_every_step_of_the_levels_each_density_runs() {
    // Wyman & Nichols 2009 Fig. 11: the fixed steps are timed at every density, a traversal
    // level only where the density reaches it (64²: level 0; 128²: levels 0-1).
    let (dir, r) = quick_run("wyman_nichols2009_fig11.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 4);
    for c in cells {
        let photons = c["cell"]["photons"].as_u64().expect("photons");
        let finest = (photons / 64).trailing_zeros();
        let fixed = ["shadow map", "receivers", "geometry buffers", "coverage pyramid", "splat", "eye render"];
        for m in fixed.into_iter().chain(["batch bookkeeping", "fps"]) {
            assert!(metric(c, m).unwrap_or(-1.0) > 0.0, "{}: {m} not timed", c["cell"]);
        }
        for k in 0..=6u32 {
            let timed = metric(c, &format!("level {k}")).is_some();
            assert_eq!(timed, k <= finest, "{}: level {k}", c["cell"]);
        }
    }
    let md = std::fs::read_to_string(dir.join("wyman_nichols2009_fig11.md")).expect("md");
    assert!(md.contains("level 6") && md.contains("eye render"), "{md}");
}

#[test]
fn quick_traversal_paths_process_the_same_photons_and_sparse_gathers_splat_fewer() {
    // P1: the transform-feedback and compute traversals read and emit the same photons in
    // every clustering mode, and every frame is timed.
    let (_, r) = quick_run("hcm_paths.toml");
    for photons in [64u64, 128] {
        for cluster in ["none", "last", "all"] {
            let (x, c) =
                (cell(&r, &format!("{cluster} · xfb"), photons), cell(&r, &format!("{cluster} · compute"), photons));
            let px = metric(x, "processed").unwrap_or(-1.0);
            assert!(px > 0.0, "{cluster} {photons}: nothing processed");
            assert_eq!(Some(px), metric(c, "processed"), "{cluster} {photons}: the paths processed different photons");
            for m in ["Traversal", "Gather", "Frame"] {
                assert!(metric(x, m).unwrap_or(-1.0) > 0.0, "{cluster} · xfb {photons}: {m} not timed");
            }
            assert!(metric(c, "Frame").unwrap_or(-1.0) > 0.0, "{cluster} · compute {photons}: Frame not timed");
        }
    }
    // Table 3 on a sparse photon buffer: the hierarchy splats only the valid photons.
    let (_, r) = quick_run("wyman2008_table3_sparse.toml");
    for photons in [64u64, 128] {
        let dense = metric(cell(&r, "W&D + Sec. 4", photons), "splatted").unwrap_or(-1.0);
        let hier = metric(cell(&r, "hierarchical", photons), "splatted").unwrap_or(-1.0);
        assert!(dense >= (photons * photons) as f64, "{photons}: dense splatted {dense}");
        assert!(hier > 0.0 && hier < 0.5 * dense, "{photons}: hierarchical splatted {hier} of {dense}: not sparse");
        for t in ["W&D 2006", "W&D + Sec. 4", "hierarchical", "combine last", "combine all"] {
            assert!(metric(cell(&r, t, photons), "Gather").unwrap_or(-1.0) > 0.0, "{t} {photons}: Gather not timed");
        }
    }
}

#[test]
fn quick_splat_paths_splat_the_same_photons_and_time_every_splat() {
    // P2: points and the compute splat splat the same photons (the maps themselves are compared
    // in crates/caustics/tests/compute_splat.rs), and every splat is timed, the compute splat's
    // clear and resolve passes included.
    let (_, r) = quick_run("splat_paths.toml");
    for photons in [64u64, 128] {
        for t in ["W&D + Sec. 4", "combine all", "varying multi-res"] {
            let (raster, compute) =
                (cell(&r, &format!("{t} · raster"), photons), cell(&r, &format!("{t} · compute"), photons));
            let splatted = metric(raster, "splatted").unwrap_or(-1.0);
            assert!(splatted > 0.0, "{t} {photons}: nothing splatted");
            assert_eq!(
                Some(splatted),
                metric(compute, "splatted"),
                "{t} {photons}: the paths splatted different photons"
            );
            for (c, path) in [(raster, "raster"), (compute, "compute")] {
                for m in ["Splat", "Gather", "Frame"] {
                    assert!(metric(c, m).unwrap_or(-1.0) > 0.0, "{t} · {path} {photons}: {m} not timed");
                }
            }
        }
        let dense = metric(cell(&r, "W&D + Sec. 4 · compute", photons), "splatted");
        assert_eq!(dense, Some((photons * photons) as f64), "{photons}: the dense compute splat covers every texel");
    }
}

#[test]
fn photon_trace_paths_without_ray_queries_is_refused_before_its_first_cell() {
    // T2 compares the tracer's compute traversal with ray queries, T3 times ray queries following
    // a moving object: a device without them (here hidden; Mesa 22.3's lavapipe has none)
    // refuses each by name before any cell is measured, naming the first technique entry that
    // needs them, and no table is written. scripts/mesa25_check.sh runs both --quick on Mesa 25's
    // lavapipe.
    for (config, entry) in [("photon_trace_paths.toml", "technique[1]"), ("photon_trace_moving.toml", "technique[0]")] {
        let root = common::scratch(&format!("bench-ray-query-{config}"));
        let cfg = workspace().join("bench_configs").join(config);
        let r = common::causticlab(&[
            "--without-feature".as_ref(),
            "acceleration_structure".as_ref(),
            "bench".as_ref(),
            cfg.as_os_str(),
            "--quick".as_ref(),
            "--results".as_ref(),
            root.as_os_str(),
        ]);
        assert_eq!(r.code, Some(2), "{config}: {}", r.describe());
        assert!(
            r.stderr.contains("trace `ray-query`") && r.stderr.contains("acceleration_structure"),
            "{config}: {}",
            r.describe()
        );
        assert!(
            r.stderr.contains(entry) && !r.stderr.contains("cells,"),
            "{config}: refused before a cell: {}",
            r.describe()
        );
        let tables: Vec<_> =
            files_under(&root).into_iter().filter(|p| bench::results::table_name(p).is_some()).collect();
        assert!(tables.is_empty(), "{config}: {tables:?}");
    }
}

#[test]
fn quick_photon_trace_rate_times_the_trace_and_counts_every_emitted_photon() {
    // T1: the tracer's pass (on the device's clock and, submitted alone, on the host's) and the
    // whole frame are timed in every cell, and each rate is, frame for frame, the photons emitted
    // (N², one light) over that frame's time (the JSON keeps six decimals).
    let (_, r) = quick_run("photon_trace_rate.toml");
    let samples = |c: &serde_json::Value, m: &str| -> Vec<f64> {
        c["metrics"][m]["samples"].as_array().expect("samples").iter().filter_map(|v| v.as_f64()).collect()
    };
    for scene in ["sphere_on_plane.toml", "bunny_in_room.toml"] {
        for photons in [64u64, 128] {
            for t in ["Fresnel on", "Fresnel off"] {
                let c = cell_in(&r, scene, t, photons);
                for (time, rate) in [("Trace", "rate"), ("Trace (host)", "host rate"), ("Frame", "frame rate")] {
                    let (ms, per_s) = (samples(c, time), samples(c, rate));
                    assert!(
                        !ms.is_empty() && ms.len() == per_s.len(),
                        "{scene} {t} {photons}: {time} {ms:?}, {rate} {per_s:?}"
                    );
                    for (ms, per_s) in ms.iter().zip(&per_s) {
                        let expected = (photons * photons) as f64 / ms / 1000.0;
                        assert!(
                            *ms > 0.0 && (per_s / expected - 1.0).abs() < 1e-4,
                            "{scene} {t} {photons}: {per_s} M/s over {ms} ms"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn quick_photon_trace_progressive_draws_each_curve_frame_by_frame() {
    // T4: every cell's curve has a point per frame (8 under --quick), its accumulated time
    // growing; the plain tracer's frames are the same photons, so its error is the same at every
    // frame; progressive's first frame is the plain tracer's (the same seed and radius), and its
    // later ones are new photons (the error moves); the 1- and 4-frame columns read the curve.
    let (_, r) = quick_run("photon_trace_progressive.toml");
    let curve = |c: &Value| -> Vec<(u64, f64, f64)> {
        c["progressive"]
            .as_array()
            .expect("a curve")
            .iter()
            .map(|p| {
                (
                    p["frames"].as_u64().expect("frames"),
                    p["ms"].as_f64().expect("ms"),
                    p["rel_rmse"].as_f64().expect("rel_rmse"),
                )
            })
            .collect()
    };
    for scene in ["sphere_on_plane.toml", "ring_cardioid.toml", "bunny_in_room.toml"] {
        let plain = curve(cell_in(&r, scene, "photon-trace", 64));
        for t in ["photon-trace", "progressive", "alpha 1", "binned"] {
            let c = cell_in(&r, scene, t, 64);
            let points = curve(c);
            assert_eq!(points.iter().map(|p| p.0).collect::<Vec<_>>(), (1..=8).collect::<Vec<_>>(), "{scene} {t}");
            assert!(points.windows(2).all(|w| w[1].1 > w[0].1 && w[0].1 > 0.0), "{scene} {t}: {points:?}");
            for (label, frame) in [("1 frame", 0), ("4 frames", 3)] {
                assert_eq!(c["metrics"][label]["value"].as_f64(), Some(points[frame].2), "{scene} {t} {label}");
            }
            assert!(c["metrics"]["64 frames"]["value"].is_null(), "{scene} {t}: --quick stops at 8 frames");
        }
        assert!(plain.iter().all(|p| p.2 == plain[0].2), "{scene}: the plain tracer's error moved: {plain:?}");
        let progressive = curve(cell_in(&r, scene, "progressive", 64));
        assert_eq!(progressive[0].2, plain[0].2, "{scene}: progressive's first frame is the plain tracer's");
        assert!(progressive[1..].iter().all(|p| p.2 != plain[0].2), "{scene}: no new photons? {progressive:?}");
    }
}

#[test]
fn quick_photon_trace_reconstructions_time_and_judge_every_reconstruction() {
    // T5: every cell times its caustic stages and has its error; the exact photons keep their
    // power whole however they are reconstructed, so each of their rows' caustic flux is the
    // reference's within 5% (seen at 64² on the ring: 1.018 fixed, 0.996 differentials; the
    // receiver map's lookup of the caustic map moves it, not the splats).
    let (_, r) = quick_run("photon_trace_reconstructions.toml");
    let value = |c: &Value, m: &str| c["metrics"][m]["value"].as_f64();
    for scene in ["sphere_on_plane.toml", "ring_cardioid.toml", "bunny_in_room.toml"] {
        let photons = 64u64;
        for t in [
            "wd-points",
            "wd-quads light Eq. 4",
            "hcm varying multi-res",
            "photon-trace",
            "differentials",
            "binned",
            "wd-eye-points Eq. 10",
            "screen-space",
        ] {
            let c = cell_in(&r, scene, t, photons);
            assert!(value(c, "Caustic map").is_some_and(|ms| ms > 0.0), "{scene} {t} {photons}: no time");
            assert!(value(c, "rel. RMSE").is_some_and(|e| e.is_finite()), "{scene} {t} {photons}: no error");
        }
        for t in ["photon-trace", "differentials", "binned", "screen-space"] {
            let flux = value(cell_in(&r, scene, t, photons), "flux ratio").expect("a flux ratio");
            assert!((flux - 1.0).abs() < 0.05, "{scene} {t} {photons}: flux ratio {flux}");
        }
    }
}

#[test]
fn quick_trendall_stewart2000_table1_times_the_passes_and_the_height_field() {
    let (dir, r) = quick_run("trendall_stewart2000_table1.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 2 * 3 * 2, "2 scenes x 3 techniques x 2 grid sides");
    for c in cells {
        for m in ["caustics fps", "height field fps"] {
            assert!(metric(c, m).is_some_and(|v| v.is_finite() && v > 0.0), "{m}: {}", c["cell"]);
        }
    }
    let md = std::fs::read_to_string(dir.join("trendall_stewart2000_table1.md")).expect("md");
    assert!(md.contains("37.9") && md.contains("178"), "the paper's values beside ours");
}

#[test]
fn quick_fig10_times_five_caustic_maps_each_with_its_own_passes() {
    // Wyman & Nichols 2009 Fig. 10: simple and deferred photon buffers, the deferred hierarchy,
    // adaptive with both metrics; each cell timed, each technique running the passes it names.
    let (_, r) = quick_run("wyman_nichols2009_fig10.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 3 * 5, "3 scenes x 5 techniques at the quick run's one photon count");
    for c in cells {
        let label = c["cell"]["technique_label"].as_str().unwrap_or_default();
        for m in ["fps", "caustic map"] {
            assert!(metric(c, m).is_some_and(|v| v.is_finite() && v > 0.0), "{label}: {m}");
        }
        let passes: Vec<&str> =
            c["passes"].as_array().expect("passes").iter().filter_map(|p| p["name"].as_str()).collect();
        let has = |prefix: &str| passes.iter().any(|p| p.starts_with(prefix));
        let expect = match label {
            "Simple" => [true, false, false, false],
            "Deferred" => [false, true, false, false],
            "Deferred Hier." => [false, true, true, false],
            _ => [false, false, false, true],
        };
        let got = [has("photon_buffer."), has("deferred_photons."), has("hierarchy."), has("adaptive.traverse")];
        assert_eq!(got, expect, "{label}: {passes:?}");
        assert!(has("deferred_refraction."), "{label}: the eye view is rendered deferred (Sec. 5)");
    }
}

#[test]
fn quick_wyman_davis2006_fig6_counts_the_quads_fragments_of_every_cell() {
    // Fig. 6: the quads' depth complexity per cell, its percentiles in order, the share of the
    // view they touch, and their pass timed on the host.
    let (dir, r) = quick_run("wyman_davis2006_fig6.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 3 * 2 * 2, "3 scenes x 2 ways to draw x 2 photon counts");
    for c in cells {
        let label = format!("{} {}", c["cell"]["scene"], c["cell"]["technique_label"]);
        let get = |m: &str| metric(c, m).unwrap_or_else(|| panic!("{label}: no {m}"));
        let (mean, p50, p90, p99, max) = (get("mean"), get("median"), get("p90"), get("p99"), get("max"));
        assert!(mean >= 1.0 && mean <= max, "{label}: mean {mean}, max {max}");
        assert!(1.0 <= p50 && p50 <= p90 && p90 <= p99 && p99 <= max, "{label}: {p50} {p90} {p99} {max}");
        let coverage = get("coverage");
        assert!(coverage > 0.0 && coverage <= 1.0, "{label}: coverage {coverage}");
        assert!(get("quads pass") > 0.0, "{label}: the quads' pass has a host time");
    }
    let md = std::fs::read_to_string(dir.join("wyman_davis2006_fig6.md")).expect("md");
    assert!(md.contains("every pass submitted and waited for alone"), "the header says how the pass was timed");
}

#[test]
fn quick_wyman_nichols2009_fig13_times_the_dragon_alone_and_with_two_spheres() {
    // Fig. 13: both scenes, both frame modes and the caustic stages.
    let (dir, r) = quick_run("wyman_nichols2009_fig13.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 2 * 2, "2 scenes x 2 photon counts");
    for c in cells {
        let scene = c["cell"]["scene"].as_str().unwrap_or_default();
        for m in ["fps", "fps per-pass", "caustic map"] {
            assert!(metric(c, m).is_some_and(|v| v.is_finite() && v > 0.0), "{scene}: {m}");
        }
    }
    let md = std::fs::read_to_string(dir.join("wyman_nichols2009_fig13.md")).expect("md");
    assert!(md.contains("dragon_two_spheres"), "both scenes in the table:\n{md}");
}

#[test]
fn quick_viewer_frame_time_times_throughput_frames_that_create_nothing() {
    // V1: the bench's side of the viewer's frame-time check (scripts/viewer_frame_time.sh).
    let (_, r) = quick_run("viewer_frame_time.toml");
    let cells = r["cells"].as_array().expect("cells");
    assert_eq!(cells.len(), 1, "one scene, one technique, one size");
    let cell = &cells[0];
    let (ms, fps) = (metric(cell, "frame").unwrap_or(-1.0), metric(cell, "fps").unwrap_or(-1.0));
    assert!(ms > 0.0 && fps > 0.0, "{}", cell["cell"]);
    let t = &cell["frame_counters"]["throughput"];
    assert_eq!(t["most_objects"].as_u64(), Some(0), "{t}");
    assert_eq!(t["submits"].as_f64(), Some(1.0), "{t}");
}

#[test]
fn every_bench_config_has_a_quick_test() {
    // A config no test runs could rot unnoticed: each must be named in one of these files.
    let src = [include_str!("bench_papers.rs"), include_str!("bench_quality.rs")].concat();
    for config in bench_config_names() {
        assert!(
            src.contains(&format!("\"{config}.toml\"")),
            "bench_configs/{config}.toml is run by no test in tests/bench_papers.rs or bench_quality.rs"
        );
    }
}

#[test]
fn every_bench_config_is_in_the_gpu_suite_or_says_why_not() {
    // A config left out of scripts/gpu_suite.sh never gets a GPU column; one listed twice runs
    // twice; a listed name without its config fails only on the lent machine. Each config in the
    // suite has its row (cells, seconds) in docs/bench.md's table of expected times.
    let list = |flag: &str| -> Vec<String> {
        let out = std::process::Command::new("bash")
            .arg("scripts/gpu_suite.sh")
            .arg(flag)
            .current_dir(workspace())
            .output()
            .expect("bash");
        assert!(out.status.success(), "gpu_suite.sh {flag}: {}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8(out.stdout).expect("utf-8").lines().map(str::to_string).collect()
    };
    let (run, left_out) = (list("--list-configs"), list("--list-not-run"));
    let docs = std::fs::read_to_string(workspace().join("docs/bench.md")).expect("docs/bench.md");
    let configs = bench_config_names();
    for c in &configs {
        let times = run.iter().chain(&left_out).filter(|n| *n == c).count();
        assert_eq!(times, 1, "bench_configs/{c}.toml is named {times} times in scripts/gpu_suite.sh's lists");
    }
    for n in run.iter().chain(&left_out) {
        assert!(configs.contains(n), "scripts/gpu_suite.sh names '{n}', which is not in bench_configs/");
    }
    for n in &run {
        assert!(
            docs.contains(&format!("| `{n}` |")),
            "docs/bench.md's table of expected GPU times has no row for `{n}`"
        );
    }
}

/// The names of the configs in bench_configs/ (without `.toml`).
fn bench_config_names() -> Vec<String> {
    let mut names = vec![];
    for e in std::fs::read_dir(workspace().join("bench_configs")).expect("bench_configs") {
        let name = e.expect("entry").file_name().to_string_lossy().to_string();
        if let Some(stem) = name.strip_suffix(".toml") {
            names.push(stem.to_string());
        }
    }
    names
}
