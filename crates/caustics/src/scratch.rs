//! Scratch directories for tests (this crate's, `bench`'s and the binary's): a fresh, empty
//! directory under the system temp dir, removed when its [`ScratchDir`] is dropped, unless the
//! thread is panicking, so that a failed test leaves its files to look at.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// A path in a scratch directory that lives as long as this value (see the module).
#[derive(Debug)]
pub struct ScratchDir {
    root: PathBuf,
    path: PathBuf,
}

impl ScratchDir {
    /// `<temp>/<prefix>-<tag>-<pid>-<n>`, emptied and created; `n` counts the calls in this process.
    pub fn new(prefix: &str, tag: &str) -> ScratchDir {
        static N: AtomicU32 = AtomicU32::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        let root = std::env::temp_dir().join(format!("{prefix}-{tag}-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap_or_else(|e| panic!("creating {}: {e}", root.display()));
        ScratchDir { path: root.clone(), root }
    }

    /// `rel` inside this directory (not created), still owning the whole directory: for a helper
    /// that returns an output folder or a file it wrote there.
    pub fn within(mut self, rel: impl AsRef<Path>) -> ScratchDir {
        self.path = self.path.join(rel);
        self
    }
}

impl std::ops::Deref for ScratchDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for ScratchDir {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<std::ffi::OsStr> for ScratchDir {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.path.as_os_str()
    }
}

impl Drop for ScratchDir {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.root);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removed_on_drop_kept_on_panic() {
        let dir = ScratchDir::new("causticlab-scratch", "drop").within("out");
        std::fs::create_dir_all(&*dir).unwrap();
        let root = dir.parent().unwrap().to_path_buf();
        assert!(root.is_dir() && dir.ends_with("out"));
        drop(dir);
        assert!(!root.exists(), "{} left behind", root.display());

        let dir = ScratchDir::new("causticlab-scratch", "panic");
        let kept = dir.to_path_buf();
        let thread = std::thread::spawn(move || {
            let _dir = dir;
            panic!("(expected: a test that fails keeps its scratch directory)");
        });
        assert!(thread.join().is_err());
        assert!(kept.is_dir(), "a panicking test's directory was removed");
        std::fs::remove_dir_all(&kept).unwrap();
    }
}
