//! vkcore's error type. Everything the driver or the user's input can make fail comes back as a
//! `VkError`; nothing in vkcore panics on a driver result.

use ash::vk;

#[derive(Debug, thiserror::Error)]
pub enum VkError {
    /// The Vulkan loader (libvulkan.so.1) could not be opened.
    #[error("could not load the Vulkan loader (libvulkan.so.1): {0}; install libvulkan1 and a driver (Debian: mesa-vulkan-drivers)")]
    Loader(String),
    /// A Vulkan call returned an error code.
    #[error("{call} failed: {result:?}")]
    Call { call: &'static str, result: vk::Result },
    /// `--device` matched nothing.
    #[error("no Vulkan device matches `{query}`; available devices: {available}")]
    NoDevice { query: String, available: String },
    /// `--device` matched devices of different names or drivers.
    #[error("--device `{query}` matches {count} different devices: {matches}; name one by index or by its driver (e.g. \"Mesa 25\")")]
    AmbiguousDevice { query: String, count: usize, matches: String },
    /// The chosen device lacks a feature something asked for.
    #[error("{who} needs the device feature `{feature}` ({vulkan_name}), which `{device}` does not report")]
    MissingFeature { who: String, feature: &'static str, vulkan_name: &'static str, device: String },
    /// The validation layer was asked for and is not installed.
    #[error("the Khronos validation layer (VK_LAYER_KHRONOS_validation) is not installed; Debian: apt-get install vulkan-validationlayers")]
    NoValidationLayer,
    /// GLSL failed to compile; `message` is `file:line: message` lines.
    #[error("shader compilation failed:\n{0}")]
    Shader(String),
    /// A shader file or include could not be read.
    #[error("reading shader `{path}`: {source}")]
    ShaderIo { path: String, source: std::io::Error },
    /// gpu-allocator failed (out of memory, no suitable memory type).
    #[error("allocating `{name}` ({bytes} bytes): {message}")]
    Alloc { name: String, bytes: u64, message: String },
    /// A submitted frame did not finish: its fence wait timed out or the device was lost. The
    /// crash marker says which passes had finished.
    #[error("{}", frame_failed(*.result, .last_finished, .next, .passes, .ring))]
    FrameFailed {
        result: vk::Result,
        last_finished: Option<String>,
        next: Option<String>,
        passes: Vec<String>,
        /// A ring frame: its number, its slot, and the last frame number the slot's crash marker
        /// says had finished (ring frames write it once, at their end).
        ring: Option<(u64, usize, Option<u64>)>,
    },
    /// A request that can never work (zero-sized image, size above the device limit, ...).
    #[error("{0}")]
    Invalid(String),
}

pub type Result<T> = std::result::Result<T, VkError>;

fn frame_failed(
    result: vk::Result,
    last: &Option<String>,
    next: &Option<String>,
    passes: &[String],
    ring: &Option<(u64, usize, Option<u64>)>,
) -> String {
    let what = if result == vk::Result::TIMEOUT { "the frame timed out" } else { "the frame failed" };
    if let Some((frame, slot, finished)) = ring {
        let before = match finished {
            Some(f) => format!("the last frame that finished in this slot was frame {f}"),
            None => "no earlier frame had finished in this slot".into(),
        };
        return format!(
            "frame {frame} (ring slot {slot}): {what} ({result:?}); {before}; the frame's {} passes: {}",
            passes.len(),
            passes.join(", ")
        );
    }
    let at = match (last, next) {
        (Some(l), Some(n)) => format!("the last pass that finished was `{l}`; the one after it, `{n}`, had not"),
        (None, Some(n)) => format!("no pass had finished, not even the first, `{n}`"),
        (Some(l), None) => format!("every pass had finished, the last `{l}`"),
        (None, None) => "the frame had no passes".into(),
    };
    format!("vkWaitForFences: {result:?}: {what}; {at} (the frame held: {})", passes.join(", "))
}

/// Maps an `ash` result into a `VkError` naming the call.
pub(crate) trait VkResultExt<T> {
    fn call(self, call: &'static str) -> Result<T>;
}

impl<T> VkResultExt<T> for std::result::Result<T, vk::Result> {
    fn call(self, call: &'static str) -> Result<T> {
        self.map_err(|result| VkError::Call { call, result })
    }
}
