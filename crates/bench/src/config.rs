//! Bench configs (`bench_configs/*.toml`, format in `bench_configs/README.md`): which paper
//! table a config reproduces, the matrix of cells it measures, how each cell is run, which
//! metrics fill the table, how the table is laid out, and the paper's published values.
//! Unknown keys are errors; every message names the file and the key.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Largest photon count (per side) a config may ask for: the most any technique takes
/// (`adaptive` under a `photon_memory_limit`, Wyman & Nichols 2009 Sec. 4.3). A cell whose
/// technique cannot run at its count is not run (see [`Config::runs`]).
pub const MAX_PHOTONS: u32 = caustics::techniques::wyman_nichols2009::settings::TOP_PHOTONS
    << caustics::techniques::wyman_nichols2009::settings::MAX_LEVEL;
/// Largest output side.
pub const MAX_RESOLUTION: u32 = 8192;
/// Most frames a cell may measure (and warm up).
pub const MAX_FRAMES: u32 = 10_000;

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Config {
    pub table: TableSpec,
    #[serde(default)]
    pub run: RunSpec,
    pub matrix: MatrixSpec,
    /// Caustic settings for every technique entry, applied before each entry's own (which win):
    /// the paper's setup, e.g. `photon_view = "fixed-fov"` and `back_face_iterations = 0`.
    /// Neither `technique`, `photons` nor a setting of some techniques only may be set here.
    #[serde(default)]
    pub caustics: caustics::scene::CausticOverrides,
    #[serde(rename = "technique")]
    pub techniques: Vec<TechniqueSpec>,
    #[serde(rename = "metric")]
    pub metrics: Vec<MetricSpec>,
    pub layout: LayoutSpec,
    #[serde(default)]
    pub quick: QuickSpec,
    #[serde(default)]
    pub quality: QualitySpec,
    #[serde(default)]
    pub paper: Vec<PaperEntry>,
    /// The plausibility rules' declarations (`crate::plausibility`).
    #[serde(default)]
    pub plausibility: PlausibilitySpec,
    /// An error-against-time front instead of the usual plot (`crate::front`).
    #[serde(default)]
    pub front: Option<FrontSpec>,
}

/// `[front]`: plot one metric against another per scene, log-log, with the Pareto front, and
/// list the cheapest cell per error level (`crate::front`).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FrontSpec {
    /// The labels of the time metrics on the x axis (lower is better): one, or a list, each a
    /// front of its own (e.g. the caustic stages' time and the whole frame's).
    #[serde(deserialize_with = "one_or_many")]
    pub x: Vec<String>,
    /// The labels of the error metrics on the y axis (lower is better): one, or a list, each a
    /// panel beside the others (e.g. the receiver map's relative RMSE and the final image's FLIP).
    #[serde(deserialize_with = "one_or_many")]
    pub y: Vec<String>,
    /// The error levels of the table of the cheapest cells, each above 0: a list for one y
    /// metric, or a table of lists keyed by the y metrics' labels.
    pub levels: FrontLevels,
    /// Progressive accumulation's curves from another table of the results folder, drawn on
    /// one x and y pair's panels (`crate::front_curves`).
    #[serde(default)]
    pub curves: Option<crate::front_curves::CurvesSpec>,
}

/// `[front] levels`: one list, or one per y metric.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(untagged)]
pub enum FrontLevels {
    All(Vec<f64>),
    ByMetric(BTreeMap<String, Vec<f64>>),
}

impl FrontSpec {
    /// The error levels of y metric `y` (none where a table of levels leaves it out).
    pub fn levels_of(&self, y: &str) -> &[f64] {
        match &self.levels {
            FrontLevels::All(v) => v,
            FrontLevels::ByMetric(m) => m.get(y).map_or(&[], Vec::as_slice),
        }
    }
}

/// A string, or a list of strings.
fn one_or_many<'de, D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Vec<String>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum OneOrMany {
        One(String),
        Many(Vec<String>),
    }
    Ok(match OneOrMany::deserialize(d)? {
        OneOrMany::One(s) => vec![s],
        OneOrMany::Many(v) => v,
    })
}

/// What the plausibility rules need to know about a table (`crate::plausibility`).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlausibilitySpec {
    /// Axes along which the work grows, in the matrix's order of their values: `photons`,
    /// `resolution`, `lights`, and `scene` where the config lists its scenes by model size.
    #[serde(default = "default_grows")]
    pub work_grows_with: Vec<String>,
    /// Findings explained by a measurement: they are listed as explained, not marked `?`.
    #[serde(default)]
    pub explained: Vec<ExplainedSpec>,
}

fn default_grows() -> Vec<String> {
    vec!["photons".into(), "resolution".into()]
}

impl Default for PlausibilitySpec {
    fn default() -> Self {
        PlausibilitySpec { work_grows_with: default_grows(), explained: vec![] }
    }
}

/// One explained finding: the rule, the metric and the cell's labels on the axes given (axes not
/// given match any value), and the explanation, which cites a measurement.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ExplainedSpec {
    pub rule: String,
    pub metric: String,
    #[serde(default)]
    pub scene: Option<String>,
    #[serde(default)]
    pub technique: Option<String>,
    #[serde(default)]
    pub photons: Option<u32>,
    #[serde(default)]
    pub lighting: Option<String>,
    /// Only on devices whose name contains this (case-insensitive), e.g. `llvmpipe`.
    #[serde(default)]
    pub device: Option<String>,
    pub why: String,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TableSpec {
    /// e.g. "Wyman 2008, Hierarchical caustic maps".
    pub paper: String,
    /// e.g. "1".
    pub number: String,
    pub caption: String,
    /// Free text printed under the table (what differs from the paper's setup).
    #[serde(default)]
    pub notes: Vec<String>,
    /// Log-scale y axis for the plot; default true.
    #[serde(default = "yes")]
    pub plot_log_y: bool,
}

impl TableSpec {
    /// "paper, Table number", or "paper, Fig. 10 (data)" for a figure's data.
    pub fn title(&self) -> String {
        title(&self.paper, &self.number)
    }
}

/// A table's title from its paper and number: a number naming a figure ("Fig. 10 (data)") is
/// not a table's.
pub fn title(paper: &str, number: &str) -> String {
    if number.starts_with("Fig") {
        format!("{paper}, {number}")
    } else {
        format!("{paper}, Table {number}")
    }
}

fn yes() -> bool {
    true
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RunSpec {
    #[serde(default = "default_warmup")]
    pub warmup_frames: u32,
    /// The fewest frames a cell measures; it measures until it has these and `time_budget_s`.
    #[serde(default = "default_measured")]
    pub measured_frames: u32,
    /// Seconds of measured frames a cell runs at least (once it has `measured_frames`).
    #[serde(default = "default_budget")]
    pub time_budget_s: f64,
    /// The most frames a cell measures, whatever the budget; default the larger of
    /// [`DEFAULT_MAX_FRAMES`] and `measured_frames`.
    #[serde(default)]
    pub max_frames: Option<u32>,
    /// `static` or `orbit` for each of the light, camera and specular objects.
    #[serde(default = "default_path")]
    pub light_path: String,
    #[serde(default = "default_path")]
    pub camera_path: String,
    #[serde(default = "default_path")]
    pub object_path: String,
    /// Frames per loop of every path.
    #[serde(default = "default_period")]
    pub period_frames: u32,
    /// Throughput metrics: frames per timed block (a cell measures at least
    /// [`MIN_BLOCKS`] blocks).
    #[serde(default = "default_block")]
    pub block_frames: u32,
}

/// The fewest blocks of frames a throughput cell measures.
pub const MIN_BLOCKS: u32 = 5;
/// The fewest blocks a `--quick` run's throughput cell measures (a smoke test).
pub const QUICK_MIN_BLOCKS: u32 = 2;

/// The fewest blocks a throughput cell of a run measures.
pub fn min_blocks(quick: bool) -> u32 {
    if quick {
        QUICK_MIN_BLOCKS
    } else {
        MIN_BLOCKS
    }
}
fn default_block() -> u32 {
    2
}

fn default_warmup() -> u32 {
    2
}
fn default_measured() -> u32 {
    5
}
fn default_budget() -> f64 {
    1.0
}
/// The cap on measured frames when a config gives no `max_frames`.
pub const DEFAULT_MAX_FRAMES: u32 = 1000;
fn default_path() -> String {
    "static".into()
}
fn default_period() -> u32 {
    60
}

impl Default for RunSpec {
    fn default() -> Self {
        RunSpec {
            warmup_frames: default_warmup(),
            measured_frames: default_measured(),
            time_budget_s: default_budget(),
            max_frames: None,
            light_path: default_path(),
            camera_path: default_path(),
            object_path: default_path(),
            period_frames: default_period(),
            block_frames: default_block(),
        }
    }
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MatrixSpec {
    /// Scene files, relative to the config file.
    pub scenes: Vec<String>,
    /// Photon buffer sides N (N x N photons per light).
    pub photons: Vec<u32>,
    /// Numbers of lights; empty = each scene's own. Fewer than the scene has keeps the first
    /// ones; more adds copies of the scene's last light turned about the vertical axis through
    /// the centre of the scene's bounds, spread evenly (see `measure::set_light_count`).
    #[serde(default)]
    pub lights: Vec<u32>,
    /// Output sizes [width, height]; empty = each scene's camera.
    #[serde(default)]
    pub resolution: Vec<[u32; 2]>,
    /// `dynamic` (every pass every frame) and/or `static` (the photon buffer is rendered once,
    /// in the warm-up, and reused: Wyman & Davis 2006 Table 1).
    #[serde(default = "default_lighting")]
    pub lighting: Vec<String>,
}

fn default_lighting() -> Vec<String> {
    vec!["dynamic".into()]
}

/// One column group of techniques: a name in the table and the settings behind it.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TechniqueSpec {
    pub label: String,
    /// `none` (instanced fetch), `16-to-32`, `32-to-32` or `16-to-16`.
    #[serde(default = "default_copy")]
    pub photon_copy: String,
    /// The technique (required) and any caustic setting but `photons` (the matrix sets it),
    /// by the names of the scene's `[caustics]` (one type: `caustics::scene::CausticOverrides`).
    #[serde(flatten)]
    pub settings: caustics::scene::CausticOverrides,
}

fn default_copy() -> String {
    "none".into()
}

/// Metric kinds: see `bench_configs/README.md`.
pub const METRIC_KINDS: &[&str] = &[
    "pass_ms",
    "pass_fps",
    "pass_mphotons",
    "pass_host_ms",
    "pass_host_mphotons",
    "frame_mphotons",
    "gpu_frame_ms",
    "frame_ms",
    "fps",
    "pose_ms",
    "blas_builds",
    "tlas_builds",
    "blas_refits",
    "photons_emitted",
    "splats_drawn",
    "photons_processed",
    "valid_photons",
    "valid_fraction",
    "rel_rmse",
    "flux_ratio",
    "peak_ratio",
    "peak_offset",
    "photon_storage",
    "photon_batches",
    "depth_complexity_mean",
    "depth_complexity_p50",
    "depth_complexity_p90",
    "depth_complexity_p99",
    "depth_complexity_max",
    "quad_coverage",
    "temporal_change",
    "flip",
    "progressive_rel_rmse",
    "progressive_ms",
    "progressive_frames",
];

/// Whether metric `kind` reads the caustic quads' depth complexity (`wd-quads` only).
pub fn is_depth_complexity_metric(kind: &str) -> bool {
    kind.starts_with("depth_complexity_") || kind == "quad_coverage"
}

/// Whether metric `kind` compares each frame's receiver map with the previous frame's
/// (`temporal_change`: how steady the caustic is along an animation).
pub fn is_temporal_metric(kind: &str) -> bool {
    kind == "temporal_change"
}

/// Whether metric `kind` counts the acceleration structures each pose update built or refitted
/// (what the pose updates between frames asked of the driver, timing nothing).
pub fn is_pose_count(kind: &str) -> bool {
    matches!(kind, "blas_builds" | "tlas_builds" | "blas_refits")
}

/// Whether metric `kind` measures the pose updates between frames: their host time
/// (`pose_ms`) or their counts ([`is_pose_count`]).
pub fn is_pose_metric(kind: &str) -> bool {
    kind == "pose_ms" || is_pose_count(kind)
}

/// Whether metric `kind` compares the final image with the reference final image
/// (`crate::final_flip`).
pub fn is_flip_metric(kind: &str) -> bool {
    kind == "flip"
}

/// Whether metric `kind` compares the receiver map with the CPU reference (`[quality]`).
pub fn is_quality_metric(kind: &str) -> bool {
    matches!(kind, "rel_rmse" | "flux_ratio" | "peak_ratio" | "peak_offset")
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MetricSpec {
    pub label: String,
    pub kind: String,
    /// For `pass_ms`, `pass_fps`, `pass_mphotons`, `pass_host_ms` and `pass_host_mphotons`: pass names summed per frame; `*` matches any run of characters.
    #[serde(default)]
    pub passes: Vec<String>,
    /// For `frame_ms` and `fps`: passes whose GPU time is taken off each frame's wall time, for
    /// work our pipeline does that the paper's did not (e.g. `photon_buffer.to_16bit*`, the
    /// stand-in for a 16-bit photon buffer). `*` as in `passes`.
    #[serde(default)]
    pub exclude: Vec<String>,
    /// The frame mode its frames run in: `per-pass` (default: one-shot frames, a timestamp pair
    /// around every pass) or `throughput` (a ring of frames in flight, timed per block of frames
    /// and per frame on the GPU; kinds fps, frame_ms and gpu_frame_ms). See
    /// `caustics::gpu::frame_mode`.
    #[serde(default)]
    pub mode: Option<String>,
    /// Why some cells may record no pass matching `passes`, e.g. "the instanced
    /// fetch copies nothing". Without it, a cell whose passes match none of the patterns is an
    /// error naming the patterns and the passes recorded: a renamed pass cannot silently turn a
    /// column into n/a. With it, such cells read n/a and the reason is listed under the table.
    #[serde(default)]
    pub absent: Option<String>,
    /// Axes this metric's work does not depend on: a value that varies by more than 2x along one
    /// is implausible (rule d). Its work is then also not taken to grow along them (rule a).
    #[serde(default)]
    pub independent_of: Vec<String>,
    /// Rules a and g off for this metric: its work (or count) need not grow along `work_grows_with`, and why
    /// (e.g. a per-level time whose level changes meaning with the photon count).
    #[serde(default)]
    pub not_monotonic: Option<String>,
    /// Bytes a copy reads and writes per photon and light: one number, or one per technique
    /// label. With the device's copy bandwidth (measured at the start of the run) a time that
    /// would move them faster is implausible (rule c).
    #[serde(default)]
    pub bytes_per_photon: Option<BytesPerPhoton>,
    /// For `progressive_rel_rmse` and `progressive_ms`: after this many accumulated frames
    /// (`crate::progressive`).
    #[serde(default)]
    pub frames: Option<u32>,
    /// For `progressive_rel_rmse` and `progressive_frames`: after the first frame whose
    /// accumulated time reaches this many ms.
    #[serde(default)]
    pub after_ms: Option<f64>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(untagged)]
pub enum BytesPerPhoton {
    All(f64),
    ByTechnique(std::collections::BTreeMap<String, f64>),
}

impl BytesPerPhoton {
    pub fn of(&self, technique: &str) -> Option<f64> {
        match self {
            BytesPerPhoton::All(b) => Some(*b),
            BytesPerPhoton::ByTechnique(m) => m.get(technique).copied(),
        }
    }
}

impl MetricSpec {
    /// `per-pass` or `throughput`.
    pub fn mode(&self) -> &str {
        self.mode.as_deref().unwrap_or("per-pass")
    }
    pub fn throughput(&self) -> bool {
        self.mode() == "throughput"
    }
}

/// Metric kinds a `throughput` metric may have.
pub const THROUGHPUT_KINDS: &[&str] = &["fps", "frame_ms", "gpu_frame_ms"];

/// The matrix axes a table can lay out.
pub const AXES: &[&str] = &["scene", "technique", "photons", "lights", "resolution", "lighting", "metric"];

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LayoutSpec {
    /// Axes nested into rows, outermost first.
    pub rows: Vec<String>,
    /// Axes nested into columns, outermost first. Every axis with more than one value must be
    /// in `rows` or `columns`.
    pub columns: Vec<String>,
    /// Ratios against one value of an axis: `{ axis = "technique", baseline = "points" }`.
    pub compare: Option<CompareSpec>,
    /// The paper's columns, in its order: each picks one column of `columns` and names it.
    /// Empty: every column, one table per metric when `columns` crosses the metrics with
    /// another axis.
    #[serde(default, rename = "column")]
    pub pick: Vec<ColumnSpec>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CompareSpec {
    pub axis: String,
    pub baseline: String,
    /// The metrics that get a ratio grid; empty = every metric.
    #[serde(default)]
    pub metrics: Vec<String>,
}

/// One column of a table laid out like the paper's: a label for each column axis, and the
/// header to print (default: the labels joined by ` · `).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ColumnSpec {
    pub header: Option<String>,
    pub scene: Option<String>,
    pub technique: Option<String>,
    pub photons: Option<u32>,
    pub lights: Option<u32>,
    pub resolution: Option<String>,
    pub lighting: Option<String>,
    pub metric: Option<String>,
}

/// How many frames a cell renders: `warmup` unrecorded, then measured frames until there are at
/// least `min` and they took at least `budget_s` seconds, but never more than `max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FramePlan {
    pub warmup: u32,
    pub min: u32,
    pub budget_s: f64,
    pub max: u32,
}

impl FramePlan {
    /// Is a cell that has measured `frames` frames in `elapsed_s` seconds done?
    pub fn done(&self, frames: u32, elapsed_s: f64) -> bool {
        frames >= self.max || (frames >= self.min && elapsed_s >= self.budget_s)
    }
}

impl Config {
    /// Technique entry `t`'s settings as the config gives them: the defaults, then `[caustics]`,
    /// then the entry (the scene's own `[caustics]` comes in only when a cell runs).
    pub fn technique_settings(&self, t: usize) -> caustics::scene::CausticSettings {
        let mut s = caustics::scene::CausticSettings::default();
        self.caustics.apply(&mut s);
        self.techniques[t].settings.apply(&mut s);
        s
    }

    /// Whether technique entry `t` can run at `photons` per side, by the renderer's own rule
    /// (`CausticSettings::most_photons`: 16384 for `adaptive` under a memory limit, else 4096).
    /// A cell that cannot is not run, and its table entry reads N/A (Wyman & Nichols 2009
    /// Table 1: "previous techniques could not handle more than 4096² photons").
    pub fn runs(&self, t: usize, photons: u32) -> bool {
        photons <= self.technique_settings(t).most_photons()
    }

    /// The kind of the `[[metric]]` labelled `label`.
    pub fn metric_kind(&self, label: &str) -> Option<&str> {
        self.metrics.iter().find(|m| m.label == label).map(|m| m.kind.as_str())
    }

    /// Whether the per-pass frames submit every pass alone to time it on the host: a
    /// `pass_host_ms` or `pass_host_mphotons` metric asks for it.
    pub fn host_pass_times(&self) -> bool {
        self.metrics.iter().any(|m| {
            matches!(m.kind.as_str(), "pass_host_ms" | "pass_host_mphotons")
                || (crate::progressive::is_progressive_metric(&m.kind) && !m.passes.is_empty())
        })
    }

    /// The frames of every cell: `[run]`, or `[quick]` under `--quick`.
    pub fn frame_plan(&self, quick: bool) -> FramePlan {
        let r = &self.run;
        if quick {
            let q = &self.quick;
            let max = q.measured_frames.max(q.max_frames.unwrap_or(q.measured_frames));
            FramePlan { warmup: q.warmup_frames, min: q.measured_frames, budget_s: q.time_budget_s, max }
        } else {
            let max = r.max_frames.unwrap_or(DEFAULT_MAX_FRAMES.max(r.measured_frames));
            FramePlan { warmup: r.warmup_frames, min: r.measured_frames, budget_s: r.time_budget_s, max }
        }
    }
}

/// Overrides for `--quick` (smoke tests: few frames, small sizes).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct QuickSpec {
    #[serde(default = "quick_photons")]
    pub photons: Vec<u32>,
    #[serde(default)]
    pub warmup_frames: u32,
    #[serde(default = "quick_measured")]
    pub measured_frames: u32,
    /// Default 0: a quick cell measures exactly `measured_frames`.
    #[serde(default)]
    pub time_budget_s: f64,
    #[serde(default)]
    pub max_frames: Option<u32>,
    #[serde(default = "quick_resolution")]
    pub resolution: Vec<[u32; 2]>,
    #[serde(default = "quick_caustic_map")]
    pub caustic_map_resolution: u32,
    #[serde(default = "quick_reference")]
    pub reference_photons: u64,
    /// The scenes a quick run uses, some of `matrix.scenes` (default: all of them): a config
    /// whose scenes repeat one costly mesh can smoke-test its techniques on fewer.
    #[serde(default)]
    pub scenes: Option<Vec<String>>,
}

fn quick_photons() -> Vec<u32> {
    vec![64, 128]
}
fn quick_measured() -> u32 {
    2
}
fn quick_resolution() -> Vec<[u32; 2]> {
    vec![[128, 128]]
}
fn quick_caustic_map() -> u32 {
    256
}
fn quick_reference() -> u64 {
    1 << 16
}

impl Default for QuickSpec {
    fn default() -> Self {
        QuickSpec {
            photons: quick_photons(),
            warmup_frames: 0,
            measured_frames: quick_measured(),
            time_budget_s: 0.0,
            max_frames: None,
            resolution: quick_resolution(),
            caustic_map_resolution: quick_caustic_map(),
            reference_photons: quick_reference(),
            scenes: None,
        }
    }
}

/// The CPU reference that `rel_rmse` and `flux_ratio` compare against.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct QualitySpec {
    /// Photon samples per light.
    #[serde(default = "reference_photons")]
    pub reference_photons: u64,
    #[serde(default = "one")]
    pub seed: u64,
    /// The refinement level of the reference final image that `flip` compares against
    /// (`causticlab reference --final --level`), 0..=4.
    #[serde(default = "final_level")]
    pub final_level: u32,
}

fn final_level() -> u32 {
    caustics::final_reference::TABLE_LEVEL
}

fn reference_photons() -> u64 {
    1 << 22
}
fn one() -> u64 {
    1
}

impl Default for QualitySpec {
    fn default() -> Self {
        QualitySpec { reference_photons: reference_photons(), seed: one(), final_level: final_level() }
    }
}

/// Published values: axes fixed by name (those with one value may be left out), `values`
/// keyed by the labels of the innermost column axis.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PaperEntry {
    pub scene: Option<String>,
    pub technique: Option<String>,
    pub photons: Option<u32>,
    pub lights: Option<u32>,
    pub resolution: Option<String>,
    pub lighting: Option<String>,
    pub metric: Option<String>,
    pub values: BTreeMap<String, f64>,
    /// The scene the paper measured these on, when it is not ours (e.g. `"Buddha"`): the cell
    /// reads `ours (paper, Buddha)` and no ratio against the paper is printed for it.
    pub scene_note: Option<String>,
    /// Why these values measure different work than our cell: the cell is marked, the reason
    /// listed under the table, and no ratio against the paper is printed for it.
    pub not_comparable: Option<String>,
    /// Where in the paper the values are: `Table 3, row 2048²`, `Sec. 5.2, paragraph 'words'`
    /// or `read from Fig. 8` (grammar: [`crate::paper::citations`]). Required by the config's
    /// validation, not by parsing: the configs embedded in tables measured before it existed
    /// still parse. A citation, not a measurement: `bench explain` ignores it.
    pub source: Option<String>,
}

/// A config as read from its file, with the file's path, name and a hash of its bytes.
#[derive(Debug, Clone)]
pub struct LoadedConfig {
    pub path: PathBuf,
    /// File stem: the output files' names.
    pub name: String,
    /// FNV-1a 64 of the file's bytes, hex.
    pub hash: String,
    /// The file's text as loaded (what the hash covers; embedded in the results).
    pub text: String,
    pub config: Config,
}

pub fn fnv1a(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

impl LoadedConfig {
    /// A scene path of the matrix, resolved against the config's folder.
    pub fn scene_path(&self, scene: &str) -> PathBuf {
        self.path.parent().unwrap_or(Path::new(".")).join(scene)
    }
}
