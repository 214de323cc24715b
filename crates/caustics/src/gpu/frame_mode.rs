//! The two frame modes (`--frame-mode`, a bench metric's `mode`):
//! - **per-pass**: one-shot frames (`vkcore::Context::frame`), each with its own command
//!   buffer, queries, crash marker and fence, a timestamp pair and a crash-marker barrier around
//!   every pass, waited for before the next: per-pass GPU times for stage tables.
//! - **throughput**: a ring of persistent frame slots (`vkcore::FrameRing`), 2 frames in flight
//!   by default, uniforms written into per-slot buffers, moved meshes (and a pool's CPU-path
//!   fields) copied from per-slot staging buffers inside the frame, one timestamp pair per
//!   frame and no per-pass barrier: what a real-time application pays per frame.
//!
//! Both render the same images (tested); `super::frames` records and submits both.

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrameMode {
    #[default]
    PerPass,
    Throughput {
        /// Frames in flight.
        slots: usize,
    },
}

impl FrameMode {
    /// Frames in flight by default in the throughput mode.
    pub const SLOTS: usize = 2;

    pub fn throughput() -> FrameMode {
        FrameMode::Throughput { slots: Self::SLOTS }
    }

    /// `per-pass` or `throughput` (as in `timings.json` and the bench tables).
    pub fn name(&self) -> &'static str {
        match self {
            FrameMode::PerPass => "per-pass",
            FrameMode::Throughput { .. } => "throughput",
        }
    }

    pub fn parse(s: &str) -> Option<FrameMode> {
        match s {
            "per-pass" => Some(FrameMode::PerPass),
            "throughput" => Some(FrameMode::throughput()),
            _ => None,
        }
    }
}

impl std::fmt::Display for FrameMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What one frame does.
#[derive(Debug, Clone, Copy, Default)]
pub struct FrameStep {
    /// Keep the previous frame's photon buffer (static lighting); ignored on the first frame,
    /// after a pose moved the lights or meshes, and with more than one light.
    pub reuse_photons: bool,
    /// Pipeline-statistics queries around every pass (where the device has them).
    pub pipeline_statistics: bool,
    /// Per-pass frames: submit and wait after every pass, timing each on the host
    /// (`vkcore::FrameOptions::host_pass_times`); ignored by throughput frames.
    pub host_pass_times: bool,
}
