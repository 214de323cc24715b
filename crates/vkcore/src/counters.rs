//! What the host asked of the driver, counted: Vulkan objects created or allocated (buffers,
//! images, views, samplers, memory allocations, pipelines and their layouts and modules, query
//! pools, command buffers, fences), queue submissions, pipeline barriers and timestamps written,
//! and acceleration structures built (bottom and top levels apart) and refitted: what a moving
//! object costs.
//! A real-time frame creates nothing once it is warm: throughput frames are tested for that, and
//! the bench and `timings.json` report each count per frame.

use std::sync::atomic::{AtomicU64, Ordering};

/// A snapshot of the counts since the context was made (or, from [`Counters::since`], between
/// two snapshots).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Vulkan objects created and memory allocations made.
    pub objects: u64,
    /// `vkQueueSubmit2` calls.
    pub submits: u64,
    /// `vkCmdPipelineBarrier2` calls recorded.
    pub barriers: u64,
    /// `vkCmdWriteTimestamp2` calls recorded.
    pub timestamps: u64,
    /// Bottom-level acceleration structures built (over a mesh's triangles).
    pub blas_builds: u64,
    /// Top-level acceleration structures built (over instances).
    pub tlas_builds: u64,
    /// Bottom-level acceleration structures refitted in place to moved vertices.
    pub blas_refits: u64,
}

impl Counters {
    /// The counts from `earlier` to `self`.
    pub fn since(&self, earlier: &Counters) -> Counters {
        Counters {
            objects: self.objects.saturating_sub(earlier.objects),
            submits: self.submits.saturating_sub(earlier.submits),
            barriers: self.barriers.saturating_sub(earlier.barriers),
            timestamps: self.timestamps.saturating_sub(earlier.timestamps),
            blas_builds: self.blas_builds.saturating_sub(earlier.blas_builds),
            tlas_builds: self.tlas_builds.saturating_sub(earlier.tlas_builds),
            blas_refits: self.blas_refits.saturating_sub(earlier.blas_refits),
        }
    }
}

#[derive(Default)]
pub(crate) struct AtomicCounters {
    objects: AtomicU64,
    submits: AtomicU64,
    barriers: AtomicU64,
    timestamps: AtomicU64,
    blas_builds: AtomicU64,
    tlas_builds: AtomicU64,
    blas_refits: AtomicU64,
}

impl AtomicCounters {
    pub fn object(&self, n: u64) {
        self.objects.fetch_add(n, Ordering::Relaxed);
    }
    pub fn submit(&self) {
        self.submits.fetch_add(1, Ordering::Relaxed);
    }
    pub fn barrier(&self) {
        self.barriers.fetch_add(1, Ordering::Relaxed);
    }
    pub fn timestamp(&self) {
        self.timestamps.fetch_add(1, Ordering::Relaxed);
    }
    /// An acceleration structure built: a top level (`top`) or a bottom one.
    pub fn acceleration_structure(&self, top: bool) {
        let c = if top { &self.tlas_builds } else { &self.blas_builds };
        c.fetch_add(1, Ordering::Relaxed);
    }
    /// A bottom level refitted.
    pub fn acceleration_structure_refit(&self) {
        self.blas_refits.fetch_add(1, Ordering::Relaxed);
    }
    pub fn snapshot(&self) -> Counters {
        Counters {
            objects: self.objects.load(Ordering::Relaxed),
            submits: self.submits.load(Ordering::Relaxed),
            barriers: self.barriers.load(Ordering::Relaxed),
            timestamps: self.timestamps.load(Ordering::Relaxed),
            blas_builds: self.blas_builds.load(Ordering::Relaxed),
            tlas_builds: self.tlas_builds.load(Ordering::Relaxed),
            blas_refits: self.blas_refits.load(Ordering::Relaxed),
        }
    }
}
