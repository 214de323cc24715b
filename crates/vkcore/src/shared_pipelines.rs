//! Pipelines shared between identical descriptions. Asking for a pipeline whose name, SPIR-V
//! and fixed-function state equal those of a live one returns that one: no second
//! `vkCreate*Pipelines`. This is what makes shader hot reload cheap: the viewer builds its
//! renderers again after an edit while the old ones still run, and only the pipelines whose
//! SPIR-V the edit changed are made; every other one is the running pipeline, shared. A pipeline
//! is destroyed when the last [`crate::Pipeline`] holding it goes; the table keeps only weak
//! references.

use crate::error::Result;
use crate::pipeline::{Blend, Built, Cull, Topology, VertexLayout};
use crate::shader::Stage;
use ash::vk;
use std::collections::{HashMap, VecDeque};
use std::sync::{Arc, Mutex, Weak};

/// The fixed-function state of a graphics pipeline (`GraphicsDesc` without its shaders).
pub(crate) type GraphicsState =
    (Option<VertexLayout>, Topology, Cull, Vec<vk::Format>, Blend, Option<vk::Format>, bool, bool, bool, u32);

/// Everything a pipeline is made from: equal keys make equal pipelines.
#[derive(PartialEq, Eq, Hash)]
pub(crate) struct Key {
    pub name: String,
    /// Each stage's SPIR-V words (compared by content).
    pub stages: Vec<(Stage, Arc<Vec<u32>>)>,
    /// `None` for a compute pipeline.
    pub state: Option<GraphicsState>,
}

#[derive(Default)]
pub(crate) struct SharedPipelines {
    live: Mutex<HashMap<Key, Weak<Built>>>,
    /// How many pipelines were made, and the names of the last `NAMES_KEPT` (what a reload
    /// reports), oldest first.
    made: Mutex<(usize, VecDeque<String>)>,
}

/// Names of made pipelines kept for [`SharedPipelines::made_since`].
const NAMES_KEPT: usize = 1024;

impl SharedPipelines {
    /// The live pipeline of `key`, or a new one from `make`. The table is not locked while
    /// `make` runs: two threads asking at once for one key may both make it (both are valid).
    pub fn get_or_make(&self, key: Key, make: impl FnOnce() -> Result<Built>) -> Result<Arc<Built>> {
        if let Some(p) = self.live.lock().ok().and_then(|live| live.get(&key).and_then(Weak::upgrade)) {
            return Ok(p);
        }
        let name = key.name.clone();
        let p = Arc::new(make()?);
        if let Ok(mut live) = self.live.lock() {
            live.retain(|_, w| w.strong_count() > 0);
            live.insert(key, Arc::downgrade(&p));
        }
        if let Ok(mut made) = self.made.lock() {
            made.0 += 1;
            made.1.push_back(name);
            if made.1.len() > NAMES_KEPT {
                made.1.pop_front();
            }
        }
        Ok(p)
    }

    /// How many pipelines were made so far.
    pub fn made_count(&self) -> usize {
        self.made.lock().map(|m| m.0).unwrap_or(0)
    }

    /// The names of the pipelines made after the first `from` (the last `NAMES_KEPT` of them).
    pub fn made_since(&self, from: usize) -> Vec<String> {
        let Ok(m) = self.made.lock() else { return vec![] };
        let first_kept = m.0 - m.1.len();
        m.1.iter().skip(from.saturating_sub(first_kept)).cloned().collect()
    }
}
