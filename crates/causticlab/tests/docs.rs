//! The house rules a reader relies on: the README starts with the two commands and stays short
//! (the rest lives in `docs/`), its links lead somewhere, and only `vkcore` may say `unsafe`
//! (every other crate root forbids it, so the compiler keeps the rule; their test files say
//! no `unsafe` and no crate but vkcore depends on ash).

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

/// The workspace's member crates, from the root `Cargo.toml`.
fn member_crates() -> Vec<String> {
    let manifest: toml::Value = toml::from_str(&read(&repo().join("Cargo.toml"))).expect("Cargo.toml parses");
    let members = manifest["workspace"]["members"].as_array().expect("workspace.members");
    members.iter().map(|m| m.as_str().expect("a member path").to_string()).collect()
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The keyword, spelled apart so that this file does not say it.
const UNSAFE: &str = "unsafe";

#[test]
fn only_vkcore_may_say_unsafe_or_use_ash() {
    let members = member_crates();
    assert!(members.iter().any(|m| m == "crates/vkcore") && members.len() >= 4, "{members:?}");
    for member in members.iter().filter(|m| *m != "crates/vkcore") {
        let dir = repo().join(member);
        // The crate root forbids unsafe code (an attribute line, not a comment that mentions it).
        let root = ["src/lib.rs", "src/main.rs"].iter().map(|r| dir.join(r)).find(|p| p.is_file());
        let root = root.unwrap_or_else(|| panic!("{member}: no src/lib.rs or src/main.rs"));
        let forbids = read(&root).lines().any(|l| l.trim() == "#![forbid(unsafe_code)]");
        assert!(forbids, "{} does not forbid unsafe code", root.display());
        // Its integration tests, examples and benches are crates of their own: no unsafe block,
        // function, impl, trait or extern block in the code of any file (comments aside).
        let mut files = vec![];
        rust_files(&dir, &mut files);
        for f in files {
            for (n, line) in read(&f).lines().enumerate() {
                let code = line.split("//").next().unwrap_or("");
                let says =
                    [" {", " fn", " impl", " trait", " extern"].iter().any(|k| code.contains(&format!("{UNSAFE}{k}")));
                assert!(!says, "{}:{}: `unsafe` outside vkcore: {line}", f.display(), n + 1);
            }
        }
        // ash (and its window and UI glue) only through vkcore.
        let manifest: toml::Value = toml::from_str(&read(&dir.join("Cargo.toml"))).expect("a crate's Cargo.toml");
        for table in ["dependencies", "dev-dependencies", "build-dependencies"] {
            if let Some(deps) = manifest.get(table).and_then(|d| d.as_table()) {
                let ash: Vec<&String> = deps.keys().filter(|k| k.split('-').any(|w| w == "ash")).collect();
                assert!(ash.is_empty(), "{member}: [{table}] names {ash:?}: only vkcore calls ash");
            }
        }
    }
}
