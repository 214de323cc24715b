//! What a run records about where and when it ran: device and driver, CPU, commit, date.

use crate::results::Meta;
use vkcore::DeviceInfo;

pub fn meta(info: &DeviceInfo) -> Meta {
    Meta {
        device: info.name.clone(),
        device_type: info.device_type.clone(),
        device_slug: results_slug(info),
        driver_name: info.driver_name.clone(),
        driver_info: info.driver_info.clone(),
        vulkan_version: info.api_version.clone(),
        timestamp_period_ns: info.timestamp_period_ns,
        cpu: cpu_model(),
        commit: commit(),
        date: utc_now(),
        causticlab_version: env!("CARGO_PKG_VERSION").to_string(),
        quirks: info.quirks.iter().map(|q| q.to_string()).collect(),
    }
}

/// The results folder of a device: its driver, name and driver version, e.g.
/// `llvmpipe-llvmpipe-llvm-15-0-6-256-bits-mesa-22-3-6-llvm-15-0-6` or
/// `nvidia-nvidia-h100-80gb-hbm3-580-159-04`, so that a driver update writes a new folder
/// instead of overwriting the tables of the old driver.
pub fn results_slug(info: &DeviceInfo) -> String {
    let version = slug(&info.driver_info);
    if version.is_empty() {
        info.slug()
    } else {
        format!("{}-{version}", info.slug())
    }
}

/// Lower-case ASCII letters and digits, every other run of characters one `-`, at most 40.
fn slug(text: &str) -> String {
    let mut s = String::new();
    for c in text.to_lowercase().chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c);
        } else if !s.ends_with('-') {
            s.push('-');
        }
    }
    s.trim_matches('-').chars().take(40).collect::<String>().trim_end_matches('-').to_string()
}

/// Whether `path` (which may not exist yet) lies in the work tree of the git repository the
/// current directory is in: a results folder whose tables are committed.
pub fn in_work_tree(path: &std::path::Path) -> bool {
    let toplevel = std::process::Command::new("git")
        .args(["rev-parse", "--show-toplevel"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| std::path::PathBuf::from(String::from_utf8_lossy(&o.stdout).trim()));
    let Some(top) = toplevel.and_then(|t| t.canonicalize().ok()) else { return false };
    // The nearest existing ancestor decides (the folder is made by the run).
    let abs = std::env::current_dir().map(|d| d.join(path)).unwrap_or_else(|_| path.to_path_buf());
    abs.ancestors().find_map(|a| a.canonicalize().ok()).is_some_and(|a| a.starts_with(&top))
}

/// `model name` from /proc/cpuinfo and the number of logical CPUs.
pub fn cpu_model() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let threads = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    format!("{model}, {threads} threads")
}

/// `$CAUSTICLAB_COMMIT` when set (a binary run away from its repository, as on the GPU machine,
/// where `scripts/gpu_suite.sh` sets it from the pack's manifest: the commit the binary was built
/// from); else `git rev-parse --short HEAD` (with `-dirty` when tracked files other than
/// `results/` and Markdown documents have changes: what was measured differs from the commit), or
/// `unknown`.
/// (`scripts/commit.sh` computes the same for the shell scripts that name a commit.)
pub fn commit() -> String {
    if let Some(c) = std::env::var("CAUSTICLAB_COMMIT").ok().filter(|c| !c.trim().is_empty()) {
        return c.trim().to_string();
    }
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    match git(&["rev-parse", "--short", "HEAD"]) {
        Some(c) if !c.is_empty() => {
            // Results being rewritten by this very run, or docs edited while it runs, do not
            // make the measured code dirty.
            let dirty = git(&[
                "status",
                "--porcelain",
                "--untracked-files=no",
                "--",
                ".",
                ":(exclude)results",
                ":(exclude,glob)**/*.md",
            ])
            .is_some_and(|s| !s.is_empty());
            if dirty {
                format!("{c}-dirty")
            } else {
                c
            }
        }
        _ => "unknown".into(),
    }
}

/// The current UTC time as `YYYY-MM-DDTHH:MM:SSZ`.
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_secs()).unwrap_or(0);
    format_utc(secs)
}

/// Seconds since 1970 as an ISO 8601 UTC time (civil-from-days, proleptic Gregorian).
pub fn format_utc(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + if m <= 2 { 1 } else { 0 };
    format!("{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z", rem / 3600, rem % 3600 / 60, rem % 60)
}

#[cfg(test)]
mod tests {
    #[test]
    fn utc_dates() {
        assert_eq!(super::format_utc(0), "1970-01-01T00:00:00Z");
        // 2000-02-29 (a leap day) 12:34:56 and 2026-11-22 00:00:00, from `date -u -d ... +%s`.
        assert_eq!(super::format_utc(951_827_696), "2000-02-29T12:34:56Z");
        assert_eq!(super::format_utc(1_795_305_600), "2026-11-22T00:00:00Z");
    }

    #[test]
    fn driver_versions_slug() {
        assert_eq!(super::slug("Mesa 22.3.6 (LLVM 15.0.6)"), "mesa-22-3-6-llvm-15-0-6");
        assert_eq!(super::slug("580.159.04"), "580-159-04");
        assert_eq!(super::slug("  "), "");
    }
}
