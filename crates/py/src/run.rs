//! Long calls (batches, studies): the work runs with the GIL released on a worker thread
//! (and rayon's pool, or a pool of the threads asked for), while the calling thread
//! reports progress to a Python callback and watches for Ctrl-C.
//!
//! Progress: the work counts finished simulations in atomics; the calling thread, every
//! [`POLL`], takes the GIL, calls `progress(phase, done, total)` when the count moved and
//! runs Python's signal handlers. A `KeyboardInterrupt` there asks the work to stop: a
//! batch skips the simulations not yet started, a study unwinds from its next finished
//! simulation (its journals keep every simulation that finished, so a rerun continues
//! where it stopped), and the call raises `KeyboardInterrupt` once the work is over.

use crate::errors::{Cancelled, guarded, unwind_error};
use pyo3::prelude::*;
use slipload_opt::eval::progress::{Phase, Progress};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

/// How often the calling thread reports progress and checks for Ctrl-C.
const POLL: Duration = Duration::from_millis(50);

/// The state a running call shares with the thread that watches it.
#[derive(Debug, Default)]
pub struct Control {
    phase: Mutex<(String, usize)>,
    done: AtomicUsize,
    cancel: AtomicBool,
    finished: AtomicBool,
}

impl Control {
    /// A phase starts (`label`, about `total` simulations).
    pub fn begin(&self, label: &str, total: usize) {
        if let Ok(mut p) = self.phase.lock() {
            *p = (label.to_string(), total);
        }
        self.done.store(0, Ordering::Relaxed);
    }

    /// One simulation finished; unwinds with [`Cancelled`] when a stop was asked for (a
    /// study's simulations report here, from worker threads).
    pub fn tick(&self) {
        self.done.fetch_add(1, Ordering::Relaxed);
        if self.cancelled() {
            std::panic::resume_unwind(Box::new(Cancelled));
        }
    }

    /// One simulation finished (a batch's: it stops by itself, it need not unwind).
    pub fn count(&self) {
        self.done.fetch_add(1, Ordering::Relaxed);
    }

    /// Whether a stop was asked for.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    fn snapshot(&self) -> (String, usize, usize) {
        let (label, total) = self
            .phase
            .lock()
            .map(|p| p.clone())
            .unwrap_or_else(|_| (String::new(), 0));
        (label, self.done.load(Ordering::Relaxed), total)
    }
}

impl Progress for Control {
    fn start(&self, phase: Phase, work: usize) {
        self.begin(phase.label(), work);
    }
    fn tick(&self) {
        Control::tick(self);
    }
}

/// Runs `work` off the GIL on `threads` worker threads (rayon's global pool when `None`),
/// reporting to `progress` and stopping on Ctrl-C, as the module says. A panic in the work
/// becomes `slipload.InternalError`.
pub fn watched<T: Send>(
    py: Python<'_>,
    threads: Option<&Bound<'_, PyAny>>,
    progress: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce(&Control) -> PyResult<T> + Send,
) -> PyResult<T> {
    const EXPECTS: &str = "a whole number of worker threads, 1 or more";
    let pool = match crate::args::count(threads, "threads", EXPECTS)? {
        None => None,
        Some((n, text)) => Some({
            // the command line's rule (`--threads`), from the library
            slipload_sim::limits::check_threads(n)
                .map_err(|e| crate::errors::input(format!("threads={text}: {e}")))?;
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| {
                    crate::errors::input(format!("threads={text}: cannot start them: {e}"))
                })?
        }),
    };
    let control = Control::default();
    let mut interrupted: Option<PyErr> = None;
    let mut callback_error: Option<PyErr> = None;
    let mut last = (String::new(), usize::MAX, usize::MAX);
    let outcome = std::thread::scope(|s| {
        let ctl = &control;
        let pool = pool.as_ref();
        let handle = s.spawn(move || {
            let r = catch_unwind(AssertUnwindSafe(|| match pool {
                Some(p) => p.install(|| work(ctl)),
                None => work(ctl),
            }));
            ctl.finished.store(true, Ordering::Release);
            r
        });
        loop {
            let finished = py.detach(|| {
                let mut waited = Duration::ZERO;
                while waited < POLL && !control.finished.load(Ordering::Acquire) {
                    std::thread::sleep(Duration::from_millis(2));
                    waited += Duration::from_millis(2);
                }
                control.finished.load(Ordering::Acquire)
            });
            if let Some(cb) = progress
                && callback_error.is_none()
            {
                let now = control.snapshot();
                if now != last && !now.0.is_empty() {
                    if let Err(e) = cb.call1((now.0.as_str(), now.1, now.2)) {
                        // a failing callback stops the run as Ctrl-C would
                        callback_error = Some(e);
                        control.cancel.store(true, Ordering::Relaxed);
                    }
                    last = now;
                }
            }
            if interrupted.is_none()
                && let Err(e) = py.check_signals()
            {
                interrupted = Some(e);
                control.cancel.store(true, Ordering::Relaxed);
            }
            if finished {
                break;
            }
        }
        handle.join()
    });
    if let Some(e) = interrupted {
        return Err(e);
    }
    if let Some(e) = callback_error {
        return Err(e);
    }
    // the work's own unwind is caught inside its thread; the thread's, should the catch
    // itself fail, at the join
    match outcome {
        Ok(Ok(r)) => r,
        Ok(Err(payload)) | Err(payload) => Err(unwind_error(payload)),
    }
}

/// As [`watched`] for a call with no progress and no pool: the GIL released, panics caught.
pub fn detached<T: Send>(py: Python<'_>, work: impl FnOnce() -> PyResult<T> + Send) -> PyResult<T> {
    py.detach(|| guarded(work))
}
