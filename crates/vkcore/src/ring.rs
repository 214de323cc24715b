//! The throughput frame mode: a ring of persistent frame slots, as a real-time application runs
//! its frames. Each slot keeps its command buffer (reset, not reallocated), its fence, its query
//! pools (sized to the passes its frames record, reset from the host) and its crash marker; a
//! frame is submitted without waiting, and the host waits for a slot's previous frame only when
//! it comes round again, so up to `slots` frames are in flight. There is no crash-marker barrier
//! after every pass: a frame writes its number into its slot's marker once, at its end, so a
//! timeout or a lost device still names the frame and the slot.
//!
//! Barriers between frames come from the shared tracker, as between passes: a frame's first use
//! of a resource waits for the last frame's use of it in submission order (one queue), so frames
//! in flight never race on the targets they share. What the host writes per frame (uniforms,
//! staging for moved meshes) must be per slot: see [`FrameRing::slot`].

use crate::context::Context;
use crate::error::{Result, VkError, VkResultExt};
use crate::frame::{read_report, Frame, FrameResources, RingTag};
use crate::profiler::FrameReport;
use ash::vk;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// How ring frames are timed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Timing {
    /// No timestamps.
    None,
    /// One timestamp pair around the whole frame (`FrameReport::frame_gpu_ms`).
    #[default]
    PerFrame,
    /// A pair around every pass (an interactive viewer's per-pass graph), still without the
    /// per-pass crash-marker barrier.
    PerPass,
}

#[derive(Debug, Clone, Copy)]
pub struct RingOptions {
    /// Frames in flight (at least 1).
    pub slots: usize,
    pub timing: Timing,
    /// How long the host waits for a slot's previous frame before it gives up with an error
    /// naming that frame and its slot; None: ten minutes.
    pub fence_timeout: Option<Duration>,
}

impl Default for RingOptions {
    fn default() -> Self {
        RingOptions { slots: 2, timing: Timing::PerFrame, fence_timeout: None }
    }
}

struct Pending {
    frame: u64,
    passes: Vec<String>,
    graph: Vec<crate::frame::PassNode>,
    counters: crate::Counters,
}

struct Slot {
    /// None while a frame of this slot is being recorded (the frame holds them).
    res: Option<FrameResources>,
    fence: vk::Fence,
    pending: Option<Pending>,
    /// Passes of the slot's last frame: the queries to reset before its next.
    last_passes: u32,
}

static NEXT_RING: AtomicU64 = AtomicU64::new(1);

pub struct FrameRing {
    ctx: Context,
    id: u64,
    slots: Vec<Slot>,
    opts: RingOptions,
    next_frame: u64,
    done: Vec<FrameReport>,
}

impl FrameRing {
    pub fn new(ctx: &Context, opts: RingOptions) -> Result<FrameRing> {
        if opts.slots == 0 {
            return Err(VkError::Invalid("a frame ring needs at least one slot".into()));
        }
        let mut ring = FrameRing {
            ctx: ctx.clone(),
            id: NEXT_RING.fetch_add(1, Ordering::Relaxed),
            slots: vec![],
            opts,
            next_frame: 0,
            done: vec![],
        };
        for _ in 0..opts.slots {
            let fence = unsafe { ctx.shared.raw().create_fence(&vk::FenceCreateInfo::default(), None) }
                .call("vkCreateFence")?;
            ctx.shared.counters.object(1);
            // Pushed at once so that Drop destroys it if a later slot fails.
            ring.slots.push(Slot { res: None, fence, pending: None, last_passes: 0 });
            let res = FrameResources::new(ctx, ring.timestamps(), false)?;
            if let Some(s) = ring.slots.last_mut() {
                s.res = Some(res);
            }
        }
        Ok(ring)
    }

    fn timestamps(&self) -> bool {
        self.opts.timing != Timing::None && self.ctx.info().has(crate::Feature::Timestamps)
    }

    /// Frames in flight.
    pub fn slots(&self) -> usize {
        self.slots.len()
    }

    /// The slot the next frame records into: index per-slot host data (uniforms, staging) by it.
    pub fn slot(&self) -> usize {
        (self.next_frame % self.slots.len() as u64) as usize
    }

    /// The number the next frame will have.
    pub fn next_frame(&self) -> u64 {
        self.next_frame
    }

    /// Waits for slot `s`'s frame in flight, if any, and keeps its report.
    fn retire(&mut self, s: usize) -> Result<()> {
        let timeout = self.opts.fence_timeout.unwrap_or(crate::frame::FENCE_TIMEOUT);
        let timeout = timeout.as_nanos().min(u64::MAX as u128) as u64;
        let d = self.ctx.shared.raw();
        let per_frame = self.opts.timing == Timing::PerFrame;
        let slot = &mut self.slots[s];
        let Some(p) = slot.pending.take() else { return Ok(()) };
        // The queries the frame used, to reset before the slot's next frame, whatever happens.
        slot.last_passes = if per_frame { 1 } else { p.passes.len() as u32 };
        if let Err(result) = unsafe { d.wait_for_fences(&[slot.fence], true, timeout) } {
            let finished = slot.res.as_ref().map(|r| r.marker.read()).filter(|&m| m > 0).map(|m| m as u64 - 1);
            // Let the GPU finish (or fail) before anything of the frame is reused or destroyed.
            let _ = unsafe { d.device_wait_idle() };
            let _ = unsafe { d.reset_fences(&[slot.fence]) };
            return Err(VkError::FrameFailed {
                result,
                last_finished: None,
                next: None,
                passes: p.passes,
                ring: Some((p.frame, s, finished)),
            });
        }
        unsafe { d.reset_fences(&[slot.fence]) }.call("vkResetFences")?;
        let res = slot.res.as_ref().ok_or_else(|| VkError::Invalid("ring slot lost its resources".into()))?;
        let mut report = read_report(&self.ctx, res, &p.passes, per_frame.then_some(()))?;
        report.index = p.frame;
        report.slot = Some(s);
        report.counters = p.counters;
        report.graph = p.graph;
        self.done.push(report);
        Ok(())
    }

    /// Starts the next frame in its slot: waits for the slot's previous frame (keeping its
    /// report for [`FrameRing::reports`]), then resets and begins the slot's command buffer.
    pub fn frame(&mut self) -> Result<Frame> {
        let s = self.slot();
        self.retire(s)?;
        let counters_at_begin = self.ctx.counters();
        let d = self.ctx.shared.raw();
        let res = match self.slots[s].res.take() {
            Some(r) => r,
            // A frame of this slot was dropped unsubmitted: it freed the slot's resources.
            None => FrameResources::new(&self.ctx, self.timestamps(), false)?,
        };
        res.queries.reset(&self.ctx, self.slots[s].last_passes);
        unsafe { d.reset_command_buffer(res.cb, vk::CommandBufferResetFlags::empty()) }.call("vkResetCommandBuffer")?;
        let begin = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
        unsafe { d.begin_command_buffer(res.cb, &begin) }.call("vkBeginCommandBuffer")?;
        let tag = RingTag { ring: self.id, slot: s, frame: self.next_frame };
        let mut res = res;
        let per_frame = self.opts.timing == Timing::PerFrame && res.queries.timestamps();
        if per_frame {
            res.queries.begin(&self.ctx, res.cb, 0)?;
        }
        self.next_frame += 1;
        let pass_queries = self.opts.timing == Timing::PerPass;
        Ok(Frame::from_ring(&self.ctx, res, tag, counters_at_begin, pass_queries))
    }

    /// Ends and submits `frame` without waiting for it.
    pub fn submit(&mut self, mut frame: Frame) -> Result<()> {
        let tag = frame
            .ring
            .filter(|t| t.ring == self.id)
            .ok_or_else(|| VkError::Invalid("FrameRing::submit was given a frame that is not this ring's".into()))?;
        frame.finished = true;
        let res = frame.res.take().ok_or_else(|| VkError::Invalid("the frame was already submitted".into()))?;
        let passes = std::mem::take(&mut frame.passes);
        let graph = std::mem::take(&mut frame.graph);
        let counters_at_begin = frame.counters_at_begin;
        drop(frame);
        let d = self.ctx.shared.raw();
        if self.opts.timing == Timing::PerFrame && res.queries.timestamps() {
            res.queries.end(&self.ctx, res.cb, 0);
        }
        // The frame's number + 1, once every command of it has finished.
        res.marker.record(&self.ctx, res.cb, (tag.frame + 1).min(u32::MAX as u64) as u32);
        let slot = &mut self.slots[tag.slot];
        let ended = unsafe { d.end_command_buffer(res.cb) }.call("vkEndCommandBuffer");
        let cbs = [vk::CommandBufferSubmitInfo::default().command_buffer(res.cb)];
        let submit = vk::SubmitInfo2::default().command_buffer_infos(&cbs);
        let submitted = ended.and_then(|_| {
            self.ctx.shared.counters.submit();
            crate::crash::ring_submitted();
            unsafe { d.queue_submit2(self.ctx.shared.device.queue, &[submit], slot.fence) }.call("vkQueueSubmit2")
        });
        slot.res = Some(res);
        submitted?;
        let counters = self.ctx.counters().since(&counters_at_begin);
        slot.pending = Some(Pending { frame: tag.frame, passes, graph, counters });
        Ok(())
    }

    /// Reports of the frames finished so far, oldest first (each slot's frame is collected when
    /// the slot comes round again, or by [`FrameRing::finish`]).
    pub fn reports(&mut self) -> Vec<FrameReport> {
        std::mem::take(&mut self.done)
    }

    /// Waits for every frame in flight, oldest first, and returns every report not yet taken.
    pub fn finish(&mut self) -> Result<Vec<FrameReport>> {
        let n = self.slots.len() as u64;
        for k in 0..n {
            let s = ((self.next_frame + k) % n) as usize;
            self.retire(s)?;
        }
        crate::crash::ring_idle();
        Ok(self.reports())
    }
}

impl Drop for FrameRing {
    fn drop(&mut self) {
        let d = self.ctx.shared.raw();
        let fences: Vec<vk::Fence> = self.slots.iter().filter(|s| s.pending.is_some()).map(|s| s.fence).collect();
        if !fences.is_empty() {
            let _ = unsafe { d.wait_for_fences(&fences, true, u64::MAX) };
        }
        crate::crash::ring_idle();
        for s in self.slots.drain(..) {
            unsafe { d.destroy_fence(s.fence, None) };
            drop(s.res);
        }
    }
}
