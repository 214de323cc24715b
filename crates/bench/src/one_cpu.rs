//! One results folder, one CPU. On lavapipe the CPU is the device (its times are CPU time), and
//! on any device it runs the host's side of every frame (recording, submitting, waiting, and
//! the fps of one-shot frames): two tables of one device folder compare only if one CPU
//! measured both. The device folder's name says the driver and the device, not the CPU, so a
//! timing run into the repository's `results/` checks the folder's other tables first and is
//! refused when another CPU measured them (`causticlab bench --allow-other-cpu` writes anyway).

use crate::results::{read, table_name};
use std::path::Path;

/// The tables in `dir` other than `name`'s whose CPU is not `cpu`: (file name, its CPU), sorted.
/// A file that does not read as a table is not one.
pub fn other_cpus(dir: &Path, name: &str, cpu: &str) -> Vec<(String, String)> {
    let Ok(entries) = std::fs::read_dir(dir) else { return vec![] };
    let mut out: Vec<(String, String)> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| table_name(p).is_some_and(|n| n != name))
        .filter_map(|p| {
            let r = read(&p, "table").ok()?;
            let file = p.file_name()?.to_string_lossy().to_string();
            (r.meta.cpu != cpu).then_some((file, r.meta.cpu))
        })
        .collect();
    out.sort();
    out
}

/// The refusal for [`other_cpus`]'s `others`, or none.
pub fn refusal(config: &Path, dir: &Path, cpu: &str, others: &[(String, String)]) -> Option<String> {
    let (first, other_cpu) = others.first()?;
    Some(format!(
        "{}: {} of the tables in {} were measured on another CPU ({other_cpu}: {first}{}), and this machine's is {cpu}: \
         a device folder's tables compare only if one CPU measured them all (on lavapipe the CPU is the device). \
         Run this on that machine, write elsewhere with --results, or pass --allow-other-cpu and run the folder's \
         other tables again here",
        config.display(),
        others.len(),
        dir.display(),
        if others.len() > 1 { ", ..." } else { "" }
    ))
}
