//! Query pools a technique reads itself: transform-feedback primitive counts (primitives
//! written and needed, stream 0) and occlusion-style counters.

use crate::context::{Context, Shared};
use crate::error::{Result, VkResultExt};
use ash::vk;
use std::sync::Arc;

pub struct QueryPool {
    shared: Arc<Shared>,
    pub(crate) raw: vk::QueryPool,
    kind: vk::QueryType,
    count: u32,
}

impl QueryPool {
    /// `count` transform-feedback stream queries (needs transformFeedbackQueries).
    pub fn transform_feedback(ctx: &Context, count: u32) -> Result<QueryPool> {
        ctx.require("transform-feedback queries", &[crate::Feature::TransformFeedbackQueries])?;
        Self::new(ctx, vk::QueryType::TRANSFORM_FEEDBACK_STREAM_EXT, count)
    }

    fn new(ctx: &Context, kind: vk::QueryType, count: u32) -> Result<QueryPool> {
        let info = vk::QueryPoolCreateInfo::default().query_type(kind).query_count(count);
        let d = ctx.shared.raw();
        let raw = unsafe { d.create_query_pool(&info, None) }.call("vkCreateQueryPool")?;
        ctx.shared.counters.object(1);
        unsafe { d.reset_query_pool(raw, 0, count) };
        Ok(QueryPool { shared: ctx.shared.clone(), raw, kind, count })
    }

    pub(crate) fn is_xfb(&self) -> bool {
        self.kind == vk::QueryType::TRANSFORM_FEEDBACK_STREAM_EXT
    }

    /// Resets every query from the host (before reuse in a new frame).
    pub fn reset(&self) {
        unsafe { self.shared.raw().reset_query_pool(self.raw, 0, self.count) };
    }

    /// For xfb pools: (primitives written, primitives needed) per query; waits for results.
    pub fn read_xfb(&self) -> Result<Vec<(u64, u64)>> {
        let mut raw = vec![[0u64; 2]; self.count as usize];
        unsafe {
            self.shared.raw().get_query_pool_results(
                self.raw,
                0,
                &mut raw,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .call("vkGetQueryPoolResults(transform feedback)")?;
        Ok(raw.iter().map(|c| (c[0], c[1])).collect())
    }
}

impl Drop for QueryPool {
    fn drop(&mut self) {
        unsafe { self.shared.raw().destroy_query_pool(self.raw, None) };
    }
}
