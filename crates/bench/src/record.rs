//! `timings.json`: which device and code path produced the numbers, then per-pass median/min/max
//! with every raw sample (and pipeline statistics where the device has them).

use caustics::scene::CausticSettings;
use serde::{Deserialize, Serialize};
use std::path::Path;
use vkcore::{DeviceInfo, FrameReport, PipelineStats, Profiler};

#[derive(Debug, Serialize)]
pub struct Timings {
    pub causticlab_version: &'static str,
    /// The commit the binary was built from (`bench::meta::commit`, `-dirty` where tracked code
    /// differed), as the EXR headers and the bench's tables name it.
    pub commit: String,
    pub device: Device,
    pub technique: String,
    /// The caustic technique's full configuration (the code path the numbers belong to).
    pub caustics: CausticSettings,
    /// The ray/receiver intersection in effect (`caustics.intersect` or the technique's own).
    pub intersect: String,
    /// Photons emitted per frame over all lights (0 for `none`).
    pub photons_emitted: u64,
    pub scene: String,
    /// `per-pass` (one-shot frames, timestamps around every pass) or `throughput` (a ring of
    /// frames in flight, one timestamp pair per frame): `caustics::gpu::frame_mode`.
    pub frame_mode: String,
    pub frames: usize,
    pub validation: bool,
    /// Passes in first-seen order; times are GPU milliseconds between the pass's timestamps
    /// (per-pass frames; throughput frames time only the whole frame, see `per_frame`).
    pub passes: Vec<Pass>,
    /// Each frame: its GPU time where it was timed as a whole, and what recording and
    /// submitting it asked of the driver.
    pub per_frame: Vec<FrameEntry>,
    /// Per-pass frames: each frame's host wall time in ms, recording, submitting and waiting
    /// for it (`render` sets them). The passes' timestamps need not add up to it: see
    /// `docs/command_line.md`, "What render's pass table does not time".
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub host_frame_ms: Vec<f64>,
    /// The last frame's photon counts, read back from the GPU (`render` sets them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counts: Option<caustics::render::Counts>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FrameEntry {
    pub index: u64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slot: Option<usize>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gpu_frame_ms: Option<f64>,
    pub passes: usize,
    pub submits: u64,
    pub barriers: u64,
    pub timestamps: u64,
    /// Vulkan objects created or allocated (zero for a warm throughput frame).
    pub objects: u64,
}

#[derive(Debug, Serialize)]
pub struct Device {
    pub name: String,
    pub device_type: String,
    pub driver_name: String,
    pub driver_info: String,
    pub vulkan_version: String,
    pub timestamp_valid_bits: u32,
    pub timestamp_period_ns: f32,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Pass {
    pub name: String,
    pub median_ms: f64,
    pub min_ms: f64,
    pub max_ms: f64,
    pub samples_ms: Vec<f64>,
    /// Pipeline-statistics counters of this pass in the last frame that had them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pipeline_stats: Option<Stats>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    pub input_vertices: u64,
    pub input_primitives: u64,
    pub vertex_invocations: u64,
    pub geometry_invocations: u64,
    pub geometry_primitives: u64,
    pub clipping_invocations: u64,
    pub clipping_primitives: u64,
    pub fragment_invocations: u64,
    pub compute_invocations: u64,
}

impl From<PipelineStats> for Stats {
    fn from(s: PipelineStats) -> Stats {
        Stats {
            input_vertices: s.input_vertices,
            input_primitives: s.input_primitives,
            vertex_invocations: s.vertex_invocations,
            geometry_invocations: s.geometry_invocations,
            geometry_primitives: s.geometry_primitives,
            clipping_invocations: s.clipping_invocations,
            clipping_primitives: s.clipping_primitives,
            fragment_invocations: s.fragment_invocations,
            compute_invocations: s.compute_invocations,
        }
    }
}

impl Timings {
    pub fn new(
        info: &DeviceInfo,
        caustics: &CausticSettings,
        photons_emitted: u64,
        scene: &Path,
        validation: bool,
        frame_mode: &str,
        frames: &[FrameReport],
    ) -> Timings {
        let last_stats = |name: &str| frames.iter().rev().find_map(|f| f.pass(name).and_then(|p| p.stats));
        let passes = pass_summaries(frames, last_stats);
        Timings {
            causticlab_version: env!("CARGO_PKG_VERSION"),
            commit: crate::meta::commit(),
            device: Device {
                name: info.name.clone(),
                device_type: info.device_type.clone(),
                driver_name: info.driver_name.clone(),
                driver_info: info.driver_info.clone(),
                vulkan_version: info.api_version.clone(),
                timestamp_valid_bits: info.timestamp_valid_bits,
                timestamp_period_ns: info.timestamp_period_ns,
            },
            technique: caustics.technique.to_string(),
            caustics: caustics.clone(),
            intersect: caustics.intersect().to_string(),
            photons_emitted,
            scene: scene.display().to_string(),
            frame_mode: frame_mode.to_string(),
            frames: frames.len(),
            validation,
            passes,
            per_frame: frames
                .iter()
                .enumerate()
                .map(|(i, f)| FrameEntry {
                    index: if f.slot.is_some() { f.index } else { i as u64 },
                    slot: f.slot,
                    gpu_frame_ms: f.frame_gpu_ms,
                    passes: f.passes.len(),
                    submits: f.counters.submits,
                    barriers: f.counters.barriers,
                    timestamps: f.counters.timestamps,
                    objects: f.counters.objects,
                })
                .collect(),
            host_frame_ms: vec![],
            counts: None,
        }
    }
}

/// Per-pass median/min/max GPU times over `frames` with every raw sample, in first-seen order;
/// `stats` gives a pass's pipeline statistics (from whichever frame the caller trusts).
pub fn pass_summaries(frames: &[FrameReport], stats: impl Fn(&str) -> Option<PipelineStats>) -> Vec<Pass> {
    let mut profiler = Profiler::default();
    for f in frames {
        profiler.record(f);
    }
    profiler
        .summary()
        .into_iter()
        .map(|s| Pass {
            pipeline_stats: stats(&s.name).map(Stats::from),
            name: s.name,
            median_ms: s.median_ms,
            min_ms: s.min_ms,
            max_ms: s.max_ms,
            samples_ms: s.samples_ms,
        })
        .collect()
}
