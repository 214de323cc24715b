//! A progress bar with an ETA on stderr: redrawn in place on a terminal, one line per cell
//! otherwise (logs and CI). The ETA weights cells by their work (photons and pixels times
//! frames), so a sweep that ends at 4096² photons does not promise to finish early.

use std::io::{IsTerminal, Write};
use std::time::Instant;

pub struct Progress {
    costs: Vec<f64>,
    done: usize,
    done_cost: f64,
    start: Instant,
    tty: bool,
}

fn duration(s: f64) -> String {
    let s = s.max(0.0).round() as u64;
    if s >= 3600 {
        format!("{}h{:02}m", s / 3600, s % 3600 / 60)
    } else if s >= 60 {
        format!("{}m{:02}s", s / 60, s % 60)
    } else {
        format!("{s}s")
    }
}

impl Progress {
    /// `costs`: the relative work of each cell to run, in order.
    pub fn new(costs: Vec<f64>) -> Progress {
        Progress { costs, done: 0, done_cost: 0.0, start: Instant::now(), tty: std::io::stderr().is_terminal() }
    }

    /// Call before running a cell.
    pub fn start_cell(&self, what: &str) {
        let n = self.costs.len();
        let total: f64 = self.costs.iter().sum();
        let elapsed = self.start.elapsed().as_secs_f64();
        let eta = if self.done_cost > 0.0 {
            format!("ETA {}", duration(elapsed * (total - self.done_cost) / self.done_cost))
        } else {
            "ETA –".into()
        };
        let width = 24;
        let filled = if total > 0.0 { ((self.done_cost / total) * width as f64) as usize } else { 0 }.min(width);
        let bar = format!("[{}{}]", "#".repeat(filled), "-".repeat(width - filled));
        let line = format!("{bar} {}/{n} cells, {} elapsed, {eta} · {what}", self.done, duration(elapsed));
        let mut err = std::io::stderr();
        if self.tty {
            let _ = write!(err, "\r\x1b[2K{line}");
        } else {
            let _ = writeln!(err, "{line}");
        }
        let _ = err.flush();
    }

    pub fn finish_cell(&mut self) {
        self.done_cost += self.costs.get(self.done).copied().unwrap_or(0.0);
        self.done += 1;
    }

    pub fn finish(&self) {
        let mut err = std::io::stderr();
        if self.tty {
            let _ = writeln!(err);
        }
        let cells = if self.done == 1 { "cell" } else { "cells" };
        let _ = writeln!(err, "{} {cells} in {}", self.done, duration(self.start.elapsed().as_secs_f64()));
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn durations() {
        assert_eq!(super::duration(5.4), "5s");
        assert_eq!(super::duration(125.0), "2m05s");
        assert_eq!(super::duration(3725.0), "1h02m");
    }
}
