//! Replays what the fuzzers found and kept (fuzz/README.md) through the property they check
//! (`fuzz/src/check.rs`, included here): every reader of user files returns `Ok` or an error
//! naming the file, without panicking, within a deadline. The inputs: each finding, committed
//! as a small file under `tests/fuzz_regressions/<target>/`, and each target's minimized corpus
//! under `fuzz/corpus/<target>/`, where one has been committed.

#[path = "../../../fuzz/src/check.rs"]
mod check;

use check::Target;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// The fuzzer's hang limit (scripts/fuzz.sh); a debug build is slower, so twice that here.
const DEADLINE: Duration = Duration::from_secs(20);

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn inputs(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = match std::fs::read_dir(dir) {
        Ok(d) => d.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect(),
        Err(_) => vec![],
    };
    v.retain(|p| p.file_name().and_then(|n| n.to_str()).is_some_and(|n| !n.starts_with('.') && n != "README.md"));
    v.sort();
    v
}

/// Runs one input in a thread of its own: Err says what went wrong (property, panic, deadline).
fn replay(target: Target, root: &Path, input: &Path) -> Result<(), String> {
    let bytes = std::fs::read(input).map_err(|e| format!("reading {}: {e}", input.display()))?;
    let root = root.to_path_buf();
    let (tx, rx) = mpsc::channel();
    let worker = std::thread::spawn(move || {
        let r = check::check(target, &root, &bytes);
        let _ = tx.send(r);
    });
    match rx.recv_timeout(DEADLINE) {
        Ok(r) => r,
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            let why = worker.join().err().and_then(|p| {
                p.downcast_ref::<String>().cloned().or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            });
            Err(format!("panicked: {}", why.unwrap_or_default()))
        }
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!("took over {DEADLINE:?}")),
    }
}

#[test]
fn every_finding_and_corpus_input_is_read_or_refused_by_name() {
    let mut failures = vec![];
    let mut replayed = 0;
    for target in Target::ALL {
        let root = caustics::scratch::ScratchDir::new("causticlab-fuzz-replay", target.name());
        check::prepare(&root, &repo()).expect("preparing the replay folder");
        let dirs = [
            repo().join("crates/causticlab/tests/fuzz_regressions").join(target.name()),
            repo().join("fuzz/corpus").join(target.name()),
        ];
        for input in dirs.iter().flat_map(|d| inputs(d)) {
            replayed += 1;
            if let Err(e) = replay(target, &root, &input) {
                failures.push(format!("{} ({}): {e}", input.display(), target.name()));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {replayed} inputs broke the property:\n{}",
        failures.len(),
        failures.join("\n")
    );
    // Every target has its findings folder, so that a target cannot silently replay nothing.
    for target in Target::ALL {
        let dir = repo().join("crates/causticlab/tests/fuzz_regressions").join(target.name());
        assert!(!inputs(&dir).is_empty(), "{}: no inputs to replay", dir.display());
    }
}

/// The property can fail: an error that does not name the file breaks it; one that names it,
/// and `Ok`, keep it. And the real readers keep it on a shipped scene and on garbage.
#[test]
fn the_property_fails_on_an_error_that_names_no_file() {
    let file = Path::new("/tmp/x/scene.toml");
    assert!(check::holds(file, Err(anyhow::anyhow!("key `camera`: bad"))).is_err());
    assert_eq!(check::holds(file, Err(anyhow::anyhow!("/tmp/x/scene.toml: key `camera`: bad"))), Ok(()));
    assert_eq!(check::holds(file, Ok(())), Ok(()));
    let root = caustics::scratch::ScratchDir::new("causticlab", "fuzz-self");
    check::prepare(&root, &repo()).expect("prepare");
    let scene = std::fs::read(repo().join("scenes/sphere_on_plane.toml")).expect("shipped scene");
    assert_eq!(check::check(Target::Scene, &root, &scene), Ok(()));
    assert_eq!(check::check(Target::Scene, &root, b"[camera\n"), Ok(()));
    assert_eq!(check::check(Target::Exr, &root, b"not an exr"), Ok(()));
}

/// The fuzzed scenes read stand-ins for the shipped scenes' models (`check::prepare`); a scene
/// naming a model not on that list would load the real one, a second per input.
#[test]
fn the_stand_in_models_are_the_ones_the_shipped_scenes_name() {
    let mut named = std::collections::BTreeSet::new();
    for e in std::fs::read_dir(repo().join("scenes")).expect("scenes/") {
        let path = e.expect("entry").path();
        if path.extension().is_some_and(|x| x == "toml") {
            let text = std::fs::read_to_string(&path).expect("scene");
            for piece in text.split('"').filter(|p| p.ends_with(".obj") && !p.contains(' ')) {
                named.insert(piece.to_string());
            }
        }
    }
    let stand_ins: std::collections::BTreeSet<String> = check::STAND_IN_MODELS.iter().map(|s| s.to_string()).collect();
    assert_eq!(stand_ins, named);
}
