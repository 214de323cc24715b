//! `<config>.md`: the tables laid out like the paper's (ours beside the paper's, with the
//! spread of every time), the legend, the ratios against the config's baseline as one grid per
//! metric, the notes and the plot; the same tables in plain text as the terminal summary; and
//! `<config>.csv`, one row per cell and metric.

use crate::config::Config;
use crate::format::unit;
use crate::results::{is_timing, Results};
use crate::sections::{legend, ratio_tables, value_tables, Footnotes};
use crate::table::grid;
use crate::text_table::Style;
use std::fmt::Write as _;

/// The table's Markdown; `root` is the results folder it is written under (its "Regenerate"
/// line names it where it is not the default `results`).
pub fn markdown(config: &Config, results: &Results, root: &std::path::Path) -> String {
    let g = grid(config, results);
    let m = &results.meta;
    let r = &results.run;
    let mut s = String::new();
    let _ = writeln!(s, "# {}\n", config.table.title());
    let _ = writeln!(s, "> {}\n", config.table.caption);
    if r.quick {
        let _ = writeln!(
            s,
            "**Quick run (`--quick`): small sizes and few frames, a smoke test, not a measurement: its spreads \
             (`!`) and plausibility findings (`?`) come from those few frames and say nothing of the techniques.**\n"
        );
    }
    if r.validation {
        let _ = writeln!(s, "**Validation layers were on: these times are not measurements.**\n");
    }
    if let Some(line) = partial_line(results) {
        let _ = writeln!(s, "**{line}**\n");
    }
    let _ = writeln!(
        s,
        "- **Device:** {} ({}), driver {} {}, Vulkan {}\n- **CPU:** {}\n- **Commit:** {} · **date:** {} · \
         **config:** `{}` (hash {})",
        m.device,
        m.device_type,
        m.driver_name,
        m.driver_info,
        m.vulkan_version,
        m.cpu,
        m.commit,
        m.date,
        results.config.file,
        results.config.hash
    );
    if let Some(e) = &r.explained {
        let front = if config.front.is_some() { " and its `[front]` drawn" } else { "" };
        let _ = writeln!(
            s,
            "- **Explained after the run:** read again with its config as it was at commit {} ({}): its \
             `[[plausibility.explained]]` entries and rules applied{front} by `causticlab bench explain`, which \
             times nothing; the config was hash {} when measured and differs from it at most in what measures \
             nothing (its text, layout, `[[paper]]` sources, how its cells are judged, its `[front]`, and the \
             `[quick]` sizes a full table did not use)",
            e.commit, e.date, e.measured_config_hash
        );
    }
    let _ = writeln!(
        s,
        "- **Run:** {}; light path {}, camera path {}, object path {} ({} frames per loop). Times are medians \
         over the measured frames; fps is 1000 / mean frame time.",
        frames_line(results),
        r.light_path,
        r.camera_path,
        r.object_path,
        r.period_frames
    );
    let _ = writeln!(s, "{}", modes_line(config, results));
    if let Some(gbs) = r.copy_bandwidth_gbs {
        let _ = writeln!(s, "- **Device copy bandwidth:** {gbs:.1} GB/s (bytes read plus written by a buffer copy, measured at the start of the run)");
    }
    if let Some(line) = crate::final_flip::header_line(results) {
        let _ = writeln!(s, "{line}");
    }
    if let Some(line) = models_line(results) {
        let _ = writeln!(s, "{line}");
    }
    if let Some(line) = host_speed_line(results) {
        let _ = writeln!(s, "{line}");
    }
    if let Some(line) = load_line(results) {
        let _ = writeln!(s, "{line}");
    }
    if !m.quirks.is_empty() {
        let _ = writeln!(s, "- **Device quirks worked around:** {}", m.quirks.join("; "));
    }
    if let Some(line) = steal_line(results) {
        let _ = writeln!(s, "{line}");
    }
    let _ = writeln!(s);
    let mut notes = Footnotes::default();
    s.push_str(&value_tables(&g, Style::Markdown, &mut notes));
    let mut below: Vec<String> = units_line(config.metrics.iter().map(|m| (m.label.as_str(), m.kind.as_str())))
        .into_iter()
        .chain(legend(&g, &notes))
        .collect();
    if let Some(hidden) = hidden_columns(&g) {
        below.push(hidden);
    }
    for line in below {
        let _ = writeln!(s, "{line}\n");
    }
    let ratios = ratio_tables(config, &g, Style::Markdown);
    if !ratios.is_empty() {
        let _ = writeln!(s, "{ratios}");
    }
    s.push_str(&crate::front::markdown(config, results));
    s.push_str(&plausibility_section(results));
    let mut notes = config.table.notes.clone();
    for m in &config.metrics {
        if let Some(why) = &m.absent {
            notes.push(format!("`{}` reads n/a where a cell recorded no pass it sums: {why}.", m.label));
        }
    }
    if m.driver_name.to_lowercase().contains("llvmpipe") || m.device.to_lowercase().contains("llvmpipe") {
        notes.push(
            "lavapipe runs every pass serially on the CPU: its times are CPU time, fine for ratios between \
             techniques on this machine, never comparable with GPU numbers. Its timestamps miss the draws that \
             stream out with rasterization discarded (the `xfb` hierarchical traversal): their work falls \
             outside every timestamp pair, so those passes read near zero; `frame_ms` (host wall time) counts it."
                .into(),
        );
    }
    if !notes.is_empty() {
        let _ = writeln!(s, "## Notes\n");
        for n in notes {
            let _ = writeln!(s, "- {n}");
        }
        let _ = writeln!(s);
    }
    let name = &results.config.name;
    let _ = writeln!(s, "![plot]({name}.png)\n\nThe plot as SVG: [{name}.svg]({name}.svg).\n");
    let quick = if r.quick { " --quick" } else { "" };
    let default_root = std::path::Path::new("results");
    if root.components().eq(default_root.components()) {
        let _ = writeln!(
            s,
            "Regenerate: `causticlab bench {}{quick}`; raw samples in `{name}.json.gz` (gzip-compressed JSON), \
             one row per cell and metric in `{name}.csv`; redraw this table from the JSON with `causticlab bench \
             merge` of its `{name}.json.gz`, `--results` naming the results folder it was written under \
             (`results/`, the default, from the repository's root: `causticlab bench merge {}/{name}.json.gz`).",
            results.config.file,
            crate::run::device_dir(default_root, results).display(),
        );
    } else {
        let _ = writeln!(
            s,
            "Regenerate: `causticlab bench {}{quick} --results {}`; raw samples in `{name}.json.gz` \
             (gzip-compressed JSON), one row per cell and metric in `{name}.csv`; redraw this table from the JSON: \
             `causticlab bench merge {}/{name}.json.gz --results {}`.",
            results.config.file,
            root.display(),
            crate::run::device_dir(root, results).display(),
            root.display(),
        );
    }
    s
}

/// The terminal's view of a run: what ran where, the tables and the ratio grids in plain text.
pub fn summary(config: &Config, results: &Results) -> String {
    let g = grid(config, results);
    let m = &results.meta;
    let mut s = format!(
        "{}{}\n{} ({}) · {} cells · {}\n\n",
        config.table.title(),
        if results.run.quick { " (quick run: not a measurement)" } else { "" },
        m.device,
        m.driver_info,
        results.cells.len(),
        frames_line(results)
    );
    if let Some(line) = partial_line(results) {
        let _ = writeln!(s, "{line}\n");
    }
    let mut notes = Footnotes::default();
    s.push_str(&value_tables(&g, Style::Plain, &mut notes));
    for line in units_line(config.metrics.iter().map(|m| (m.label.as_str(), m.kind.as_str())))
        .into_iter()
        .chain(legend(&g, &notes))
    {
        let _ = writeln!(s, "{}", crate::text_table::wrap(&line, crate::text_table::WIDTH));
    }
    let ratios = ratio_tables(config, &g, Style::Plain);
    if !ratios.is_empty() {
        let _ = write!(s, "\n{ratios}");
    }
    s
}

/// `1 warm-up frame, then at least 3 measured frames and 1 s (at most 1000): 3 to 41 frames,
/// median 5`.
/// Which frame mode each timed metric ran in, and what a frame of each mode asked of the driver
/// (medians over the cells of their per-frame medians).
fn modes_line(config: &Config, results: &Results) -> String {
    let timed: Vec<&crate::config::MetricSpec> = config.metrics.iter().filter(|m| is_timing(&m.kind)).collect();
    let names = |throughput: bool| -> Vec<String> {
        timed.iter().filter(|m| m.throughput() == throughput).map(|m| m.label.clone()).collect()
    };
    let mut parts = vec![];
    for (mode, throughput, what) in [
        (
            "per-pass",
            false,
            if config.host_pass_times() {
                "one-shot frames, a timestamp pair and a crash-marker barrier around every pass, every pass submitted \
                 and waited for alone (host pass times), each frame waited for"
                    .to_string()
            } else {
                "one-shot frames, a timestamp pair and a crash-marker barrier around every pass, each frame waited for"
                    .to_string()
            },
        ),
        (
            "throughput",
            true,
            format!(
                "a ring of {} frames in flight, no object made once warm, one timestamp pair per frame; fps and frame_ms \
                 per block of {} frames, the median over at least {} blocks",
                caustics::render::FrameMode::SLOTS,
                config.run.block_frames,
                crate::config::min_blocks(results.run.quick)
            ),
        ),
    ] {
        let labels = names(throughput);
        if labels.is_empty() {
            continue;
        }
        let per_frame: Vec<&crate::results::FrameCounters> =
            results.cells.iter().filter_map(|c| c.frame_counters.get(mode)).collect();
        let median = |f: &dyn Fn(&crate::results::FrameCounters) -> f64| {
            let v: Vec<f64> = per_frame.iter().map(|c| f(c)).collect();
            crate::stats::quartiles(&v).map(|(_, m, _)| m)
        };
        let counts = match (median(&|c| c.submits), median(&|c| c.barriers), median(&|c| c.timestamps), median(&|c| c.objects)) {
            (Some(s), Some(b), Some(t), Some(o)) => format!(
                "; per frame {s} submit(s), {b} barriers, {t} timestamps, {o} Vulkan objects made (most in any frame: {})",
                per_frame.iter().map(|c| c.most_objects).max().unwrap_or(0)
            ),
            _ => String::new(),
        };
        parts.push(format!("`{mode}` for {} ({what}{counts})", labels.join(", ")));
    }
    if parts.is_empty() {
        return "- **Frame modes:** no timed metric".into();
    }
    format!("- **Frame modes:** {}.", parts.join("; "))
}

/// The plausibility rules' findings: the open ones (`?`), then the explained ones.
fn plausibility_section(results: &Results) -> String {
    let f = &results.plausibility;
    let mut s = String::new();
    if f.is_empty() {
        return s;
    }
    let _ = writeln!(s, "## Plausibility\n");
    let _ = writeln!(
        s,
        "Rules (bench_configs/README.md#plausibility): a) more work, less time; b) dynamic beats static; c) faster \
         than the device's memory; d) varies along an axis it does not depend on; e) the device's timestamps missed \
         the work its host time shows; f) photons faster than the device can write them; g) a count that falls as \
         the work grows. Entries found by c, e or f read `not measured`.\n"
    );
    let row = |x: &crate::plausibility::Finding| {
        let cell: Vec<String> = x.keys.iter().filter(|(_, v)| !v.is_empty()).map(|(k, v)| format!("{k}={v}")).collect();
        format!("- ({}) {} [{}]", x.rule, x.text, cell.join(" "))
    };
    let open: Vec<String> = f.iter().filter(|x| x.explained.is_none()).map(row).collect();
    if !open.is_empty() {
        let _ = writeln!(s, "Implausible (`?`), {} entries:\n", open.len());
        for r in open {
            let _ = writeln!(s, "{r}");
        }
        let _ = writeln!(s);
    }
    let explained: Vec<String> =
        f.iter().filter_map(|x| Some(format!("{}; explained: {}", row(x), x.explained.as_ref()?))).collect();
    if !explained.is_empty() {
        let _ = writeln!(s, "Explained, {} entries:\n", explained.len());
        for r in explained {
            let _ = writeln!(s, "{r}");
        }
        let _ = writeln!(s);
    }
    s
}

/// The model files the cells loaded, by checksum; a table made with a file other than the one
/// docs/scenes.md lists says so first.
fn models_line(results: &Results) -> Option<String> {
    let mut models: Vec<&caustics::scene::models::ModelFile> = results.cells.iter().flat_map(|c| &c.models).collect();
    models.sort();
    models.dedup();
    if models.is_empty() {
        return None;
    }
    let list: Vec<String> = models.iter().map(|m| m.describe()).collect();
    Some(if models.iter().any(|m| m.differs()) {
        format!(
            "- **Made with another model:** a model file is not the one the project's tables use, so these \
             numbers are of another scene: {}",
            list.join("; ")
        )
    } else {
        format!("- **Models:** {}", list.join("; "))
    })
}

/// How fast the host ran from cell to cell (`crate::host_speed`), where that was measured.
fn host_speed_line(results: &Results) -> Option<String> {
    let probes: Vec<f64> = results.cells.iter().filter_map(|c| c.host_probe_ms).collect();
    let (fastest, median, slowest) = crate::host_speed::summary(&probes)?;
    let ratio = slowest / fastest;
    let warning = if ratio > crate::host_speed::DRIFT_WARNING {
        ": the host's speed drifted while the table ran, so cells measured far apart may differ for that alone"
    } else {
        ""
    };
    Some(format!(
        "- **Host speed** (a fixed single-threaded CPU loop timed before each cell, best of 3): median {median:.2} ms, \
         fastest {fastest:.2}, slowest {slowest:.2} ({ratio:.2}x){warning}"
    ))
}

/// How busy the host was with other processes while the cells ran, where that was measured.
fn load_line(results: &Results) -> Option<String> {
    let mut v: Vec<f64> = results.cells.iter().filter_map(|c| c.other_cores).collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let busy = results.cells.iter().filter(|c| c.busy).count();
    Some(format!(
        "- **Other processes on the host** (CPU time besides this run's, in cores, while a cell ran): median {:.2}, \
         max {:.2}; {busy} busy cells (`~`)",
        v[v.len() / 2],
        v[v.len() - 1]
    ))
}

/// What a partial merge left out, or `None` for a whole table.
fn partial_line(results: &Results) -> Option<String> {
    let n = results.run.not_run.len();
    (n > 0).then(|| {
        format!(
            "Partial table: {n} of {} cells were not run (cut off by a time budget, as in `scripts/gpu_suite.sh`, or \
             failed); they read `not run` (`bench merge --partial`).",
            results.run.total_cells
        )
    })
}

fn frames_line(results: &Results) -> String {
    let r = &results.run;
    let plural = |n: u32, what: &str| format!("{n} {what}{}", if n == 1 { "" } else { "s" });
    let mut s = format!("{}, then ", plural(r.warmup_frames, "warm-up frame"));
    match r.time_budget_s.filter(|b| *b > 0.0) {
        Some(b) => {
            let _ = write!(s, "at least {} and {b} s of them", plural(r.measured_frames, "measured frame"));
            if let Some(max) = r.max_frames {
                let _ = write!(s, " (at most {max})");
            }
        }
        None => s.push_str(&plural(r.measured_frames, "measured frame")),
    }
    s.push_str(" per cell");
    let mut counts: Vec<usize> = results.cells.iter().map(|c| c.wall_ms.len()).collect();
    counts.sort_unstable();
    if let (Some(lo), Some(hi)) = (counts.first(), counts.last()) {
        if lo != hi {
            let _ = write!(s, ": {lo} to {hi} frames, median {}", counts[counts.len() / 2]);
        }
    }
    s
}

/// Says how many measured columns the paper's layout leaves out of the Markdown.
fn hidden_columns(g: &crate::table::Grid) -> Option<String> {
    let shown: usize = g.sections.iter().map(|s| s.cols.len()).sum();
    let hidden = g.cols.len().saturating_sub(shown);
    (hidden > 0).then(|| {
        format!(
            "The paper's columns only: {hidden} more measured column{} ({}) are in the CSV and JSON.",
            if hidden == 1 { "" } else { "s" },
            g.col_axes.join(" · ")
        )
    })
}

/// The unit of every column: `Values in ms.` when all metrics share one, else each unit with the
/// metrics (by label) in it, e.g. ``Values: `Gather`, `Frame` in ms; `processed` in points.``.
/// `None` when no metric has a unit (quality tables).
fn units_line<'a>(metrics: impl Iterator<Item = (&'a str, &'a str)>) -> Option<String> {
    let mut groups: Vec<(&str, Vec<&str>)> = vec![];
    for (label, kind) in metrics {
        let u = unit(kind);
        match groups.iter_mut().find(|(g, _)| *g == u) {
            Some((_, labels)) => labels.push(label),
            None => groups.push((u, vec![label])),
        }
    }
    match groups.as_slice() {
        [] | [("", _)] => None,
        [(u, _)] => Some(format!("Values in {u}.")),
        _ => {
            let parts: Vec<String> = groups
                .iter()
                .map(|(u, labels)| {
                    let names = labels.iter().map(|l| format!("`{l}`")).collect::<Vec<_>>().join(", ");
                    if u.is_empty() {
                        format!("{names} unitless")
                    } else {
                        format!("{names} in {u}")
                    }
                })
                .collect();
            Some(format!("Values: {}.", parts.join("; ")))
        }
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

pub fn csv(config: &Config, results: &Results) -> String {
    let mut s = String::from(
        "config,device,scene,technique,photons,lights,resolution,lighting,metric,kind,value,min,max,q1,q3,frames,\
         paper,paper_note\n",
    );
    let num = |v: Option<f64>| v.map(|v| format!("{v}")).unwrap_or_default();
    for c in &results.cells {
        for m in &config.metrics {
            let Some(v) = c.metrics.get(&m.label) else { continue };
            let mut keys: std::collections::BTreeMap<String, String> =
                ["scene", "technique", "photons", "lights", "resolution", "lighting"]
                    .iter()
                    .map(|a| (a.to_string(), c.cell.key(a)))
                    .collect();
            keys.insert("metric".into(), m.label.clone());
            let paper = crate::paper::value(config, &keys);
            let quartiles = crate::stats::quartiles(&v.samples).filter(|_| is_timing(&v.kind));
            let note = paper.as_ref().map(|p| match (&p.scene_note, &p.not_comparable) {
                (Some(s), Some(r)) => format!("scene: {s}; not comparable: {r}"),
                (Some(s), None) => format!("scene: {s}"),
                (None, Some(r)) => format!("not comparable: {r}"),
                (None, None) => String::new(),
            });
            let fields = [
                results.config.name.clone(),
                results.meta.device.clone(),
                c.cell.key("scene"),
                c.cell.key("technique"),
                c.cell.key("photons"),
                c.cell.key("lights"),
                c.cell.key("resolution"),
                c.cell.key("lighting"),
                m.label.clone(),
                m.kind.clone(),
                num(v.value),
                num(v.min),
                num(v.max),
                num(quartiles.map(|q| q.0)),
                num(quartiles.map(|q| q.2)),
                if v.samples.is_empty() { String::new() } else { v.samples.len().to_string() },
                num(paper.as_ref().map(|p| p.value)),
                note.unwrap_or_default(),
            ];
            let _ = writeln!(s, "{}", fields.iter().map(|f| csv_field(f)).collect::<Vec<_>>().join(","));
        }
    }
    s
}

/// Cells above this CPU steal are named in the table's header.
const NOTABLE_STEAL: f64 = 0.10;

/// How much CPU the hypervisor took while the cells ran, and which cells lost most: on a
/// software device their times are inflated by about 1 / (1 - steal).
fn steal_line(results: &Results) -> Option<String> {
    let mut steal: Vec<(f64, String)> =
        results.cells.iter().filter_map(|c| Some((c.cpu_steal?, short(&c.cell)))).collect();
    if steal.is_empty() {
        return None;
    }
    steal.sort_by(|a, b| a.0.total_cmp(&b.0));
    let pct = |v: f64| format!("{:.0}%", v * 100.0);
    let median = steal[steal.len() / 2].0;
    let mut line = format!(
        "- **Host CPU steal** (CPU time the hypervisor gave to other guests while a cell's frames ran): median {}, \
         max {}",
        pct(median),
        pct(steal[steal.len() - 1].0)
    );
    let notable: Vec<String> =
        steal.iter().rev().filter(|(v, _)| *v > NOTABLE_STEAL).map(|(v, d)| format!("{d} ({})", pct(*v))).collect();
    if !notable.is_empty() {
        let shown = notable.len().min(5);
        let more = if notable.len() > shown { format!(" and {} more", notable.len() - shown) } else { String::new() };
        line.push_str(&format!(
            ". Above {}, times run long by about 1 / (1 − steal): {}{more}",
            pct(NOTABLE_STEAL),
            notable[..shown].join("; ")
        ));
    }
    Some(line)
}

fn short(cell: &crate::plan::Cell) -> String {
    format!("{} · {} · {}²", cell.key("scene"), cell.key("technique"), cell.key("photons"))
}

#[cfg(test)]
mod tests {
    #[test]
    fn units_line_names_the_unit_of_every_metric() {
        let line = |m: &[(&'static str, &'static str)]| super::units_line(m.iter().copied());
        assert_eq!(line(&[("a", "pass_ms"), ("b", "frame_ms")]).as_deref(), Some("Values in ms."));
        assert_eq!(line(&[("rel", "rel_rmse"), ("flux", "flux_ratio")]), None);
        // hcm_paths: times and a photon count in one table.
        assert_eq!(
            line(&[("Traversal", "pass_ms"), ("Frame", "frame_ms"), ("processed", "photons_processed")]).as_deref(),
            Some("Values: `Traversal`, `Frame` in ms; `processed` in points.")
        );
        assert_eq!(
            line(&[("fps", "fps"), ("rel", "rel_rmse")]).as_deref(),
            Some("Values: `fps` in fps; `rel` unitless.")
        );
    }
}
