//! Helpers shared by the binary's integration tests: run `causticlab`, scratch directories,
//! channel lookup in EXR files.
#![allow(dead_code)]

pub mod bench;

use caustics::image_io::ImageF32;
pub use caustics::scratch::ScratchDir as Scratch;
use std::path::{Path, PathBuf};
use std::process::Command;

pub struct Run {
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    pub fn describe(&self) -> String {
        format!("exit code {:?}\n--- stdout ---\n{}\n--- stderr ---\n{}", self.code, self.stdout, self.stderr)
    }
}

pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

pub fn scene(stem: &str) -> String {
    workspace().join("scenes").join(format!("{stem}.toml")).display().to_string()
}

pub fn causticlab<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_causticlab"))
        .args(args)
        .current_dir(workspace())
        .env_remove("VK_LOADER_DEBUG")
        .output()
        .expect("running the causticlab binary");
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// A fresh, empty directory under the system temp dir, unique to this process and call; removed
/// when dropped, unless the test is panicking (a failed test leaves its files to look at).
pub fn scratch(name: &str) -> Scratch {
    Scratch::new("causticlab-cli", name)
}

/// (layer, channel) of `want`, matched as the full `layer.channel` name first, then by channel.
pub fn find_channel(img: &ImageF32, want: &str) -> Option<(usize, usize)> {
    let full = |l: usize, c: &str| match &img.layers[l].name {
        Some(n) => format!("{n}.{c}"),
        None => c.to_string(),
    };
    for (li, layer) in img.layers.iter().enumerate() {
        if let Some(ci) = layer.channels.iter().position(|c| full(li, c) == want) {
            return Some((li, ci));
        }
    }
    for (li, layer) in img.layers.iter().enumerate() {
        if let Some(ci) = layer.channels.iter().position(|c| c == want) {
            return Some((li, ci));
        }
    }
    None
}

pub fn value(img: &ImageF32, ch: (usize, usize), i: u32, j: u32) -> f64 {
    img.layers[ch.0].sample(img.width, i, j, ch.1) as f64
}
