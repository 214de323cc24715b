//! The module layers of `caustics` (issue 26, item 6), checked on the source rather than by
//! reading it:
//! - no cycle between its parts: the top-level modules (`render`, `scene`, `gpu`, ...), the
//!   techniques' registry (`techniques/{mod,uniforms}.rs`, `techniques/stages/`), each paper's folder, `shared`, and
//!   the settings layer (every `settings.rs`, `technique.rs`, `value_enum.rs`, and the pure
//!   arithmetic their validation runs: what a scene file names, below `scene`, so that the scene
//!   description does not depend on the passes);
//! - no paper imports another paper, and `techniques/shared` imports no paper.
//!
//! A dependency is any `crate::`/`super::` path in code that is not a test (`#[cfg(test)]` items
//! and test modules are left out), including uses through a module imported by `use`. Items
//! must be named by the module that defines them: a re-export in `techniques/mod.rs` belongs
//! to the registry.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

mod layers;

#[test]
fn caustics_has_no_module_cycle_and_no_paper_imports_another() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = layers::read_tree(&src);
    assert!(files.len() > 50, "read only {} files under {}", files.len(), src.display());
    let deps = layers::dependencies(&files);
    // The check sees the dependencies the layers are built on (so it is not vacuous).
    for (from, to) in [("render", "techniques"), ("techniques", "techniques::wyman2008"), ("scene", "settings")] {
        assert!(deps.iter().any(|d| d.from == from && d.to == to), "no dependency {from} -> {to} found");
    }
    let mut problems = layers::problems(&deps);
    problems.extend(layers::out_of_order(&deps, LAYERS));
    assert!(problems.is_empty(), "module layers of caustics:\n{}", problems.join("\n"));
}

/// The parts from the bottom up (`docs/architecture.md`): each imports only parts of lower
/// layers. The papers share a layer (and import no other paper).
const LAYERS: &[&[&str]] = &[
    &["error", "workers"],
    &["image_io", "bvh"],
    // FLIP below compare, which reports it; a dump's declaration checks an image.
    &["flip", "dump"],
    &["compare", "diff", "error_png", "settings"],
    &["scene"],
    &["animation", "reference", "gpu"],
    &["techniques::shared"],
    &[
        "techniques::shah2007",
        "techniques::trendall_stewart2000",
        "techniques::wyman2008",
        "techniques::wyman_davis2006",
        "techniques::wyman_nichols2009",
        // Beyond the papers: a technique folder like theirs.
        "techniques::photon_trace",
    ],
    &["techniques"],
    &["render"],
    // The reference final image: the eye render of exact photons (`render` with photon-trace).
    &["final_reference"],
];

#[test]
fn an_import_from_a_higher_layer_or_an_unplaced_part_is_reported() {
    let files = tree(&[
        ("lib.rs", "pub mod scene;\npub mod render;\npub mod extra;\n"),
        ("scene/mod.rs", "use crate::render::Frame;\n"),
        ("render/mod.rs", "pub struct Frame;\n"),
        ("extra.rs", "use crate::scene::Scene;\n"),
    ]);
    let all = layers::out_of_order(&layers::dependencies(&files), &[&["scene"], &["render"]]).join("\n");
    assert!(all.contains("scene/mod.rs:1: scene imports render, a higher layer"), "{all}");
    assert!(all.contains("extra.rs:1: extra is in no layer"), "{all}");
}

fn tree(files: &[(&str, &str)]) -> BTreeMap<String, String> {
    files.iter().map(|(p, s)| (p.to_string(), s.to_string())).collect()
}

#[test]
fn a_cycle_between_two_modules_is_reported_with_both_edges() {
    let files = tree(&[
        ("lib.rs", "pub mod scene;\npub mod render;\n"),
        ("scene/mod.rs", "use crate::render::Frame;\n"),
        ("render/mod.rs", "pub struct Frame;\nfn f(s: &crate::scene::Scene) {}\n"),
    ]);
    let problems = layers::problems(&layers::dependencies(&files));
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(problems[0].contains("cycle"), "{}", problems[0]);
    assert!(problems[0].contains("scene/mod.rs:1"), "{}", problems[0]);
    assert!(problems[0].contains("render/mod.rs:2"), "{}", problems[0]);
}

#[test]
fn a_paper_importing_another_paper_is_reported_even_through_a_module_alias() {
    let files = tree(&[
        ("techniques/mod.rs", "pub mod wyman2008;\npub mod wyman_nichols2009;\npub mod shared;\n"),
        ("techniques/wyman2008/mod.rs", "pub mod settings;\n"),
        ("techniques/wyman2008/settings.rs", "pub enum TraversalPath {}\n"),
        ("techniques/shared/mod.rs", "use super::wyman_nichols2009;\nconst N: usize = wyman_nichols2009::N;\n"),
        (
            "techniques/wyman_nichols2009/mod.rs",
            "pub const N: usize = 1;\n// crate::techniques::wyman2008 in a comment\nuse super::wyman2008::settings::TraversalPath;\n",
        ),
    ]);
    let problems = layers::problems(&layers::dependencies(&files));
    let all = problems.join("\n");
    assert!(all.contains("techniques/wyman_nichols2009/mod.rs:3") && all.contains("another paper"), "{all}");
    assert!(all.contains("techniques/shared/mod.rs:2") && all.contains("shared imports"), "{all}");
    assert!(!all.contains("wyman_nichols2009/mod.rs:2"), "a comment was read: {all}");
}

#[test]
fn test_code_and_strings_are_not_dependencies() {
    let files = tree(&[
        ("lib.rs", "pub mod scene;\npub mod render;\n"),
        ("scene/mod.rs", "const S: &str = \"crate::render::x\";\n#[cfg(test)]\nmod tests {\n    use crate::render::Frame;\n}\n#[cfg(test)]\nmod more;\n"),
        ("scene/more.rs", "use crate::render::Frame;\n"),
        ("render/mod.rs", "use crate::scene::Scene;\n"),
    ]);
    let deps = layers::dependencies(&files);
    let to_render: BTreeSet<_> =
        deps.iter().filter(|d| d.to == "render" && d.from != "render").map(|d| d.at.clone()).collect();
    assert!(to_render.is_empty(), "test code or a string read as a dependency: {to_render:?}");
    assert!(layers::problems(&deps).is_empty());
}

/// The paper rule holds inside the settings layer too (every paper's `settings.rs` is one part),
/// and a module re-exported under `pub(in path)` is a dependency while the visibility's path
/// is not.
#[test]
fn settings_importing_another_papers_settings_and_re_exports_are_reported() {
    let files = tree(&[
        ("techniques/mod.rs", "pub mod wyman2008;\npub mod wyman_nichols2009;\npub mod shared;\n"),
        ("techniques/wyman2008/mod.rs", "pub mod settings;\n"),
        ("techniques/wyman2008/settings.rs", "pub enum Cluster {}\n"),
        ("techniques/wyman_nichols2009/mod.rs", "pub mod settings;\n"),
        ("techniques/wyman_nichols2009/settings.rs", "use crate::techniques::wyman2008::settings::Cluster;\n"),
        (
            "techniques/shared/mod.rs",
            "pub(in crate::techniques) use crate::techniques::wyman2008;\npub(in crate::techniques) fn f() {}\n",
        ),
    ]);
    let deps = layers::dependencies(&files);
    let all = layers::problems(&deps).join("\n");
    assert!(
        all.contains("techniques/wyman_nichols2009/settings.rs:1: wyman_nichols2009 imports another paper"),
        "{all}"
    );
    assert!(all.contains("techniques/shared/mod.rs:1: shared imports a paper"), "{all}");
    assert!(!all.contains("shared/mod.rs:2"), "a visibility path read as a dependency: {all}");
}

/// `render/` knows no paper (issue 26, item 1; issue 50, item 7): the caustic techniques reach
/// it as one `techniques::CausticPipeline` of stages, the eye's refraction as the stage
/// `techniques::stages::EyeRefraction`, a technique with a renderer of its own (the pool) as a
/// `gpu::frames::FrameRenderer` made by `techniques::own_renderer`.
#[test]
fn render_names_no_paper() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let deps = layers::dependencies(&layers::read_tree(&src));
    let from_render: Vec<_> = deps.iter().filter(|d| d.file.starts_with("render/")).collect();
    assert!(
        from_render.iter().any(|d| d.file == "render/renderer.rs" && d.to == "techniques"),
        "no dependency of render/renderer.rs read"
    );
    let papers: Vec<String> = from_render
        .iter()
        .filter(|d| layers::PAPERS.iter().any(|p| d.path.iter().any(|s| s == p)))
        .map(|d| format!("{}: {}", d.at, d.path.join("::")))
        .collect();
    assert!(papers.is_empty(), "render/ names papers:\n{}", papers.join("\n"));
}
