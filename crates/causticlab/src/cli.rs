//! The command line: global device options and one subcommand per job.

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

#[derive(Debug, Parser)]
#[command(
    name = "causticlab",
    version,
    about = "Raw-Vulkan caustics research renderer",
    after_help = "Exit codes: 0 ok, 1 failure, 2 input error, 3 validation messages under --validate, 141 \
                  stdout closed by its reader (| head); diff: 0 same, 1 different, 2 cannot compare."
)]
pub struct Cli {
    #[command(flatten)]
    pub global: GlobalOpts,
    #[command(subcommand)]
    pub command: Command,
}

/// Options every subcommand accepts, before or after the subcommand name.
#[derive(Debug, Args, Clone, Default)]
pub struct GlobalOpts {
    /// Device to use: an index from `causticlab devices`, or a case-insensitive substring of its
    /// name or driver (`llvmpipe`, `Mesa 25`).
    #[arg(long, global = true, value_name = "INDEX|NAME", help_heading = "Device")]
    pub device: Option<String>,
    /// Enable Khronos validation with synchronization validation, print every message and exit
    /// with code 3 if any warning or error was reported.
    #[arg(long, global = true, help_heading = "Device")]
    pub validate: bool,
    /// Pretend the device lacks this feature (repeatable); names as in `causticlab devices`.
    #[arg(long = "without-feature", global = true, value_name = "NAME", help_heading = "Device",
          value_parser = clap::builder::PossibleValuesParser::new(vkcore::Feature::ALL.iter().map(|f| f.name())))]
    pub without_feature: Vec<String>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// List every Vulkan device with its features and limits.
    Devices,
    /// Render a scene and write final.exr, final.png, timings.json and the requested dumps.
    Render(RenderArgs),
    /// Trace the exact CPU photon reference of a scene's receiver map into DIR/receiver.exr; for
    /// a pool scene, evaluate passes 1-6 in f64 (or Eq. 2 itself with --direct); with --final,
    /// render the reference final image (the eye's frame, exact GPU photons) into DIR/final.exr.
    Reference(ReferenceArgs),
    /// Compare two receiver maps or two final images (B is the reference): errors, peak, flux,
    /// HDR-FLIP; writes an error image and the FLIP error image beside it.
    Compare(CompareArgs),
    /// Compare two renders texel by texel: two EXR files, or two `render --out` folders (every
    /// dump, final.exr, and the pass names and photon counts in timings.json). Exit 0 when
    /// everything is the same, 1 when anything differs, 2 when they cannot be compared.
    Diff(DiffArgs),
    /// Regenerate a paper's table from a bench config (bench_configs/*.toml), or merge shards.
    Bench(BenchArgs),
    /// Open a window on a scene: the technique renders continuously, with a panel of its
    /// settings, A/B and split view, camera and light controls, per-pass GPU timings, keys to
    /// save and dump the frame, and shader hot reload (docs/viewer.md).
    View(ViewArgs),
    /// Render many animated throughput frames and sample resident memory, device memory and
    /// Vulkan objects made: a real-time loop holds them flat (scripts/soak.sh).
    Soak(SoakArgs),
    /// The registry of variants: every technique variant the project stands behind, with its
    /// paper, section, stated accuracy and flags (crates/caustics/src/techniques/variants.toml).
    Variants(VariantsArgs),
    /// Every intermediate buffer `--dump` can write, as its owner declares it: owner, space,
    /// format, the techniques that have it, its layers and channels (a Markdown table; the same
    /// as docs/dumps.md's "Every dump").
    Dumps,
}

#[derive(Debug, Args)]
pub struct VariantsArgs {
    /// One line per row, `name|label|scenes|flags|needs`, for scripts (default: a Markdown table).
    #[arg(long)]
    pub lines: bool,
    /// Only the rows in the quality tables (scripts/quality_table.sh).
    #[arg(long)]
    pub quality: bool,
}

#[derive(Debug, Args)]
pub struct SoakArgs {
    /// Scene file (TOML, see scenes/README.md).
    #[arg(long)]
    pub scene: PathBuf,
    #[command(flatten)]
    pub caustics: caustics::scene::CausticOverrides,
    /// The eye's width and height in pixels (default: the scene's camera).
    #[arg(long, value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub size: Option<u32>,
    /// Frames to render.
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..=10_000_000))]
    pub frames: u32,
    /// Sample every N frames.
    #[arg(long, default_value_t = 500, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub every: u32,
    /// Frames per loop of the light, camera and object orbits.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub period: u32,
    /// Judge flatness from this frame on (the warm-up before it may grow).
    #[arg(long, default_value_t = 1000)]
    pub after: u32,
    /// Write the samples as CSV here.
    #[arg(long)]
    pub csv: Option<PathBuf>,
}

#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub merge: Option<BenchCommand>,
    /// The bench config (format: bench_configs/README.md).
    #[arg(required = true)]
    pub config: Option<PathBuf>,
    /// Smoke test: the config's [quick] sizes and frame counts; tables go to <results>/<device>/quick/.
    #[arg(long)]
    pub quick: bool,
    /// Run only the cells matching axis=value[,axis=value...] (e.g. photons=256,technique=points);
    /// writes a part for `bench merge` and prints the partial table.
    #[arg(long, value_name = "AXIS=VALUE,...")]
    pub filter: Option<String>,
    /// Run every n-th cell starting at the i-th (1-based) of the matrix; merge the parts with
    /// `causticlab bench merge`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Results folder; tables go to <results>/<device-slug>/ (driver, device and driver version).
    #[arg(long, default_value = "results")]
    pub results: PathBuf,
    /// Write into a results folder inside the repository even though the work tree has
    /// uncommitted changes (the tables record the commit as `<hash>-dirty`).
    #[arg(long)]
    pub allow_dirty: bool,
    /// Cap each cell's time budget at SECONDS (the config's `[run].time_budget_s` when lower);
    /// the frame counts still apply, and the tables record the budget used. For a run that must
    /// fit a fixed amount of device time (`scripts/gpu_suite.sh`).
    #[arg(long, value_name = "SECONDS", value_parser = parse_budget)]
    pub max_time_budget: Option<f64>,
    /// A timing cell that ran while other processes used more than this many cores (from
    /// /proc/stat, less this process) is measured again after a pause, then marked busy (`~`).
    #[arg(long, value_name = "CORES", default_value_t = 0.1, value_parser = parse_cores)]
    pub busy_cores: f64,
    /// How many times a busy cell is measured again before it is marked busy.
    #[arg(long, value_name = "N", default_value_t = 2, value_parser = clap::value_parser!(u32).range(0..=10))]
    pub busy_retries: u32,
    /// How many times a timing cell whose spread is over 10% (`!`) is measured again (after a
    /// short pause); the attempt with the smallest spread is kept and every attempt's spread is
    /// recorded (`spread_attempts` in the JSON).
    #[arg(long, value_name = "N", default_value_t = 2, value_parser = clap::value_parser!(u32).range(0..=10))]
    pub spread_retries: u32,
    /// Write a table with busy cells into the repository's results/ anyway (it is refused:
    /// committed tables come from a quiet machine).
    #[arg(long)]
    pub allow_busy: bool,
    /// Run into a device folder of the repository's results/ whose other tables another CPU
    /// measured (it is refused: a folder's tables compare only if one CPU measured them all).
    #[arg(long)]
    pub allow_other_cpu: bool,
}

fn parse_cores(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && (0.0..=1024.0).contains(&v) => Ok(v),
        _ => Err(format!("`{s}`: cores from 0 to 1024")),
    }
}

fn parse_threads(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(v) if v <= 1024 => Ok(v),
        _ => Err(format!("`{s}`: a thread count from 0 (all cores) to 1024")),
    }
}

fn parse_budget(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && (0.0..=3600.0).contains(&v) => Ok(v),
        _ => Err(format!("`{s}`: seconds from 0 to 3600")),
    }
}

#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Merge the parts of a sharded or filtered sweep into the full table.
    Merge(MergeArgs),
    /// Read a written table again with its config as it is now: judge it with the config's
    /// rules and `[[plausibility.explained]]` entries, and write its text, layout and `[front]`
    /// again (nothing is timed; the config may differ only in what measures nothing: its text,
    /// layout, paper sources, judging and front).
    Explain(ExplainArgs),
    /// Recompute every number the README, docs/ and results/ pages quote from the committed
    /// tables (their `<!--= ... -->` claims), and find measured-looking numbers without one
    /// (docs/claims.md). Fails naming the page, the line, the number written and the number
    /// computed.
    Claims(ClaimsArgs),
    /// Compare two results of one config (results/<device>/<config>.json.gz) cell by cell in
    /// everything but the timings: the same cells, the same counts, and the same errors and FLIP
    /// values within --tolerance. Names every difference and exits 1 if there is one (a sharded
    /// and merged sweep against an unsharded run: scripts/cluster/slurm_check.sh).
    Same(SameArgs),
    /// Rebuild the results folder's index (<results>/README.md: every table with its device,
    /// date, commit, and whether its config file today still describes its run); with --check,
    /// write nothing and fail naming each line that is out of date.
    Index(IndexArgs),
}

#[derive(Debug, Args)]
pub struct IndexArgs {
    /// Results folder: the index is <results>/README.md.
    #[arg(long, default_value = "results")]
    pub results: PathBuf,
    /// Compare the written index with what it would be now, and exit 1 if they differ.
    #[arg(long)]
    pub check: bool,
}

#[derive(Debug, Args)]
pub struct SameArgs {
    /// The first result's JSON.
    pub first: PathBuf,
    /// The second result's JSON.
    pub second: PathBuf,
    /// Relative tolerance for errors, ratios and FLIP (counts are compared exactly).
    #[arg(long, default_value_t = 1e-5, value_parser = parse_tolerance)]
    pub tolerance: f64,
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && (0.0..1.0).contains(&v) => Ok(v),
        _ => Err(format!("`{s}`: a relative tolerance from 0 to below 1")),
    }
}

#[derive(Debug, Args)]
pub struct ClaimsArgs {
    /// Pages to check (default: README.md, docs/ and results/ under --root, less the tables the
    /// bench writes).
    pub pages: Vec<PathBuf>,
    /// The repository root: the folder the pages' `<!--claims results/<device>/ -->` paths are
    /// relative to.
    #[arg(long, default_value = ".")]
    pub root: PathBuf,
    /// Print every entry of this table (results/<device>/<config>.json.gz, or a script's data
    /// file, FILE.csv) with the pick that selects it, instead of checking pages.
    #[arg(long, value_name = "TABLE.json.gz|FILE.csv")]
    pub list: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct ExplainArgs {
    /// The bench config (bench_configs/*.toml) as it is now: the same as the table's in what
    /// it measures.
    pub config: PathBuf,
    /// The table's JSON (results/<device>/<config>.json.gz).
    pub table: PathBuf,
    /// Results folder; the table goes to <results>/<device-slug>/.
    #[arg(long, default_value = "results")]
    pub results: PathBuf,
    /// Write into the repository's results/ from a work tree with uncommitted changes (the
    /// table then names a `-dirty` commit).
    #[arg(long)]
    pub allow_dirty: bool,
}

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Part files (<results>/<device>/parts/<config>.shard-I-of-N.json).
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// Results folder; the table goes to <results>/<device-slug>/.
    #[arg(long, default_value = "results")]
    pub results: PathBuf,
    /// Allow cells that no part has (a suite cut off by its time budget): the table marks them
    /// `not run` and says how many, instead of failing.
    #[arg(long)]
    pub partial: bool,
}

#[derive(Debug, Args)]
pub struct ReferenceArgs {
    /// Scene file with a [receiver_map].
    #[arg(long)]
    pub scene: PathBuf,
    /// Photons per light (default 4194304, 2^22). The photon options (this to
    /// --facet-normals) are refused on a pool scene, whose reference traces no photons.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=(1u64 << 36)))]
    pub photons: Option<u64>,
    /// Random seed (default 1; the result is deterministic for a seed, whatever the thread count).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Exact Fresnel and internal bounces (true), or what image-space techniques approximate:
    /// two refractions, all power transmitted (false). Default: the scene's `caustics.fresnel`.
    #[arg(long)]
    pub fresnel: Option<bool>,
    /// Most specular interactions per photon (with --fresnel true; default 8).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub max_bounces: Option<u32>,
    /// With --fresnel true: trace the light a refractive object reflects off its outside (true),
    /// or leave it out (false), keeping only the light that enters the object, the only light
    /// the image-space techniques draw. Default true.
    #[arg(long, action = clap::ArgAction::Set)]
    pub outside_reflection: Option<bool>,
    /// Worker threads (0, the default: all cores), at most 1024.
    #[arg(long, value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Scatter about the facets' geometric normals instead of the interpolated vertex normals
    /// (the smooth surface the mesh stands for, as the renderer shades it).
    #[arg(long)]
    pub facet_normals: bool,
    /// Pool scenes: evaluate Eq. 2 directly (the Gaussian lobe, P from the surface point) instead
    /// of the f64 convolution passes (Trendall & Stewart 2000).
    #[arg(long)]
    pub direct: bool,
    /// Pool scenes: the grid side (default: the scene's `caustics.photons`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(64..=4096))]
    pub grid: Option<u32>,
    /// Pool scenes: the Pass 6 kernel side, odd (default: the scene's `caustics.kernel`).
    #[arg(long)]
    pub kernel: Option<u32>,
    /// Render the reference final image instead of the receiver map: the eye's frame as every
    /// technique renders it, its caustic map filled by exact photons traced on the GPU
    /// (photon-trace) at refinement --level; writes final.exr, final.png and reference.json
    /// (docs/flip.md). Needs a Vulkan device; --seed, --fresnel, --max-bounces and
    /// --outside-reflection apply.
    #[arg(long = "final", conflicts_with_all = ["photons", "threads", "facet_normals", "direct", "grid", "kernel"])]
    pub final_image: bool,
    /// With --final: the refinement, 0 to 4: a 256·2^L caustic map, 1024²·8^L photons per light
    /// (the default, 1, is the one every table's FLIP is against). Without a default here:
    /// clap drops `requires` when the arg it requires conflicts with one given (`--photons`), so
    /// `cmd_reference` refuses a --level without --final itself.
    #[arg(long, requires = "final_image",
          value_parser = clap::value_parser!(u32).range(0..=caustics::final_reference::MAX_LEVEL as i64))]
    pub level: Option<u32>,
    /// Output directory (receiver.exr, reference.json; with --final final.exr, final.png,
    /// reference.json).
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The map or image to judge (a technique's receiver.exr, or its final.exr).
    pub a: PathBuf,
    /// The reference (`causticlab reference`'s receiver.exr, or `reference --final`'s final.exr).
    pub b: PathBuf,
    /// Where to write the error image (default: no image): `.exr` for its layers (A, B,
    /// diff = A − B, in_region), `.png` for a picture of it (red: A too bright, blue: too dark,
    /// saturated at --error-scale; outside the region the reference in dim grey). The HDR-FLIP
    /// error image goes beside it: `x.png` gives `x.flip.png` (magma), `x.exr` `x.flip.exr`.
    #[arg(long)]
    pub error_image: Option<PathBuf>,
    /// The |A − B| (in E/E0) at which the PNG error image saturates (default: half the
    /// reference's peak over the region, at least 0.5).
    #[arg(long)]
    pub error_scale: Option<f32>,
    /// Print the figures as one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// The texels compared: `caustic` (where either map differs from 1 by more than 0.05) or
    /// `lit` (every texel with E0 > 0: Trendall & Stewart 2000's relative RMS error).
    #[arg(long, value_enum, default_value_t = caustics::compare::Region::Caustic)]
    pub region: caustics::compare::Region,
}

#[derive(Debug, Args)]
pub struct DiffArgs {
    /// An EXR file or a folder `causticlab render` wrote.
    pub a: PathBuf,
    /// The same of the run compared with (the recording).
    pub b: PathBuf,
    /// The largest difference allowed in a channel, relative to the channel's largest |B|
    /// (0: identical texels). Photon counts are always compared exactly.
    #[arg(long, default_value_t = 0.0)]
    pub tolerance: f64,
    /// Files (comma-separated stems, e.g. `splats,hierarchy_lists`) compared as unordered lists:
    /// each layer's texels sorted first, for the lists a compute path appends to with an atomic
    /// counter, in an order that changes from run to run.
    #[arg(long, value_delimiter = ',')]
    pub unordered: Vec<String>,
    /// Every list dump compared as an unordered list: the dumps declared as lists of records
    /// (`dump::Format::Records`: `splats`, `hierarchy_lists`, `adaptive_lists`), as `--unordered`
    /// would name them.
    #[arg(long)]
    pub unordered_records: bool,
    /// Files (comma-separated stems) not compared in folders, e.g. the batched compute
    /// traversal's `adaptive_lists`, whose split of the clusters into batches follows the
    /// append order.
    #[arg(long, value_delimiter = ',')]
    pub ignore: Vec<String>,
}

/// `view --pass-timing`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PassTiming {
    /// Every pass on a GPU, whole frames on a software device.
    Auto,
    /// A timestamp pair around every pass.
    Pass,
    /// A timestamp pair around each frame.
    Frame,
}

impl PassTiming {
    /// Whether to time every pass on a device that `is_software`.
    pub fn every_pass(self, is_software: bool) -> bool {
        match self {
            PassTiming::Auto => !is_software,
            PassTiming::Pass => true,
            PassTiming::Frame => false,
        }
    }
}

#[derive(Debug, Args)]
pub struct ViewArgs {
    /// Scene file (TOML, see scenes/README.md).
    #[arg(long, help_heading = "Scene")]
    pub scene: PathBuf,
    #[command(flatten)]
    pub caustics: caustics::scene::CausticOverrides,
    /// The window's (and the render's) size, N or WxH pixels (default: the scene's camera).
    #[arg(long, value_name = "N|WxH", help_heading = "Window")]
    pub size: Option<String>,
    /// A second technique for the A/B toggle (Tab) and split view (V), with the same settings
    /// where it has them.
    #[arg(long, value_name = "TECHNIQUE", help_heading = "Window")]
    pub compare: Option<caustics::techniques::Technique>,
    /// Wait for the display's refresh (off: the frame rate shown is the renderer's).
    #[arg(long, help_heading = "Window")]
    pub vsync: bool,
    /// Where the save key (S) writes final.png, final.exr and display.png, and the dump key (D)
    /// writes dumps/<buffer>.exr.
    #[arg(long, default_value = "view-out", help_heading = "Output")]
    pub out: PathBuf,
    /// The buffers the dump key writes: `all` or a comma-separated list (default: every buffer
    /// of the technique shown).
    #[arg(long, value_name = "all|NAME,...", help_heading = "Output")]
    pub dump: Option<String>,
    /// Timed actions, one a line: `<frame> key NAME|set KEY VALUE|screenshot DIR|dump DIR
    /// [NAMES]|resize W H|reload|await PATH|exit` (docs/viewer.md).
    #[arg(long, value_name = "FILE", help_heading = "Driving")]
    pub script: Option<PathBuf>,
    /// Exit after this many frames.
    #[arg(long, value_name = "N", help_heading = "Driving")]
    pub exit_after: Option<u32>,
    /// What the GPU timestamps bracket: every pass (the per-pass graph) or whole frames (as the
    /// bench's throughput frames). `auto`: every pass on a GPU, whole frames on a software
    /// device such as lavapipe, where each timestamp flushes the rasterizer and the per-pass
    /// frame ran longer (results/viewer_frame_time.md). T switches while running.
    #[arg(long, value_enum, default_value_t = PassTiming::Auto, help_heading = "Window")]
    pub pass_timing: PassTiming,
    /// Do not watch shaders_glsl/ for edits (R still reloads).
    #[arg(long, help_heading = "Driving")]
    pub no_hot_reload: bool,
}

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene file (TOML, see scenes/README.md).
    #[arg(long, help_heading = "Scene")]
    pub scene: PathBuf,
    #[command(flatten)]
    pub caustics: caustics::scene::CausticOverrides,
    /// Output directory; files appear only when the whole run succeeded.
    #[arg(long, help_heading = "Output")]
    pub out: PathBuf,
    /// Intermediate buffers to write as EXR (see docs/dumps.md): `all` or a comma-separated list.
    #[arg(long, value_name = "all|NAME,...", help_heading = "Output")]
    pub dump: Option<String>,
    /// Frames to render (timings are kept for each; the image is the last frame's).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=100_000), help_heading = "Output")]
    pub frames: u32,
    /// `per-pass`: one-shot frames with a timestamp pair around every pass; `throughput`: a ring
    /// of 2 frames in flight, timed per frame, creating nothing once warm (docs/bench.md).
    #[arg(long, default_value = "per-pass", value_parser = ["per-pass", "throughput"], help_heading = "Output")]
    pub frame_mode: String,
    /// Write the frame graph of the last frame: graph.txt (every pass in recording order with the
    /// resources it read and wrote, from vkcore's declarations; also printed) and graph.dot
    /// (Graphviz: `dot -Tpng graph.dot -o graph.png`).
    #[arg(long, help_heading = "Output")]
    pub graph: bool,
}

/// Writes the `render` flags that override the scene's `[caustics]` (`flags`) over `s`, the
/// caustic settings of the scene file `scene`, and checks the result.
pub fn apply_caustic_flags(
    flags: &caustics::scene::CausticOverrides,
    s: &mut caustics::scene::CausticSettings,
    scene: &std::path::Path,
) -> anyhow::Result<()> {
    flags.apply(s);
    s.validate("command line", "--")?;
    s.validate_combination(&format!("{} and the command line's flags", scene.display()), "caustics.")
}
