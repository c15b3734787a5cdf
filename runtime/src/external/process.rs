//! `impl = "process"`: an agent served by a child process speaking newline-delimited JSON on its
//! stdin and stdout. One process per role instance, started on the first call and reused; its
//! stderr goes to the log. A process that exits is reported as a crash (the supervisor restarts
//! the role, and the next call starts a new process); one that does not answer within the
//! deadline is killed and reaped.
//!
//! Each process leads a process group of its own ([`super::group`]): whatever it forks is killed
//! with it, when it misses its deadline, breaks the protocol, crashes, or its role actor stops
//! (restart, fallback, scene end). Every read from it is capped ([`super::capped`]): a reply line
//! over `max_reply_bytes` is an unusable answer, and a stderr line is logged up to
//! [`STDERR_LINE_BYTES`], the rest of it skipped unread.

use std::collections::VecDeque;
use std::process::Stdio;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use async_trait::async_trait;
use tokio::io::{AsyncWriteExt, BufReader};
use tokio::process::{Child, ChildStdin, ChildStdout, Command};

use super::Transport;
use super::capped::{self, Line, MAX_REPLY_BYTES};
use super::group::{Group, StartError};
use disco_core::roles::RoleError;

/// How many of the last stderr lines a crash report quotes.
const STDERR_KEPT: usize = 3;

/// The longest stderr line logged; the rest of a longer line is skipped unread.
pub const STDERR_LINE_BYTES: usize = 4096;

/// The longest piece of one stderr line a crash report quotes.
const STDERR_QUOTED: usize = 300;

/// How long a killed or exiting process is waited for before it is left to the reaper.
const REAP_WAIT: Duration = Duration::from_secs(2);

/// A running agent process and its pipes.
struct Running {
    /// The process group; declared first, so that it is dropped (and killed) first.
    group: Group,
    child: Child,
    stdin: ChildStdin,
    stdout: BufReader<ChildStdout>,
    /// The task forwarding stderr to the log; it ends when the process closes its stderr.
    stderr: tokio::task::JoinHandle<()>,
}

impl Running {
    /// Kills the whole group and reaps the process (waiting at most [`REAP_WAIT`]).
    async fn stop(mut self) {
        self.group.kill();
        let _ = tokio::time::timeout(REAP_WAIT, self.child.wait()).await;
    }
}

/// A role served by a child process.
pub struct ProcessTransport {
    agent: String,
    command: Vec<String>,
    deadline: Duration,
    max_reply: usize,
    running: tokio::sync::Mutex<Option<Running>>,
    stderr_tail: Arc<Mutex<VecDeque<String>>>,
    /// The id of the last process started (0: none yet).
    last_pid: AtomicU32,
}

impl ProcessTransport {
    /// A transport for agent `agent` that runs `command` (program first) when first called, and
    /// waits at most `deadline` for each reply, of at most [`MAX_REPLY_BYTES`].
    pub fn new(agent: &str, command: Vec<String>, deadline: Duration) -> Result<Self, String> {
        if command.first().is_none_or(|p| p.trim().is_empty()) {
            return Err("impl \"process\" needs `command = [\"program\", \"arg\", ...]`".into());
        }
        Ok(ProcessTransport {
            agent: agent.to_string(),
            command,
            deadline,
            max_reply: MAX_REPLY_BYTES,
            running: tokio::sync::Mutex::new(None),
            stderr_tail: Arc::new(Mutex::new(VecDeque::new())),
            last_pid: AtomicU32::new(0),
        })
    }

    /// The same transport with replies capped at `bytes` (the agent's `max_reply_bytes`).
    pub fn with_max_reply(mut self, bytes: usize) -> Self {
        self.max_reply = bytes.max(1);
        self
    }

    /// The id of the running process, if one runs.
    pub async fn pid(&self) -> Option<u32> {
        self.running
            .lock()
            .await
            .as_ref()
            .and_then(|r| r.child.id())
    }

    /// The id of the last process started, if any (it may have ended since). It is also the id
    /// of the process group the agent runs in.
    pub fn last_pid(&self) -> Option<u32> {
        Some(self.last_pid.load(Ordering::Relaxed)).filter(|p| *p != 0)
    }

    /// The command as typed, for messages.
    fn shown(&self) -> String {
        self.command.join(" ")
    }

    /// A reply that breaks the protocol.
    fn broken(&self, why: &str) -> RoleError {
        RoleError::Failed(format!(
            "the {} agent broke the protocol: {why}",
            self.agent
        ))
    }

    /// Starts the process in a process group of its own, with its stderr forwarded to the log.
    fn start(&self) -> Result<Running, RoleError> {
        let mut command = Command::new(&self.command[0]);
        command
            .args(&self.command[1..])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .kill_on_drop(true);
        let (mut child, group) = Group::spawn(&mut command).map_err(|e| match e {
            StartError::ShuttingDown => RoleError::Failed(e.to_string()),
            StartError::Spawn(e) => {
                RoleError::Failed(format!("cannot start `{}`: {e}", self.shown()))
            }
        })?;
        let (Some(stdin), Some(stdout), Some(stderr)) =
            (child.stdin.take(), child.stdout.take(), child.stderr.take())
        else {
            return Err(RoleError::Failed(format!(
                "`{}` started without its pipes",
                self.shown()
            )));
        };
        let (agent, tail) = (self.agent.clone(), Arc::clone(&self.stderr_tail));
        let stderr = tokio::spawn(forward_stderr(BufReader::new(stderr), agent, tail));
        self.last_pid
            .store(child.id().unwrap_or(0), Ordering::Relaxed);
        tracing::debug!(agent = %self.agent, pid = ?child.id(), "started `{}`", self.shown());
        Ok(Running {
            group,
            child,
            stdin,
            stdout: BufReader::new(stdout),
            stderr,
        })
    }

    /// The process ended: reap it, kill what is left of its group and report a crash, quoting
    /// the end of its stderr.
    async fn crashed(&self, mut running: Running, what: &str) -> RoleError {
        let status = match tokio::time::timeout(REAP_WAIT, running.child.wait()).await {
            Ok(Ok(s)) => s.to_string(),
            _ => "killed".to_string(),
        };
        // What it forked goes with it, and their stderr closes.
        running.group.kill();
        if status == "killed" {
            let _ = tokio::time::timeout(REAP_WAIT, running.child.wait()).await;
        }
        // Let the stderr forwarder read the last words.
        let _ = tokio::time::timeout(Duration::from_millis(500), &mut running.stderr).await;
        drop(running);
        let tail: Vec<String> = self
            .stderr_tail
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .drain(..)
            .collect();
        let said = match tail.is_empty() {
            true => String::new(),
            false => format!("; its stderr ended with: {}", tail.join(" | ")),
        };
        RoleError::Panicked(format!(
            "the agent process `{}` {what} ({status}){said}",
            self.shown()
        ))
    }
}

/// Forwards an agent's stderr to the log, line by line, each line capped at
/// [`STDERR_LINE_BYTES`] (the rest of a longer one is skipped unread), keeping the last
/// [`STDERR_KEPT`] lines for a crash report.
async fn forward_stderr(
    mut reader: BufReader<tokio::process::ChildStderr>,
    agent: String,
    tail: Arc<Mutex<VecDeque<String>>>,
) {
    loop {
        let (text, skipped) = match capped::read_line(&mut reader, STDERR_LINE_BYTES).await {
            Ok(Line::Line(bytes)) => (String::from_utf8_lossy(&bytes).into_owned(), 0),
            Ok(Line::TooLong(bytes)) => {
                let skipped = capped::skip_line(&mut reader).await.unwrap_or(0);
                (String::from_utf8_lossy(&bytes).into_owned(), skipped)
            }
            Ok(Line::End) | Err(_) => return,
        };
        let rest = match skipped {
            0 => String::new(),
            n => format!(" [... {n} more bytes of this line not shown]"),
        };
        tracing::info!(target: "disco::agent", agent = %agent, "{text}{rest}");
        // A crash report quotes the start of the line, and says when there was more.
        let mut quoted: String = text.chars().take(STDERR_QUOTED).collect();
        if quoted.len() < text.len() && skipped == 0 {
            quoted.push_str(" [...]");
        }
        quoted.push_str(&rest);
        let mut tail = tail.lock().unwrap_or_else(|e| e.into_inner());
        if tail.len() == STDERR_KEPT {
            tail.pop_front();
        }
        tail.push_back(quoted);
    }
}

#[async_trait]
impl Transport for ProcessTransport {
    async fn exchange(&self, line: String) -> Result<String, RoleError> {
        let mut slot = self.running.lock().await;
        let mut running = match slot.take() {
            Some(r) => r,
            None => self.start()?,
        };
        let mut out = line.into_bytes();
        out.push(b'\n');
        // The deadline covers the whole exchange: an agent that never reads its stdin must not
        // hold disco on a full pipe.
        let due = tokio::time::Instant::now() + self.deadline;
        let send = async {
            running.stdin.write_all(&out).await?;
            running.stdin.flush().await
        };
        let read = match tokio::time::timeout_at(due, send).await {
            Ok(Ok(())) => {
                let read = capped::read_line(&mut running.stdout, self.max_reply);
                tokio::time::timeout_at(due, read).await
            }
            Ok(Err(_)) => {
                return Err(self
                    .crashed(running, "exited before reading the request")
                    .await);
            }
            Err(elapsed) => Err(elapsed),
        };
        match read {
            Ok(Ok(Line::Line(reply))) => match capped::utf8(reply) {
                Ok(text) => {
                    *slot = Some(running);
                    Ok(text)
                }
                Err(why) => {
                    running.stop().await;
                    Err(self.broken(&why))
                }
            },
            Ok(Ok(Line::TooLong(_))) => {
                running.stop().await;
                tracing::warn!(agent = %self.agent, "killed `{}`: its reply passed {}", self.shown(), capped::shown(self.max_reply));
                Err(self.broken(&capped::too_long(self.max_reply)))
            }
            Ok(Ok(Line::End)) | Ok(Err(_)) => {
                Err(self.crashed(running, "exited before answering").await)
            }
            Err(_) => {
                running.stop().await;
                tracing::warn!(agent = %self.agent, "killed `{}`: no answer within {:.1} s", self.shown(), self.deadline.as_secs_f64());
                Err(RoleError::Deadline(self.deadline.as_secs_f64()))
            }
        }
    }

    async fn discard(&self) {
        if let Some(running) = self.running.lock().await.take() {
            running.stop().await;
        }
    }
}
