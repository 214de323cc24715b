//! `causticlab diff A B`: whether two renders made the same images, texel by texel
//! (`caustics::diff`): two EXR files, or two `render --out` folders, where every EXR file
//! (final.exr and the dumps), and the pass names and photon counts of timings.json, are compared.
//! `scripts/same_maps.sh` shows with it that a refactor kept every image.

use crate::cli::DiffArgs;
use crate::exit;
use anyhow::{Context as _, Result};
use caustics::diff::{diff_images, sort_texels};
use caustics::error::InputError;
use caustics::image_io::read_exr;
use caustics::input_error;
use std::collections::BTreeSet;
use std::path::Path;

/// The exit code: `exit::OK` when everything is the same, `exit::DIFFERENT` when anything differs.
pub fn run(args: &DiffArgs) -> Result<u8> {
    if !(args.tolerance.is_finite() && args.tolerance >= 0.0) {
        return Err(input_error!("--tolerance {}: must be a number >= 0", args.tolerance).into());
    }
    for p in [&args.a, &args.b] {
        if !p.exists() {
            return Err(input_error!("{}: no such file or folder", p.display()).into());
        }
    }
    check_names(args)?;
    let differing = match (args.a.is_dir(), args.b.is_dir()) {
        (true, true) => diff_dirs(&args.a, &args.b, args)?,
        (false, false) => usize::from(!diff_file(&args.a, &args.b, args)?),
        _ => {
            return Err(input_error!(
                "{} and {}: compare two EXR files or two folders, not one of each",
                args.a.display(),
                args.b.display()
            )
            .into())
        }
    };
    if differing > 0 {
        println!("{differing} difference(s) between {} and {}", args.a.display(), args.b.display());
        return Ok(exit::DIFFERENT);
    }
    println!("same");
    Ok(exit::OK)
}

/// `--unordered` and `--ignore` name dumps (or `final`; comparing two files, `--unordered` may
/// name B's stem, which is what it is matched against): a misspelt name would switch its option
/// off without a word. `--ignore` leaves out files of folders, so beside two files it is refused.
fn check_names(args: &DiffArgs) -> Result<()> {
    let files = !args.a.is_dir() && !args.b.is_dir();
    if files && !args.ignore.is_empty() {
        return Err(input_error!(
            "--ignore: leaves out files of two folders, and {} and {} are files",
            args.a.display(),
            args.b.display()
        )
        .into());
    }
    let b_stem = files.then(|| args.b.file_stem().map(|s| s.to_string_lossy().into_owned())).flatten();
    let dumps = caustics::render::all_dump_names();
    let known = |n: &str| n == "final" || dumps.contains(&n) || b_stem.as_deref() == Some(n);
    for (flag, names) in [("--unordered", &args.unordered), ("--ignore", &args.ignore)] {
        if let Some(n) = names.iter().find(|n| !known(n)) {
            return Err(
                input_error!("{flag} {n}: no dump of that name (`final`, or a name `causticlab dumps` lists)").into()
            );
        }
    }
    Ok(())
}

/// Every EXR file of either folder, then the counts of their timings.json; the number of files
/// (or counts) that differ.
fn diff_dirs(a: &Path, b: &Path, args: &DiffArgs) -> Result<usize> {
    let exrs = |dir: &Path| -> Result<BTreeSet<String>> {
        let mut names = BTreeSet::new();
        for e in std::fs::read_dir(dir).with_context(|| format!("listing {}", dir.display()))? {
            let name = e?.file_name().to_string_lossy().into_owned();
            if name.ends_with(".exr") {
                names.insert(name);
            }
        }
        Ok(names)
    };
    let (in_a, in_b) = (exrs(a)?, exrs(b)?);
    let mut differing = 0;
    for name in in_a.union(&in_b) {
        if args.ignore.iter().any(|i| name.strip_suffix(".exr") == Some(i.as_str())) {
            println!("{name}: ignored");
            continue;
        }
        match (in_a.contains(name), in_b.contains(name)) {
            (true, true) => differing += usize::from(!diff_file(&a.join(name), &b.join(name), args)?),
            (true, false) => {
                println!("{name}: only in {}", a.display());
                differing += 1;
            }
            _ => {
                println!("{name}: only in {}", b.display());
                differing += 1;
            }
        }
    }
    let timings = |dir: &Path| -> Result<Option<serde_json::Value>> {
        let path = dir.join("timings.json");
        if !path.is_file() {
            return Ok(None);
        }
        let text = std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
        let v: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| input_error!("{}: not JSON: {e}", path.display()))?;
        Ok(Some(v))
    };
    match (timings(a)?, timings(b)?) {
        (Some(ta), Some(tb)) => {
            // The passes the frame recorded, by name and in order (not their times).
            let names = |t: &serde_json::Value| -> serde_json::Value {
                t.get("passes")
                    .and_then(|p| p.as_array())
                    .map(|p| p.iter().filter_map(|x| x.get("name").cloned()).collect())
                    .unwrap_or(serde_json::Value::Null)
            };
            let (na, nb) = (names(&ta), names(&tb));
            if na == nb {
                println!("timings.json pass names: same");
            } else {
                println!("timings.json pass names: {na} against {nb}");
                differing += 1;
            }
            for key in ["photons_emitted", "counts"] {
                if ta.get(key) == tb.get(key) {
                    println!("timings.json {key}: same");
                } else {
                    println!(
                        "timings.json {key}: {} against {}",
                        ta.get(key).map_or("none".into(), |v| v.to_string()),
                        tb.get(key).map_or("none".into(), |v| v.to_string())
                    );
                    differing += 1;
                }
            }
        }
        (None, None) => {}
        (Some(_), None) => {
            println!("timings.json: only in {}", a.display());
            differing += 1;
        }
        (None, Some(_)) => {
            println!("timings.json: only in {}", b.display());
            differing += 1;
        }
    }
    Ok(differing)
}

/// Prints how `a` differs from `b` (or `same`); whether every channel is within the tolerance.
fn diff_file(a: &Path, b: &Path, args: &DiffArgs) -> Result<bool> {
    let tolerance = args.tolerance;
    let name = b.file_name().map_or_else(|| b.display().to_string(), |n| n.to_string_lossy().into_owned());
    // A file read_exr refuses is already an input error naming it; anything else that stops
    // the comparison (a disk error) is one here too (exit 2, as diff(1)).
    let read = |p: &Path| read_exr(p).map_err(|e| if e.is::<InputError>() { e } else { input_error!("{e:#}").into() });
    let (mut ia, mut ib) = (read(a)?, read(b)?);
    let stem = name.strip_suffix(".exr").unwrap_or(&name);
    let unordered = args.unordered.iter().any(|u| u == stem) || (args.unordered_records && is_records(stem));
    if unordered {
        sort_texels(&mut ia);
        sort_texels(&mut ib);
    }
    let name = if unordered { format!("{name} (unordered)") } else { name };
    let channels = match diff_images(&ia, &ib) {
        Ok(c) => c,
        Err(shape) => {
            println!("{name}: different shapes: {shape}");
            return Ok(false);
        }
    };
    let over: Vec<_> = channels.iter().filter(|c| c.relative() > tolerance).collect();
    if over.is_empty() {
        let worst = channels.iter().map(|c| c.relative()).fold(0.0, f64::max);
        if worst == 0.0 {
            println!("{name}: same");
        } else {
            println!("{name}: same within {tolerance:e} (largest relative difference {worst:.3e})");
        }
        return Ok(true);
    }
    for c in over {
        println!(
            "{name}: {}: {} texels differ, max |a-b| {:.6e} of max |b| {:.6e} (relative {:.3e})",
            c.channel,
            c.texels_differing,
            c.max_abs_diff,
            c.max_abs,
            c.relative()
        );
    }
    Ok(false)
}

/// Whether the dump of file stem `stem` is declared as a list of records (by any technique:
/// one name is one format across the declarations).
fn is_records(stem: &str) -> bool {
    caustics::render::dumps::all().iter().any(|d| d.name == stem && d.format == caustics::dump::Format::Records)
}
