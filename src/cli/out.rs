//! Everything the commands print on stdout goes through here (`outln!` and `out!`), so that
//! a reader that stops early (`disco batch ... | head -1`, `| true`) is not an error: the first
//! write that meets a closed pipe (EPIPE) silently drops the rest of the output and the command
//! goes on to finish its work; its exit code is its own (0 when it succeeded), never a panic.
//! Any other failure to write stdout (a full disk behind a redirect) ends the process with exit
//! code 1 and a message on stderr.
//!
//! Messages on stderr go through `errln!` (`disco_layout::io::to_stderr`): a stderr whose
//! reader has gone away drops them, and the command still ends with its own exit code.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once stdout's reader has gone away: later output is dropped.
static CLOSED: AtomicBool = AtomicBool::new(false);

/// Writes `text` to stdout as `outln!` and `out!` do.
pub fn write(text: &str) {
    if let Err(e) = try_write(&mut std::io::stdout().lock(), text) {
        disco_layout::io::to_stderr(&format!("error: cannot write the output: {e}\n"));
        std::process::exit(1);
    }
}

/// Writes `text` to `to` and flushes it; a closed pipe is remembered and not an error.
fn try_write(to: &mut impl Write, text: &str) -> std::io::Result<()> {
    if CLOSED.load(Ordering::Relaxed) {
        return Ok(());
    }
    match to.write_all(text.as_bytes()).and_then(|()| to.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
            CLOSED.store(true, Ordering::Relaxed);
            Ok(())
        }
        other => other,
    }
}

/// `println!` for the commands' output on stdout: a closed pipe ends the output quietly.
macro_rules! outln {
    () => {
        $crate::cli::out::write("\n")
    };
    ($($arg:tt)*) => {
        $crate::cli::out::write(&format!("{}\n", format_args!($($arg)*)))
    };
}

/// `print!` for the commands' output on stdout: a closed pipe ends the output quietly.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::out::write(&format!($($arg)*))
    };
}

/// `eprintln!` for messages on stderr: a closed or broken stderr drops them, never a panic.
macro_rules! errln {
    ($($arg:tt)*) => {
        disco_layout::io::to_stderr(&format!("{}\n", format_args!($($arg)*)))
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer whose reader has gone away.
    struct ClosedPipe;

    impl Write for ClosedPipe {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::ErrorKind::BrokenPipe.into())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_closed_pipe_is_not_an_error_but_a_full_disk_is() {
        assert!(try_write(&mut ClosedPipe, "x\n").is_ok());
        let mut full = std::io::Cursor::new([0u8; 1]);
        CLOSED.store(false, Ordering::Relaxed);
        assert!(try_write(&mut full, "too long").is_err());
    }
}
