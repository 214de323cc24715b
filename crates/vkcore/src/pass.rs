//! The pass builder: `frame.pass(name).bind(&pipeline, binds).uses(..).record(|cmd| ..)`.
//! Every descriptor is named once: its barrier comes from its kind and the pipeline's bind
//! point (see `Bind`), and the pipeline and descriptors are bound at the start of the pass.
//! `uses` declares what no descriptor covers: attachments, vertex and index buffers, indirect
//! arguments, transfers, transform feedback.

use crate::bind::{check_binds, Named};
use crate::error::{Result, VkError};
use crate::frame::{Frame, Use};
use crate::pipeline::Pipeline;
use crate::recorder::Cmd;

/// One pass being described; nothing is recorded until [`Pass::record`].
pub struct Pass<'f, 'a> {
    frame: &'f mut Frame,
    name: String,
    bound: Option<(&'a Pipeline, Vec<Named<'a>>)>,
    uses: Vec<Use<'a>>,
    error: Option<VkError>,
}

impl<'f, 'a> Pass<'f, 'a> {
    pub(crate) fn new(frame: &'f mut Frame, name: &str) -> Self {
        Pass { frame, name: name.to_string(), bound: None, uses: vec![], error: None }
    }

    fn fail(&mut self, e: VkError) {
        if self.error.is_none() {
            self.error = Some(VkError::Invalid(format!("pass `{}`: {e}", self.name)));
        }
    }

    /// The pipeline the pass runs and its descriptors, each under its shader's name for the
    /// binding, in binding order (checked: `bind.rs`): both are bound before `record` runs
    /// (outside any rendering scope; the state carries into it), and each descriptor's barrier
    /// is declared. At most once per pass.
    pub fn bind(mut self, pipeline: &'a Pipeline, binds: impl IntoIterator<Item = Named<'a>>) -> Self {
        let binds: Vec<Named<'a>> = binds.into_iter().collect();
        if self.bound.is_some() {
            self.fail(VkError::Invalid("bind() given twice".into()));
        } else if let Err(e) = check_binds(&pipeline.name, pipeline.bindings(), &binds) {
            self.fail(e);
        } else {
            self.uses.extend(binds.iter().map(|(_, b)| b.to_use(pipeline.built.bind_point)));
            self.bound = Some((pipeline, binds));
        }
        self
    }

    /// The barriers of a descriptor set that `record` pushes itself with `Cmd::bind` (passes
    /// that rebind per draw, e.g. one set per mesh). Declare each set once.
    pub fn declare(mut self, pipeline: &Pipeline, binds: &[Named<'a>]) -> Self {
        match check_binds(&pipeline.name, pipeline.bindings(), binds) {
            Ok(()) => self.uses.extend(binds.iter().map(|(_, b)| b.to_use(pipeline.built.bind_point))),
            Err(e) => self.fail(e),
        }
        self
    }

    /// Accesses that are not descriptors.
    pub fn uses(mut self, uses: impl IntoIterator<Item = Use<'a>>) -> Self {
        self.uses.extend(uses);
        self
    }

    /// Records the pass: its barriers, a label, timestamps and statistics around the bound
    /// pipeline and descriptors and whatever `record` does.
    pub fn record<F>(self, record: F) -> Result<()>
    where
        F: FnOnce(&mut Cmd) -> Result<()>,
    {
        let Pass { frame, name, bound, uses, error } = self;
        if let Some(e) = error {
            return Err(e);
        }
        frame.record_pass(&name, &uses, |cmd| {
            if let Some((pipeline, binds)) = &bound {
                cmd.bind_pipeline(pipeline);
                cmd.push_descriptors(binds)?;
            }
            record(cmd)
        })
    }
}
