//! Automatic synchronization2 barriers. Every buffer and every (mip, layer) of every image has a
//! tracked state: its layout, the last write and which stages have since been made to see it.
//! A pass declares what it reads and writes; the tracker emits exactly the barriers needed.

use ash::vk;
use std::collections::HashMap;

/// How a pass touches a resource: pipeline stages, access types and (for images) the layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Access {
    pub stage: vk::PipelineStageFlags2,
    pub access: vk::AccessFlags2,
    pub layout: vk::ImageLayout,
}

type S = vk::PipelineStageFlags2;
type A = vk::AccessFlags2;
type L = vk::ImageLayout;

const fn acc(stage: S, access: A, layout: L) -> Access {
    Access { stage, access, layout }
}

const GFX_SHADERS: S =
    S::from_raw(S::VERTEX_SHADER.as_raw() | S::GEOMETRY_SHADER.as_raw() | S::FRAGMENT_SHADER.as_raw());
const ALL_SHADERS: S = S::from_raw(GFX_SHADERS.as_raw() | S::COMPUTE_SHADER.as_raw());

impl Access {
    /// Sampled (texture()) or read as a storage buffer/image by any shader stage.
    pub const SHADER_READ: Access = acc(ALL_SHADERS, A::SHADER_READ, L::SHADER_READ_ONLY_OPTIMAL);
    /// A uniform buffer read by any shader stage.
    pub const UNIFORM_READ: Access = acc(ALL_SHADERS, A::UNIFORM_READ, L::UNDEFINED);
    /// Storage image/buffer written (and read) by compute.
    pub const COMPUTE_READ_WRITE: Access = acc(
        S::COMPUTE_SHADER,
        A::from_raw(A::SHADER_STORAGE_READ.as_raw() | A::SHADER_STORAGE_WRITE.as_raw()),
        L::GENERAL,
    );
    /// Storage image/buffer read and written by graphics shaders (atomics in fragment shaders).
    pub const GRAPHICS_READ_WRITE: Access =
        acc(GFX_SHADERS, A::from_raw(A::SHADER_STORAGE_READ.as_raw() | A::SHADER_STORAGE_WRITE.as_raw()), L::GENERAL);
    /// Storage buffer read by any shader.
    pub const STORAGE_READ: Access = acc(ALL_SHADERS, A::SHADER_STORAGE_READ, L::GENERAL);
    /// An acceleration structure read by ray queries.
    pub const ACCELERATION_STRUCTURE_READ: Access = acc(ALL_SHADERS, A::ACCELERATION_STRUCTURE_READ_KHR, L::UNDEFINED);
    pub const COLOR_ATTACHMENT: Access = acc(
        S::COLOR_ATTACHMENT_OUTPUT,
        A::from_raw(A::COLOR_ATTACHMENT_READ.as_raw() | A::COLOR_ATTACHMENT_WRITE.as_raw()),
        L::COLOR_ATTACHMENT_OPTIMAL,
    );
    pub const DEPTH_ATTACHMENT: Access = acc(
        S::from_raw(S::EARLY_FRAGMENT_TESTS.as_raw() | S::LATE_FRAGMENT_TESTS.as_raw()),
        A::from_raw(A::DEPTH_STENCIL_ATTACHMENT_READ.as_raw() | A::DEPTH_STENCIL_ATTACHMENT_WRITE.as_raw()),
        L::DEPTH_ATTACHMENT_OPTIMAL,
    );
    pub const VERTEX_INPUT: Access =
        acc(S::VERTEX_INPUT, A::from_raw(A::VERTEX_ATTRIBUTE_READ.as_raw() | A::INDEX_READ.as_raw()), L::UNDEFINED);
    /// Indirect draw/dispatch arguments, including the transform-feedback counter read by
    /// vkCmdDrawIndirectByteCountEXT.
    pub const INDIRECT: Access = acc(
        S::DRAW_INDIRECT,
        A::from_raw(A::INDIRECT_COMMAND_READ.as_raw() | A::TRANSFORM_FEEDBACK_COUNTER_READ_EXT.as_raw()),
        L::UNDEFINED,
    );
    pub const TRANSFER_READ: Access = acc(S::ALL_TRANSFER, A::TRANSFER_READ, L::TRANSFER_SRC_OPTIMAL);
    pub const TRANSFER_WRITE: Access = acc(S::ALL_TRANSFER, A::TRANSFER_WRITE, L::TRANSFER_DST_OPTIMAL);
    /// Read by the host after the frame (mapped readback memory).
    pub const HOST_READ: Access = acc(S::HOST, A::HOST_READ, L::UNDEFINED);
    /// Written as a transform-feedback buffer.
    pub const XFB_WRITE: Access = acc(S::TRANSFORM_FEEDBACK_EXT, A::TRANSFORM_FEEDBACK_WRITE_EXT, L::UNDEFINED);
    /// A transform-feedback counter buffer (read at begin, written at end).
    pub const XFB_COUNTER: Access = acc(
        S::TRANSFORM_FEEDBACK_EXT,
        A::from_raw(A::TRANSFORM_FEEDBACK_COUNTER_READ_EXT.as_raw() | A::TRANSFORM_FEEDBACK_COUNTER_WRITE_EXT.as_raw()),
        L::UNDEFINED,
    );

    pub(crate) fn is_write(&self) -> bool {
        let w = A::SHADER_WRITE
            | A::SHADER_STORAGE_WRITE
            | A::COLOR_ATTACHMENT_WRITE
            | A::DEPTH_STENCIL_ATTACHMENT_WRITE
            | A::TRANSFER_WRITE
            | A::TRANSFORM_FEEDBACK_WRITE_EXT
            | A::TRANSFORM_FEEDBACK_COUNTER_WRITE_EXT
            | A::HOST_WRITE;
        self.access.intersects(w)
    }
    /// Whether the access reads: any access type beyond its writes (a read-modify-write, a
    /// sampled read, an attachment load).
    pub(crate) fn is_read(&self) -> bool {
        !(self.access & !self.write_part()).is_empty()
    }
    fn write_part(&self) -> A {
        self.access
            & (A::SHADER_WRITE
                | A::SHADER_STORAGE_WRITE
                | A::COLOR_ATTACHMENT_WRITE
                | A::DEPTH_STENCIL_ATTACHMENT_WRITE
                | A::TRANSFER_WRITE
                | A::TRANSFORM_FEEDBACK_WRITE_EXT
                | A::TRANSFORM_FEEDBACK_COUNTER_WRITE_EXT
                | A::HOST_WRITE)
    }
}

/// One subresource's history.
#[derive(Debug, Clone, Copy)]
pub(crate) struct State {
    layout: vk::ImageLayout,
    write_stage: S,
    write_access: A,
    /// Stages/accesses that already have the last write visible.
    visible_stage: S,
    visible_access: A,
    /// Stages that read since the last write (a later write must wait for them).
    read_stage: S,
}

impl Default for State {
    fn default() -> Self {
        State {
            layout: L::UNDEFINED,
            write_stage: S::NONE,
            write_access: A::NONE,
            visible_stage: S::NONE,
            visible_access: A::NONE,
            read_stage: S::NONE,
        }
    }
}

/// A barrier the tracker decided on; `sub` is (mip, layer) for images.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Transition {
    pub src_stage: S,
    pub src_access: A,
    pub dst_stage: S,
    pub dst_access: A,
    pub old_layout: L,
    pub new_layout: L,
}

impl State {
    /// Updates the state for `access` and returns the barrier it needs, if any.
    /// `is_image` false: layouts are ignored.
    fn apply(&mut self, access: Access, is_image: bool) -> Option<Transition> {
        let layout_change = is_image && self.layout != access.layout;
        let mut t = Transition {
            src_stage: S::NONE,
            src_access: A::NONE,
            dst_stage: access.stage,
            dst_access: access.access,
            old_layout: if is_image { self.layout } else { L::UNDEFINED },
            new_layout: if is_image { access.layout } else { L::UNDEFINED },
        };
        if access.is_write() || layout_change {
            // Write-after-write / write-after-read / layout transition: wait for everything.
            t.src_stage = self.write_stage | self.read_stage;
            t.src_access = self.write_access;
            let needed = layout_change || !t.src_stage.is_empty();
            if access.is_write() {
                *self = State {
                    layout: if is_image { access.layout } else { L::UNDEFINED },
                    write_stage: access.stage,
                    write_access: access.write_part(),
                    visible_stage: S::NONE,
                    visible_access: A::NONE,
                    read_stage: S::NONE,
                };
            } else {
                // A read that transitions the layout: the transition is ordered before `access`.
                *self = State {
                    layout: access.layout,
                    write_stage: access.stage,
                    write_access: A::NONE,
                    visible_stage: access.stage,
                    visible_access: access.access,
                    read_stage: access.stage,
                };
            }
            return needed.then_some(t);
        }
        // Read after write, same layout: make the write visible once per stage/access.
        let covered = self.visible_stage.contains(access.stage) && self.visible_access.contains(access.access);
        self.read_stage |= access.stage;
        if self.write_stage.is_empty() || covered {
            return None;
        }
        t.src_stage = self.write_stage;
        t.src_access = self.write_access;
        self.visible_stage |= access.stage;
        self.visible_access |= access.access;
        Some(t)
    }
}

/// Subresource states of every live resource, keyed by the resource's id.
#[derive(Default)]
pub(crate) struct Tracker {
    states: HashMap<u64, Vec<State>>,
}

impl Tracker {
    pub fn register(&mut self, id: u64, subresources: usize) {
        self.states.insert(id, vec![State::default(); subresources.max(1)]);
    }
    pub fn forget(&mut self, id: u64) {
        self.states.remove(&id);
    }
    /// Applies `access` to the listed subresource indices; returns (index, transition) pairs.
    pub fn access(
        &mut self,
        id: u64,
        subs: impl Iterator<Item = usize>,
        access: Access,
        is_image: bool,
    ) -> Vec<(usize, Transition)> {
        let Some(states) = self.states.get_mut(&id) else { return vec![] };
        let mut out = vec![];
        for i in subs {
            if let Some(s) = states.get_mut(i) {
                if let Some(t) = s.apply(access, is_image) {
                    out.push((i, t));
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn read_after_write_needs_one_barrier_per_new_stage() {
        let mut s = State::default();
        let w = Access::COMPUTE_READ_WRITE;
        assert!(s.apply(w, false).is_none(), "first write of a fresh buffer waits for nothing");
        let t = s.apply(Access::SHADER_READ, false).expect("read after write needs a barrier");
        assert_eq!(t.src_stage, vk::PipelineStageFlags2::COMPUTE_SHADER);
        assert!(t.src_access.contains(vk::AccessFlags2::SHADER_STORAGE_WRITE));
        assert!(s.apply(Access::SHADER_READ, false).is_none(), "second identical read is covered");
        assert!(s.apply(Access::INDIRECT, false).is_some(), "a new stage needs visibility");
    }

    #[test]
    fn write_after_read_waits_for_readers_and_layouts_change() {
        let mut s = State::default();
        let t = s.apply(Access::COLOR_ATTACHMENT, true).expect("layout transition from UNDEFINED");
        assert_eq!(t.old_layout, L::UNDEFINED);
        assert_eq!(t.new_layout, L::COLOR_ATTACHMENT_OPTIMAL);
        let t = s.apply(Access::SHADER_READ, true).expect("transition to read");
        assert_eq!(t.new_layout, L::SHADER_READ_ONLY_OPTIMAL);
        assert!(t.src_access.contains(vk::AccessFlags2::COLOR_ATTACHMENT_WRITE));
        let t = s.apply(Access::COLOR_ATTACHMENT, true).expect("write after read");
        assert!(t.src_stage.intersects(vk::PipelineStageFlags2::FRAGMENT_SHADER));
    }
}
