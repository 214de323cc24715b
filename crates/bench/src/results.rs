//! `<config>.json.gz`: everything a run measured (raw samples included) and what it ran on, as
//! gzip-compressed JSON (`zcat` or Python's `gzip.open` read it; a plain `<config>.json` is read
//! too). Shard files (`parts/`) have the same shape, uncompressed, with a subset of the cells;
//! `bench merge` reads them back.

use crate::measure::CellRun;
use crate::plan::{Cell, Filter, Shard};
use crate::record::{pass_summaries, Pass};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::Read as _;
use std::path::{Path, PathBuf};
use vkcore::PipelineStats;

pub const SCHEMA: u32 = 1;

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Results {
    pub schema: u32,
    pub config: ConfigInfo,
    pub run: RunInfo,
    pub meta: Meta,
    /// In cell-index order.
    pub cells: Vec<CellResult>,
    /// The plausibility rules' findings (`crate::plausibility`), recomputed whenever the table
    /// is written.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub plausibility: Vec<crate::plausibility::Finding>,
    /// The curves a front drew from another table (`crate::front_curves`), read when the table
    /// is written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub front_curves: Option<crate::front_curves::FrontCurves>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ConfigInfo {
    pub file: String,
    pub name: String,
    pub hash: String,
    pub paper: String,
    pub table: String,
    pub caption: String,
    /// The config file's text, so that `bench merge` needs nothing but the parts.
    pub toml: String,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct RunInfo {
    pub quick: bool,
    pub warmup_frames: u32,
    /// The fewest frames a cell measured (`run.measured_frames`).
    pub measured_frames: u32,
    /// Seconds of measured frames each cell ran at least, and the most frames it could
    /// measure; absent in results written before cells ran to a time budget.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_budget_s: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_frames: Option<u32>,
    pub light_path: String,
    pub camera_path: String,
    pub object_path: String,
    pub period_frames: u32,
    pub validation: bool,
    pub filter: Filter,
    pub shard: Option<Shard>,
    /// Cells in the full matrix (the table's size).
    pub total_cells: usize,
    /// The device's buffer copy bandwidth measured at the start of the run (GB/s read plus
    /// written), for the plausibility rule on copies.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub copy_bandwidth_gbs: Option<f64>,
    /// Indices of the cells no part had, in a table merged with `bench merge --partial` (a GPU
    /// suite cut off by its time budget): they read `not run`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub not_run: Vec<usize>,
    /// Read again after the run with its config's explanations, text and judging
    /// (`bench explain`); the timings are the run's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub explained: Option<Explained>,
}

/// When a table was read again (`bench explain`) with what its config changed after the run in
/// what measures nothing: explanations, text, layout, judging.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Explained {
    /// The commit whose `causticlab bench explain` did it.
    pub commit: String,
    pub date: String,
    /// The config's hash when the table was measured.
    pub measured_config_hash: String,
}

/// Where and when the numbers were taken.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Meta {
    pub device: String,
    pub device_type: String,
    pub device_slug: String,
    pub driver_name: String,
    pub driver_info: String,
    pub vulkan_version: String,
    pub timestamp_period_ns: f32,
    pub cpu: String,
    pub commit: String,
    pub date: String,
    pub causticlab_version: String,
    /// Device quirks the run worked around (e.g. features treated as absent).
    pub quirks: Vec<String>,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct CellResult {
    pub cell: Cell,
    /// The caustic settings in effect (`[caustics]` of the scene, the technique entry, `--quick`).
    pub caustics: serde_json::Value,
    pub photon_copy: String,
    pub triangles: usize,
    /// The model files the cell's scene loaded, by checksum (absent in results written before
    /// they were kept, and for scenes without models).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub models: Vec<caustics::scene::models::ModelFile>,
    /// Metric label → value.
    pub metrics: BTreeMap<String, Value>,
    /// Host wall time of each measured frame, ms.
    pub wall_ms: Vec<f64>,
    /// Host time of each pose update before a measured frame (`Renderer::set_pose`), ms; absent
    /// on a static path and in results written before it was kept.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pose_ms: Vec<f64>,
    /// Per-pass GPU times over the measured frames.
    pub passes: Vec<Pass>,
    /// Share of the host's CPU time the hypervisor gave to other guests while the cell's frames
    /// ran (Linux steal time; absent where unknown, and in results written before it was kept).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_steal: Option<f64>,
    /// Cores' worth of CPU time other processes on the host used while the cell ran.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub other_cores: Option<f64>,
    /// The host speed probe before the cell's frames, ms (`crate::host_speed`; absent in results
    /// written before it was kept).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub host_probe_ms: Option<f64>,
    /// The cell ran while other processes used more than the run's threshold, even after it was
    /// measured again: its times are not a quiet machine's (`~` in the table).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub busy: bool,
    /// Per light, the traversal's list sizes of the last frame: `hcm`'s from its 16² level down
    /// to the splatted list; `adaptive`'s pending clusters of each level (64² photons first),
    /// then the photons splatted (Wyman & Nichols 2009 Table 1, Fig. 7). Absent otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub list_sizes: Option<Vec<Vec<u64>>>,
    /// Per frame mode (`per-pass`, `throughput`): what its measured frames asked of the driver.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub frame_counters: BTreeMap<String, FrameCounters>,
    /// Throughput frames: host ms per frame of each timed block.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub block_ms: Vec<f64>,
    /// `temporal_change`: the receiver map's relative RMS change from each measured frame to the
    /// next (the metric is their mean).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub temporal_changes: Vec<f64>,
    /// Progressive accumulation's curve: every frame's accumulated time and error
    /// (`crate::progressive`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub progressive: Vec<crate::progressive::Point>,
    /// A cell measured again because its spread was over 10%: the largest spread of its timed
    /// metrics at each attempt, in order (the attempt with the smallest is the one kept).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub spread_attempts: Vec<f64>,
    /// `flip`: the final image's HDR-FLIP against the reference final image, with the size,
    /// pixels per degree, exposures and reference it was computed at (`crate::final_flip`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub final_flip: Option<crate::final_flip::FinalFlip>,
}

/// What the measured frames of one mode asked of the driver, per frame (medians, and the most
/// objects any frame created: zero for warm throughput frames).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct FrameCounters {
    pub frames: usize,
    /// Passes recorded.
    pub passes: f64,
    pub submits: f64,
    pub barriers: f64,
    pub timestamps: f64,
    pub objects: f64,
    pub most_objects: u64,
}

impl FrameCounters {
    pub fn of(counters: &[vkcore::Counters], passes: &[usize]) -> Option<FrameCounters> {
        if counters.is_empty() {
            return None;
        }
        let p: Vec<f64> = passes.iter().map(|&n| n as f64).collect();
        let median = |f: &dyn Fn(&vkcore::Counters) -> u64| {
            let v: Vec<f64> = counters.iter().map(|c| f(c) as f64).collect();
            crate::stats::quartiles(&v).map(|(_, m, _)| m).unwrap_or(0.0)
        };
        Some(FrameCounters {
            frames: counters.len(),
            passes: crate::stats::quartiles(&p).map(|(_, m, _)| m).unwrap_or(0.0),
            submits: median(&|c| c.submits),
            barriers: median(&|c| c.barriers),
            timestamps: median(&|c| c.timestamps),
            objects: median(&|c| c.objects),
            most_objects: counters.iter().map(|c| c.objects).max().unwrap_or(0),
        })
    }
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Value {
    pub kind: String,
    /// The table's number (median for times, 1000 / mean frame time for fps; exact for
    /// counts).
    pub value: Option<f64>,
    pub min: Option<f64>,
    pub max: Option<f64>,
    /// First and third quartiles of `samples` (absent in results written before they were
    /// kept; the table computes its spread from `samples` either way).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q1: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q3: Option<f64>,
    /// Per measured frame, where the metric has one value per frame.
    pub samples: Vec<f64>,
}

/// The spread the table flags: a timed metric's samples' relative interquartile range (`None`
/// for counts and errors, which do not vary between runs, and without samples).
pub fn timed_spread(kind: &str, value: &Value) -> Option<f64> {
    is_timing(kind).then(|| crate::stats::relative_spread(&value.samples)).flatten()
}

/// Is `kind` a time or rate (varies between runs) rather than a count or an error measure?
pub fn is_timing(kind: &str) -> bool {
    matches!(
        kind,
        "pass_ms"
            | "pass_host_ms"
            | "gpu_frame_ms"
            | "frame_ms"
            | "pose_ms"
            | "fps"
            | "pass_fps"
            | "pass_mphotons"
            | "pass_host_mphotons"
            | "frame_mphotons"
    )
}

pub fn cell_result(cell: &Cell, run: &CellRun, metrics: BTreeMap<String, Value>, photon_copy: &str) -> CellResult {
    let stats = |name: &str| -> Option<PipelineStats> { run.stats_frame.as_ref()?.pass(name)?.stats };
    let passes = pass_summaries(&run.frames, stats);
    CellResult {
        cell: cell.clone(),
        caustics: serde_json::to_value(&run.caustics).unwrap_or(serde_json::Value::Null),
        photon_copy: photon_copy.to_string(),
        triangles: run.triangles,
        models: run.models.clone(),
        metrics,
        wall_ms: run.wall_ms.clone(),
        pose_ms: run.pose_ms.clone(),
        passes,
        cpu_steal: run.cpu_steal,
        other_cores: run.other_cores,
        host_probe_ms: Some(run.host_probe_ms),
        busy: false,
        list_sizes: run.hierarchy_sizes.clone(),
        frame_counters: [
            (
                "per-pass",
                FrameCounters::of(&run.counters, &run.frames.iter().map(|f| f.passes.len()).collect::<Vec<_>>()),
            ),
            ("throughput", run.throughput.as_ref().and_then(|t| FrameCounters::of(&t.counters, &t.passes))),
        ]
        .into_iter()
        .filter_map(|(k, v)| Some((k.to_string(), v?)))
        .collect(),
        block_ms: run.throughput.as_ref().map(|t| t.block_ms.clone()).unwrap_or_default(),
        temporal_changes: run.temporal_changes.clone(),
        progressive: run.progressive.clone(),
        spread_attempts: vec![],
        final_flip: run.final_flip.clone(),
    }
}

/// How the bench names a table's file: `<config>.json.gz`. Its raw samples compress about
/// ninefold, and the tracked tree must travel to a GPU machine in 64 MiB (`scripts/gpu_pack.sh`).
pub const TABLE_EXT: &str = "json.gz";

/// The most a results file may decompress to (256 MiB): over fifty times the largest table yet
/// (a GPU table of 4.6 MB), so that a corrupt or hostile file fails before it fills memory.
pub const MAX_JSON_BYTES: u64 = 1 << 28;

/// The file of table `name` in `dir`: `<name>.json.gz` as the bench writes it, or `<name>.json`
/// where only that is there (a folder written before tables were compressed, or unpacked by
/// hand); where neither is, the compressed name, for the error that reads it. Both there is an
/// error: which of the two is the table (an edited copy, an older causticlab's run) is not for
/// the reader to guess.
pub fn table_file(dir: &Path, name: &str) -> anyhow::Result<PathBuf> {
    let gz = dir.join(format!("{name}.{TABLE_EXT}"));
    let plain = dir.join(format!("{name}.json"));
    match (gz.exists(), plain.exists()) {
        (true, true) => Err(caustics::input_error!(
            "{}: two tables of `{name}`, {name}.{TABLE_EXT} (as the bench writes it) and {name}.json: remove the one that is not the table",
            dir.display()
        )
        .into()),
        (false, true) => Ok(plain),
        _ => Ok(gz),
    }
}

/// The config name of a table file (`x.json.gz` or `x.json` gives `x`); None for any other file.
pub fn table_name(path: &Path) -> Option<String> {
    let file = path.file_name()?.to_str()?;
    let stem = file.strip_suffix(&format!(".{TABLE_EXT}")).or_else(|| file.strip_suffix(".json"))?;
    (!stem.is_empty()).then(|| stem.to_string())
}

/// A results file's JSON text: gzip-compressed (known by its first two bytes, whatever its name)
/// or plain; `what` names the file in errors.
pub fn read_text(path: &Path, what: &str) -> anyhow::Result<String> {
    read_capped(path, what, MAX_JSON_BYTES)
}

/// [`read_text`] with at most `limit` bytes read from the file and at most `limit` decompressed.
fn read_capped(path: &Path, what: &str, limit: u64) -> anyhow::Result<String> {
    let p = path.display();
    let cannot = |e: std::io::Error| caustics::input_error!("{p}: cannot read the {what}: {e}");
    let mut bytes = vec![];
    std::fs::File::open(path).map_err(cannot)?.take(limit + 1).read_to_end(&mut bytes).map_err(cannot)?;
    if bytes.len() as u64 > limit {
        return Err(caustics::input_error!("{p}: the {what} is larger than {} MiB", limit >> 20).into());
    }
    Ok(decode(bytes, limit).map_err(|why| caustics::input_error!("{p}: the {what} {why}"))?)
}

/// `bytes` as text, gunzipped first where they are gzip's (RFC 1952's magic 1f 8b); an error
/// where they decompress to more than `limit` bytes, are a broken stream or are not UTF-8.
fn decode(bytes: Vec<u8>, limit: u64) -> Result<String, String> {
    let text = if bytes.starts_with(&[0x1f, 0x8b]) {
        let mut out = vec![];
        flate2::read::MultiGzDecoder::new(bytes.as_slice())
            .take(limit + 1)
            .read_to_end(&mut out)
            .map_err(|e| format!("is not a whole gzip stream: {e}"))?;
        if out.len() as u64 > limit {
            return Err(format!("decompresses to more than {} MiB", limit >> 20));
        }
        out
    } else {
        bytes
    };
    String::from_utf8(text).map_err(|e| format!("is not UTF-8 text: {e}"))
}

/// `text` gzip-compressed as the bench keeps a table: the best compression and no name or time
/// in the header, so that the same table gives the same bytes.
pub fn gzip(text: &str) -> anyhow::Result<Vec<u8>> {
    use std::io::Write as _;
    let mut z = flate2::GzBuilder::new().mtime(0).write(vec![], flate2::Compression::best());
    z.write_all(text.as_bytes())?;
    Ok(z.finish()?)
}

/// A results file the bench wrote (a table or a part, compressed or not; `what` names it in
/// errors), checked to be of this causticlab's schema.
pub fn read(path: &Path, what: &str) -> anyhow::Result<Results> {
    let p = path.display();
    let text = read_text(path, what)?;
    let r: Results =
        serde_json::from_str(&text).map_err(|e| caustics::input_error!("{p}: not a causticlab bench result: {e}"))?;
    if r.schema != SCHEMA {
        return Err(caustics::input_error!("{p}: results schema {} (this causticlab reads {SCHEMA})", r.schema).into());
    }
    Ok(r)
}

/// The results as JSON, one line per top-level key and one per cell, every number to 9
/// significant digits (1 ns on a 1 s frame: below every timer's resolution here), so that a GPU
/// table's thousands of per-frame samples stay small enough to travel (`scripts/gpu_pack.sh`).
pub fn to_json(results: &Results) -> anyhow::Result<String> {
    use anyhow::Context as _;
    let value = round_numbers(serde_json::to_value(results).context("serialising the results")?);
    let compact = |v: &serde_json::Value| serde_json::to_string(v).context("serialising the results");
    let serde_json::Value::Object(top) = &value else { return compact(&value) };
    let mut lines = vec![];
    for (key, v) in top {
        let k = compact(&serde_json::Value::String(key.clone()))?;
        match v {
            serde_json::Value::Array(items) if !items.is_empty() => {
                let items: Vec<String> = items.iter().map(compact).collect::<anyhow::Result<_>>()?;
                lines.push(format!("{k}: [\n{}\n]", items.join(",\n")));
            }
            _ => lines.push(format!("{k}: {}", compact(v)?)),
        }
    }
    Ok(format!("{{\n{}\n}}\n", lines.join(",\n")))
}

/// The results exactly as their JSON will read back: every number to 9 significant digits, so
/// that the CSV, the tables and the plots of a run equal those `bench merge` redraws from its JSON.
pub fn rounded(results: &Results) -> anyhow::Result<Results> {
    use anyhow::Context as _;
    let value = round_numbers(serde_json::to_value(results).context("serialising the results")?);
    serde_json::from_value(value).context("re-reading the rounded results")
}

fn round_numbers(v: serde_json::Value) -> serde_json::Value {
    use serde_json::Value;
    match v {
        Value::Number(n) if n.is_f64() => {
            let x = n.as_f64().unwrap_or(0.0);
            let r: f64 = format!("{x:.8e}").parse().unwrap_or(x);
            serde_json::Number::from_f64(r).map(Value::Number).unwrap_or(Value::Null)
        }
        Value::Array(a) => Value::Array(a.into_iter().map(round_numbers).collect()),
        Value::Object(o) => Value::Object(o.into_iter().map(|(k, v)| (k, round_numbers(v))).collect()),
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_is_gzip_with_no_name_or_time_and_reads_back() {
        let text = "{\n\"schema\": 1\n}\n".repeat(50);
        let z = gzip(&text).unwrap();
        assert_eq!(&z[..3], &[0x1f, 0x8b, 8], "gzip's magic and deflate");
        assert_eq!(z[3], 0, "no name, comment or extra field in the header");
        assert_eq!(&z[4..8], &[0, 0, 0, 0], "no modification time");
        assert!(z.len() < text.len() / 4, "{} bytes for {}", z.len(), text.len());
        assert_eq!(gzip(&text).unwrap(), z, "the same table gives the same bytes");
        assert_eq!(decode(z, MAX_JSON_BYTES).unwrap(), text);
        // A plain file reads as it is.
        assert_eq!(decode(text.clone().into_bytes(), MAX_JSON_BYTES).unwrap(), text);
    }

    #[test]
    fn decoding_stops_at_the_limit_and_names_what_is_wrong() {
        let text = "a".repeat(1000);
        let z = gzip(&text).unwrap();
        assert_eq!(decode(z.clone(), 1000).unwrap(), text, "exactly the limit is read whole");
        let over = decode(z.clone(), 999).unwrap_err();
        assert!(over.contains("decompresses to more than"), "{over}");
        let cut = decode(z[..z.len() - 9].to_vec(), MAX_JSON_BYTES).unwrap_err();
        assert!(cut.contains("not a whole gzip stream"), "{cut}");
        let binary = decode(vec![b'{', 0xff, 0xfe], MAX_JSON_BYTES).unwrap_err();
        assert!(binary.contains("not UTF-8"), "{binary}");
    }

    #[test]
    fn a_file_over_the_limit_is_refused_before_it_is_read_whole() {
        let dir = std::env::temp_dir().join(format!("causticlab-read-capped-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (plain, gz) = (dir.join("t.json"), dir.join("t.json.gz"));
        let text = "b".repeat(3 << 20);
        std::fs::write(&plain, &text).unwrap();
        std::fs::write(&gz, gzip(&text).unwrap()).unwrap();
        for path in [&plain, &gz] {
            assert_eq!(read_capped(path, "table", 3 << 20).unwrap(), text, "{}: exactly the limit", path.display());
        }
        let err = format!("{:#}", read_capped(&plain, "table", (3 << 20) - 1).unwrap_err());
        assert!(err.contains("t.json: the table is larger than 2 MiB"), "{err}");
        let err = format!("{:#}", read_capped(&gz, "table", (3 << 20) - 1).unwrap_err());
        assert!(err.contains("t.json.gz: the table decompresses to more than 2 MiB"), "{err}");
        let err = format!("{:#}", read_text(&dir.join("none.json.gz"), "table").unwrap_err());
        assert!(err.contains("none.json.gz: cannot read the table"), "{err}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_tables_name_and_file() {
        assert_eq!(table_name(Path::new("r/dev/wyman2008_table2.json.gz")).as_deref(), Some("wyman2008_table2"));
        assert_eq!(table_name(Path::new("r/dev/wyman2008_table2.json")).as_deref(), Some("wyman2008_table2"));
        assert_eq!(table_name(Path::new("r/dev/wyman2008_table2.csv")), None);
        assert_eq!(table_name(Path::new("r/dev/.json.gz")), None);

        let dir = std::env::temp_dir().join(format!("causticlab-table-file-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (gz, plain) = (dir.join("t.json.gz"), dir.join("t.json"));
        assert_eq!(table_file(&dir, "t").unwrap(), gz, "neither there: the name the bench writes");
        std::fs::write(&plain, "{}").unwrap();
        assert_eq!(table_file(&dir, "t").unwrap(), plain, "only a plain file there");
        std::fs::write(&gz, gzip("{}").unwrap()).unwrap();
        let both = format!("{:#}", table_file(&dir, "t").unwrap_err());
        assert!(both.contains("two tables of `t`, t.json.gz (as the bench writes it) and t.json"), "{both}");
        std::fs::remove_file(&plain).unwrap();
        assert_eq!(table_file(&dir, "t").unwrap(), gz, "only the compressed file there");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
