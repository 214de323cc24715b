//! The crash marker: a small host-visible buffer per frame into which, after each pass, the
//! GPU writes the number of passes finished so far (an execution barrier waits for all earlier
//! work, then vkCmdFillBuffer writes pass index + 1). When the frame's fence wait fails (a
//! timeout, a lost device), the host reads it to name the last pass that finished and the one
//! after it. kajiya's `record_crash_marker` fills such a buffer with vkCmdFillBuffer too.

use crate::buffer::{Buffer, Memory};
use crate::context::Context;
use crate::error::Result;
use ash::vk;

pub(crate) struct CrashMarker {
    buffer: Buffer,
}

impl CrashMarker {
    /// A marker reading 0: no pass finished.
    pub fn new(ctx: &Context) -> Result<CrashMarker> {
        let mut buffer = Buffer::new(ctx, "crash marker", 4, Memory::Readback)?;
        buffer.write_mapped(0, &0u32.to_le_bytes())?;
        Ok(CrashMarker { buffer })
    }

    /// Records "`finished` passes have finished": waits for every earlier command (and the
    /// previous marker write), then writes `finished`. Outside any rendering scope.
    pub fn record(&self, ctx: &Context, cb: vk::CommandBuffer, finished: u32) {
        let barrier = [vk::MemoryBarrier2::default()
            .src_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
            .src_access_mask(vk::AccessFlags2::TRANSFER_WRITE)
            .dst_stage_mask(vk::PipelineStageFlags2::ALL_TRANSFER)
            .dst_access_mask(vk::AccessFlags2::TRANSFER_WRITE)];
        let dep = vk::DependencyInfo::default().memory_barriers(&barrier);
        let d = ctx.shared.raw();
        unsafe {
            d.cmd_pipeline_barrier2(cb, &dep);
            d.cmd_fill_buffer(cb, self.buffer.raw, 0, 4, finished);
        }
        ctx.shared.counters.barrier();
    }

    /// The mapped word, for the fatal-signal handler (crash.rs); null where it is not mapped.
    pub fn ptr(&self) -> *const u32 {
        match self.buffer.mapped() {
            Some(m) if m.len() >= 4 => m.as_ptr() as *const u32,
            _ => std::ptr::null(),
        }
    }

    /// How many passes had finished, as far as the GPU wrote it.
    pub fn read(&self) -> u32 {
        let p = self.ptr();
        // The GPU may still be writing: a volatile read of the mapped (coherent) memory.
        if p.is_null() {
            0
        } else {
            unsafe { std::ptr::read_volatile(p) }
        }
    }
}

/// Where a failed frame stood: the last pass that finished and the one after it, from
/// `finished` passes out of `passes`.
pub(crate) fn progress(passes: &[String], finished: u32) -> (Option<String>, Option<String>) {
    let finished = (finished as usize).min(passes.len());
    let last = finished.checked_sub(1).map(|i| passes[i].clone());
    (last, passes.get(finished).cloned())
}

#[cfg(test)]
mod tests {
    use super::progress;

    #[test]
    fn progress_names_the_last_finished_pass_and_the_next() {
        let passes: Vec<String> = ["a", "b", "c"].map(String::from).to_vec();
        assert_eq!(progress(&passes, 0), (None, Some("a".into())));
        assert_eq!(progress(&passes, 2), (Some("b".into()), Some("c".into())));
        assert_eq!(progress(&passes, 3), (Some("c".into()), None));
        assert_eq!(progress(&passes, 99), (Some("c".into()), None), "a garbage marker is clamped");
    }
}
