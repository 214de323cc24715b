//! What keeps committed tables trustworthy: no committed table from a dirty tree or a busy
//! machine, and every committed table fits its paper and a terminal.

mod common;

use common::bench::*;
use common::{scratch, workspace};

/// A timing run from a work tree with uncommitted changes does not write into that tree's
/// results folder (the tables would name no commit), unless told to; `--quick` runs (ignored
/// by git) and folders outside the tree are not refused.
#[test]
fn a_dirty_tree_does_not_write_committed_tables() {
    let repo = scratch("bench-dirty");
    let git = |args: &[&str]| {
        let out = std::process::Command::new("git")
            .args(["-c", "user.name=t", "-c", "user.email=t@t", "-c", "init.defaultBranch=main"])
            .args(args)
            .current_dir(&repo)
            .output()
            .expect("git");
        assert!(out.status.success(), "git {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    };
    git(&["init", "-q"]);
    let cfg = config_file(&repo, "small.toml", SMALL);
    git(&["add", "configs/small.toml"]);
    git(&["commit", "-qm", "config"]);
    let text = std::fs::read_to_string(&cfg).expect("the config");
    std::fs::write(&cfg, format!("{text}\n# edited\n")).expect("editing the config");
    let run = |extra: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_causticlab"))
            .args(["bench", "--device", "no-such-gpu"])
            .arg(&cfg)
            .args(extra)
            .current_dir(&repo)
            .env_remove("VK_LOADER_DEBUG")
            .output()
            .expect("causticlab");
        (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (code, stderr) = run(&[]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("uncommitted changes") && stderr.contains("--allow-dirty"), "{stderr}");
    assert!(!repo.join("results").exists(), "a refused run wrote results");
    // Told to, or writing elsewhere, or a smoke test: the run goes on (and stops at the
    // device, which does not exist: the refusal is not what stopped it).
    let outside = scratch("bench-dirty-outside");
    for extra in [vec!["--allow-dirty"], vec!["--quick"], vec!["--results", outside.to_str().expect("utf-8 path")]] {
        let (code, stderr) = run(&extra);
        assert_ne!(code, Some(0), "{extra:?}: {stderr}");
        assert!(!stderr.contains("uncommitted changes") && stderr.contains("no-such-gpu"), "{extra:?}: {stderr}");
    }
    let _ = std::fs::remove_dir_all(&repo);
    let _ = std::fs::remove_dir_all(&outside);
}

/// Burns one core in another process until dropped.
struct Burner(std::process::Child);
impl Drop for Burner {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn a_cell_measured_while_another_process_burns_a_core_is_marked_busy_and_kept_out_of_results() {
    // A git work tree whose results/ folder is where committed tables would go.
    let repo = scratch("bench-busy");
    let git = std::process::Command::new("git").args(["init", "-q"]).current_dir(&repo).status().expect("git");
    assert!(git.success());
    let one_cell = SMALL
        .replace(
            "scenes = [\"SCENES/sphere_on_plane.toml\", \"SCENES/sphere_oblique.toml\"]",
            "scenes = [\"SCENES/sphere_on_plane.toml\"]",
        )
        .replace("photons = [80, 128]", "photons = [80]")
        .replace("measured_frames = 1", "measured_frames = 3")
        .replace("time_budget_s = 0", "time_budget_s = 1.0");
    assert!(one_cell.contains("measured_frames = 3\n") && one_cell.contains("time_budget_s = 1.0\n"), "{one_cell}");
    let cfg = config_file(&repo, "busy.toml", &one_cell);
    let _burner =
        Burner(std::process::Command::new("sh").args(["-c", "while :; do :; done"]).spawn().expect("a busy process"));
    std::thread::sleep(std::time::Duration::from_millis(300));
    let run = |extra: &[&str], results: &str| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_causticlab"))
            .args(["bench".as_ref(), cfg.as_os_str(), "--results".as_ref(), results.as_ref()])
            .args(extra)
            .current_dir(&repo)
            .env_remove("VK_LOADER_DEBUG")
            .output()
            .expect("causticlab");
        (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
    };
    // Into the work tree's results/: measured again once, still busy, refused; nothing written.
    let (code, stderr) = run(&["--busy-retries", "1"], "results");
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("measuring it again"), "the busy cell was not measured again: {stderr}");
    assert!(stderr.contains("kept the machine busy") && stderr.contains("cores"), "{stderr}");
    assert!(!repo.join("results").join("README.md").exists(), "a busy run wrote into results/");
    // Elsewhere the table is written, with the cells marked.
    let elsewhere = scratch("bench-busy-out");
    let (code, stderr) = run(&["--busy-retries", "0"], &elsewhere.display().to_string());
    assert_eq!(code, Some(0), "{stderr}");
    let dir = device_dir(&elsewhere);
    let md = std::fs::read_to_string(dir.join("busy.md")).expect("table");
    assert!(md.contains("busy cells (`~`)") && md.contains("~"), "{md}");
    let json = json(&dir.join("busy.json.gz"));
    for c in json["cells"].as_array().expect("cells") {
        assert_eq!(c["busy"], true, "{}", c["cell"]);
        assert!(
            c["other_cores"].as_f64().is_some_and(|x| x > 0.5),
            "another process burned a core: {}",
            c["other_cores"]
        );
    }
}

/// The columns of each paper table a config reproduces, row labels included, counted in the
/// papers (../shared/papers): Wyman 2008 Tables 1-5 (Table 3-sparse lays out Table 3), Wyman &
/// Davis 2006 Table 1 (scene, photons, 4 techniques x static/dynamic), Wyman & Nichols 2009
/// Table 1, Trendall & Stewart 2000 Table 1 (size, 3 configurations x 2 machines).
const PAPER_COLUMNS: [(&str, usize); 9] = [
    ("wyman2008_table1", 5),
    ("wyman2008_table2", 4),
    ("wyman2008_table3", 11),
    ("wyman2008_table3_sparse", 11),
    ("wyman2008_table4", 7),
    ("wyman2008_table5", 6),
    ("wyman_davis2006_table1", 10),
    ("wyman_nichols2009_table1", 5),
    ("trendall_stewart2000_table1", 7),
];

#[test]
fn every_committed_table_fits_its_paper_and_a_terminal() {
    // Every table `bench` wrote into results/<device>/ (a .md beside its .json.gz; quick runs are
    // not committed): each table line within 120 columns, and a paper table with at most one
    // column more than the paper's (its distinct header cells over the wrapped blocks of the
    // value tables, before the ratio grids).
    let mut checked = 0;
    let mut failures = vec![];
    for device in std::fs::read_dir(workspace().join("results")).expect("results/") {
        let device = device.expect("entry").path();
        if !device.is_dir() {
            continue;
        }
        for file in std::fs::read_dir(&device).expect("device folder") {
            let md = file.expect("entry").path();
            if md.extension().is_none_or(|e| e != "md") || !md.with_extension("json.gz").exists() {
                continue;
            }
            let text = std::fs::read_to_string(&md).expect("table");
            let name = md.file_stem().and_then(|s| s.to_str()).unwrap_or_default().to_string();
            for line in text.lines().filter(|l| l.starts_with('|') && l.chars().count() > 120) {
                failures.push(format!("{}: a line of {} columns: {line}", md.display(), line.chars().count()));
            }
            let values = &text[..text.find("## Ratios").unwrap_or(text.len())];
            let lines: Vec<&str> = values.lines().filter(|l| l.starts_with('|')).collect();
            let rule = |l: &str| l.chars().all(|c| matches!(c, '|' | '-' | ':' | ' '));
            let headers: std::collections::BTreeSet<&str> = lines
                .windows(2)
                .filter(|w| rule(w[1]))
                .flat_map(|w| w[0].split('|').map(str::trim).filter(|c| !c.is_empty()))
                .collect();
            if let Some((_, paper)) = PAPER_COLUMNS.iter().find(|(n, _)| *n == name) {
                if headers.len() > paper + 1 {
                    failures.push(format!(
                        "{}: {} columns, the paper's {paper}: {headers:?}",
                        md.display(),
                        headers.len()
                    ));
                }
            }
            checked += 1;
        }
    }
    assert!(checked >= 10, "only {checked} committed tables found under results/");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
