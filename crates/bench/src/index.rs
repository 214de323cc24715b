//! `results/README.md`: an index of every table under the results folder, with its device,
//! date and commit, and whether its config file today still describes its run
//! (`crate::drift`), rebuilt from the `<config>.json.gz` files after each run or merge, and by
//! `causticlab bench index` (whose `--check` CI runs: a config edited without its tables run
//! again shows in the index).

use crate::results::Results;
use anyhow::Result;
use caustics::image_io::write_file_atomically;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

const HEADER: &str = "# Results

Every table here was written by `causticlab bench` (or `causticlab bench merge`); this index is
rebuilt after each run. One folder per device (`<driver>-<device>` slug); in each, per config:
`<config>.md` (the table beside the paper's), `.csv` (one row per cell and metric), `.json.gz`
(everything, raw samples included, as gzip-compressed JSON: `zcat` reads it) and `.png` and
`.svg` (the plot). lavapipe numbers are serialized CPU
time: compare techniques within one device, never lavapipe against a GPU.

*config today* compares the config each table embeds with its file in `bench_configs/` today
(the file only: the code may have changed since, and each table names its commit): `same`;
`reading changed` where only what measures nothing differs (the table's text and layout, the
papers' sources, how the cells are judged, the front's drawing), which `causticlab bench
explain` writes into the table; **changed** where the table was measured with settings the file
no longer has (the keys named, the papers' values last): its numbers are still that run's, but
today's config would measure them otherwise, so run it again before comparing it with a table of
today's.
";

/// What else the repository's results folder holds, each named only where it is there (a
/// `--results` folder elsewhere has none of them).
const OTHERS: [(&str, &str); 5] = [
    ("quality", "`quality/` (caustic error against the CPU reference, `scripts/quality_table.sh`)"),
    ("criterion", "`criterion/` (CPU benchmarks, `scripts/criterion.sh`)"),
    (
        "wyman2008_findings.md",
        "[`wyman2008_findings.md`](wyman2008_findings.md) and the other `*_findings.md` (which of the papers' claims hold, and why)",
    ),
    (
        "trendall_stewart2000",
        "[`trendall_stewart2000/`](trendall_stewart2000/README.md) (Trendall & Stewart 2000's Sec. 5.2 errors, `scripts/pool_rms.sh`)",
    ),
    (
        "final_reference.csv",
        "`final_reference.csv`: the reference final image's convergence on `sphere_on_plane` (HDR-FLIP of levels 0-3 against every finer level and of every technique against levels 1-3, `scripts/final_reference.sh sphere_on_plane 3`; read in [docs/flip.md](../docs/flip.md#the-reference-final-image))",
    ),
];

/// Rebuilds `<root>/README.md` from `<root>/*/*.json.gz` (and plain `*.json` tables).
pub fn write_index(root: &Path) -> Result<PathBuf> {
    let path = root.join("README.md");
    write_file_atomically(&path, index_text(root).as_bytes())?;
    Ok(path)
}

/// What `write_index` writes. A table's config file (`bench_configs/<name>.toml`, as the bench
/// was given it) is looked for from the results folder's parent (the repository of `results/`),
/// then from the current folder.
pub fn index_text(root: &Path) -> String {
    let here = Path::new(".");
    let above = root.parent().unwrap_or(here);
    let mut rows: Vec<(String, String, String)> = vec![];
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root)
        .map(|rd| rd.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_dir()).collect())
        .unwrap_or_default();
    dirs.sort();
    for d in dirs {
        let mut files: Vec<PathBuf> = std::fs::read_dir(&d)
            .map(|rd| {
                rd.filter_map(|e| e.ok())
                    .map(|e| e.path())
                    // A table, once: a plain twin of a `.json.gz` is an older copy, or an edit.
                    .filter(|p| crate::results::table_name(p).is_some())
                    .filter(|p| {
                        p.extension().is_none_or(|x| x != "json")
                            || !p.with_extension(crate::results::TABLE_EXT).exists()
                    })
                    .collect()
            })
            .unwrap_or_default();
        files.sort();
        for f in files {
            let Ok(text) = crate::results::read_text(&f, "table") else { continue };
            let Ok(r) = serde_json::from_str::<Results>(&text) else { continue };
            let folder = d.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
            let md = format!("{folder}/{}.md", r.config.name);
            // As the bench was given it, or where it keeps it when that was an absolute path.
            let file = match Path::new(&r.config.file).is_absolute() {
                true => format!("bench_configs/{}.toml", r.config.name),
                false => r.config.file.clone(),
            };
            let today = crate::drift::drift(&r.config.toml, &file, &[above, here], r.run.quick);
            let line = format!(
                "| {} | [{}]({md}) | {} ({}) | {} | {} | {} | {} |",
                crate::config::title(&r.config.paper, &r.config.table),
                r.config.name,
                r.meta.device,
                r.meta.driver_info,
                r.cells.len(),
                r.meta.date,
                r.meta.commit,
                crate::drift::describe(&today, 3)
            );
            rows.push((r.config.paper.clone(), r.config.name.clone(), line));
        }
    }
    rows.sort();
    let mut s = String::from(HEADER);
    let others: Vec<&str> = OTHERS.iter().filter(|(p, _)| root.join(p).exists()).map(|(_, what)| *what).collect();
    if !others.is_empty() {
        let _ = writeln!(s, "\nAlso here: {}.", others.join("; "));
    }
    if rows.is_empty() {
        let _ = writeln!(s, "\nNo tables yet (`--quick` tables go to `<device>/quick/` and are not listed).");
    } else {
        let _ = writeln!(
            s,
            "\n| paper, table | config | device (driver) | cells | date | commit | config today |\n|---|---|---|---|---|---|---|"
        );
    }
    for (_, _, line) in rows {
        let _ = writeln!(s, "{line}");
    }
    s
}

/// `bench index --check`: the lines where `<root>/README.md` differs from what `write_index`
/// would write now (empty when it is current), each as `README.md:LINE: ...`.
pub fn stale_lines(root: &Path) -> Result<Vec<String>> {
    let path = root.join("README.md");
    let now = index_text(root);
    let Ok(written) = std::fs::read_to_string(&path) else {
        return Ok(vec![format!("{}: not there (`causticlab bench index` writes it)", path.display())]);
    };
    let (a, b): (Vec<&str>, Vec<&str>) = (written.lines().collect(), now.lines().collect());
    let mut out = vec![];
    for i in 0..a.len().max(b.len()) {
        match (a.get(i), b.get(i)) {
            (Some(x), Some(y)) if x == y => {}
            (x, y) => out.push(format!(
                "{}:{}: written `{}`, now `{}`",
                path.display(),
                i + 1,
                x.unwrap_or(&"(no line)"),
                y.unwrap_or(&"(no line)")
            )),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_index_names_only_the_folders_it_has() {
        let root = std::env::temp_dir().join(format!("causticlab-index-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).expect("a temp folder");
        let text = std::fs::read_to_string(write_index(&root).expect("the index")).expect("README.md");
        assert!(!text.contains("quality/") && !text.contains("findings"), "{text}");
        assert!(text.contains("No tables yet") && !text.contains("| paper, table |"), "no empty table: {text}");
        std::fs::create_dir_all(root.join("quality")).expect("quality/");
        let text = std::fs::read_to_string(write_index(&root).expect("the index")).expect("README.md");
        assert!(text.contains("Also here: `quality/`") && !text.contains("criterion/"), "{text}");
        // A file the index names (the reference final image's convergence) only where it is.
        assert!(!text.contains("final_reference.csv"), "{text}");
        std::fs::write(root.join("final_reference.csv"), "a,reference\n").expect("a csv");
        let text = std::fs::read_to_string(write_index(&root).expect("the index")).expect("README.md");
        assert!(text.contains("`final_reference.csv`: the reference final image's convergence"), "{text}");
        let _ = std::fs::remove_dir_all(&root);
    }
}
