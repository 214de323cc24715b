//! The Vulkan instance, with optional Khronos validation (synchronization validation on) and a
//! debug-utils messenger that counts every warning and error it sees.

use crate::error::{Result, VkError, VkResultExt};
use ash::{ext, vk};
use std::ffi::{c_void, CStr};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex};

const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// Counts the messages the debug messenger received. Shared with the messenger callback.
#[derive(Default)]
pub struct ValidationLog {
    warnings: AtomicU32,
    errors: AtomicU32,
    messages: Mutex<Vec<String>>,
    /// Print each message to stderr as it arrives (`--validate`).
    pub echo: bool,
}

impl ValidationLog {
    /// Warnings and errors reported so far (performance warnings included).
    pub fn count(&self) -> u32 {
        self.warnings.load(Ordering::SeqCst) + self.errors.load(Ordering::SeqCst)
    }
    pub fn errors(&self) -> u32 {
        self.errors.load(Ordering::SeqCst)
    }
    /// Every message received so far, `[severity] text`.
    pub fn messages(&self) -> Vec<String> {
        self.messages.lock().map(|m| m.clone()).unwrap_or_default()
    }
    fn record(&self, severity: vk::DebugUtilsMessageSeverityFlagsEXT, text: String) {
        let tag = if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::ERROR) {
            self.errors.fetch_add(1, Ordering::SeqCst);
            "error"
        } else {
            self.warnings.fetch_add(1, Ordering::SeqCst);
            "warning"
        };
        let line = format!("[validation {tag}] {text}");
        if self.echo {
            eprintln!("{line}");
        }
        if let Ok(mut m) = self.messages.lock() {
            m.push(line);
        }
    }
}

unsafe extern "system" fn debug_callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    _types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    if data.is_null() || user.is_null() {
        return vk::FALSE;
    }
    let log = &*(user as *const ValidationLog);
    let data = &*data;
    let text = if data.p_message.is_null() {
        String::from("(no message)")
    } else {
        CStr::from_ptr(data.p_message).to_string_lossy().into_owned()
    };
    log.record(severity, text);
    vk::FALSE
}

pub(crate) struct InstanceShared {
    /// Keeps the loader library loaded while the instance lives.
    #[allow(dead_code)]
    pub entry: ash::Entry,
    pub raw: ash::Instance,
    pub debug_utils: Option<ext::debug_utils::Instance>,
    messenger: vk::DebugUtilsMessengerEXT,
    pub log: Arc<ValidationLog>,
    pub validation: bool,
}

impl Drop for InstanceShared {
    fn drop(&mut self) {
        unsafe {
            if let Some(du) = &self.debug_utils {
                if self.messenger != vk::DebugUtilsMessengerEXT::null() {
                    du.destroy_debug_utils_messenger(self.messenger, None);
                }
            }
            self.raw.destroy_instance(None);
        }
    }
}

/// A Vulkan instance. Cheap to clone (shared).
#[derive(Clone)]
pub struct Instance {
    pub(crate) shared: Arc<InstanceShared>,
}

impl Instance {
    /// Creates the instance. With `validation`, enables VK_LAYER_KHRONOS_validation with
    /// synchronization validation and fails if the layer is missing; with `echo`, every
    /// message is printed to stderr as it arrives.
    pub fn new(validation: bool, echo: bool) -> Result<Instance> {
        Instance::with_extensions(validation, echo, &[])
    }

    /// [`Instance::new`] with the instance extensions in `extra` enabled too (a window's
    /// surface extensions: `crate::window`); a missing one fails naming it.
    pub(crate) fn with_extensions(validation: bool, echo: bool, extra: &[*const std::ffi::c_char]) -> Result<Instance> {
        let entry = unsafe { ash::Entry::load() }.map_err(|e| VkError::Loader(e.to_string()))?;
        let layers_avail =
            unsafe { entry.enumerate_instance_layer_properties() }.call("vkEnumerateInstanceLayerProperties")?;
        let exts_avail = unsafe { entry.enumerate_instance_extension_properties(None) }
            .call("vkEnumerateInstanceExtensionProperties")?;
        let has_layer = layers_avail.iter().any(|l| l.layer_name_as_c_str().ok() == Some(VALIDATION_LAYER));
        if validation && !has_layer {
            return Err(VkError::NoValidationLayer);
        }
        let has_debug_utils =
            exts_avail.iter().any(|e| e.extension_name_as_c_str().ok() == Some(ext::debug_utils::NAME));

        let app = vk::ApplicationInfo::default()
            .application_name(c"causticlab")
            .engine_name(c"vkcore")
            .api_version(vk::API_VERSION_1_3);
        let layers = if validation { vec![VALIDATION_LAYER.as_ptr()] } else { vec![] };
        let mut exts = vec![];
        if has_debug_utils {
            exts.push(ext::debug_utils::NAME.as_ptr());
        }
        for &e in extra {
            // The pointers are ash's extension-name constants (NUL-terminated, static).
            let name = unsafe { CStr::from_ptr(e) };
            if !exts_avail.iter().any(|a| a.extension_name_as_c_str().ok() == Some(name)) {
                return Err(VkError::Invalid(format!(
                    "the Vulkan loader has no instance extension {} (needed to show a window)",
                    name.to_string_lossy()
                )));
            }
            exts.push(e);
        }
        let log = Arc::new(ValidationLog { echo, ..Default::default() });
        let severity = vk::DebugUtilsMessageSeverityFlagsEXT::WARNING | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR;
        let types = vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
            | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
            | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE;
        let mut messenger_info = vk::DebugUtilsMessengerCreateInfoEXT::default()
            .message_severity(severity)
            .message_type(types)
            .pfn_user_callback(Some(debug_callback))
            .user_data(Arc::as_ptr(&log) as *mut c_void);
        let enables = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
        let mut features = vk::ValidationFeaturesEXT::default().enabled_validation_features(&enables);
        let mut info = vk::InstanceCreateInfo::default()
            .application_info(&app)
            .enabled_layer_names(&layers)
            .enabled_extension_names(&exts);
        if validation {
            info = info.push_next(&mut features);
            if has_debug_utils {
                // Also catches messages from vkCreateInstance/vkDestroyInstance themselves.
                info = info.push_next(&mut messenger_info);
            }
        }
        let raw = unsafe { entry.create_instance(&info, None) }.call("vkCreateInstance")?;
        let debug_utils = has_debug_utils.then(|| ext::debug_utils::Instance::new(&entry, &raw));
        let mut messenger = vk::DebugUtilsMessengerEXT::null();
        if let (true, Some(du)) = (validation, &debug_utils) {
            let info = vk::DebugUtilsMessengerCreateInfoEXT::default()
                .message_severity(severity)
                .message_type(types)
                .pfn_user_callback(Some(debug_callback))
                .user_data(Arc::as_ptr(&log) as *mut c_void);
            messenger = match unsafe { du.create_debug_utils_messenger(&info, None) } {
                Ok(m) => m,
                Err(result) => {
                    unsafe { raw.destroy_instance(None) };
                    return Err(VkError::Call { call: "vkCreateDebugUtilsMessengerEXT", result });
                }
            };
        }
        Ok(Instance { shared: Arc::new(InstanceShared { entry, raw, debug_utils, messenger, log, validation }) })
    }

    /// The messenger's counters (all zero when validation is off).
    pub fn validation_log(&self) -> Arc<ValidationLog> {
        self.shared.log.clone()
    }

    pub fn validation_enabled(&self) -> bool {
        self.shared.validation
    }
}
