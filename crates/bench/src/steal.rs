//! Host CPU steal: the share of this machine's CPU time that the hypervisor gave to other guests
//! while a cell ran (Linux `/proc/stat`, its `steal` column). A shared cloud VM can lose a third
//! of its CPU this way. On a software rasteriser such as lavapipe that slows every pass of the
//! cell, so each cell records its steal and the table reports it beside the times.

/// Cumulative CPU time of all cores, in clock ticks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CpuTimes {
    /// user + nice + system + idle + iowait + irq + softirq + steal.
    total: u64,
    steal: u64,
}

/// Now, where the OS reports it (Linux); `None` elsewhere.
pub fn sample() -> Option<CpuTimes> {
    parse(&std::fs::read_to_string("/proc/stat").ok()?)
}

fn parse(stat: &str) -> Option<CpuTimes> {
    let line = stat.lines().find(|l| l.starts_with("cpu "))?;
    let v: Vec<u64> = line.split_whitespace().skip(1).map(|x| x.parse().ok()).collect::<Option<_>>()?;
    // Fields 9-10 (guest, guest_nice) are already inside user and nice.
    let fields = v.get(..8)?;
    Some(CpuTimes { total: fields.iter().sum(), steal: fields[7] })
}

/// The stolen share of the CPU time between `a` and `b`, in 0..=1; `None` when none passed.
pub fn fraction(a: CpuTimes, b: CpuTimes) -> Option<f64> {
    let total = b.total.checked_sub(a.total).filter(|t| *t > 0)?;
    Some(b.steal.saturating_sub(a.steal) as f64 / total as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steal_is_the_eighth_field_of_the_cpu_line() {
        let before = "cpu  100 0 50 800 10 0 0 40 0 0\ncpu0 50 0 25 400 5 0 0 20 0 0\nintr 1\n";
        let after = "cpu  160 0 80 900 10 0 0 140 5 0\ncpu0 1 1 1 1 1 1 1 1 0 0\n";
        let (a, b) = (parse(before).unwrap(), parse(after).unwrap());
        assert_eq!(a, CpuTimes { total: 1000, steal: 40 });
        // 60 + 30 + 100 + 100 stolen = 290 ticks passed, 100 of them stolen.
        assert!((fraction(a, b).unwrap() - 100.0 / 290.0).abs() < 1e-12);
        assert_eq!(fraction(a, a), None);
        assert_eq!(parse("cpu  1 2 3\n"), None, "a line too short is not read");
        assert_eq!(parse("intr 5\n"), None);
    }

    #[test]
    fn this_machine_can_be_sampled_where_it_is_linux() {
        if cfg!(target_os = "linux") {
            let (a, b) = (sample().expect("/proc/stat"), sample().expect("/proc/stat"));
            assert!(b.total >= a.total && b.steal >= a.steal);
        }
    }
}
