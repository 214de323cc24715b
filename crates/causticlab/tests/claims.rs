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
fn the_results_index_is_current() {
    let results = workspace().join("results").display().to_string();
    let run = causticlab(&["bench", "index", "--check", "--results", &results]);
    assert_eq!(run.code, Some(0), "`causticlab bench index` rewrites it: {}", run.describe());
}

#[test]
fn the_index_says_which_tables_their_config_would_measure_otherwise() {
    let s = common::Scratch::new("claims", "index");
    let device = "llvmpipe-llvmpipe-llvm-15-0-6-256-bits-mesa-22-3-6-llvm-15-0-6";
    std::fs::create_dir_all(s.join("bench_configs")).unwrap();
    std::fs::create_dir_all(s.join("results").join(device)).unwrap();
    let name = "wyman2008_table4";
    let table = format!("{device}/{name}.json.gz");
    std::fs::copy(workspace().join("results").join(&table), s.join("results").join(&table)).unwrap();
    // The config the table embeds, whatever the file says today.
    let config = bench::results::read(&s.join("results").join(&table), "table").unwrap().config.toml;
    let config_file = s.join(format!("bench_configs/{name}.toml"));
    let results = s.join("results").display().to_string();
    let index = || std::fs::read_to_string(s.join("results/README.md")).unwrap();
    let row = || index().lines().find(|l| l.contains(&format!("[{name}]"))).unwrap_or_default().to_string();
    // The file as the table was measured with: `same`; then with a note: its reading changed.
    std::fs::write(&config_file, &config).unwrap();
    assert_eq!(causticlab(&["bench", "index", "--results", &results]).code, Some(0));
    assert!(row().ends_with("| same |"), "{}", index());
    std::fs::write(&config_file, config.replace("notes = [", "notes = [\"A note.\", ")).unwrap();
    let run = causticlab(&["bench", "index", "--check", "--results", &results]);
    assert_eq!(run.code, Some(1), "the index is out of date: {}", run.describe());
    assert!(run.stdout.contains("README.md:") && run.stdout.contains("now `"), "{}", run.describe());
    assert_eq!(causticlab(&["bench", "index", "--results", &results]).code, Some(0));
    assert!(row().contains("| reading changed: `table.notes` (`bench explain` rewrites it) |"), "{}", row());
    // Another orbit period: the table was measured otherwise.
    assert!(config.contains("period_frames = "), "the config has an orbit period");
    let changed = config.replace("period_frames = ", "period_frames = 1");
    std::fs::write(&config_file, changed).unwrap();
    assert_eq!(causticlab(&["bench", "index", "--results", &results]).code, Some(0));
    assert!(row().contains("| **changed**: `run.period_frames` (run it again) |"), "{}", row());
    assert_eq!(causticlab(&["bench", "index", "--check", "--results", &results]).code, Some(0));
    // A results folder that is not there is an input error.
    let run = causticlab(&["bench", "index", "--results", &s.join("nothing").display().to_string()]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
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

/// A root or page that is not there is an input error naming it, and a root with no page fails:
/// a check that read nothing must not pass.
#[test]
fn a_missing_root_or_page_or_no_page_at_all_is_an_input_error() {
    let s = common::Scratch::new("claims", "missing");
    let nowhere = s.join("nowhere").display().to_string();
    let run = causticlab(&["bench", "claims", "--root", &nowhere]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains(&nowhere) && run.stderr.contains("--root"), "{}", run.describe());
    let empty = s.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let empty = empty.display().to_string();
    let run = causticlab(&["bench", "claims", "--root", &empty]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains("no page") && run.stderr.contains(&empty), "{}", run.describe());
    let run = causticlab(&["bench", "claims", "no_such_page.md"]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains("no_such_page.md"), "{}", run.describe());
}
