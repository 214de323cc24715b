//! `scripts/new_technique.sh` (issue 50, item 5), run on a copy of the files it edits: what it
//! stamps for a new paper and for an existing one, and what it refuses. (That the first build
//! of a stamped tree then fails at each `match` over `Technique` without the new arm is the
//! compiler's part: docs/adding_a_technique.md shows that output.)

use std::path::{Path, PathBuf};
use std::process::Command;

/// The files the script edits, copied from the repository into a fresh tree.
const EDITED: &[&str] = &[
    "rustfmt.toml",
    "scripts/new_technique.sh",
    "crates/caustics/src/techniques/variants.rs",
    "crates/caustics/tests/common/mod.rs",
    "crates/caustics/src/techniques/technique.rs",
    "crates/caustics/src/techniques/mod.rs",
    "crates/caustics/src/techniques/variants.toml",
    "crates/caustics/src/techniques/wyman2008/mod.rs",
    "crates/caustics/tests/module_layers/main.rs",
    "crates/caustics/tests/module_layers/layers.rs",
];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tree(name: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("causticlab_new_technique_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    for f in EDITED {
        let to = root.join(f);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(repo().join(f), &to).unwrap_or_else(|e| panic!("{f}: {e}"));
    }
    std::fs::create_dir_all(root.join("shaders_glsl")).unwrap();
    root
}

fn stamp(root: &Path, args: &[&str]) -> (i32, String) {
    let out = Command::new("bash").arg(root.join("scripts/new_technique.sh")).args(args).output().expect("bash");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out.status.code().unwrap_or(-1), text)
}

fn read(root: &Path, f: &str) -> String {
    std::fs::read_to_string(root.join(f)).unwrap_or_else(|e| panic!("{f}: {e}"))
}

/// Every file of the tree with its contents (to show a refused run wrote nothing).
fn snapshot(root: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    fn walk(dir: &Path, out: &mut Vec<(PathBuf, Vec<u8>)>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else {
                out.push((p.clone(), std::fs::read(&p).unwrap()));
            }
        }
    }
    let mut out = vec![];
    walk(root, &mut out);
    out
}

/// The last `[[variant]]` of the registry.
fn last_row(root: &Path) -> toml::Table {
    let t: toml::Table = toml::from_str(&read(root, "crates/caustics/src/techniques/variants.toml")).expect("toml");
    let rows = t["variant"].as_array().expect("rows");
    rows.last().unwrap().as_table().unwrap().clone()
}

#[test]
fn a_new_paper_gets_its_folder_its_layer_its_variant_row_and_a_failing_test() {
    let root = tree("paper");
    let (code, out) = stamp(&root, &["my-splat", "smith2024"]);
    assert_eq!(code, 0, "{out}");
    let src = "crates/caustics/src/techniques";

    // The variant, inside the enum, before its end.
    let technique = read(&root, &format!("{src}/technique.rs"));
    let at = technique.find("        MySplat = \"my-splat\",\n").expect("the variant");
    let enum_at = technique.find("    pub enum Technique {").unwrap();
    let enum_end = enum_at + technique[enum_at..].find("\n    }\n").unwrap();
    assert!(enum_at < at && at < enum_end, "the variant is outside the enum");

    // The paper's folder, its module in order, its place in the layers.
    let module = read(&root, &format!("{src}/mod.rs"));
    assert!(module.contains("\npub mod smith2024;\n"), "{module}");
    assert_modules_in_order(&module);
    let paper_mod = read(&root, &format!("{src}/smith2024/mod.rs"));
    assert!(paper_mod.contains("pub mod my_splat;\npub mod settings;\n"), "{paper_mod}");
    let settings = read(&root, &format!("{src}/smith2024/settings.rs"));
    assert!(settings.contains("pub const PAPER: &str") && settings.contains("pub static DUMPS"));
    assert!(read(&root, "crates/caustics/tests/module_layers/main.rs").contains("\"techniques::smith2024\","));
    let layers = read(&root, "crates/caustics/tests/module_layers/layers.rs");
    assert!(words(papers(&layers)).contains("\"photon_trace\",\"smith2024\""), "{}", papers(&layers));
    let variants = read(&root, &format!("{src}/variants.rs"));
    assert!(words(papers(&variants)).ends_with("\"wyman_nichols2009\",\"smith2024\"]"), "{}", papers(&variants));

    // Its stage variant, shader, registry row and test.
    let stage = read(&root, &format!("{src}/smith2024/my_splat.rs"));
    assert!(stage.contains("pub struct MySplat") && stage.contains("\"smith2024/my_splat.comp\""));
    let sh = vkcore::ShaderCompiler::new(&root.join("shaders_glsl")).expect("shaderc");
    sh.compile("smith2024/my_splat.comp", &[]).expect("the stamped shader compiles");
    let row = last_row(&root);
    assert_eq!(row["name"].as_str(), Some("my-splat"));
    assert_eq!(row["paper"].as_str(), Some("smith2024"));
    assert_eq!(row["settings"]["technique"].as_str(), Some("my-splat"));
    assert_eq!(row["default"].as_bool(), Some(true));
    assert!(row["stated"]["rel_rmse"].as_float().is_some(), "the row states no accuracy");
    rustfmt_check(&root, &[&format!("{src}/technique.rs"), &format!("{src}/smith2024/mod.rs")]);
    rustfmt_check(&root, &["crates/caustics/tests/smith2024_my_splat.rs"]);

    // A second new paper, after the first (the lists now longer than one line allows).
    let (code, out) = stamp(&root, &["veach-splat", "veach1997"]);
    assert_eq!(code, 0, "{out}");
    let layers = read(&root, "crates/caustics/tests/module_layers/layers.rs");
    let list = papers(&layers);
    assert!(words(list).contains("\"photon_trace\",\"smith2024\",\"veach1997\""), "{list}");
    let variants = read(&root, &format!("{src}/variants.rs"));
    assert!(words(papers(&variants)).contains("\"smith2024\",\"veach1997\""), "{}", papers(&variants));
    assert!(read(&root, "crates/caustics/tests/module_layers/main.rs").contains("\"techniques::veach1997\","));
    assert_modules_in_order(&read(&root, &format!("{src}/mod.rs")));
    rustfmt_check(&root, &["crates/caustics/tests/module_layers/layers.rs", &format!("{src}/variants.rs")]);
    let test = read(&root, "crates/caustics/tests/smith2024_my_splat.rs");
    assert!(test.contains("\"my-splat\".parse()") && test.contains("assert!(power > 0.0"), "{test}");
    assert!(test.contains("p.starts_with(\"my_splat\")"), "the test does not ask for a pass of its own: {test}");
    let _ = std::fs::remove_dir_all(&root);
}

/// The `pub const PAPERS` list of a source file, from its `[` to its `]`.
fn papers(text: &str) -> &str {
    let at = text.find("pub const PAPERS").expect("a PAPERS list");
    let open = at + text[at..].find('[').unwrap() + 1;
    let open = open + text[open..].find('[').unwrap();
    &text[open..=open + text[open..].find(']').unwrap()]
}

/// `text` without its white space.
fn words(text: &str) -> String {
    text.split_whitespace().collect()
}

/// The module lines of `techniques/mod.rs` sorted by name, as rustfmt keeps them.
fn assert_modules_in_order(module: &str) {
    let names: Vec<&str> = module
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod ").or_else(|| l.strip_prefix("mod ")))
        .map(|m| m.trim_end_matches(';'))
        .collect();
    let mut sorted = names.clone();
    sorted.sort();
    assert_eq!(names, sorted, "techniques/mod.rs's modules out of order");
}

/// rustfmt (the project's rustfmt.toml) would leave `files` as the script wrote them.
fn rustfmt_check(root: &Path, files: &[&str]) {
    let out = Command::new("rustfmt")
        .current_dir(root)
        .args(["--check", "--edition", "2021"])
        .args(files)
        .output()
        .expect("rustfmt (rustup component add rustfmt)");
    assert!(out.status.success(), "rustfmt would change {files:?}:\n{}", String::from_utf8_lossy(&out.stdout));
}

#[test]
fn an_existing_paper_keeps_its_folder_and_its_claims_key() {
    let root = tree("existing");
    let before = read(&root, "crates/caustics/src/techniques/mod.rs");
    let (code, out) = stamp(&root, &["hcm-2", "wyman2008"]);
    assert_eq!(code, 0, "{out}");
    assert_eq!(read(&root, "crates/caustics/src/techniques/mod.rs"), before, "a module added for an existing paper");
    assert!(!root.join("crates/caustics/src/techniques/wyman2008/settings.rs").exists());
    assert!(read(&root, "crates/caustics/src/techniques/wyman2008/mod.rs").ends_with("pub mod hcm_2;\n"));
    assert!(read(&root, "crates/caustics/src/techniques/technique.rs").contains("        Hcm2 = \"hcm-2\",\n"));
    assert_eq!(last_row(&root)["paper"].as_str(), Some("wyman2008"));
    let (code, _) = stamp(&root, &["my-trace", "shah2007"]);
    assert_eq!(code, 0);
    assert_eq!(last_row(&root)["paper"].as_str(), Some("shah"), "shah2007's claims key");
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_bad_name_or_a_technique_already_there_is_refused_and_nothing_written() {
    let root = tree("refused");
    let before = snapshot(&root);
    let refused: [(&[&str], &str); 11] = [
        (&["hcm", "wyman2008"], "`hcm` is a technique already"),
        (&["shah-box", "shah2007"], "`shah-box` is a row of the registry already"),
        (&["my-splat", "technique"], "technique.rs is a module of the registry"),
        (&["type", "smith2024"], "`type` is a Rust keyword"),
        (&["my-splat", "crate"], "`crate` is a Rust keyword"),
        (&["photon-trace", "smith2024"], "`photon-trace` is a technique already"),
        (&["My-Splat", "smith2024"], "NAME `My-Splat`"),
        (&["my--splat", "smith2024"], "NAME `my--splat`"),
        (&["my-splat", "../x"], "PAPER `../x`"),
        (&["my-splat", "shared"], "PAPER `shared`"),
        (&["my-splat"], "usage"),
    ];
    for (args, says) in refused {
        let (code, out) = stamp(&root, args);
        assert_eq!(code, 2, "{args:?}: {out}");
        assert!(out.contains(says), "{args:?}: `{out}` does not say {says}");
        assert!(snapshot(&root) == before, "{args:?} wrote something");
    }
    let _ = std::fs::remove_dir_all(&root);
}
