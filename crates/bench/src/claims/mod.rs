//! Checked claims: every number a page states about a measurement is recomputed from the
//! committed tables (`causticlab bench claims`).
//!
//! A findings page, the README or a doc quotes the tables in prose: a ratio, a range, a count,
//! "on every scene". Each such number carries a claim after it (an HTML comment, so the rendered
//! page shows only the number) that says which entries of which table it comes from and the
//! arithmetic that turns them into the number ([`page`] has the forms, [`expr`] the language,
//! [`eval`] the tables). The check recomputes each one from the JSON and fails naming the page,
//! the line, the number written and the number computed; so a re-run that changes a cell makes
//! every sentence that quoted it fail until the sentence is updated. A number that looks measured
//! (a time, a rate, a ratio, a percentage, a decimal) and has no claim fails too: a number cannot
//! enter a page without a source. Tables the bench writes (a `.md` beside its `.json.gz`) and pages a
//! script writes from its data (a `.md` beside a `.csv` of the same name, [`data`]) are not
//! read: they are the source.

pub mod data;
pub mod eval;
pub mod expr;
pub mod page;

use anyhow::{Context as _, Result};
use std::path::{Path, PathBuf};

/// One page's findings.
pub struct Checked {
    pub page: PathBuf,
    pub report: page::PageReport,
}

/// The pages the check reads under `root`: the README, `docs/` and `results/`, less the tables
/// the bench writes (a `.json.gz`, or a plain `.json`, beside) and the pages scripts write from
/// their data (a `.csv` beside).
pub fn pages(root: &Path) -> Result<Vec<PathBuf>> {
    let mut out = vec![];
    let readme = root.join("README.md");
    if readme.is_file() {
        out.push(readme);
    }
    for dir in ["docs", "results"] {
        walk(&root.join(dir), &mut out)?;
    }
    out.sort();
    Ok(out)
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
    if !dir.is_dir() {
        return Ok(());
    }
    for e in std::fs::read_dir(dir).with_context(|| format!("reading {}", dir.display()))? {
        let p = e?.path();
        if p.is_dir() {
            walk(&p, out)?;
        } else if p.extension().is_some_and(|x| x == "md")
            && !p.with_extension(crate::results::TABLE_EXT).is_file()
            && !p.with_extension("json").is_file()
            && !p.with_extension("csv").is_file()
        {
            out.push(p);
        }
    }
    Ok(())
}

/// Checks `pages` (paths under `root`, which holds the table folders the pages name).
pub fn check(root: &Path, pages: &[PathBuf]) -> Result<Vec<Checked>> {
    let mut cache = eval::Cache::new();
    let mut out = vec![];
    for p in pages {
        let text = std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
        out.push(Checked { page: p.clone(), report: page::check_page(&text, root, &mut cache) });
    }
    Ok(out)
}

/// Every entry of a table (or data file) with the pick that selects it alone, its value and flags: what a
/// claim's author reads to write `table{axis=label ...}`.
pub fn list(table: &Path) -> Result<String> {
    // The file itself first, so that a wrong path or a file that is no table is named as given.
    let csv = table.extension().is_some_and(|x| x == "csv");
    if csv {
        data::read(table)?;
    } else {
        crate::results::read(table, "table")?;
    }
    let name = match (csv, crate::results::table_name(table)) {
        (true, _) => table.file_stem().and_then(|s| s.to_str()).unwrap_or_default().to_string(),
        (false, Some(name)) => name,
        (false, None) => {
            return Err(caustics::input_error!(
                "{}: a table is the bench's `<config>.json.gz` (or `.json`) or a script's `.csv`",
                table.display()
            )
            .into())
        }
    };
    let dir = table.parent().unwrap_or(Path::new("."));
    let mut cache = eval::Cache::new();
    let mut scope = eval::Scope::new(Path::new(""), &mut cache);
    scope.devices.push((None, dir.to_path_buf()));
    let all = scope.eval(&expr::Expr::Entries { device: None, name: name.clone(), pick: vec![] })?;
    let eval::Val::Set(items, _) = all else { unreachable!("a table's entries are a set") };
    let mut out = String::new();
    for it in items {
        let value = match &it.value {
            Ok(v) => format!("{v}"),
            Err(why) => why.clone(),
        };
        let spread = it.spread.map(|s| format!(" ±{:.0}%", 100.0 * s)).unwrap_or_default();
        let paper = it.paper.map(|p| format!(" (paper {p})")).unwrap_or_default();
        let flag = it.flag.map(|f| format!(" [{f}]")).unwrap_or_default();
        let q = if it.implausible { " [?]" } else { "" };
        let picks: Vec<String> = it
            .keys
            .iter()
            .map(|(a, k)| if expr::is_bare_label(k) { format!("{a}={k}") } else { format!("{a}=\"{k}\"") })
            .collect();
        out.push_str(&format!("{name}{{{}}} = {value}{spread}{paper}{flag}{q}\n", picks.join(" ")));
    }
    Ok(out)
}
