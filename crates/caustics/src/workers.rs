//! CPU work spread over threads that take their tasks from a shared queue, so that a thread the
//! system refuses to start (its limit on threads or memory) leaves its share to the others
//! rather than panicking, as `std::thread::scope`'s `spawn` does.

/// How many threads ran a [`run`], and why the system refused the first one it did not start.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Started {
    pub threads: usize,
    pub refused: Option<String>,
}

/// Runs `work` on this thread and on up to `threads - 1` more (named `name`), returning when
/// every copy has returned. Each copy must take tasks until none is left: the result does not
/// depend on how many started.
pub fn run<F: Fn() + Sync>(threads: usize, name: &str, work: F) -> Started {
    let work = &work;
    std::thread::scope(|s| {
        let mut started = Started { threads: 1, refused: None };
        for _ in 1..threads {
            match std::thread::Builder::new().name(name.into()).spawn_scoped(s, work) {
                Ok(_) => started.threads += 1,
                Err(e) => {
                    started.refused = Some(e.to_string());
                    break;
                }
            }
        }
        work();
        started
    })
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Every task is done once, by as many threads as asked (this one included), and one
    /// thread alone does them all.
    #[test]
    fn the_started_threads_share_every_task_once() {
        for threads in [1, 4] {
            let (next, sum) = (AtomicUsize::new(0), AtomicUsize::new(0));
            let started = super::run(threads, "test-worker", || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= 1000 {
                    break;
                }
                sum.fetch_add(i, Ordering::Relaxed);
            });
            assert_eq!(started, super::Started { threads, refused: None });
            assert_eq!(sum.into_inner(), 999 * 1000 / 2, "{threads} thread(s)");
        }
    }
}
