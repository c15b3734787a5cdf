//! `impl = "process"`: an agent served by a child process speaking newline-delimited JSON on its
//! stdin and stdout. One process per role instance, started on the first call and reused; its
//! stderr goes to the log. A process that exits is reported as a crash (the supervisor restarts
//! the role, and the next call starts a new process); one that does not answer within the
//! deadline is killed and reaped.

use std::collections::VecDeque;
use std::process::Stdio;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use async_trait::async_trait;
use tokio::io::{AsyncBufReadExt, AsyncWriteExt, BufReader, Lines};
use tokio::process::{Child, ChildStdin, ChildStdout, Command};

use super::Transport;
use disco_core::roles::RoleError;

/// How many of the last stderr lines a crash report quotes.
const STDERR_KEPT: usize = 3;

/// A running agent process and its pipes.
struct Running {
    child: Child,
    stdin: ChildStdin,
    stdout: Lines<BufReader<ChildStdout>>,
    /// The task forwarding stderr to the log; it ends when the process closes its stderr.
    stderr: tokio::task::JoinHandle<()>,
}

/// A role served by a child process.
pub struct ProcessTransport {
    agent: String,
    command: Vec<String>,
    deadline: Duration,
    running: tokio::sync::Mutex<Option<Running>>,
    stderr_tail: Arc<Mutex<VecDeque<String>>>,
    /// The id of the last process started (0: none yet).
    last_pid: AtomicU32,
}

impl ProcessTransport {
    /// A transport for agent `agent` that runs `command` (program first) when first called, and
    /// waits at most `deadline` for each reply.
    pub fn new(agent: &str, command: Vec<String>, deadline: Duration) -> Result<Self, String> {
        if command.first().is_none_or(|p| p.trim().is_empty()) {
            return Err("impl \"process\" needs `command = [\"program\", \"arg\", ...]`".into());
        }
        Ok(ProcessTransport {
            agent: agent.to_string(),
            command,
            deadline,
            running: tokio::sync::Mutex::new(None),
            stderr_tail: Arc::new(Mutex::new(VecDeque::new())),
            last_pid: AtomicU32::new(0),
        })
    }

    /// The id of the running process, if one runs.
    pub async fn pid(&self) -> Option<u32> {
        self.running
            .lock()
            .await
            .as_ref()
            .and_then(|r| r.child.id())
    }

    /// The id of the last process started, if any (it may have ended since).
    pub fn last_pid(&self) -> Option<u32> {
        Some(self.last_pid.load(Ordering::Relaxed)).filter(|p| *p != 0)
    }

    /// The command as typed, for messages.
    fn shown(&self) -> String {
        self.command.join(" ")
    }

    /// Starts the process, with its stderr forwarded to the log.
    fn start(&self) -> Result<Running, RoleError> {
        let mut child = Command::new(&self.command[0])
            .args(&self.command[1..])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .kill_on_drop(true)
            .spawn()
            .map_err(|e| RoleError::Failed(format!("cannot start `{}`: {e}", self.shown())))?;
        let (Some(stdin), Some(stdout), Some(stderr)) =
            (child.stdin.take(), child.stdout.take(), child.stderr.take())
        else {
            return Err(RoleError::Failed(format!(
                "`{}` started without its pipes",
                self.shown()
            )));
        };
        let (agent, tail) = (self.agent.clone(), Arc::clone(&self.stderr_tail));
        let stderr = tokio::spawn(async move {
            let mut lines = BufReader::new(stderr).lines();
            while let Ok(Some(line)) = lines.next_line().await {
                tracing::info!(target: "disco::agent", agent = %agent, "{line}");
                let mut tail = tail.lock().unwrap_or_else(|e| e.into_inner());
                if tail.len() == STDERR_KEPT {
                    tail.pop_front();
                }
                tail.push_back(line);
            }
        });
        self.last_pid
            .store(child.id().unwrap_or(0), Ordering::Relaxed);
        tracing::debug!(agent = %self.agent, pid = ?child.id(), "started `{}`", self.shown());
        Ok(Running {
            child,
            stdin,
            stdout: BufReader::new(stdout).lines(),
            stderr,
        })
    }

    /// The process ended: reap it and report a crash, quoting the end of its stderr.
    async fn crashed(&self, mut running: Running, what: &str) -> RoleError {
        let status = match tokio::time::timeout(Duration::from_secs(2), running.child.wait()).await
        {
            Ok(Ok(s)) => s.to_string(),
            _ => {
                let _ = running.child.kill().await;
                "killed".to_string()
            }
        };
        // Let the stderr forwarder read the last words.
        let _ = tokio::time::timeout(Duration::from_millis(500), running.stderr).await;
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
        let sent = async {
            running.stdin.write_all(&out).await?;
            running.stdin.flush().await
        }
        .await;
        if sent.is_err() {
            return Err(self
                .crashed(running, "exited before reading the request")
                .await);
        }
        match tokio::time::timeout(self.deadline, running.stdout.next_line()).await {
            Ok(Ok(Some(reply))) => {
                *slot = Some(running);
                Ok(reply)
            }
            Ok(Ok(None)) | Ok(Err(_)) => {
                Err(self.crashed(running, "exited before answering").await)
            }
            Err(_) => {
                let _ = running.child.kill().await;
                tracing::warn!(agent = %self.agent, "killed `{}`: no answer within {:.1} s", self.shown(), self.deadline.as_secs_f64());
                Err(RoleError::Deadline(self.deadline.as_secs_f64()))
            }
        }
    }

    async fn discard(&self) {
        if let Some(mut running) = self.running.lock().await.take() {
            let _ = running.child.kill().await;
        }
    }
}
