//! The table, summary and plot of a result built from synthetic samples, through the same code
//! that renders a real run: a noisy cell is flagged and a steady one is not; a paper value from
//! another scene or for other work is marked and gets no ratio; the ratios are one grid; every
//! line fits a 120-column terminal; the plot has a ratio panel and draws as SVG and PNG.

mod common;
use bench::config::Config;
use bench::results::Results;
use common::{cell, results};

const CONFIG: &str = r#"
[table]
paper = "Synthetic"
number = "S"
caption = "Synthetic samples."

[matrix]
scenes = ["../scenes/sphere_on_plane.toml"]
photons = [256, 512]

[[technique]]
label = "base"
technique = "wd-points"

[[technique]]
label = "fast"
technique = "hcm"

[[metric]]
label = "Gather"
kind = "pass_ms"
passes = ["splat.*"]

[layout]
rows = ["photons"]
columns = ["technique"]
compare = { axis = "technique", baseline = "base" }

[[paper]]
photons = 256
values = { base = 10.0, fast = 5.0 }

[[paper]]
photons = 512
values = { base = 20.0, fast = 8.0 }
not_comparable = "the paper's fast gather skips the copy"
"#;

/// Steady: IQR 0.1 of a median of 10 (1%). Noisy: IQR 14 - 6 = 8 of a median of 10 (80%).
const STEADY: [f64; 5] = [10.0, 10.1, 9.9, 10.0, 10.05];
const NOISY: [f64; 5] = [5.0, 10.0, 15.0, 6.0, 14.0];

fn synthetic() -> (Config, Results) {
    let config: Config = toml::from_str(CONFIG).expect("the test config parses");
    let cells = vec![
        cell(0, 0, "base", 256, &STEADY),
        cell(1, 0, "base", 512, &STEADY),
        cell(2, 1, "fast", 256, &NOISY),
        cell(3, 1, "fast", 512, &STEADY),
    ];
    let r = results(&config, CONFIG, cells);
    (config, r)
}

/// The cells of the Markdown table row (or ratio row) that starts with `label`, after `skip`
/// earlier such rows.
fn row<'a>(md: &'a str, label: &str, skip: usize) -> Vec<&'a str> {
    let line = md
        .lines()
        .filter(|l| l.starts_with(&format!("| {label}")))
        .nth(skip)
        .unwrap_or_else(|| panic!("no row {label} #{skip} in\n{md}"));
    line.split('|').map(str::trim).filter(|c| !c.is_empty()).collect()
}

#[test]
fn a_noisy_cell_is_flagged_and_a_steady_one_is_not() {
    let (config, r) = synthetic();
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    // Columns: photons, base, fast.
    let r256 = row(&md, "256²", 0);
    assert!(r256[1].starts_with("10.0 ±1% (10.0)") && !r256[1].contains('!'), "steady cell: {r256:?}");
    assert!(r256[2].contains("±80%!"), "noisy cell not flagged: {r256:?}");
    assert!(!row(&md, "512²", 0)[2].contains("%!"), "{md}");
    assert!(md.contains("(1 of 4 timed cells)"), "{md}");
    // The terminal summary flags the same cell.
    let summary = bench::report::summary(&config, &r);
    assert_eq!(summary.matches("%!").count(), 1, "{summary}");
    assert!(!summary.contains("| "), "the summary is plain text, not Markdown:\n{summary}");
}

/// A cell measured again for its spread is counted under the table; one measured once is not.
#[test]
fn cells_measured_again_for_their_spread_are_counted_under_the_table() {
    let (config, mut r) = synthetic();
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    assert!(!md.contains("measured again because"), "{md}");
    r.cells[1].spread_attempts = vec![0.31, 0.04];
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    assert!(md.contains("1 timed entries come from cells measured again because"), "{md}");
}

/// The host speed probe: no line without probes; with them the fastest, median and slowest, and
/// a warning once the slowest is over 1.15x the fastest.
#[test]
fn the_header_gives_the_host_speed_and_warns_when_it_drifted() {
    let (config, mut r) = synthetic();
    assert!(!bench::report::markdown(&config, &r, std::path::Path::new("results")).contains("Host speed"));
    for (c, ms) in r.cells.iter_mut().zip([5.0, 5.1, 5.2, 5.5]) {
        c.host_probe_ms = Some(ms);
    }
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    let line = md.lines().find(|l| l.contains("**Host speed**")).unwrap_or_else(|| panic!("no host speed line:\n{md}"));
    assert!(line.contains("fastest 5.00, slowest 5.50 (1.10x)") && !line.contains("drifted"), "{line}");
    r.cells[3].host_probe_ms = Some(6.0);
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    let line = md.lines().find(|l| l.contains("**Host speed**")).expect("host speed line");
    assert!(line.contains("(1.20x): the host's speed drifted"), "{line}");
}

#[test]
fn a_not_comparable_paper_value_is_marked_and_gets_no_ratio() {
    let (config, r) = synthetic();
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    assert!(row(&md, "512²", 0)[2].ends_with("(8.0¹)"), "{md}");
    assert!(md.contains("¹ The paper's value measures other work: the paper's fast gather skips the copy"), "{md}");
    // One ratio grid: photons x the techniques other than the baseline.
    let ratios = &md[md.find("## Ratios against technique `base`").expect("ratio section")..];
    assert_eq!(row(ratios, "photons", 0), vec!["photons", "fast"], "{ratios}");
    // Ours 5 / 10 = 0.50 (flagged: the fast cell is noisy) beside the paper's 5 / 10.
    assert_eq!(row(ratios, "256²", 0)[1], "1.00! (0.50)", "{ratios}");
    // At 512² the paper's value is not comparable: our ratio alone.
    assert_eq!(row(ratios, "512²", 0)[1], "1.00", "{ratios}");
}

#[test]
fn a_paper_value_from_another_scene_names_it_and_gets_no_ratio() {
    let text = CONFIG.replace("not_comparable = \"the paper's fast gather skips the copy\"", "scene_note = \"Buddha\"");
    let config: Config = toml::from_str(&text).expect("parses");
    let (_, r) = synthetic();
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    assert!(row(&md, "512²", 0)[1].ends_with("(20.0, Buddha)"), "{md}");
    let ratios = &md[md.find("## Ratios").expect("ratio section")..];
    assert_eq!(row(ratios, "512²", 0)[1], "1.00", "{ratios}");
}

#[test]
fn every_line_of_a_wide_table_fits_a_terminal() {
    // Twelve techniques: wider than 120 columns in one block.
    let mut text = CONFIG.to_string();
    for i in 0..10 {
        text.push_str(&format!("\n[[technique]]\nlabel = \"technique number {i}\"\ntechnique = \"hcm\"\n"));
    }
    let config: Config = toml::from_str(&text).expect("parses");
    let mut cells = vec![];
    for (t, tech) in config.techniques.iter().enumerate() {
        for (k, p) in [256, 512].into_iter().enumerate() {
            cells.push(cell(t * 2 + k, t, &tech.label, p, &NOISY));
        }
    }
    let r = results(&config, CONFIG, cells);
    for out in
        [bench::report::markdown(&config, &r, std::path::Path::new("results")), bench::report::summary(&config, &r)]
    {
        let table_lines =
            out.lines().filter(|l| l.starts_with('|') || l.starts_with("photons") || l.starts_with("256"));
        for l in table_lines {
            assert!(l.chars().count() <= 120, "{} columns: {l}", l.chars().count());
        }
        for t in &config.techniques {
            assert!(out.contains(&t.label), "column {} missing", t.label);
        }
    }
}

#[test]
fn the_plot_has_a_ratio_panel_and_draws_as_svg_and_png() {
    let (config, r) = synthetic();
    let g = bench::table::grid(&config, &r);
    let fig = bench::figure::figure(&config, &r, &g);
    assert_eq!(fig.panels.len(), 2, "values and ratios");
    let ratio = &fig.panels[1];
    assert!(ratio.title.contains("ratio against base") && ratio.unit_line, "{}", ratio.title);
    // The ratio panel: ours for `fast`, and the paper's at 256² only (512² is not comparable).
    let paper: Vec<_> = ratio.series.iter().filter(|s| s.paper).collect();
    assert_eq!(paper.len(), 1);
    assert_eq!(paper[0].points, vec![(0, 0.5)]);
    let plot = bench::plot::render(&fig).expect("a font is installed (fonts-dejavu-core)");
    assert!(plot.svg.starts_with("<svg") && plot.svg.contains("<polyline"), "no lines in the SVG");
    assert!(plot.svg.contains("fast (paper)"), "legend missing from the SVG");
    assert!(plot.png.starts_with(b"\x89PNG\r\n\x1a\n") && plot.png.len() > 10_000, "not a PNG");
}

#[test]
fn rows_without_photons_plot_as_grouped_bars() {
    let text = CONFIG
        .replace("photons = [256, 512]", "photons = [256]")
        .replace("rows = [\"photons\"]", "rows = [\"technique\"]")
        .replace("columns = [\"technique\"]", "columns = [\"metric\"]")
        .replace("compare = { axis = \"technique\", baseline = \"base\" }\n", "");
    let text = &text[..text.find("[[paper]]").expect("paper")];
    let config: Config = toml::from_str(text).expect("parses");
    let r = results(&config, text, vec![cell(0, 0, "base", 256, &STEADY), cell(1, 1, "fast", 256, &NOISY)]);
    let fig = bench::figure::figure(&config, &r, &bench::table::grid(&config, &r));
    assert_eq!(fig.panels.len(), 1);
    assert!(fig.panels[0].bars, "categorical rows are bars");
    assert_eq!(fig.panels[0].x_labels, vec!["base", "fast"]);
    let plot = bench::plot::render(&fig).expect("plot");
    assert!(plot.svg.contains("<rect"), "bars");
}

/// A linear panel whose values span more than a hundredfold is drawn on a log axis and says so
/// (W&D 2006 Fig. 10: one technique at 957, the others under 0.5, all on the zero line before);
/// one spanning less stays linear, and a bar panel's linear axis starts at zero.
#[test]
fn a_panel_whose_values_span_decades_is_drawn_on_a_log_axis() {
    let text =
        CONFIG.replace("caption = \"Synthetic samples.\"", "caption = \"Synthetic samples.\"\nplot_log_y = false");
    let text = &text[..text.find("[[paper]]").expect("paper")];
    let config: Config = toml::from_str(text).expect("parses");
    let panel_of = |fast: f64| {
        let cells = vec![
            cell(0, 0, "base", 256, &STEADY),
            cell(1, 0, "base", 512, &STEADY),
            cell(2, 1, "fast", 256, &[fast; 5]),
            cell(3, 1, "fast", 512, &[fast; 5]),
        ];
        let r = results(&config, text, cells);
        bench::figure::figure(&config, &r, &bench::table::grid(&config, &r)).panels[0].clone()
    };
    // 10 against 1500: 150-fold.
    let wide = panel_of(1500.0);
    assert!(wide.log_y && wide.y_label.ends_with("(log scale)"), "{} log {}", wide.y_label, wide.log_y);
    // 10 against 900: 90-fold, and 10 against 0.05: 200-fold the other way.
    let narrow = panel_of(900.0);
    assert!(!narrow.log_y && narrow.y_label == "ms", "{} log {}", narrow.y_label, narrow.log_y);
    assert!(panel_of(0.05).log_y, "a small value 200 times under the largest");
    assert!(bench::plot::render(&bench::figure::Figure {
        title: "t".into(),
        subtitle: "s".into(),
        panels: vec![wide]
    })
    .is_ok_and(|p| p.svg.contains("<polyline") && p.svg.contains("(log scale)")));
    // The config's own log axis is not relabelled.
    let (config, r) = synthetic();
    let fig = bench::figure::figure(&config, &r, &bench::table::grid(&config, &r));
    assert!(fig.panels[0].log_y && !fig.panels[0].y_label.contains("log scale"));
}

#[test]
fn a_linear_axis_starts_at_zero_for_bars_and_near_zero_values_only() {
    // Bars of 54 to 96 (W&N Fig. 8's storage) start at zero: a bar's length is its value.
    assert_eq!(bench::plot::linear_range(54.0, 96.0, true).0, 0.0);
    // Lines of the same values are drawn around them; lines from 10 to 96 from zero.
    let (lo, hi) = bench::plot::linear_range(54.0, 96.0, false);
    assert!(lo > 50.0 && lo < 54.0 && hi > 96.0, "{lo}..{hi}");
    assert_eq!(bench::plot::linear_range(10.0, 96.0, false).0, 0.0);
    // Negative values keep their room below zero, bars or not.
    assert!(bench::plot::linear_range(-2.0, 5.0, true).0 < -2.0);
}

#[test]
fn a_log_axis_is_labelled_more_often_than_at_each_power_of_ten_when_it_spans_few() {
    let ticks = |lo, hi| bench::plot::log_ticks(lo, hi);
    // Five decades: the powers of ten.
    assert_eq!(ticks(0.05, 2000.0), [0.1, 1.0, 10.0, 100.0, 1000.0]);
    // Two decades: 1, 2 and 5 times them.
    assert_eq!(ticks(0.3, 60.0), [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0]);
    // A ratio panel from 0.4 to 3 (W&N Fig. 9): every tenth up to 1, then 2 and 3.
    assert_eq!(ticks(0.4, 3.0), [0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 2.0, 3.0]);
    // Eighteen decades: every second power (at most ten labels).
    let t = ticks(1e-6, 1e12);
    assert_eq!(t.len(), 10, "{t:?}");
    assert!(t[0] == 1e-6 && (t[1] - 1e-4).abs() < 1e-18 && t[9] == 1e12, "{t:?}");
    // Inside one step (the F1 front's axis about a single value, 1.01 to 1.99): round tenths.
    let t = ticks(1.014, 1.988);
    assert_eq!(t.len(), 9, "{t:?}");
    assert!((t[0] - 1.1).abs() < 1e-12 && (t[8] - 1.9).abs() < 1e-12, "{t:?}");
    // Nothing to label on an empty or non-positive range.
    assert!(ticks(0.0, 1.0).is_empty() && ticks(2.0, 1.0).is_empty());
    // The light grid: every multiple, here 0.4 ... 0.9, 1, 2, 3.
    assert_eq!(bench::plot::log_light_lines(0.4, 3.0).len(), 9);
}

/// Bar categories too many for their labels to fit across (Table Q4: 56 scene and technique
/// pairs, each cut to `…`) are labelled upright under the chart, which grows to hold them;
/// a few short labels stay across, and lines never turn.
#[test]
fn bar_labels_that_do_not_fit_across_stand_upright_under_a_taller_panel() {
    // Labels are measured in the plot's font (as `render` does first).
    bench::font::load().expect("a font is installed (fonts-dejavu-core)");
    let panel = |n: usize, label: &str, bars: bool| bench::figure::Panel {
        title: "rel. RMSE".into(),
        y_label: "rel. RMSE".into(),
        log_y: false,
        x_labels: (0..n).map(|i| format!("{label} {i}")).collect(),
        bars,
        unit_line: false,
        series: vec![bench::figure::Series {
            label: "256²".into(),
            colour: 0,
            paper: false,
            points: (0..n).map(|i| (i, 1.0 + i as f64)).collect(),
        }],
    };
    let many = panel(56, "sphere_on_plane · shah, the tutorial's (one refraction, 1 iteration)", true);
    let (drop, font) = bench::plot::upright_labels(&many).expect("56 long labels do not fit across");
    assert!(drop > 100 && drop <= 360 && (8.0..=13.0).contains(&font), "{drop} {font}");
    assert_eq!(bench::plot::panel_height(&many), 420 + drop);
    let few = panel(4, "base", true);
    assert!(bench::plot::upright_labels(&few).is_none() && bench::plot::panel_height(&few) == 420);
    assert!(bench::plot::upright_labels(&panel(56, "sphere_on_plane · shah", false)).is_none(), "lines");
    let fig = bench::figure::Figure { title: "t".into(), subtitle: "s".into(), panels: vec![many, few] };
    let plot = bench::plot::render(&fig).expect("plot");
    assert_eq!(plot.svg.matches("transform=\"rotate(90").count(), 56, "one upright label per bar");
    assert!(plot.svg.contains(&format!("height=\"{}\"", 64 + 420 + drop + 420)), "the figure grew by the drop");
}

/// A result with `scenes` scenes as a row axis beside photons, both techniques in every cell.
fn by_scene(scenes: usize) -> (Config, Results) {
    let names: Vec<String> = (0..scenes).map(|i| format!("../scenes/s{i}.toml")).collect();
    let list = names.iter().map(|n| format!("\"{n}\"")).collect::<Vec<_>>().join(", ");
    let text = CONFIG
        .replace("scenes = [\"../scenes/sphere_on_plane.toml\"]", &format!("scenes = [{list}]"))
        .replace("rows = [\"photons\"]", "rows = [\"scene\", \"photons\"]");
    let text = &text[..text.find("[[paper]]").expect("paper")];
    let config: Config = toml::from_str(text).expect("parses");
    let mut cells = vec![];
    for name in &names {
        for (t, label) in ["base", "fast"].iter().enumerate() {
            for photons in [256, 512] {
                let mut c = cell(cells.len(), t, label, photons, &STEADY);
                c.cell.scene = name.clone();
                cells.push(c);
            }
        }
    }
    let r = results(&config, CONFIG, cells);
    (config, r)
}

#[test]
fn a_plot_with_more_series_than_a_legend_lists_becomes_one_panel_per_scene() {
    // 2 scenes: 2 columns × 2 scenes, with the paper's, fit one legend: values and ratios.
    let (config, r) = by_scene(2);
    let fig = bench::figure::figure(&config, &r, &bench::table::grid(&config, &r));
    assert_eq!(fig.panels.len(), 2, "{:?}", fig.panels.iter().map(|p| &p.title).collect::<Vec<_>>());
    assert!(fig.panels[0].series.iter().any(|s| s.label == "s1 · fast"), "series name their scene");
    // 9 scenes: 2 × 9 × 2 = 36 series would not fit, so each scene gets its two panels.
    let (config, r) = by_scene(9);
    let fig = bench::figure::figure(&config, &r, &bench::table::grid(&config, &r));
    assert_eq!(fig.panels.len(), 18);
    for (i, p) in fig.panels.iter().enumerate() {
        assert!(p.title.starts_with(&format!("s{} · ", i / 2)), "panel {i}: {}", p.title);
        assert!(p.series.len() <= bench::figure::MAX_SERIES, "panel {i}: {} series", p.series.len());
        assert!(p.series.iter().all(|s| s.label.starts_with("base") || s.label.starts_with("fast")));
        assert!(p.series.iter().all(|s| s.points.len() == 2 || s.paper), "panel {i}: a point per photon count");
    }
    // A column keeps its colour from scene to scene.
    let colour = |p: &bench::figure::Panel| p.series.iter().find(|s| s.label == "fast").map(|s| s.colour);
    assert_eq!(colour(&fig.panels[0]), colour(&fig.panels[16]));
    let plot = bench::plot::render(&fig).expect("plot");
    assert!(plot.png.starts_with(b"\x89PNG"), "not a PNG");
}

/// Wyman & Nichols 2009 Table 1's N/A: a technique that cannot run at a photon count (the
/// renderer's rule: above 4096 only `adaptive` with a memory limit) has no cell, and its
/// entry reads N/A, beside the paper's value where it has one; the others are measured.
#[test]
fn a_technique_that_cannot_run_at_a_photon_count_reads_na() {
    let text = CONFIG
        .replace("photons = [256, 512]", "photons = [4096, 16384]")
        .replace("technique = \"hcm\"", "technique = \"adaptive\"\nphoton_memory_limit = 96")
        .replace("photons = 256\n", "photons = 4096\n")
        .replace("photons = 512\n", "photons = 16384\n");
    let config: Config = toml::from_str(&text).expect("the test config parses");
    let matrix = bench::plan::Matrix::new(&config, None);
    let planned: Vec<(usize, u32)> = matrix.cells(&config).iter().map(|c| (c.technique, c.photons)).collect();
    assert_eq!(planned, [(0, 4096), (1, 4096), (1, 16384)], "the plan skips wd-points at 16384²");
    let cells =
        vec![cell(0, 0, "base", 4096, &STEADY), cell(1, 1, "fast", 4096, &STEADY), cell(2, 1, "fast", 16384, &NOISY)];
    let r = results(&config, CONFIG, cells);
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    let big = row(&md, "16384²", 0);
    assert!(big[1].starts_with("N/A (20.0"), "wd-points at 16384²: {big:?}\n{md}");
    assert!(big[2].starts_with("10.0"), "adaptive at 16384² measured: {big:?}");
    let small = row(&md, "4096²", 0);
    assert!(!small.iter().any(|c| c.contains("N/A")), "{small:?}");
    assert!(bench::report::summary(&config, &r).contains("N/A"));
}

#[test]
fn a_figures_data_is_not_titled_a_table() {
    assert_eq!(bench::config::title("Wyman & Nichols 2009", "Fig. 10 (data)"), "Wyman & Nichols 2009, Fig. 10 (data)");
    assert_eq!(bench::config::title("Wyman 2008", "3"), "Wyman 2008, Table 3");
    let (config, r) = synthetic();
    assert!(bench::report::markdown(&config, &r, std::path::Path::new("results")).starts_with("# Synthetic, Table S\n"));
}

/// The "Regenerate" line names the results folder a table was written under: nothing more for
/// the default `results` (the committed tables), `--results DIR` and DIR's path otherwise.
#[test]
fn the_regenerate_line_names_a_results_folder_other_than_the_default() {
    let (config, r) = synthetic();
    for default in ["results", "results/"] {
        let md = bench::report::markdown(&config, &r, std::path::Path::new(default));
        assert!(!md.contains("--results results"), "{default}: {md}");
        assert!(md.contains("`causticlab bench merge results/"), "{default}: {md}");
    }
    let md = bench::report::markdown(&config, &r, std::path::Path::new("/tmp/elsewhere"));
    let line = md.lines().find(|l| l.starts_with("Regenerate:")).expect("a Regenerate line");
    assert!(line.contains(" --results /tmp/elsewhere`"), "{line}");
    assert!(
        line.contains("`causticlab bench merge /tmp/elsewhere/") && line.contains(" --results /tmp/elsewhere`."),
        "{line}"
    );
}

/// The model files behind a table: listed by checksum; a file other than docs/scenes.md's is
/// said first, so a table made with another dragon cannot pass for the committed one.
#[test]
fn the_header_names_the_models_and_says_when_one_is_not_the_listed_file() {
    use caustics::scene::models::{ModelFile, KNOWN};
    let (config, mut r) = synthetic();
    assert!(
        !bench::report::markdown(&config, &r, std::path::Path::new("results")).contains("odel"),
        "no models, no line"
    );
    let listed = ModelFile {
        file: "stanford-bunny.obj".into(),
        sha256: KNOWN[0].sha256.into(),
        expected: Some(KNOWN[0].sha256.into()),
    };
    for c in &mut r.cells {
        c.models = vec![listed.clone()];
    }
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    let line = md.lines().find(|l| l.contains("**Models:**")).unwrap_or_else(|| panic!("{md}"));
    assert!(line.contains("stanford-bunny.obj (SHA-256 1eb35d1e21ce…, as docs/scenes.md lists)"), "{line}");
    assert_eq!(line.matches("stanford-bunny").count(), 1, "each file once: {line}");
    let other = ModelFile { sha256: "0".repeat(64), ..listed };
    r.cells[2].models.push(other);
    let md = bench::report::markdown(&config, &r, std::path::Path::new("results"));
    assert!(!md.contains("**Models:**"), "{md}");
    let line = md.lines().find(|l| l.contains("**Made with another model:**")).unwrap_or_else(|| panic!("{md}"));
    assert!(line.contains("000000000000…: NOT the file docs/scenes.md lists, 1eb35d1e21ce…"), "{line}");
    // The JSON keeps the checksums; a table without them (older) reads as before.
    let json = bench::results::to_json(&r).unwrap();
    assert!(json.contains(&"0".repeat(64)));
}

/// What each frame asked of the driver: medians per frame, the most objects any frame made.
#[test]
fn frame_counters_are_medians_per_frame_and_the_most_objects() {
    use bench::results::FrameCounters;
    let c = |objects, submits, barriers, timestamps| vkcore::Counters {
        objects,
        submits,
        barriers,
        timestamps,
        ..Default::default()
    };
    let frames = [c(0, 1, 10, 4), c(7, 3, 30, 8), c(1, 2, 20, 6)];
    let f = FrameCounters::of(&frames, &[5, 9, 7]).expect("three frames");
    assert_eq!(
        f,
        FrameCounters {
            frames: 3,
            passes: 7.0,
            submits: 2.0,
            barriers: 20.0,
            timestamps: 6.0,
            objects: 1.0,
            most_objects: 7,
        }
    );
    assert_eq!(FrameCounters::of(&[], &[]), None, "no frame measured in that mode");
}

/// The JSON a table is kept as: one cell per line (diffs name the cell that changed), empty
/// lists inline, every float to 9 significant digits so that a merge redraws the same table.
#[test]
fn the_json_keeps_a_cell_per_line_and_nine_significant_digits() {
    let (_config, mut r) = synthetic();
    r.cells[0].wall_ms = vec![0.1 + 0.2, 1.234567891234, 3.0];
    let json = bench::results::to_json(&r).unwrap();
    let start = json.lines().position(|l| l == "\"cells\": [").unwrap_or_else(|| panic!("{json}"));
    let cell_lines: Vec<&str> = json.lines().skip(start + 1).take_while(|l| *l != "]" && *l != "],").collect();
    assert_eq!(cell_lines.len(), r.cells.len(), "{json}");
    assert!(cell_lines.iter().all(|l| l.starts_with("{\"cell\":")), "{cell_lines:#?}");
    assert!(cell_lines[0].contains("\"wall_ms\":[0.3,1.23456789,3.0]"), "{}", cell_lines[0]);
    assert_eq!(bench::results::rounded(&r).unwrap().cells[0].wall_ms, [0.3, 1.23456789, 3.0]);
    // A table with no cell keeps the key, inline.
    r.cells.clear();
    let json = bench::results::to_json(&r).unwrap();
    assert!(json.lines().any(|l| l == "\"cells\": []"), "{json}");
}

/// `bench merge`: parts of one config on one device make the table; anything else is refused
/// by name, and a missing cell reads `not run` only when asked for.
#[test]
fn parts_merge_into_one_table_and_mismatched_parts_are_refused() {
    use std::path::PathBuf;
    let (_config, whole) = synthetic();
    let dir = caustics::scratch::ScratchDir::new("bench", "merge");
    let root = dir.join("results");
    let write = |name: &str, r: &Results| -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, bench::results::to_json(r).unwrap()).unwrap();
        p
    };
    let part = |indices: &[usize]| {
        let mut r = whole.clone();
        r.cells.retain(|c| indices.contains(&c.cell.index));
        r.run.filter.terms = vec![("photons".into(), "256".into())];
        r
    };
    let (a, b) = (write("a.json", &part(&[0, 2])), write("b.json", &part(&[1, 3])));
    // An uncompressed table an older causticlab left there: the merged one replaces it.
    let stale = root.join("synthetic/synthetic.json");
    std::fs::create_dir_all(stale.parent().unwrap()).unwrap();
    std::fs::write(&stale, bench::results::to_json(&part(&[0])).unwrap()).unwrap();
    let out = bench::run::merge(&[a.clone(), b.clone()], &root, false).expect("two halves merge");
    assert!(!stale.exists(), "the uncompressed twin is removed");
    assert_eq!(out.removed, std::slice::from_ref(&stale), "and said to be");
    let gz = root.join("synthetic/synthetic.json.gz");
    assert!(std::fs::read(&gz).unwrap().starts_with(&[0x1f, 0x8b]), "the table is gzip-compressed");
    let index = std::fs::read_to_string(root.join("README.md")).unwrap();
    assert!(index.contains("[synthetic](synthetic/synthetic.md)"), "the index reads the compressed table: {index}");
    // A plain twin unpacked beside it: listed once, and a reader refuses to guess.
    std::fs::write(&stale, bench::results::read_text(&gz, "table").unwrap()).unwrap();
    let index = std::fs::read_to_string(bench::index::write_index(&root).unwrap()).unwrap();
    assert_eq!(index.matches("[synthetic](synthetic/synthetic.md)").count(), 1, "{index}");
    let err = bench::run::merge(&[a.clone(), b.clone()], &root, false);
    assert!(err.is_ok(), "a write replaces the twin: {err:?}");
    assert!(!stale.exists());
    let merged = bench::results::read(&gz, "table").unwrap();
    let indices: Vec<usize> = merged.cells.iter().map(|c| c.cell.index).collect();
    assert_eq!(indices, [0, 1, 2, 3]);
    assert!(merged.run.filter.terms.is_empty() && merged.run.not_run.is_empty());
    // A half alone: refused unless --partial, which marks the rest `not run`.
    let err = bench::run::merge(std::slice::from_ref(&a), &root, false).unwrap_err();
    assert!(format!("{err:#}").contains("2 cell(s) missing"), "{err:#}");
    bench::run::merge(std::slice::from_ref(&a), &root, true).expect("a partial table");
    let merged = bench::results::read(&root.join("synthetic/synthetic.json.gz"), "table").unwrap();
    assert_eq!(merged.run.not_run, [1, 3]);
    // The same cell twice, and no part at all.
    let err = bench::run::merge(&[a.clone(), a.clone()], &root, false).unwrap_err();
    assert!(format!("{err:#}").contains("is also in another part"), "{err:#}");
    let err = bench::run::merge(&[], &root, false).unwrap_err();
    assert!(format!("{err:#}").contains("give the part files"), "{err:#}");
    // Parts of another config, device, driver or mode.
    type Change = fn(&mut Results);
    let changes: [(&str, Change); 5] = [
        ("config hash", |r| r.config.hash = "1".into()),
        ("device", |r| r.meta.device = "another".into()),
        ("driver", |r| r.meta.driver_info = "another".into()),
        ("quick flag", |r| r.run.quick = true),
        ("validation flag", |r| r.run.validation = true),
    ];
    for (what, change) in changes {
        let mut other = part(&[1, 3]);
        change(&mut other);
        let odd = write("odd.json", &other);
        let err = bench::run::merge(&[a.clone(), odd], &root, false).unwrap_err();
        assert!(format!("{err:#}").contains(&format!("{what} `")), "{what}: {err:#}");
    }
}

#[test]
fn a_device_folder_measured_on_another_cpu_is_named() {
    let dir = caustics::scratch::ScratchDir::new("causticlab", "one-cpu");
    let (_, r) = synthetic();
    let write = |name: &str, cpu: &str| {
        let mut t = r.clone();
        t.config.name = name.into();
        t.meta.cpu = cpu.into();
        let text = bench::results::to_json(&t).unwrap();
        std::fs::write(dir.join(format!("{name}.json.gz")), bench::results::gzip(&text).unwrap()).unwrap();
    };
    let here = "AMD EPYC";
    write("a", here);
    write("b", here);
    std::fs::write(dir.join("notes.json.gz"), b"not a table").unwrap();
    assert!(bench::one_cpu::other_cpus(&dir, "c", here).is_empty(), "one CPU: nothing to say");
    assert_eq!(bench::one_cpu::refusal(std::path::Path::new("c.toml"), &dir, here, &[]), None);
    // Another CPU measured `b`: named, unless `b` is the table being replaced.
    write("b", "Intel(R) Xeon(R) Processor");
    let others = bench::one_cpu::other_cpus(&dir, "c", here);
    assert_eq!(others, [("b.json.gz".to_string(), "Intel(R) Xeon(R) Processor".to_string())]);
    assert!(bench::one_cpu::other_cpus(&dir, "b", here).is_empty(), "the table the run replaces is not another's");
    let why = bench::one_cpu::refusal(std::path::Path::new("c.toml"), &dir, here, &others).unwrap();
    assert!(
        why.starts_with("c.toml: 1 of the tables in ")
            && why.contains("(Intel(R) Xeon(R) Processor: b.json.gz)")
            && why.contains("this machine's is AMD EPYC")
            && why.contains("--allow-other-cpu"),
        "{why}"
    );
    write("a", "Intel(R) Xeon(R) Processor");
    let others = bench::one_cpu::other_cpus(&dir, "c", here);
    assert_eq!(others.len(), 2);
    let why = bench::one_cpu::refusal(std::path::Path::new("c.toml"), &dir, here, &others).unwrap();
    assert!(why.contains("2 of the tables") && why.contains(": a.json.gz, ...)"), "{why}");
    // No folder yet: nothing to compare with.
    assert!(bench::one_cpu::other_cpus(&dir.join("none"), "c", here).is_empty());
}
