//! The trace of a run: every message between a scene's supervisor and its roles — who, what, how
//! long, how many tokens — so a user can see what each agent said and decided. Written as JSON lines.

use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

use serde::Serialize;
use serde_json::Value;

use disco_core::error::Result;
use disco_core::roles::Usage;

/// What happened.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TraceKind {
    /// The supervisor sent a role a request.
    Request,
    /// The role answered.
    Reply,
    /// The role failed (an error or a panic).
    Error,
    /// The role missed its deadline and was cut off.
    Timeout,
    /// The supervisor restarted the role's actor.
    Restart,
    /// The supervisor swapped in the role's fallback implementation.
    Fallback,
    /// A stage of the loop began (`detail` says which).
    Stage,
    /// One model call made by the role (`detail`: purpose, latency, tokens, attempts, error).
    ModelCall,
    /// The layout after a step of the loop (`detail`: step, group, round, objects, dropped);
    /// recorded only by a trace made with [`Trace::with_snapshots`].
    Snapshot,
    /// The scene finished.
    Done,
}

/// One event.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TraceEvent {
    /// Milliseconds since the trace began.
    pub t_ms: u64,
    /// The scene's id.
    pub scene: String,
    /// The agent (`planner`, `designer`, ... or a custom stage), or `supervisor`.
    pub role: String,
    /// The implementation serving the role.
    pub implementation: String,
    /// What happened.
    pub kind: TraceKind,
    /// How long the call took, for replies, errors and timeouts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ms: Option<f64>,
    /// Model usage, for replies.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub usage: Option<Usage>,
    /// The content: the request or reply in brief, the error, the stage.
    pub detail: Value,
}

/// A run's events, in order, shared by all scenes of the run.
#[derive(Debug)]
pub struct Trace {
    start: Instant,
    events: Mutex<Vec<TraceEvent>>,
    snapshots: bool,
    /// Whether events are kept at all.
    keeps: bool,
}

impl Default for Trace {
    fn default() -> Self {
        Trace {
            start: Instant::now(),
            events: Mutex::new(Vec::new()),
            snapshots: false,
            keeps: true,
        }
    }
}

impl Trace {
    /// A trace that also keeps the layout after every step (design, SRT, PRT of each group), for
    /// step-by-step renders and reports. Costs memory: a copy of the placed objects per step.
    pub fn with_snapshots() -> Self {
        Trace {
            snapshots: true,
            ..Trace::default()
        }
    }

    /// A trace that keeps nothing, for runs whose events nobody reads: a big scene's trace
    /// grows with every message, and the messages with the scene.
    pub fn discarding() -> Self {
        Trace {
            keeps: false,
            ..Trace::default()
        }
    }

    /// Whether events are kept (false for [`Trace::discarding`]): callers may skip building
    /// them.
    pub fn keeps_events(&self) -> bool {
        self.keeps
    }

    /// Whether snapshots are wanted.
    pub fn wants_snapshots(&self) -> bool {
        self.snapshots
    }

    /// Records one event (the time is filled in).
    pub fn record(&self, mut event: TraceEvent) {
        if !self.keeps {
            return;
        }
        event.t_ms = self.start.elapsed().as_millis() as u64;
        self.events
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(event);
    }

    /// A copy of every event so far.
    pub fn events(&self) -> Vec<TraceEvent> {
        self.events
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
    }

    /// Writes every event as one JSON line each, atomically.
    pub fn write_jsonl(&self, path: &Path) -> Result<()> {
        let mut out = String::new();
        for e in self.events() {
            out.push_str(&serde_json::to_string(&e).unwrap_or_default());
            out.push('\n');
        }
        disco_core::io::write_atomic(path, out.as_bytes())
    }
}
