//! The process groups of agent processes: each agent runs in a group of its own, so that what it
//! forks goes with it, and every live group is listed here, so that disco can kill them all when
//! it is itself told to stop (SIGTERM, SIGINT).
//!
//! A [`Group`] is the handle of one live group: dropping it kills the whole group with SIGKILL
//! (deadline, restart, discard, scene end, a cut-off call). [`kill_all`] kills every live group
//! and refuses to start new ones; the binary calls it from its signal handler.
//!
//! A process that leaves its group on purpose (`setsid`, `setpgid`) is out of reach; the
//! protocol's agents have no reason to.

use std::collections::BTreeSet;
use std::sync::Mutex;

/// The live groups (by their leader's process id), and whether disco is shutting down.
struct Live {
    groups: BTreeSet<u32>,
    closed: bool,
}

static LIVE: Mutex<Live> = Mutex::new(Live {
    groups: BTreeSet::new(),
    closed: false,
});

fn live() -> std::sync::MutexGuard<'static, Live> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Why a group could not be started.
#[derive(Debug, thiserror::Error)]
pub enum StartError {
    /// disco is shutting down ([`kill_all`] ran): no new agent starts.
    #[error("disco is shutting down; no agent process is started")]
    ShuttingDown,
    /// The program could not be started.
    #[error("{0}")]
    Spawn(#[from] std::io::Error),
}

/// A live process group, killed (SIGKILL to every member) when dropped.
#[derive(Debug)]
pub struct Group {
    pgid: u32,
}

impl Group {
    /// Starts `command` as the leader of a new process group and lists the group as live. The
    /// list is held while the process starts, so that [`kill_all`] either sees the group or
    /// runs before it and makes this refuse.
    pub fn spawn(
        command: &mut tokio::process::Command,
    ) -> Result<(tokio::process::Child, Group), StartError> {
        #[cfg(unix)]
        command.process_group(0);
        let mut live = live();
        if live.closed {
            return Err(StartError::ShuttingDown);
        }
        let child = command.spawn()?;
        let pgid = child.id().unwrap_or(0);
        live.groups.insert(pgid);
        Ok((child, Group { pgid }))
    }

    /// The group's id (its leader's process id).
    pub fn id(&self) -> u32 {
        self.pgid
    }

    /// Kills every process of the group now (the leader still has to be reaped by its owner).
    pub fn kill(&self) {
        kill_group(self.pgid);
    }
}

impl Drop for Group {
    fn drop(&mut self) {
        kill_group(self.pgid);
        live().groups.remove(&self.pgid);
    }
}

/// Sends SIGKILL to every process of group `pgid`; a group that is gone already is no error.
fn kill_group(pgid: u32) {
    #[cfg(unix)]
    {
        let Some(pid) = i32::try_from(pgid)
            .ok()
            .and_then(rustix::process::Pid::from_raw)
        else {
            return;
        };
        // Process 1's "group" would be everything we may signal: never.
        if pid == rustix::process::Pid::INIT {
            return;
        }
        let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
    }
    #[cfg(not(unix))]
    let _ = pgid;
}

/// Kills every live agent process group and refuses to start new ones from now on; returns how
/// many groups there were. For the binary's SIGTERM/SIGINT handler: no agent outlives disco.
pub fn kill_all() -> usize {
    let mut live = live();
    live.closed = true;
    let groups = std::mem::take(&mut live.groups);
    for pgid in &groups {
        kill_group(*pgid);
    }
    groups.len()
}

/// How many agent process groups are live now.
pub fn live_count() -> usize {
    live().groups.len()
}
