//! Errors that are the user's to fix (bad scene file, unknown key, missing model, absurd size,
//! unknown device, a technique the device cannot run). The binary maps them to exit code 2.

use std::fmt;

/// A problem with the user's input. The message names the file, the key and what was expected.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputError(pub String);

impl InputError {
    pub fn new(message: impl Into<String>) -> Self {
        Self(message.into())
    }
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

/// Shorthand: `Err(input_error!("{}: key `x`: ...", path))`.
#[macro_export]
macro_rules! input_error {
    ($($arg:tt)*) => { $crate::error::InputError(format!($($arg)*)) };
}
