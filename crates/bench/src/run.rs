//! `causticlab bench`: run a config's cells and write its table; `bench merge`: put shards back
//! together. Nothing is written until every cell has run, and each file is written to a
//! temporary name and renamed, so an interrupted run never leaves a half-written table.

use crate::config::{Config, LoadedConfig};
use crate::measure::Runner;
use crate::plan::{Filter, Matrix, Shard};
use crate::progress::Progress;
use crate::results::{cell_result, ConfigInfo, Results, RunInfo, SCHEMA};
use anyhow::{Context as _, Result};
use caustics::image_io::write_file_atomically;
use caustics::input_error;
use std::path::{Path, PathBuf};
use vkcore::{Context, ShaderCompiler};

#[derive(Debug, Clone, Default)]
pub struct BenchOptions {
    pub quick: bool,
    pub filter: Option<String>,
    pub shard: Option<String>,
    /// The results folder (`results/` by default); tables go to `<root>/<device-slug>/`.
    pub results_root: PathBuf,
    /// A timing cell that ran while other processes used more than this many cores is measured
    /// again (after a pause), up to `busy_retries` times, then marked busy.
    pub busy_cores: f64,
    pub busy_retries: u32,
    /// A timing cell whose largest spread is over `stats::NOISY_SPREAD` is measured again, up to
    /// `spread_retries` times; the attempt with the smallest spread is kept.
    pub spread_retries: u32,
    /// Refuse to write a table with busy cells (a timing run into the repository's results/).
    pub refuse_busy: bool,
    /// Refuse to run into a device folder whose other tables another CPU measured (a timing run
    /// into the repository's results/: `crate::one_cpu`).
    pub refuse_other_cpu: bool,
}

/// Seconds to wait before measuring a busy cell again.
const BUSY_PAUSE_S: u64 = 3;

/// Seconds to wait before measuring a cell with a wide spread again: this VM's CPU speed changes
/// from one second to the next (results/llvmpipe-*/anomalies.md, "The host's own speed").
const SPREAD_PAUSE_S: u64 = 1;

#[derive(Debug)]
pub struct Outcome {
    pub written: Vec<PathBuf>,
    /// A table's plain `<name>.json` the write replaced with its `.json.gz`.
    pub removed: Vec<PathBuf>,
    pub markdown: String,
    /// The tables in plain text, for the terminal.
    pub summary: String,
}

/// Measures a cell with `measure`, again after `pause` (given the attempt and the other
/// processes' cores) while other processes kept the machine busy, up to `busy_retries` times;
/// whether the run kept was still busy. Only a config that times something (`timed`) can be
/// busy: its errors and counts are the same on a busy machine.
fn measure_quiet(
    mut measure: impl FnMut() -> Result<crate::measure::CellRun>,
    mut pause: impl FnMut(u32, f64),
    opts: &BenchOptions,
    timed: bool,
) -> Result<(crate::measure::CellRun, bool)> {
    let mut attempt = 0;
    loop {
        let run = measure()?;
        let busy = timed && !opts.quick && run.other_cores.is_some_and(|c| c > opts.busy_cores);
        if !busy || attempt >= opts.busy_retries {
            return Ok((run, busy));
        }
        attempt += 1;
        pause(attempt, run.other_cores.unwrap_or(0.0));
    }
}

/// A cell's measurements while its spread is over `stats::NOISY_SPREAD`: which to keep (a quiet
/// one before a busy one, then the smallest spread; the first among equals) and whether to
/// measure again (up to `retries` more times).
struct Attempts {
    retries: u32,
    /// The largest spread of each attempt, in order.
    spreads: Vec<f64>,
    /// The kept attempt's (busy, spread).
    best: Option<(bool, f64)>,
}

impl Attempts {
    fn new(retries: u32) -> Attempts {
        Attempts { retries, spreads: vec![], best: None }
    }

    /// Records an attempt: (keep it, measure again).
    fn add(&mut self, busy: bool, spread: f64) -> (bool, bool) {
        self.spreads.push(spread);
        let keep = self.best.is_none_or(|best| (busy, spread) < best);
        if keep {
            self.best = Some((busy, spread));
        }
        let again = crate::stats::is_noisy(spread) && self.spreads.len() <= self.retries as usize;
        (keep, again)
    }
}

/// The largest relative spread of a cell's timed metrics, as the table flags them (0 without
/// any).
fn worst_spread(
    specs: &[crate::config::MetricSpec],
    values: &std::collections::BTreeMap<String, crate::results::Value>,
) -> f64 {
    specs.iter().filter_map(|m| crate::results::timed_spread(&m.kind, values.get(&m.label)?)).fold(0.0, f64::max)
}

/// The cells of `all` that the filter and the shard (if any) take, in order.
fn selected(all: &[crate::plan::Cell], filter: &Filter, shard: Option<&Shard>) -> Vec<crate::plan::Cell> {
    all.iter().filter(|cell| filter.matches(cell) && shard.is_none_or(|s| s.takes(cell))).cloned().collect()
}

/// A cell's expected share of the run, for the progress line's time left: its photons (every
/// light's) and pixels (a default 1024² where the cell names no resolution), times its frames.
fn cost(cell: &crate::plan::Cell, frames: u32) -> f64 {
    let px = if cell.resolution == [0, 0] { 1 << 20 } else { cell.resolution[0] as u64 * cell.resolution[1] as u64 };
    (cell.photons as u64 * cell.photons as u64 * cell.lights.max(1) as u64 + px) as f64 * frames as f64
}

/// Runs the cells `opts` selects and writes the table (or, for a filtered or sharded run, a
/// part for `bench merge`).
pub fn run(ctx: &Context, shaders: &ShaderCompiler, lc: &LoadedConfig, opts: &BenchOptions) -> Result<Outcome> {
    let c = &lc.config;
    let quick = opts.quick.then_some(&c.quick);
    let matrix = Matrix::new(c, quick);
    let all = matrix.cells(c);
    let filter = match &opts.filter {
        Some(f) => Filter::parse(f, c, &matrix)?,
        None => Filter::default(),
    };
    let shard = opts.shard.as_deref().map(Shard::parse).transpose()?;
    let cells = selected(&all, &filter, shard.as_ref());
    if cells.is_empty() {
        return Err(input_error!("{}: --filter/--shard selects no cell", lc.path.display()).into());
    }
    if opts.refuse_other_cpu {
        let dir = opts.results_root.join(crate::meta::results_slug(ctx.info()));
        let cpu = crate::meta::cpu_model();
        let others = crate::one_cpu::other_cpus(&dir, &lc.name, &cpu);
        if let Some(why) = crate::one_cpu::refusal(&lc.path, &dir, &cpu, &others) {
            return Err(input_error!("{why}").into());
        }
    }
    let plan = c.frame_plan(opts.quick);
    let (warmup, measured) = (plan.warmup, plan.min);
    let costs = cells.iter().map(|cell| cost(cell, warmup + measured + 1)).collect();
    // The plots need a font: fail now rather than after the last cell.
    crate::font::load()?;
    // The device's copy bandwidth, for the plausibility rule on copies (GPU memory: 256 MiB is
    // beyond every cache; a quick run only smoke-tests it).
    let bandwidth_bytes = if opts.quick { 16 << 20 } else { 256 << 20 };
    let copy_bandwidth_gbs = ctx.copy_bandwidth(bandwidth_bytes).context("measuring the device's copy bandwidth")?;
    // The commit is the code's when the run starts (the dirty check's), not whatever the tree
    // holds when the last cell ends.
    let commit = crate::meta::commit();
    let mut progress = Progress::new(costs);
    let mut runner = Runner::new(ctx, shaders, lc, quick);
    // Everything that can be checked before the first cell is: every scene with every
    // technique and light count (settings, sizes, files), and the device features each
    // technique needs, so that a sweep does not fail hours in.
    for (i, cell) in cells.iter().enumerate() {
        let same =
            |c: &crate::plan::Cell| c.scene == cell.scene && c.technique == cell.technique && c.lights == cell.lights;
        if !cells[..i].iter().any(same) {
            let (mut scene, shared) = runner.cell_scene_and_shared(cell)?;
            caustics::render::check_device(ctx, &scene)
                .with_context(|| format!("{}: technique[{}]", lc.path.display(), cell.technique))?;
            if runner.needs_flip() {
                // The reference final image's photon tracer, on the same device.
                let reference = crate::final_flip::reference_scene(&scene, &shared)
                    .with_context(|| format!("{}: key `matrix.scenes`: scene `{}`", lc.path.display(), cell.scene))?;
                let traced = runner.final_refinement()?.scene(&reference, crate::final_flip::SEED, 0)?;
                caustics::render::check_device(ctx, &traced)
                    .with_context(|| format!("{}: the reference final image of `flip`", lc.path.display()))?;
            }
            // The images grow with the photons and the resolution: every size this scene and
            // technique run at must fit the device's memory.
            for c in cells[i + 1..].iter().filter(|c| same(c)) {
                scene.caustics.photons = c.photons;
                if c.resolution != [0, 0] {
                    (scene.camera.width, scene.camera.height) = (c.resolution[0], c.resolution[1]);
                }
                caustics::render::check_memory(ctx, &scene).with_context(|| {
                    format!("{}: technique[{}], cell {}", lc.path.display(), c.technique, c.describe())
                })?;
            }
        }
    }
    let mut done = vec![];
    let timed = c.metrics.iter().any(|m| crate::results::is_timing(&m.kind));
    for cell in &cells {
        progress.start_cell(&cell.describe());
        // Measured again while its spread is over NOISY_SPREAD (`!`), keeping the quiet attempt
        // with the smallest spread; each attempt's spread is recorded.
        let mut attempts = Attempts::new(if opts.quick { 0 } else { opts.spread_retries });
        let mut kept = None;
        loop {
            let (run, busy) = measure_quiet(
                || runner.run(cell).with_context(|| format!("bench cell {}", cell.describe())),
                |attempt, cores| {
                    eprintln!(
                        "bench: cell {} ran while other processes used {cores:.2} cores (above {}); measuring it \
                         again in {BUSY_PAUSE_S} s ({attempt}/{})",
                        cell.describe(),
                        opts.busy_cores,
                        opts.busy_retries
                    );
                    std::thread::sleep(std::time::Duration::from_secs(BUSY_PAUSE_S));
                },
                opts,
                timed,
            )?;
            check_patterns(lc, cell, &run)?;
            let metrics = crate::metrics::evaluate(&c.metrics, &run);
            let worst = worst_spread(&c.metrics, &metrics);
            let (keep, again) = attempts.add(busy, worst);
            if keep {
                kept = Some((busy, run, metrics));
            }
            if !again {
                break;
            }
            eprintln!(
                "bench: cell {} spread {:.0}% (over {:.0}%); measuring it again in {SPREAD_PAUSE_S} s ({}/{})",
                cell.describe(),
                worst * 100.0,
                crate::stats::NOISY_SPREAD * 100.0,
                attempts.spreads.len(),
                opts.spread_retries
            );
            std::thread::sleep(std::time::Duration::from_secs(SPREAD_PAUSE_S));
        }
        let (busy, run, metrics) = kept.expect("the first attempt is kept");
        let mut result = cell_result(cell, &run, metrics, &c.techniques[cell.technique].photon_copy);
        result.busy = busy;
        if attempts.spreads.len() > 1 {
            result.spread_attempts = attempts.spreads;
        }
        done.push(result);
        progress.finish_cell();
    }
    progress.finish();
    let busy: Vec<String> = done
        .iter()
        .filter(|r| r.busy)
        .map(|r| format!("{} ({:.2} cores)", r.cell.describe(), r.other_cores.unwrap_or(0.0)))
        .collect();
    if !busy.is_empty() && opts.refuse_busy {
        return Err(input_error!(
            "{}: {} of {} cells ran while other processes kept the machine busy, even when measured again: {}. \
             A table for the repository's results/ comes from a quiet machine: stop the other work and run again, \
             or write elsewhere with --results",
            lc.path.display(),
            busy.len(),
            done.len(),
            busy.join("; ")
        )
        .into());
    }
    let results = Results {
        schema: SCHEMA,
        config: ConfigInfo {
            file: lc.path.display().to_string(),
            name: lc.name.clone(),
            hash: lc.hash.clone(),
            paper: c.table.paper.clone(),
            table: c.table.number.clone(),
            caption: c.table.caption.clone(),
            toml: lc.text.clone(),
        },
        run: RunInfo {
            quick: opts.quick,
            warmup_frames: warmup,
            measured_frames: measured,
            time_budget_s: Some(plan.budget_s),
            max_frames: Some(plan.max),
            light_path: c.run.light_path.clone(),
            camera_path: c.run.camera_path.clone(),
            object_path: c.run.object_path.clone(),
            period_frames: c.run.period_frames,
            validation: ctx.validation_enabled(),
            filter: filter.clone(),
            shard,
            total_cells: all.len(),
            copy_bandwidth_gbs,
            not_run: vec![],
            explained: None,
        },
        meta: crate::results::Meta { commit, ..crate::meta::meta(ctx.info()) },
        cells: done,
        plausibility: vec![],
        front_curves: None,
    };
    let dir = device_dir(&opts.results_root, &results);
    if filter.is_empty() && shard.is_none() {
        write_table(c, &results, &dir, &opts.results_root)
    } else {
        let mut tags = vec![];
        if !filter.is_empty() {
            tags.push(format!("filter-{}", crate::config::fnv1a(format!("{:?}", filter.terms).as_bytes())));
        }
        if let Some(s) = shard {
            tags.push(format!("shard-{}-of-{}", s.index, s.count));
        }
        let tag = tags.join(".");
        let part = dir.join("parts").join(format!("{}.{tag}.json", lc.name));
        let results = crate::results::rounded(&results)?;
        write_json(&part, &results)?;
        let (markdown, summary) =
            (crate::report::markdown(c, &results, &opts.results_root), crate::report::summary(c, &results));
        Ok(Outcome { written: vec![part], removed: vec![], markdown, summary })
    }
}

/// A metric's `passes` must match a pass the cell's per-pass frames recorded, unless the metric
/// says why it may not (`absent`). (`exclude` patterns may match nothing: they take off work a
/// cell may not have.)
fn check_patterns(lc: &LoadedConfig, cell: &crate::plan::Cell, run: &crate::measure::CellRun) -> Result<()> {
    let Some(frame) = run.frames.first() else { return Ok(()) };
    let names: Vec<&str> = frame.passes.iter().map(|p| p.name.as_str()).collect();
    for (i, m) in lc.config.metrics.iter().enumerate() {
        if m.absent.is_some() || m.throughput() {
            continue;
        }
        for (key, patterns) in [("passes", &m.passes)] {
            if patterns.is_empty() {
                continue;
            }
            let any = names.iter().any(|n| patterns.iter().any(|p| crate::metrics::glob(p, n)));
            if !any {
                return Err(input_error!(
                    "{}: key `metric[{i}].{key}` of metric `{}`: no pass of cell {} matches {}; the cell recorded: {} \
                     (if this metric may have no such pass, say why with `absent = \"...\"`)",
                    lc.path.display(),
                    m.label,
                    cell.describe(),
                    patterns.iter().map(|p| format!("`{p}`")).collect::<Vec<_>>().join(", "),
                    names.join(", ")
                )
                .into());
            }
        }
    }
    Ok(())
}

/// The folder of `r`'s tables under `root`: its device's, and in it `quick/` for a `--quick` run.
pub fn device_dir(root: &Path, r: &Results) -> PathBuf {
    let d = root.join(&r.meta.device_slug);
    if r.run.quick {
        d.join("quick")
    } else {
        d
    }
}

fn write_json(path: &Path, results: &Results) -> Result<()> {
    make_dir(path.parent().unwrap_or(Path::new(".")))?;
    write_file_atomically(path, crate::results::to_json(results)?.as_bytes())
}

/// Writes `<name>.{json.gz,csv,svg,png,md}` into `dir` (the markdown last: it links the others),
/// removes a plain `<name>.json` left there by an older causticlab (the compressed file replaces
/// it) and refreshes the index of `root`.
pub fn write_table(c: &Config, results: &Results, dir: &Path, root: &Path) -> Result<Outcome> {
    let mut results = crate::results::rounded(results)?;
    results.plausibility = crate::plausibility::check(c, &results);
    results.front_curves = crate::front_curves::load(c, &results, dir);
    let results = &results;
    let name = &results.config.name;
    let md = crate::report::markdown(c, results, root);
    let plot = match &c.front {
        Some(spec) => crate::front_plot::render(c, results, spec)?,
        None if crate::curve_plot::has_curves(results) => crate::curve_plot::render(c, results)?,
        None => crate::plot::render(&crate::figure::figure(c, results, &crate::table::grid(c, results)))?,
    };
    make_dir(dir)?;
    let files = [
        (
            dir.join(format!("{name}.{}", crate::results::TABLE_EXT)),
            crate::results::gzip(&crate::results::to_json(results)?)?,
        ),
        (dir.join(format!("{name}.csv")), crate::report::csv(c, results).into_bytes()),
        (dir.join(format!("{name}.svg")), plot.svg.into_bytes()),
        (dir.join(format!("{name}.png")), plot.png),
        (dir.join(format!("{name}.md")), md.clone().into_bytes()),
    ];
    let mut written = vec![];
    for (path, bytes) in files {
        write_file_atomically(&path, &bytes)?;
        written.push(path);
    }
    let stale = dir.join(format!("{name}.json"));
    let mut removed = vec![];
    if stale.is_file() {
        std::fs::remove_file(&stale)
            .map_err(|e| input_error!("{}: cannot remove the table's uncompressed twin: {e}", stale.display()))?;
        removed.push(stale);
    }
    written.push(crate::index::write_index(root)?);
    Ok(Outcome { written, removed, markdown: md, summary: crate::report::summary(c, results) })
}

/// `bench merge`: the cells of every part (shards or filtered runs of one config on one device)
/// into the table an unsharded run would have written. With `partial`, cells no part has are
/// allowed: the table marks them `not run` and says how many (a suite cut off by its budget).
pub fn merge(parts: &[PathBuf], root: &Path, partial: bool) -> Result<Outcome> {
    let mut loaded: Vec<(PathBuf, Results)> = vec![];
    for p in parts {
        loaded.push((p.clone(), crate::results::read(p, "part")?));
    }
    let Some((first_path, first)) = loaded.first().cloned() else {
        return Err(input_error!("bench merge: give the part files to merge").into());
    };
    let mut cells = vec![];
    for (p, r) in &loaded {
        let same = |what: &str, a: &str, b: &str| -> Result<()> {
            if a != b {
                return Err(input_error!(
                    "{}: {what} `{a}` differs from {}'s `{b}`; parts must come from one config on one kind of device",
                    p.display(),
                    first_path.display()
                )
                .into());
            }
            Ok(())
        };
        same("config hash", &r.config.hash, &first.config.hash)?;
        same("device", &r.meta.device, &first.meta.device)?;
        same("driver", &r.meta.driver_info, &first.meta.driver_info)?;
        same("quick flag", &r.run.quick.to_string(), &first.run.quick.to_string())?;
        same("validation flag", &r.run.validation.to_string(), &first.run.validation.to_string())?;
        for c in &r.cells {
            if cells.iter().any(|x: &crate::results::CellResult| x.cell.index == c.cell.index) {
                return Err(input_error!("{}: cell {} is also in another part", p.display(), c.cell.describe()).into());
            }
            cells.push(c.clone());
        }
    }
    cells.sort_by_key(|c| c.cell.index);
    let config: Config = toml::from_str(&first.config.toml)
        .map_err(|e| input_error!("{}: the embedded config does not parse: {e}", first_path.display()))?;
    let all = Matrix::new(&config, first.run.quick.then_some(&config.quick)).cells(&config);
    let missing: Vec<&crate::plan::Cell> =
        all.iter().filter(|a| !cells.iter().any(|c| c.cell.index == a.index)).collect();
    let shards: Vec<Option<Shard>> = loaded.iter().map(|(_, r)| r.run.shard).collect();
    let whose = missing_shards(&shards, &missing).map(|s| format!(" ({s})")).unwrap_or_default();
    if !missing.is_empty() && !partial {
        return Err(input_error!(
            "bench merge: {} cell(s) missing{whose}, e.g. {} (--partial marks them `not run`)",
            missing.len(),
            missing[0].describe()
        )
        .into());
    }
    let mut results = first.clone();
    results.run.not_run = missing.iter().map(|c| c.index).collect();
    results.cells = cells;
    results.run.filter = Filter::default();
    results.run.shard = None;
    let dir = device_dir(root, &results);
    write_table(&config, &results, &dir, root)
}

/// Which shards the missing cells belong to, when every part is a shard of the same count
/// (a sweep split with `--shard i/n`, as the GPU suite and the cluster scripts split it):
/// "shard 2 of 4 missing", "shards 2 and 3 of 4 missing". None for filtered parts, mixed
/// counts, or nothing missing.
fn missing_shards(parts: &[Option<Shard>], missing: &[&crate::plan::Cell]) -> Option<String> {
    let count = parts.first()?.as_ref()?.count;
    if missing.is_empty() || parts.iter().any(|p| p.as_ref().is_none_or(|s| s.count != count)) {
        return None;
    }
    let absent: Vec<u32> =
        (1..=count).filter(|&i| missing.iter().any(|c| Shard { index: i, count }.takes(c))).collect();
    let list = match absent.as_slice() {
        [] => return None,
        [one] => format!("shard {one}"),
        [init @ .., last] => {
            format!("shards {} and {last}", init.iter().map(u32::to_string).collect::<Vec<_>>().join(", "))
        }
    };
    Some(format!("{list} of {count} missing"))
}

fn make_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir)
        .map_err(|e| input_error!("cannot create the results folder {}: {e}", dir.display()).into())
}

#[cfg(test)]
mod tests {
    use super::{cost, measure_quiet, missing_shards, selected, worst_spread, Attempts, BenchOptions};
    use crate::measure::CellRun;
    use crate::plan::Shard;

    /// Runs `measure_quiet` over runs whose other processes used `cores`, in turn: the attempts
    /// it made, the pauses it took, and whether the kept run is busy.
    fn quiet(cores: &[Option<f64>], opts: &BenchOptions) -> (usize, Vec<(u32, f64)>, bool, Option<f64>) {
        quiet_timed(cores, opts, true)
    }

    fn quiet_timed(
        cores: &[Option<f64>],
        opts: &BenchOptions,
        timed: bool,
    ) -> (usize, Vec<(u32, f64)>, bool, Option<f64>) {
        let mut made = 0;
        let mut pauses = vec![];
        let (run, busy) = measure_quiet(
            || {
                made += 1;
                Ok(CellRun { other_cores: cores[made - 1], ..CellRun::default() })
            },
            |attempt, c| pauses.push((attempt, c)),
            opts,
            timed,
        )
        .unwrap();
        (made, pauses, busy, run.other_cores)
    }

    #[test]
    fn a_busy_cell_is_measured_again_after_a_pause_then_marked_busy() {
        let opts = BenchOptions { busy_cores: 0.1, busy_retries: 2, ..BenchOptions::default() };
        // Quiet at once, or unknown: one run.
        assert_eq!(quiet(&[Some(0.05)], &opts), (1, vec![], false, Some(0.05)));
        assert_eq!(quiet(&[None], &opts), (1, vec![], false, None));
        // At the bound is quiet; just above is busy.
        assert_eq!(quiet(&[Some(0.1)], &opts), (1, vec![], false, Some(0.1)));
        // Busy, then quiet: the quiet run kept after one pause that names the cores.
        assert_eq!(quiet(&[Some(0.5), Some(0.02)], &opts), (2, vec![(1, 0.5)], false, Some(0.02)));
        // Busy every time: two pauses (the retries), the third run kept and marked busy.
        assert_eq!(quiet(&[Some(0.5), Some(0.4), Some(0.3)], &opts), (3, vec![(1, 0.5), (2, 0.4)], true, Some(0.3)));
        // No retries: the busy run is kept and marked at once.
        let none = BenchOptions { busy_retries: 0, ..opts.clone() };
        assert_eq!(quiet(&[Some(0.5)], &none), (1, vec![], true, Some(0.5)));
        // A quick run (a smoke test) never waits and marks nothing.
        let quick = BenchOptions { quick: true, ..opts.clone() };
        assert_eq!(quiet(&[Some(0.5)], &quick), (1, vec![], false, Some(0.5)));
        // Nor does a config that times nothing (errors and counts): a busy machine computes them alike.
        assert_eq!(quiet_timed(&[Some(1.5)], &opts, false), (1, vec![], false, Some(1.5)));
    }

    fn cell(index: usize, photons: u32, lights: u32, resolution: [u32; 2]) -> crate::plan::Cell {
        serde_json::from_value(serde_json::json!({
            "index": index, "scene": "s.toml", "technique": 0, "technique_label": "t", "photons": photons,
            "lights": lights, "resolution": resolution, "lighting": "dynamic"
        }))
        .unwrap()
    }

    #[test]
    fn merge_names_the_shards_whose_cells_are_missing() {
        let of = |count, present: &[u32]| -> Vec<Option<Shard>> {
            present.iter().map(|&index| Some(Shard { index, count })).collect()
        };
        let cells: Vec<crate::plan::Cell> = (0..10).map(|i| cell(i, 64, 1, [8, 8])).collect();
        // Cells 1, 5, 9 are shard 2 of 4; cells 3 and 7, shard 4 of 4.
        let missing = |idx: &[usize]| -> Vec<&crate::plan::Cell> { idx.iter().map(|&i| &cells[i]).collect() };
        assert_eq!(missing_shards(&of(4, &[1, 3, 4]), &missing(&[1, 5, 9])).as_deref(), Some("shard 2 of 4 missing"));
        assert_eq!(
            missing_shards(&of(4, &[1, 3]), &missing(&[1, 3, 5, 7, 9])).as_deref(),
            Some("shards 2 and 4 of 4 missing")
        );
        assert_eq!(
            missing_shards(&of(5, &[2]), &missing(&[0, 2, 3, 4, 5, 7, 8, 9])).as_deref(),
            Some("shards 1, 3, 4 and 5 of 5 missing")
        );
        // Nothing missing; a filtered part among the shards; shards of two counts: no claim.
        assert_eq!(missing_shards(&of(4, &[1, 2, 3, 4]), &[]), None);
        let mut mixed = of(4, &[1, 3]);
        mixed.push(None);
        assert_eq!(missing_shards(&mixed, &missing(&[1])), None);
        let mut counts = of(4, &[1, 3]);
        counts.push(Some(Shard { index: 1, count: 2 }));
        assert_eq!(missing_shards(&counts, &missing(&[1])), None);
    }

    #[test]
    fn a_cells_cost_is_its_photons_and_pixels_times_its_frames() {
        // 256² photons of 2 lights and a 64 x 32 image, 3 frames.
        assert_eq!(cost(&cell(0, 256, 2, [64, 32]), 3), ((256 * 256 * 2 + 64 * 32) * 3) as f64);
        // No light counts as one; no resolution as 1024².
        assert_eq!(cost(&cell(0, 16, 0, [0, 0]), 1), (16 * 16 + (1 << 20)) as f64);
    }

    #[test]
    fn the_filter_and_the_shard_both_select() {
        let all: Vec<_> = (0..6).map(|i| cell(i, 64, 1, [8, 8])).collect();
        let every = crate::plan::Filter::default();
        let index = |v: Vec<crate::plan::Cell>| v.iter().map(|c| c.index).collect::<Vec<_>>();
        assert_eq!(index(selected(&all, &every, None)), [0, 1, 2, 3, 4, 5]);
        let shard = crate::plan::Shard::parse("2/3").unwrap();
        let sharded = index(selected(&all, &every, Some(&shard)));
        assert!(!sharded.is_empty() && sharded.len() < 6, "{sharded:?}");
        assert!(sharded.iter().all(|&i| shard.takes(&all[i])), "{sharded:?}");
    }

    #[test]
    fn a_metric_whose_passes_the_cell_did_not_record_is_an_error_unless_it_says_why() {
        let config = |extra: &str| -> crate::config::LoadedConfig {
            let text = format!(
                "[table]\npaper = \"p\"\nnumber = \"1\"\ncaption = \"c\"\n[matrix]\nscenes = [\"s.toml\"]\n\
                 photons = [64]\n[[technique]]\nlabel = \"t\"\ntechnique = \"shah\"\n\
                 [[metric]]\nlabel = \"Gather\"\nkind = \"pass_ms\"\npasses = [\"splat*\", \"gather\"]\n{extra}\
                 [layout]\nrows = [\"photons\"]\ncolumns = [\"technique\"]\n"
            );
            crate::config::LoadedConfig {
                path: "c.toml".into(),
                name: "c".into(),
                hash: "0".into(),
                config: toml::from_str(&text).unwrap(),
                text,
            }
        };
        let run = |names: &[&str]| CellRun {
            frames: vec![vkcore::FrameReport {
                passes: names
                    .iter()
                    .map(|n| vkcore::PassTiming { name: n.to_string(), gpu_ms: None, host_ms: None, stats: None })
                    .collect(),
                ..Default::default()
            }],
            ..CellRun::default()
        };
        let c = cell(0, 64, 1, [8, 8]);
        // Either pattern matching one pass is enough.
        super::check_patterns(&config(""), &c, &run(&["eye", "gather"])).unwrap();
        super::check_patterns(&config(""), &c, &run(&["splat.light0"])).unwrap();
        let err = super::check_patterns(&config(""), &c, &run(&["eye", "shadow"])).unwrap_err();
        let msg = format!("{err:#}");
        assert!(
            msg.contains("metric[0].passes") && msg.contains("`splat*`, `gather`") && msg.contains("eye, shadow"),
            "{msg}"
        );
        // A metric that says why its pass may be missing, and a cell without per-pass frames.
        super::check_patterns(&config("absent = \"no gather on this path\"\n"), &c, &run(&["eye"])).unwrap();
        super::check_patterns(&config(""), &c, &CellRun::default()).unwrap();
    }

    #[test]
    fn the_worst_spread_is_the_largest_of_the_timed_metrics() {
        let metric = |label: &str, kind: &str| -> crate::config::MetricSpec {
            toml::from_str(&format!("label = \"{label}\"\nkind = \"{kind}\"")).unwrap()
        };
        let value = |samples: &[f64]| -> crate::results::Value {
            serde_json::from_value(serde_json::json!({
                "kind": "pass_ms", "value": samples[0], "min": null, "max": null, "samples": samples
            }))
            .unwrap()
        };
        let specs = [metric("a", "pass_ms"), metric("b", "frame_ms"), metric("n", "photons_emitted")];
        // Spreads (interquartile range over the median): a 0, b 0.5; n is a count, not timed.
        let values = [
            ("a".to_string(), value(&[10.0, 10.0, 10.0, 10.0, 10.0])),
            ("b".to_string(), value(&[8.0, 8.0, 10.0, 12.0, 12.0])),
            ("n".to_string(), value(&[1.0, 5.0, 9.0, 20.0, 40.0])),
        ]
        .into_iter()
        .collect();
        let want = crate::stats::relative_spread(&[8.0, 8.0, 10.0, 12.0, 12.0]).unwrap();
        assert!(want > 0.1, "{want}");
        assert_eq!(worst_spread(&specs, &values), want);
        assert_eq!(worst_spread(&specs[..1], &values), 0.0);
        assert_eq!(worst_spread(&[], &values), 0.0, "nothing timed: no spread");
    }

    #[test]
    fn a_wide_spread_is_measured_again_and_the_narrowest_quiet_attempt_kept() {
        // Quiet at once: one attempt.
        let mut a = Attempts::new(2);
        assert_eq!(a.add(false, 0.05), (true, false));
        // Wide, then narrow: the second kept, no third.
        let mut a = Attempts::new(2);
        assert_eq!(a.add(false, 0.30), (true, true));
        assert_eq!(a.add(false, 0.04), (true, false));
        // Wide three times: the narrowest of the three kept, then no more (2 retries).
        let mut a = Attempts::new(2);
        assert_eq!(a.add(false, 0.30), (true, true));
        assert_eq!(a.add(false, 0.20), (true, true));
        assert_eq!(a.add(false, 0.25), (false, false));
        assert_eq!(a.spreads, [0.30, 0.20, 0.25]);
        // A busy attempt never wins over a quiet one, whatever its spread.
        let mut a = Attempts::new(2);
        assert_eq!(a.add(false, 0.30), (true, true));
        assert_eq!(a.add(true, 0.01), (false, false));
        // Equal spreads: the first is kept.
        let mut a = Attempts::new(2);
        assert_eq!(a.add(false, 0.30), (true, true));
        assert_eq!(a.add(false, 0.30), (false, true));
        // No retries (quick runs): one attempt, however wide.
        let mut a = Attempts::new(0);
        assert_eq!(a.add(false, 0.90), (true, false));
    }
}
