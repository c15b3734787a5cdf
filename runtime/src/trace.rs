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
    /// A tool moved an object no model asked to move (`detail`: the object, from where to
    /// where, by which step, why); the next request of every agent says so too.
    Moved,
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
    listener: Option<Listener>,
}

/// Told of every event as it is recorded, e.g. to show a run's progress.
struct Listener(Box<dyn Fn(&TraceEvent) + Send + Sync>);

impl std::fmt::Debug for Listener {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Listener")
    }
}

impl Default for Trace {
    fn default() -> Self {
        Trace {
            start: Instant::now(),
            events: Mutex::new(Vec::new()),
            snapshots: false,
            keeps: true,
            listener: None,
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

    /// Whether anyone reads events (false for a [`Trace::discarding`] trace with no
    /// listener): callers may skip building them.
    pub fn keeps_events(&self) -> bool {
        self.keeps || self.listener.is_some()
    }

    /// Whether snapshots are wanted.
    pub fn wants_snapshots(&self) -> bool {
        self.snapshots
    }

    /// Calls `listener` with every event from now on, as it is recorded (on the recording
    /// task: it should be quick). Replaces any earlier listener.
    pub fn set_listener(&mut self, listener: impl Fn(&TraceEvent) + Send + Sync + 'static) {
        self.listener = Some(Listener(Box::new(listener)));
    }

    /// Records one event (the time is filled in) and tells the listener.
    pub fn record(&self, mut event: TraceEvent) {
        if !self.keeps_events() {
            return;
        }
        event.t_ms = self.start.elapsed().as_millis() as u64;
        if let Some(Listener(listen)) = &self.listener {
            listen(&event);
        }
        if !self.keeps {
            return;
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn the_listener_hears_every_event_as_it_is_recorded() {
        let heard = Arc::new(AtomicUsize::new(0));
        let mut trace = Trace::default();
        let counter = Arc::clone(&heard);
        trace.set_listener(move |e| {
            assert_eq!(e.kind, TraceKind::Stage);
            counter.fetch_add(1, Ordering::SeqCst);
        });
        for _ in 0..3 {
            trace.record(TraceEvent {
                t_ms: 0,
                scene: "s".into(),
                role: "supervisor".into(),
                implementation: String::new(),
                kind: TraceKind::Stage,
                ms: None,
                usage: None,
                detail: Value::Null,
            });
        }
        assert_eq!(heard.load(Ordering::SeqCst), 3);
        assert_eq!(trace.events().len(), 3);
    }

    #[test]
    fn a_discarding_trace_still_tells_its_listener_but_keeps_nothing() {
        let heard = Arc::new(AtomicUsize::new(0));
        let mut trace = Trace::discarding();
        assert!(!trace.keeps_events());
        let counter = Arc::clone(&heard);
        trace.set_listener(move |_| {
            counter.fetch_add(1, Ordering::SeqCst);
        });
        assert!(trace.keeps_events());
        trace.record(TraceEvent {
            t_ms: 0,
            scene: "s".into(),
            role: "supervisor".into(),
            implementation: String::new(),
            kind: TraceKind::Done,
            ms: None,
            usage: None,
            detail: Value::Null,
        });
        assert_eq!(heard.load(Ordering::SeqCst), 1);
        assert!(trace.events().is_empty());
    }
}
