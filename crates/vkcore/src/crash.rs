//! A crash is never silent: a fatal signal (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT), most
//! often raised inside the driver (Mesa 25's lavapipe dereferenced a null compute shader in its
//! queue thread, docs/mesa_lavapipe_statistics_crash.md), prints what the frame was doing before
//! the process dies: the driver, the frame, and the pass. For a one-shot frame the GPU was
//! running, the pass comes from the frame's crash marker (marker.rs), the host-visible word the
//! GPU writes after each pass, as a lost device reports it.
//!
//! The handler is async-signal-safe: it only loads atomics and the statics below (written by
//! the recording thread before the driver can see the frame), reads the marker with a volatile
//! load, formats into a buffer on its stack and writes it with write(2). Then it hands the signal
//! to the handler that was there before (Rust's own, which names a stack overflow) and re-raises
//! it with the default action, so the exit status is still the signal's (139 for SIGSEGV).
//! The statics describe the last frame recorded; with a ring, frames in flight before it are
//! named by number only.

use std::sync::atomic::{AtomicBool, AtomicPtr, AtomicU32, AtomicU64, AtomicU8, AtomicUsize, Ordering::Relaxed};
use std::sync::OnceLock;

/// Names a test sets to raise SIGSEGV in place of the pass of that name, after running the passes
/// before it: the crash marker then reads what a crash inside that pass would leave.
pub const TEST_SEGFAULT_ENV: &str = "CAUSTICLAB_TEST_SEGFAULT_IN_PASS";

const IDLE: u8 = 0;
const RECORDING: u8 = 1;
const RUNNING: u8 = 2;
const RING: u8 = 3;

/// Text a signal handler may read: bytes written before the length that covers them.
struct Text<const N: usize> {
    len: AtomicUsize,
    bytes: [AtomicU8; N],
}

impl<const N: usize> Text<N> {
    const fn new() -> Self {
        Text { len: AtomicUsize::new(0), bytes: [const { AtomicU8::new(0) }; N] }
    }
    fn set(&self, s: &str) {
        self.len.store(0, Relaxed);
        self.append(s.as_bytes());
    }
    /// Appends `b` (cut at the capacity).
    fn append(&self, b: &[u8]) {
        let at = self.len.load(Relaxed);
        let n = b.len().min(N - at);
        for (i, byte) in b[..n].iter().enumerate() {
            self.bytes[at + i].store(*byte, Relaxed);
        }
        self.len.store(at + n, std::sync::atomic::Ordering::Release);
    }
    fn byte(&self, i: usize) -> u8 {
        self.bytes[i].load(Relaxed)
    }
    fn len(&self) -> usize {
        self.len.load(std::sync::atomic::Ordering::Acquire).min(N)
    }
}

static DRIVER: Text<256> = Text::new();
/// The pass names of the frame being recorded or run, each followed by a NUL.
static PASSES: Text<16384> = Text::new();
static PASS_COUNT: AtomicU32 = AtomicU32::new(0);
static PHASE: AtomicU8 = AtomicU8::new(IDLE);
/// The pass being recorded (RECORDING).
static CURRENT: AtomicU32 = AtomicU32::new(0);
/// The running one-shot frame's crash marker (RUNNING).
static MARKER: AtomicPtr<u32> = AtomicPtr::new(std::ptr::null_mut());
/// Frames recorded so far by this process (the last one's number).
static FRAME: AtomicU64 = AtomicU64::new(0);
/// A ring has submitted frames that may still run (until its `finish` or drop).
static RING_IN_FLIGHT: AtomicBool = AtomicBool::new(false);
/// Set by the first fatal signal: a second one (Rust's handler aborting on a stack overflow,
/// inside ours) goes straight to the default action.
static REPORTING: AtomicBool = AtomicBool::new(false);

const SIGNALS: [(libc::c_int, &str); 5] = [
    (libc::SIGSEGV, "SIGSEGV"),
    (libc::SIGBUS, "SIGBUS"),
    (libc::SIGILL, "SIGILL"),
    (libc::SIGFPE, "SIGFPE"),
    (libc::SIGABRT, "SIGABRT"),
];

/// The handlers that were installed before ours, by signal.
struct Previous([libc::sigaction; SIGNALS.len()]);
// SAFETY: plain data (function addresses, a signal mask, flags), written once before any
// handler of ours can run and only read after.
unsafe impl Sync for Previous {}
unsafe impl Send for Previous {}
static PREVIOUS: OnceLock<Previous> = OnceLock::new();

/// Installs the handlers (once per process) and names the driver they will report.
pub(crate) fn install(driver: &str) {
    DRIVER.set(driver);
    PREVIOUS.get_or_init(|| {
        // SAFETY: sigaction with a zeroed struct filled as the man page says; the handler is
        // async-signal-safe (module doc).
        unsafe {
            let mut previous: [libc::sigaction; SIGNALS.len()] = std::mem::zeroed();
            for (i, (sig, _)) in SIGNALS.iter().enumerate() {
                let mut act: libc::sigaction = std::mem::zeroed();
                act.sa_sigaction = on_fatal_signal as *const () as usize;
                act.sa_flags = libc::SA_SIGINFO | libc::SA_ONSTACK;
                libc::sigemptyset(&mut act.sa_mask);
                libc::sigaction(*sig, &act, &mut previous[i]);
            }
            Previous(previous)
        }
    });
}

/// Pass `index` of a new or continued frame is being recorded.
pub(crate) fn recording(index: u32, name: &str) {
    if index == 0 {
        PASS_COUNT.store(0, Relaxed);
        PASSES.set("");
        FRAME.fetch_add(1, Relaxed);
    }
    PASSES.append(name.as_bytes());
    PASSES.append(&[0]);
    PASS_COUNT.store(index + 1, Relaxed);
    CURRENT.store(index, Relaxed);
    PHASE.store(RECORDING, Relaxed);
}

/// A one-shot frame (or, with host pass times, its passes so far) goes to the device, which
/// writes its progress into `marker`; until [`idle`].
pub(crate) fn running(marker: *const u32) {
    MARKER.store(marker as *mut u32, Relaxed);
    PHASE.store(RUNNING, std::sync::atomic::Ordering::Release);
}

/// A ring submitted the frame last recorded (frames before it may still be running).
pub(crate) fn ring_submitted() {
    RING_IN_FLIGHT.store(true, Relaxed);
    PHASE.store(RING, Relaxed);
}

/// A ring waited for all its frames (its `finish`, or its drop).
pub(crate) fn ring_idle() {
    RING_IN_FLIGHT.store(false, Relaxed);
    let _ = PHASE.compare_exchange(RING, IDLE, Relaxed, Relaxed);
}

/// The device has finished (or failed) what it was given: the marker is no longer read.
pub(crate) fn idle() {
    PHASE.store(IDLE, std::sync::atomic::Ordering::Release);
    MARKER.store(std::ptr::null_mut(), Relaxed);
}

/// Whether [`TEST_SEGFAULT_ENV`] names pass `name`.
/// The environment is read once per process, not at every pass.
pub(crate) fn test_segfault_requested(name: &str) -> bool {
    static PASS: OnceLock<Option<std::ffi::OsString>> = OnceLock::new();
    PASS.get_or_init(|| std::env::var_os(TEST_SEGFAULT_ENV)).as_deref().is_some_and(|v| v == name)
}

/// Raises SIGSEGV, as a driver crashing inside the running frame would (the test hook).
pub(crate) fn raise_test_segfault() -> ! {
    // SAFETY: raise(3) with a valid signal; our handler prints and re-raises with the default
    // action, which ends the process.
    unsafe {
        libc::raise(libc::SIGSEGV);
    }
    unreachable!("SIGSEGV returned")
}

/// A fixed buffer on the handler's stack (no allocation in a signal handler).
struct Message {
    buf: [u8; 2048],
    len: usize,
}

impl Message {
    fn put(&mut self, b: &[u8]) {
        let n = b.len().min(self.buf.len() - self.len);
        self.buf[self.len..self.len + n].copy_from_slice(&b[..n]);
        self.len += n;
    }
    fn text<const N: usize>(&mut self, t: &Text<N>, from: usize, to: usize) {
        for i in from..to {
            self.put(&[t.byte(i)]);
        }
    }
    fn num(&mut self, mut v: u64) {
        let mut digits = [0u8; 20];
        let mut i = digits.len();
        loop {
            i -= 1;
            digits[i] = b'0' + (v % 10) as u8;
            v /= 10;
            if v == 0 {
                break;
            }
        }
        self.put(&digits[i..]);
    }
    /// Pass `k`'s name from [`PASSES`], in backquotes.
    fn pass(&mut self, k: u32) {
        let (len, mut start, mut seen) = (PASSES.len(), 0, 0);
        for i in 0..len {
            if PASSES.byte(i) == 0 {
                if seen == k {
                    self.put(b"`");
                    self.text(&PASSES, start, i);
                    self.put(b"`");
                    return;
                }
                seen += 1;
                start = i + 1;
            }
        }
        self.put(b"(unnamed)");
    }
}

extern "C" fn on_fatal_signal(sig: libc::c_int, info: *mut libc::siginfo_t, context: *mut libc::c_void) {
    if REPORTING.swap(true, Relaxed) {
        // SAFETY: signal(2) and raise(3) are async-signal-safe.
        unsafe {
            libc::signal(sig, libc::SIG_DFL);
            libc::raise(sig);
        }
        return;
    }
    let mut m = Message { buf: [0; 2048], len: 0 };
    let name = SIGNALS.iter().find(|(s, _)| *s == sig).map_or("signal", |(_, n)| n);
    m.put(b"\ncausticlab: fatal ");
    m.put(name.as_bytes());
    m.put(b" (signal ");
    m.num(sig as u64);
    m.put(b"), on device ");
    m.text(&DRIVER, 0, DRIVER.len());
    let passes = PASS_COUNT.load(Relaxed);
    match PHASE.load(std::sync::atomic::Ordering::Acquire) {
        RECORDING => {
            m.put(b", while recording pass ");
            m.pass(CURRENT.load(Relaxed));
            m.put(b" of this process's frame ");
            m.num(FRAME.load(Relaxed));
            if RING_IN_FLIGHT.load(Relaxed) {
                m.put(b", with earlier frames of a ring running on the device (ring frames mark no pass)");
            } else {
                m.put(b" (the driver crashed taking its commands, before the device ran them)");
            }
        }
        RUNNING => {
            // What is known so far goes out first: the marker is read last.
            // SAFETY: write(2) on stderr with our own buffer.
            unsafe {
                libc::write(2, m.buf.as_ptr() as *const libc::c_void, m.len);
            }
            m.len = 0;
            let marker = MARKER.load(Relaxed);
            // SAFETY: the marker is mapped until `idle` clears it, which the recording thread
            // does before the frame's resources are freed. Another thread's frame may finish in
            // between (several contexts in one process, as in the tests): the header above is
            // already out if this read then faults.
            let finished = if marker.is_null() { 0 } else { unsafe { std::ptr::read_volatile(marker) } };
            m.put(b", while the device ran this process's frame ");
            m.num(FRAME.load(Relaxed));
            m.put(b": its crash marker says ");
            m.num(finished.min(passes) as u64);
            m.put(b" of its ");
            m.num(passes as u64);
            m.put(b" passes finished");
            if finished > 0 && finished <= passes {
                m.put(b", the last ");
                m.pass(finished - 1);
            }
            if finished < passes {
                m.put(b"; it stopped in pass ");
                m.pass(finished);
            }
        }
        RING => {
            m.put(b", while the frames of a ring ran (frame ");
            m.num(FRAME.load(Relaxed));
            m.put(b" the last submitted; ring frames mark no pass: rerun with per-pass frames to name it)");
        }
        _ => m.put(b", outside any frame (making pipelines or resources, or reading results)"),
    }
    m.put(b"\n");
    // SAFETY: write(2) on stderr with our own buffer.
    unsafe {
        libc::write(2, m.buf.as_ptr() as *const libc::c_void, m.len);
    }
    // SAFETY: the previous handler was installed for this signal by this process (Rust's runtime
    // or the default); it is called as it asked to be, then the default action ends the process.
    unsafe {
        if let (Some(prev), Some(i)) = (PREVIOUS.get(), SIGNALS.iter().position(|(s, _)| *s == sig)) {
            let p = &prev.0[i];
            if p.sa_sigaction != libc::SIG_DFL && p.sa_sigaction != libc::SIG_IGN {
                if p.sa_flags & libc::SA_SIGINFO != 0 {
                    let f: extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void) =
                        std::mem::transmute(p.sa_sigaction);
                    f(sig, info, context);
                } else {
                    let f: extern "C" fn(libc::c_int) = std::mem::transmute(p.sa_sigaction);
                    f(sig);
                }
            }
        }
        libc::signal(sig, libc::SIG_DFL);
        libc::raise(sig);
    }
}
