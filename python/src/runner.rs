//! The library's own tokio runtime, and running a call on it with the GIL released: the
//! calling thread wakes every 50 ms to let Python see Ctrl-C (the call is then abandoned and
//! `KeyboardInterrupt` raised), and to hand the caller what the task sends it (batch progress).

use std::future::Future;
use std::sync::OnceLock;
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use tokio::sync::mpsc;

/// How often a waiting call checks for Ctrl-C.
const POLL: Duration = Duration::from_millis(50);

/// The runtime every call of the package runs on: multi-threaded, one worker per core, built on
/// first use and kept for the life of the process.
static RUNTIME: OnceLock<tokio::runtime::Runtime> = OnceLock::new();

/// The package's runtime, built on first use.
pub fn runtime() -> PyResult<&'static tokio::runtime::Runtime> {
    if let Some(rt) = RUNTIME.get() {
        return Ok(rt);
    }
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .thread_name("disco-layout")
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the async runtime: {e}")))?;
    // Two threads may race here; the loser's runtime is dropped before it ran anything.
    Ok(RUNTIME.get_or_init(|| rt))
}

/// What one wait saw.
enum Woke<T, M> {
    /// The task finished.
    Done(Result<T, tokio::task::JoinError>),
    /// The task sent a message.
    Message(M),
    /// Nothing yet: time to check for signals.
    Tick,
}

/// Runs `task` on the package's runtime and waits for it with the GIL released. Messages the
/// task sends on `messages` are handed to `on_message` in the calling thread, with the GIL
/// held; an error from it, or Ctrl-C (`KeyboardInterrupt`), abandons the task and is raised.
pub fn run_with<T, M>(
    py: Python<'_>,
    task: impl Future<Output = T> + Send + 'static,
    mut messages: mpsc::UnboundedReceiver<M>,
    mut on_message: impl FnMut(Python<'_>, M) -> PyResult<()>,
) -> PyResult<T>
where
    T: Send + 'static,
    M: Send + 'static,
{
    let rt = runtime()?;
    let mut handle = rt.spawn(task);
    let mut open = true;
    loop {
        let woke = py.detach(|| {
            rt.block_on(async {
                tokio::select! {
                    done = &mut handle => Woke::Done(done),
                    Some(m) = messages.recv(), if open => Woke::Message(m),
                    _ = tokio::time::sleep(POLL) => Woke::Tick,
                }
            })
        });
        let step = match woke {
            Woke::Done(Ok(value)) => {
                // What the task sent just before it finished is still due.
                while let Ok(m) = messages.try_recv() {
                    on_message(py, m)?;
                }
                return Ok(value);
            }
            Woke::Done(Err(e)) => {
                return Err(PyRuntimeError::new_err(format!(
                    "the call stopped unexpectedly: {e}"
                )));
            }
            Woke::Message(m) => on_message(py, m),
            Woke::Tick => {
                open = !messages.is_closed() || !messages.is_empty();
                Ok(())
            }
        };
        if let Err(e) = step.and_then(|()| py.check_signals()) {
            handle.abort();
            return Err(e);
        }
    }
}

/// [`run_with`] for a task that sends nothing.
pub fn run<T: Send + 'static>(
    py: Python<'_>,
    task: impl Future<Output = T> + Send + 'static,
) -> PyResult<T> {
    let (_tx, rx) = mpsc::unbounded_channel::<()>();
    run_with(py, task, rx, |_, ()| Ok(()))
}
