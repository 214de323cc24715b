//! The house rules a reader relies on: the README starts with the two commands and stays short
//! (the rest lives in `docs/`), its links lead somewhere, and only `vkcore` may say `unsafe`
//! (every other crate root forbids it, so the compiler keeps the rule).

use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The README's limit: past it, a section belongs in `docs/`.
const README_LINES: usize = 150;

#[test]
fn the_readme_starts_with_the_two_commands_and_stays_short() {
    let readme = read(&repo().join("README.md"));
    let lines = readme.lines().count();
    assert!(lines < README_LINES, "README.md has {lines} lines; move sections to docs/ (limit {README_LINES})");
    let block: Vec<&str> = readme.lines().skip_while(|l| !l.starts_with("```")).skip(1).take(2).collect();
    assert!(block.first().is_some_and(|l| l.starts_with("bash scripts/demo.sh")), "first command: {block:?}");
    assert!(block.get(1).is_some_and(|l| l.starts_with("bash scripts/test.sh")), "second command: {block:?}");
}

#[test]
fn the_readmes_links_to_files_lead_somewhere() {
    let readme = read(&repo().join("README.md"));
    let mut missing = vec![];
    for piece in readme.split("](").skip(1) {
        let target = piece.split(')').next().unwrap_or("");
        if target.starts_with("http") || target.starts_with('#') || target.is_empty() {
            continue;
        }
        if !repo().join(target).exists() {
            missing.push(target.to_string());
        }
    }
    assert!(missing.is_empty(), "README.md links to missing files: {missing:?}");
}

#[test]
fn only_vkcore_may_say_unsafe() {
    for root in ["crates/caustics/src/lib.rs", "crates/bench/src/lib.rs", "crates/causticlab/src/main.rs"] {
        let text = read(&repo().join(root));
        assert!(text.contains("#![forbid(unsafe_code)]"), "{root} does not forbid unsafe code");
    }
}
