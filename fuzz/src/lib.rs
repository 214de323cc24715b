//! Fuzz targets for causticlab's readers of user files (README.md). The property is in
//! `check.rs`, which the replay test shares.

pub mod check;

use std::path::PathBuf;

/// The folder this process fuzzes in (one per process: AFL may run several), prepared once.
pub fn fuzz_root() -> PathBuf {
    let root = std::env::temp_dir().join(format!("causticlab-fuzz-{}", std::process::id()));
    let repo = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    check::prepare(&root, &repo).expect("preparing the fuzzing folder");
    root
}

/// The body of every target: the property holds, or the process panics (a crash for AFL).
pub fn run(target: check::Target, root: &std::path::Path, bytes: &[u8]) {
    if let Err(e) = check::check(target, root, bytes) {
        panic!("{}: {e}", target.name());
    }
}
