//! What else the host's CPUs did while a cell ran (Linux `/proc/stat` and `/proc/self/stat`):
//! - **steal**: the share of the CPU time the hypervisor gave to other guests (the `steal`
//!   column). A shared cloud VM can lose a third of its CPU this way.
//! - **other processes**: the CPU time every other process on this machine used (busy time of
//!   all cores minus this process's own, all its threads), in cores. A build or a test suite
//!   beside a benchmark shows here.
//!
//! On a software rasteriser such as lavapipe either slows every pass of the cell, so each cell
//! records both; a cell that ran while other processes used more than a threshold is measured
//! again, and marked busy if it stays so (`crate::run`).

/// Cumulative CPU time of all cores, in clock ticks, and this process's own.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CpuTimes {
    /// user + nice + system + idle + iowait + irq + softirq + steal.
    total: u64,
    steal: u64,
    /// user + nice + system + irq + softirq: time some process (or the kernel for it) ran.
    busy: u64,
    /// Cores (the `cpuN` lines).
    cpus: u64,
    /// This process's user + system time, all threads (`/proc/self/stat`), if known.
    own: Option<u64>,
}

/// Now, where the OS reports it (Linux); `None` elsewhere.
pub fn sample() -> Option<CpuTimes> {
    let mut t = parse(&std::fs::read_to_string("/proc/stat").ok()?)?;
    t.own = std::fs::read_to_string("/proc/self/stat").ok().and_then(|s| own_ticks(&s));
    Some(t)
}

fn parse(stat: &str) -> Option<CpuTimes> {
    let line = stat.lines().find(|l| l.starts_with("cpu "))?;
    let v: Vec<u64> = line.split_whitespace().skip(1).map(|x| x.parse().ok()).collect::<Option<_>>()?;
    // Fields 9-10 (guest, guest_nice) are already inside user and nice.
    let fields = v.get(..8)?;
    let cpus =
        stat.lines().filter(|l| l.starts_with("cpu") && l.as_bytes().get(3).is_some_and(u8::is_ascii_digit)).count();
    Some(CpuTimes {
        total: fields.iter().sum(),
        steal: fields[7],
        busy: fields[0] + fields[1] + fields[2] + fields[5] + fields[6],
        cpus: cpus.max(1) as u64,
        own: None,
    })
}

/// utime + stime of a `/proc/<pid>/stat` line (fields 14 and 15; the command name in
/// parentheses may hold spaces, so fields are counted after its closing parenthesis).
fn own_ticks(stat: &str) -> Option<u64> {
    let rest = &stat[stat.rfind(')')? + 1..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    // After ")": state is field 3, so utime (14) and stime (15) are at 11 and 12.
    Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
}

/// Cores' worth of CPU time other processes used between `a` and `b` (busy time of every core
/// less this process's own, over the wall time that passed); `None` when unknown or when no
/// time passed.
pub fn other_cores(a: CpuTimes, b: CpuTimes) -> Option<f64> {
    let elapsed = b.total.checked_sub(a.total).filter(|t| *t > 0)? as f64 / b.cpus as f64;
    let busy = b.busy.saturating_sub(a.busy) as f64;
    let own = b.own?.saturating_sub(a.own?) as f64;
    Some(((busy - own) / elapsed).max(0.0))
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
        assert_eq!(a, CpuTimes { total: 1000, steal: 40, busy: 150, cpus: 1, own: None });
        // 60 + 30 + 100 + 100 stolen = 290 ticks passed, 100 of them stolen.
        assert!((fraction(a, b).unwrap() - 100.0 / 290.0).abs() < 1e-12);
        assert_eq!(fraction(a, a), None);
        assert_eq!(parse("cpu  1 2 3\n"), None, "a line too short is not read");
        assert_eq!(parse("intr 5\n"), None);
    }

    #[test]
    fn other_processes_are_the_busy_time_less_this_ones() {
        // Two cores; over 100 ticks of wall time (200 of CPU), 150 busy, 40 of them ours.
        let before = "cpu  1000 0 500 8000 0 0 0 0 0 0\ncpu0 1 1 1 1 1 1 1 1\ncpu1 1 1 1 1 1 1 1 1\n";
        let after = "cpu  1100 0 550 8050 0 0 0 0 0 0\ncpu0 1 1 1 1 1 1 1 1\ncpu1 1 1 1 1 1 1 1 1\n";
        let mut a = parse(before).unwrap();
        let mut b = parse(after).unwrap();
        assert_eq!((a.cpus, b.busy - a.busy, b.total - a.total), (2, 150, 200));
        a.own = own_ticks("42 (a (b) c) R 1 1 1 0 -1 4194304 100 0 0 0 300 60 0 0 20 0 3 0").map(|_| 360);
        b.own = Some(400);
        assert!((other_cores(a, b).unwrap() - 1.1).abs() < 1e-12, "{:?}", other_cores(a, b));
        assert_eq!(own_ticks("42 (a (b) c) R 1 1 1 0 -1 4194304 100 0 0 0 300 60 0 0"), Some(360));
        assert_eq!(own_ticks("garbage"), None);
        b.own = None;
        assert_eq!(other_cores(a, b), None, "without this process's own time nothing is said");
    }

    #[test]
    fn this_machine_can_be_sampled_where_it_is_linux() {
        if cfg!(target_os = "linux") {
            let (a, b) = (sample().expect("/proc/stat"), sample().expect("/proc/stat"));
            assert!(b.total >= a.total && b.steal >= a.steal);
            assert!(a.own.is_some(), "/proc/self/stat gives this process's CPU time");
        }
    }

    #[test]
    fn busy_is_user_nice_system_irq_and_softirq_each_counted_once() {
        // Each field a distinct power of two: user 1, nice 2, system 4, idle 8, iowait 16, irq 32,
        // softirq 64, steal 128; then guest and guest_nice, already inside user and nice.
        let t = parse("cpu  1 2 4 8 16 32 64 128 256 512\ncpu0 1 1 1 1 1 1 1 1\n").unwrap();
        assert_eq!((t.busy, t.total, t.steal), (1 + 2 + 4 + 32 + 64, 255, 128));
    }

    #[test]
    fn no_time_passed_says_nothing_rather_than_divide_by_it() {
        let mut a = parse("cpu  100 0 50 800 0 0 0 0 0 0\ncpu0 1 1 1 1 1 1 1 1\n").unwrap();
        a.own = Some(10);
        assert_eq!(other_cores(a, a), None);
        let mut b = parse("cpu  101 0 50 800 0 0 0 0 0 0\ncpu0 1 1 1 1 1 1 1 1\n").unwrap();
        b.own = Some(10);
        assert_eq!(other_cores(a, b), Some(1.0), "one tick passed, all of it another process's");
    }
}
