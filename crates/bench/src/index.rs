//! `results/README.md`: an index of every table under the results folder, with its device
//! and date, rebuilt from the `<config>.json.gz` files after each run or merge.

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
            let line = format!(
                "| {} | [{}]({md}) | {} ({}) | {} | {} | {} |",
                crate::config::title(&r.config.paper, &r.config.table),
                r.config.name,
                r.meta.device,
                r.meta.driver_info,
                r.cells.len(),
                r.meta.date,
                r.meta.commit
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
            "\n| paper, table | config | device (driver) | cells | date | commit |\n|---|---|---|---|---|---|"
        );
    }
    for (_, _, line) in rows {
        let _ = writeln!(s, "{line}");
    }
    let path = root.join("README.md");
    write_file_atomically(&path, s.as_bytes())?;
    Ok(path)
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
