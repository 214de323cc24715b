//! A frame: one command buffer of passes, submitted and waited for. Each pass (see `pass.rs`)
//! says what it reads and writes, through its descriptors (`Bind`) and its other accesses
//! (`Use`), and the frame emits the synchronization2 barriers (with mip/layer ranges), a debug
//! label and a timestamp pair around it, plus an optional pipeline-statistics query. Headless:
//! `submit` waits for the GPU and returns per-pass timings.

use crate::buffer::Buffer;
use crate::context::Context;
use crate::error::{Result, VkError, VkResultExt};
use crate::image::{aspect, Image, ImageView};
use crate::marker::{progress, CrashMarker};
use crate::pass::Pass;
use crate::profiler::{FrameReport, PassTiming, PipelineStats, QueryPools};
use crate::recorder::Cmd;
use crate::tracker::{Access, Transition};
use ash::vk;
use std::ops::Range;
use std::time::Duration;

/// One resource a pass touches and how, other than through a descriptor: made only by
/// [`Use::buffer`], [`Use::view`] and [`Use::image`], so it always names a live resource.
pub struct Use<'a>(Kind<'a>);

/// What a [`Use`] holds (vkcore only: no caller sees the raw image).
pub(crate) enum Kind<'a> {
    Buffer(&'a Buffer, Access),
    Image {
        name: &'a str,
        image_id: u64,
        raw: vk::Image,
        format: vk::Format,
        total_layers: u32,
        mips: Range<u32>,
        layers: Range<u32>,
        access: Access,
    },
}

impl<'a> Use<'a> {
    pub fn buffer(b: &'a Buffer, access: Access) -> Use<'a> {
        Use(Kind::Buffer(b, access))
    }
    /// Every subresource the view covers.
    pub fn view(v: &'a ImageView, access: Access) -> Use<'a> {
        Use(Kind::Image {
            name: &v.image_name,
            image_id: v.image_id,
            raw: v.image,
            format: v.format,
            total_layers: v.total_layers,
            mips: v.mips.clone(),
            layers: v.layers.clone(),
            access,
        })
    }
    /// The resource's name and whether the pass reads and writes it (the frame graph).
    fn node_entry(&self) -> (&str, bool, bool) {
        let (name, a) = match &self.0 {
            Kind::Buffer(b, access) => (b.name(), access),
            Kind::Image { name, access, .. } => (*name, access),
        };
        (name, a.is_read(), a.is_write())
    }
    /// The resource's id and the access, to check pushed descriptors against what a pass
    /// declared.
    pub(crate) fn key(&self) -> (u64, Access) {
        match &self.0 {
            Kind::Buffer(b, access) => (b.id, *access),
            Kind::Image { image_id, access, .. } => (*image_id, *access),
        }
    }
    /// Some mips and layers of an image, without a view.
    pub fn image(i: &'a Image, mips: Range<u32>, layers: Range<u32>, access: Access) -> Use<'a> {
        Use(Kind::Image {
            name: &i.desc.name,
            image_id: i.id,
            raw: i.raw,
            format: i.desc.format,
            total_layers: i.desc.array_layers,
            mips,
            layers,
            access,
        })
    }
}

/// Removes stages and accesses of features the device does not have (the geometry stage, the
/// transform-feedback stage and accesses): barriers may not name them (VUID-*-03929 etc).
fn supported(ctx: &Context, mut a: Access) -> Access {
    let info = ctx.info();
    if !info.has(crate::Feature::GeometryShader) {
        a.stage &= !vk::PipelineStageFlags2::GEOMETRY_SHADER;
    }
    if !info.has(crate::Feature::TransformFeedback) {
        a.stage &= !vk::PipelineStageFlags2::TRANSFORM_FEEDBACK_EXT;
        a.access &= !(vk::AccessFlags2::TRANSFORM_FEEDBACK_WRITE_EXT
            | vk::AccessFlags2::TRANSFORM_FEEDBACK_COUNTER_READ_EXT
            | vk::AccessFlags2::TRANSFORM_FEEDBACK_COUNTER_WRITE_EXT);
    }
    a
}

/// Emits the barriers `uses` need into `cb`.
pub(crate) fn sync(ctx: &Context, cb: vk::CommandBuffer, uses: &[Use]) -> Result<()> {
    let mut buffer_barriers = vec![];
    let mut image_barriers = vec![];
    let mut tracker = ctx.shared.tracker.lock().map_err(|_| VkError::Invalid("tracker lock poisoned".into()))?;
    for u in uses {
        match &u.0 {
            Kind::Buffer(b, access) => {
                for (_, t) in tracker.access(b.id, std::iter::once(0), supported(ctx, *access), false) {
                    buffer_barriers.push(
                        vk::BufferMemoryBarrier2::default()
                            .src_stage_mask(t.src_stage)
                            .src_access_mask(t.src_access)
                            .dst_stage_mask(t.dst_stage)
                            .dst_access_mask(t.dst_access)
                            .buffer(b.raw)
                            .offset(0)
                            .size(vk::WHOLE_SIZE),
                    );
                }
            }
            Kind::Image { image_id, raw, format, total_layers, mips, layers, access, .. } => {
                let subs = mips.clone().flat_map(|m| layers.clone().map(move |l| (m * total_layers + l) as usize));
                for (i, t) in tracker.access(*image_id, subs, supported(ctx, *access), true) {
                    let (mip, layer) = (i as u32 / total_layers, i as u32 % total_layers);
                    image_barriers.push(image_barrier(*raw, *format, mip, layer, &t));
                }
            }
        }
    }
    drop(tracker);
    if buffer_barriers.is_empty() && image_barriers.is_empty() {
        return Ok(());
    }
    let dep =
        vk::DependencyInfo::default().buffer_memory_barriers(&buffer_barriers).image_memory_barriers(&image_barriers);
    unsafe { ctx.shared.raw().cmd_pipeline_barrier2(cb, &dep) };
    ctx.shared.counters.barrier();
    Ok(())
}

fn image_barrier(
    raw: vk::Image,
    format: vk::Format,
    mip: u32,
    layer: u32,
    t: &Transition,
) -> vk::ImageMemoryBarrier2<'static> {
    vk::ImageMemoryBarrier2::default()
        .src_stage_mask(t.src_stage)
        .src_access_mask(t.src_access)
        .dst_stage_mask(t.dst_stage)
        .dst_access_mask(t.dst_access)
        .old_layout(t.old_layout)
        .new_layout(t.new_layout)
        .image(raw)
        .subresource_range(vk::ImageSubresourceRange {
            aspect_mask: aspect(format),
            base_mip_level: mip,
            level_count: 1,
            base_array_layer: layer,
            layer_count: 1,
        })
}

/// Options for recording a one-shot frame ([`Context::frame`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct FrameOptions {
    /// Timestamp pair around every pass (on when the device has timestamps).
    pub timestamps: bool,
    /// A pipeline-statistics query around every pass.
    pub pipeline_statistics: bool,
    /// How long `submit` waits for the GPU before it gives up with an error naming the last
    /// pass that finished; None: ten minutes.
    pub fence_timeout: Option<Duration>,
    /// Submit and wait after every pass, timing each on the host ([`PassTiming::host_ms`]):
    /// a pass's time where the driver's timestamps do not bracket its work (lavapipe's
    /// transform-feedback draws and compute dispatches). Costs a submit and a wait per pass.
    pub host_pass_times: bool,
}

/// Ten minutes: lavapipe at 4096^2 photons is slow, but a hang must not block CI forever.
pub(crate) const FENCE_TIMEOUT: Duration = Duration::from_secs(600);

/// What a frame records into: its command buffer, queries and crash marker. A one-shot frame
/// makes its own and frees them after its submit; a ring slot keeps its own from frame to frame
/// (see `ring.rs`).
pub(crate) struct FrameResources {
    ctx: Context,
    pub cb: vk::CommandBuffer,
    pub queries: QueryPools,
    pub marker: CrashMarker,
}

impl FrameResources {
    pub fn new(ctx: &Context, timestamps: bool, stats: bool) -> Result<FrameResources> {
        let pool =
            *ctx.shared.command_pool.lock().map_err(|_| VkError::Invalid("command pool lock poisoned".into()))?;
        let info = vk::CommandBufferAllocateInfo::default()
            .command_pool(pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(1);
        let cb = unsafe { ctx.shared.raw().allocate_command_buffers(&info) }.call("vkAllocateCommandBuffers")?[0];
        ctx.shared.counters.object(1);
        let free = || unsafe { ctx.shared.raw().free_command_buffers(pool, &[cb]) };
        let queries = match QueryPools::new(ctx, timestamps, stats) {
            Ok(q) => q,
            Err(e) => {
                free();
                return Err(e);
            }
        };
        let marker = match CrashMarker::new(ctx) {
            Ok(m) => m,
            Err(e) => {
                free();
                return Err(e);
            }
        };
        Ok(FrameResources { ctx: ctx.clone(), cb, queries, marker })
    }
}

impl Drop for FrameResources {
    fn drop(&mut self) {
        if let Ok(pool) = self.ctx.shared.command_pool.lock() {
            unsafe { self.ctx.shared.raw().free_command_buffers(*pool, &[self.cb]) };
        }
        self.queries.destroy(&self.ctx);
    }
}

/// Which ring, slot and frame number a ring frame belongs to.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RingTag {
    pub ring: u64,
    pub slot: usize,
    pub frame: u64,
}

/// One pass of a recorded frame as the frame graph shows it: its name and the resources it
/// read and wrote, from what it declared (`Pass::bind`'s descriptors and `Pass::uses`: the same
/// declarations the barriers come from), each resource once, in declaration order.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct PassNode {
    pub name: String,
    pub reads: Vec<String>,
    pub writes: Vec<String>,
}

impl PassNode {
    fn of(name: &str, uses: &[Use]) -> PassNode {
        let mut node = PassNode { name: name.to_string(), ..Default::default() };
        for u in uses {
            let (resource, read, write) = u.node_entry();
            for (yes, list) in [(read, &mut node.reads), (write, &mut node.writes)] {
                if yes && !list.iter().any(|r| r == resource) {
                    list.push(resource.to_string());
                }
            }
        }
        node
    }
}

pub struct Frame {
    pub(crate) ctx: Context,
    /// Taken back by the ring at its submit; freed by `Drop` otherwise.
    pub(crate) res: Option<FrameResources>,
    fence_timeout: Duration,
    pub(crate) passes: Vec<String>,
    /// Each recorded pass with what it read and wrote (the frame graph).
    pub(crate) graph: Vec<PassNode>,
    pub(crate) finished: bool,
    /// A ring frame: no crash-marker barrier after each pass (one at the frame's end), and it is
    /// submitted by its ring.
    pub(crate) ring: Option<RingTag>,
    /// The context's counters when recording began.
    pub(crate) counters_at_begin: crate::Counters,
    /// Timestamps and statistics around each pass (one-shot frames; ring frames timed per pass).
    pass_queries: bool,
    /// With [`FrameOptions::host_pass_times`]: each pass's host milliseconds, from its submit
    /// to its fence.
    host_pass_ms: Option<Vec<f64>>,
}

impl Context {
    /// Starts recording a one-shot frame: its command buffer, query pools, crash marker and
    /// fence are made for it and freed after [`Frame::submit`], which waits for the GPU (the
    /// per-pass frame mode; [`crate::FrameRing`] keeps them for the throughput mode).
    pub fn frame(&self, opts: FrameOptions) -> Result<Frame> {
        let counters_at_begin = self.counters();
        let timestamps = opts.timestamps && self.info().has(crate::Feature::Timestamps);
        let stats = opts.pipeline_statistics && self.info().has(crate::Feature::PipelineStatisticsQuery);
        let res = FrameResources::new(self, timestamps, stats)?;
        let fence_timeout = opts.fence_timeout.unwrap_or(FENCE_TIMEOUT);
        let cb = res.cb;
        // From here on the frame owns (and its Drop frees) the command buffer and queries.
        let mut frame = Frame {
            ctx: self.clone(),
            res: Some(res),
            fence_timeout,
            passes: vec![],
            graph: vec![],
            finished: false,
            ring: None,
            counters_at_begin,
            pass_queries: true,
            host_pass_ms: opts.host_pass_times.then(Vec::new),
        };
        if let Err(e) = begin_one_shot(self, cb) {
            frame.finished = true;
            return Err(e);
        }
        Ok(frame)
    }
}

impl Frame {
    pub(crate) fn from_ring(
        ctx: &Context,
        res: FrameResources,
        tag: RingTag,
        counters_at_begin: crate::Counters,
        pass_queries: bool,
    ) -> Frame {
        Frame {
            ctx: ctx.clone(),
            res: Some(res),
            fence_timeout: FENCE_TIMEOUT,
            passes: vec![],
            graph: vec![],
            finished: false,
            ring: Some(tag),
            counters_at_begin,
            pass_queries,
            host_pass_ms: None,
        }
    }

    fn res(&mut self) -> Result<&mut FrameResources> {
        self.res.as_mut().ok_or_else(|| VkError::Invalid("the frame was already submitted".into()))
    }

    /// Starts describing a pass named `name` (see [`Pass`]).
    pub fn pass<'a>(&mut self, name: &str) -> Pass<'_, 'a> {
        Pass::new(self, name)
    }

    /// Passes recorded so far.
    pub fn pass_count(&self) -> usize {
        self.passes.len()
    }

    /// Records one pass: barriers for `uses`, then a label, timestamps and statistics around
    /// whatever `record` does (and, in a one-shot frame, the crash marker after it). Descriptors
    /// pushed in it must be among `uses`.
    pub(crate) fn record_pass<F>(&mut self, name: &str, uses: &[Use], record: F) -> Result<()>
    where
        F: FnOnce(&mut Cmd) -> Result<()>,
    {
        let ctx = self.ctx.clone();
        let index = self.passes.len() as u32;
        let per_pass_marker = self.ring.is_none();
        if index >= crate::MAX_PASSES {
            return Err(VkError::Invalid(format!(
                "pass `{name}`: more than {} passes in one frame",
                crate::MAX_PASSES
            )));
        }
        let pass_queries = self.pass_queries;
        crate::crash::recording(index, name);
        if self.ring.is_none() && crate::crash::test_segfault_requested(name) {
            self.segfault_in_pass()?;
        }
        let res = self.res()?;
        let cb = res.cb;
        sync(&ctx, cb, uses)?;
        if pass_queries {
            res.queries.begin(&ctx, cb, index)?;
        }
        self.passes.push(name.to_string());
        if ctx.shared.frame_graphs.load(std::sync::atomic::Ordering::Relaxed) {
            self.graph.push(PassNode::of(name, uses));
        }
        let mut cmd = Cmd::new(&ctx, cb, uses.iter().map(Use::key).collect());
        cmd.begin_label(name);
        let result = record(&mut cmd);
        cmd.end_rendering();
        cmd.end_label();
        drop(cmd);
        result?;
        let res = self.res()?;
        if pass_queries {
            res.queries.end(&ctx, cb, index);
        }
        if per_pass_marker {
            res.marker.record(&ctx, cb, index + 1);
        }
        if self.host_pass_ms.is_some() {
            let start = std::time::Instant::now();
            if let Err(e) = self.submit_and_wait(cb).and_then(|_| begin_one_shot(&ctx, cb)) {
                // The command buffer is no longer recording: Drop must not end it.
                self.finished = true;
                return Err(e);
            }
            let ms = start.elapsed().as_secs_f64() * 1e3;
            self.host_pass_ms.iter_mut().for_each(|times| times.push(ms));
        }
        Ok(())
    }

    /// The test hook ([`crate::crash::TEST_SEGFAULT_ENV`]): runs the passes recorded before
    /// the pass being recorded, then raises SIGSEGV as a driver crashing in it would, its marker
    /// reading them.
    fn segfault_in_pass(&mut self) -> Result<()> {
        let cb = self.res()?.cb;
        if let Err(e) = self.submit_and_wait(cb) {
            // The command buffer is no longer recording: Drop must not end it.
            self.finished = true;
            return Err(e);
        }
        crate::crash::running(self.res()?.marker.ptr());
        crate::crash::raise_test_segfault()
    }

    /// Ends `cb`, submits it and waits for it, with the error of a frame that failed (the last
    /// pass its crash marker saw finish) when the wait fails.
    fn submit_and_wait(&self, cb: vk::CommandBuffer) -> Result<()> {
        let d = self.ctx.shared.raw();
        unsafe { d.end_command_buffer(cb) }.call("vkEndCommandBuffer")?;
        let fence = unsafe { d.create_fence(&vk::FenceCreateInfo::default(), None) }.call("vkCreateFence")?;
        self.ctx.shared.counters.object(1);
        let cbs = [vk::CommandBufferSubmitInfo::default().command_buffer(cb)];
        let submit = vk::SubmitInfo2::default().command_buffer_infos(&cbs);
        let timeout = self.fence_timeout.as_nanos().min(u64::MAX as u128) as u64;
        self.ctx.shared.counters.submit();
        crate::crash::running(self.res.as_ref().map_or(std::ptr::null(), |r| r.marker.ptr()));
        let result = unsafe { d.queue_submit2(self.ctx.shared.device.queue, &[submit], fence) }
            .map_err(|e| {
                VkError::Invalid(format!(
                    "vkQueueSubmit2 failed: {e:?}; the frame held passes: {}",
                    self.passes.join(", ")
                ))
            })
            .and_then(|_| {
                unsafe { d.wait_for_fences(&[fence], true, timeout) }.map_err(|result| {
                    // Read the marker now: waiting below lets the GPU finish (or fail) the rest.
                    let marker = self.res.as_ref().map_or(0, |r| r.marker.read());
                    let (last_finished, next) = progress(&self.passes, marker);
                    VkError::FrameFailed { result, last_finished, next, passes: self.passes.clone(), ring: None }
                })
            });
        if result.is_err() {
            // The GPU may still be running this frame: let it finish (or fail) before the fence,
            // the command buffer and the frame's resources are destroyed.
            let _ = unsafe { d.device_wait_idle() };
        }
        crate::crash::idle();
        unsafe { d.destroy_fence(fence, None) };
        result
    }

    /// Submits, waits for the GPU, and returns each pass's time and statistics (a one-shot
    /// frame; a ring's frame goes back through [`crate::FrameRing::submit`]).
    pub fn submit(mut self) -> Result<FrameReport> {
        if self.ring.is_some() {
            return Err(VkError::Invalid("a ring's frame is submitted with FrameRing::submit".into()));
        }
        self.finished = true;
        let cb = self.res()?.cb;
        self.submit_and_wait(cb)?;
        let res = self.res.take().ok_or_else(|| VkError::Invalid("the frame was already submitted".into()))?;
        let counters = self.ctx.counters().since(&self.counters_at_begin);
        let mut report = read_report(&self.ctx, &res, &self.passes, None)?;
        report.counters = counters;
        report.graph = std::mem::take(&mut self.graph);
        if let Some(host) = &self.host_pass_ms {
            for (p, ms) in report.passes.iter_mut().zip(host) {
                p.host_ms = Some(*ms);
            }
        }
        Ok(report)
    }
}

/// The passes' times and statistics of a finished frame, from its queries (for a frame timed as
/// a whole, `frame_timing`: the frame's two timestamps are the chunk's first pair).
pub(crate) fn read_report(
    ctx: &Context,
    res: &FrameResources,
    passes: &[String],
    frame_timing: Option<()>,
) -> Result<FrameReport> {
    if frame_timing.is_some() {
        let (times, _) = res.queries.read(ctx, 1)?;
        let passes = passes
            .iter()
            .map(|name| PassTiming { name: name.clone(), gpu_ms: None, host_ms: None, stats: None })
            .collect();
        return Ok(FrameReport { passes, frame_gpu_ms: times.and_then(|t| t.first().copied()), ..Default::default() });
    }
    let (times, stats) = res.queries.read(ctx, passes.len())?;
    let passes = passes
        .iter()
        .enumerate()
        .map(|(i, name)| PassTiming {
            name: name.clone(),
            gpu_ms: times.as_ref().and_then(|t| t.get(i).copied()),
            host_ms: None,
            stats: stats.as_ref().and_then(|s| s.get(i).copied()).map(PipelineStats::from_raw),
        })
        .collect();
    Ok(FrameReport { passes, ..Default::default() })
}

/// Begins recording `cb` for one submit.
fn begin_one_shot(ctx: &Context, cb: vk::CommandBuffer) -> Result<()> {
    let begin = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
    unsafe { ctx.shared.raw().begin_command_buffer(cb, &begin) }
        .map_err(|e| VkError::Call { call: "vkBeginCommandBuffer", result: e })
}

impl Drop for Frame {
    fn drop(&mut self) {
        if let Some(res) = self.res.take() {
            if !self.finished {
                unsafe {
                    let _ = self.ctx.shared.raw().end_command_buffer(res.cb);
                }
            }
            drop(res);
        }
    }
}
