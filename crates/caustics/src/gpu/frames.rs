//! One submit and finish path for every renderer (issue 50, item 4): a renderer says what it
//! records into a frame ([`RecordFrame`]); [`Frames`] records it into a one-shot frame or into
//! the next slot of a ring (`super::frame_mode`), submits it and returns the reports. The mesh
//! renderer (`crate::render`) and Trendall & Stewart 2000's pool renderer both go through here,
//! and `crate::render::Renderer` drives either as a [`FrameRenderer`].

use super::frame_mode::{FrameMode, FrameStep};
use crate::dump::Dump;
use crate::image_io::ImageF32;
use crate::scene::Scene;
use anyhow::{Context as _, Result};
use vkcore::{Context, Frame, FrameOptions, FrameReport, FrameRing, ImageView, PassTiming, RingOptions, Timing};

/// The end-of-frame hook of [`RecordFrame::submit_with`]: records more passes (the viewer's
/// display pass), given the frame and its final image.
pub type After<'a> = &'a mut dyn FnMut(&mut Frame, &ImageView) -> Result<()>;

/// A throughput frame's place in the ring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Slot {
    pub index: usize,
    /// The ring's slots (a renderer makes each slot's buffers at once, so a warm frame makes none).
    pub count: usize,
}

/// A renderer's frames: one-shot (per-pass frames: no ring) or a ring of frames in flight.
#[derive(Default)]
pub struct Frames {
    ring: Option<FrameRing>,
}

impl Frames {
    /// `pass_timestamps`: with the throughput mode, a timestamp pair around every pass (the
    /// viewer's per-pass graph), else one around the frame.
    pub fn new(ctx: &Context, mode: FrameMode, pass_timestamps: bool) -> Result<Frames> {
        let ring = match mode {
            FrameMode::PerPass => None,
            FrameMode::Throughput { slots } => {
                let timing = if pass_timestamps { Timing::PerPass } else { Timing::PerFrame };
                Some(FrameRing::new(ctx, RingOptions { slots, timing, fence_timeout: None })?)
            }
        };
        Ok(Frames { ring })
    }

    fn frame(&mut self, r: &mut dyn RecordFrame, step: FrameStep) -> Result<FrameReport> {
        if self.ring.is_some() {
            self.submit_with(r, step, &mut |_, _| Ok(()))?;
            return self.finish()?.pop().context("the ring returned no report for its frame");
        }
        let host = r.host_passes()?;
        let mut f = r.ctx().frame(FrameOptions {
            timestamps: true,
            pipeline_statistics: step.pipeline_statistics,
            host_pass_times: step.host_pass_times && r.host_pass_times(),
            ..Default::default()
        })?;
        r.record(&mut f, None, step)?;
        let mut report = f.submit()?;
        r.submitted();
        report.passes.splice(0..0, host);
        Ok(report)
    }

    fn submit_with(&mut self, r: &mut dyn RecordFrame, step: FrameStep, after: After) -> Result<Vec<FrameReport>> {
        let ring = self.ring.as_mut().context("submit: this renderer draws one-shot frames (FrameMode::PerPass)")?;
        let slot = Slot { index: ring.slot(), count: ring.slots() };
        // The slot's previous frame is waited for here, before the slot's buffers are written.
        let mut f = ring.frame()?;
        r.record(&mut f, Some(slot), step)?;
        after(&mut f, r.final_view())?;
        ring.submit(f)?;
        r.submitted();
        Ok(ring.reports())
    }

    fn finish(&mut self) -> Result<Vec<FrameReport>> {
        match self.ring.as_mut() {
            Some(ring) => Ok(ring.finish()?),
            None => Ok(vec![]),
        }
    }
}

/// What a renderer records into each of its frames; [`frame`], [`submit_with`] and
/// [`finish`] submit them.
pub trait RecordFrame {
    fn ctx(&self) -> &Context;
    fn frames(&mut self) -> &mut Frames;
    /// Records one frame: `slot` is the ring slot it goes into (throughput frames: the slot's
    /// previous frame has finished), None for a one-shot frame.
    fn record(&mut self, f: &mut Frame, slot: Option<Slot>, step: FrameStep) -> Result<()>;
    /// The final image on the GPU (linear radiance, RGBA 32-bit float, row 0 at the top).
    fn final_view(&self) -> &ImageView;
    /// Work done on the host before a one-shot frame, timed: put before its passes.
    fn host_passes(&mut self) -> Result<Vec<PassTiming>> {
        Ok(vec![])
    }
    /// Called once a frame is submitted.
    fn submitted(&mut self) {}
    /// Whether its one-shot frames may submit every pass alone to time it on the host
    /// (`FrameStep::host_pass_times`).
    fn host_pass_times(&self) -> bool {
        true
    }
}

/// Records, submits and waits for one frame of `r`; returns its per-pass timings (one-shot
/// frames) or its frame time (a throughput frame, waited for alone).
pub fn frame(r: &mut dyn RecordFrame, step: FrameStep) -> Result<FrameReport> {
    let mut frames = std::mem::take(r.frames());
    let report = frames.frame(r, step);
    *r.frames() = frames;
    report
}

/// Throughput frames: records `r`'s next frame into its ring slot, then `after`, and submits it
/// without waiting; returns the reports of frames that finished meanwhile.
pub fn submit_with(r: &mut dyn RecordFrame, step: FrameStep, after: After) -> Result<Vec<FrameReport>> {
    let mut frames = std::mem::take(r.frames());
    let reports = frames.submit_with(r, step, after);
    *r.frames() = frames;
    reports
}

/// Waits for every throughput frame of `r` in flight; returns the reports not yet returned.
pub fn finish(r: &mut dyn RecordFrame) -> Result<Vec<FrameReport>> {
    r.frames().finish()
}

/// A renderer as `crate::render::Renderer` drives it: the mesh renderer, or a technique's own
/// (Trendall & Stewart 2000's pool, made by `crate::techniques::own_renderer`); its frames go
/// through [`frame`], [`submit_with`] and [`finish`].
pub trait FrameRenderer: RecordFrame {
    /// Moves to `scene`, a pose of the scene this renderer was made for (`crate::animation`).
    fn set_pose(&mut self, scene: &Scene) -> Result<()>;
    /// The last frame's linear radiance.
    fn final_image(&self) -> Result<ImageF32>;
    /// The buffers `wanted` of the last frame that this render has, each with its image.
    fn dumps(&mut self, wanted: &[&'static Dump]) -> Result<Vec<(&'static Dump, ImageF32)>>;
    /// The scene as this renderer was made for it (its pose may have moved since).
    fn scene(&self) -> &Scene;
    /// The declaration of this render's receiver map.
    fn receiver(&self) -> &'static Dump;
}
