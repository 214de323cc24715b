//! The pages a reader cites agree with the committed tables: `causticlab bench claims` over the
//! repository passes, and the pages that quote measurements are held to it (docs/claims.md).

mod common;

use common::{causticlab, workspace};

/// Pages that quote the tables and must name them (`<!--claims DIR -->`), so that the check
/// reads every number they write. A page leaves this list only by losing its numbers.
const ENROLLED: [&str; 8] = [
    "README.md",
    "docs/viewer.md",
    "results/front_findings.md",
    "results/wyman2008_findings.md",
    "results/wyman_davis2006_findings.md",
    "results/wyman_nichols2009_findings.md",
    "results/trendall_stewart2000/README.md",
    "results/nvidia-nvidia-h100-80gb-hbm3-580-159-04/FINDINGS.md",
];

#[test]
fn the_pages_that_quote_the_tables_name_them() {
    let missing: Vec<&str> = ENROLLED
        .iter()
        .copied()
        .filter(|p| {
            let text = std::fs::read_to_string(workspace().join(p)).unwrap_or_default();
            !text.lines().take(12).any(|l| l.trim_start().starts_with("<!--claims "))
        })
        .collect();
    assert!(missing.is_empty(), "no `<!--claims DIR -->` near the top of: {missing:?}");
}

#[test]
fn every_number_the_pages_quote_agrees_with_its_table() {
    let run = causticlab(&["bench", "claims"]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let last = run.stdout.lines().last().unwrap_or_default();
    assert!(last.ends_with(", 0 problem(s)"), "{last}");
}

#[test]
fn a_wrong_number_fails_with_page_line_written_and_computed() {
    let s = common::Scratch::new("claims", "page");
    let page = s.join("page.md");
    let dir = "results/llvmpipe-llvmpipe-llvm-15-0-6-256-bits-mesa-22-3-6-llvm-15-0-6/";
    let text = format!(
        "# p\n<!--claims {dir} -->\nThe hierarchical gather at 2048² takes 150.0<!--= wyman2008_table3{{metric=Gather photons=2048 technique=hierarchical}} --> ms.\n"
    );
    std::fs::write(&page, text).unwrap();
    let page = page.display().to_string();
    let root = workspace().display().to_string();
    let run = causticlab(&["bench", "claims", "--root", &root, &page]);
    assert_eq!(run.code, Some(1), "{}", run.describe());
    assert!(run.stdout.contains(":3: `150.0`:") && run.stdout.contains("is 147.6"), "{}", run.describe());
    assert!(run.stderr.contains("disagree"), "{}", run.describe());
}

#[test]
fn a_table_that_is_not_a_bench_result_is_named() {
    let run = causticlab(&["bench", "claims", "--list", "Cargo.toml"]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains("Cargo.toml"), "{}", run.describe());
}
