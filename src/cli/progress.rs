//! What a person watching `disco generate` sees while a scene runs: a live line (group k of n,
//! stage, model calls, tokens, elapsed) on a terminal, and log lines for `-v` (stages and the
//! supervisor's decisions) and `-vv` (each model call), all fed from the run's trace.

use std::sync::Mutex;
use std::time::Duration;

use disco_layout::trace::{TraceEvent, TraceKind};
use indicatif::{ProgressBar, ProgressStyle};

/// The live line of one scene.
pub struct SceneProgress {
    bar: ProgressBar,
    state: Mutex<State>,
}

/// What the line says, gathered from the events so far.
#[derive(Default)]
struct State {
    /// Groups of the plan, once the planner has answered.
    groups: Option<usize>,
    /// Design stages begun: the group being worked on.
    group: usize,
    /// The stage under way, in words.
    stage: String,
    /// Model calls answered.
    calls: u64,
    /// Their prompt and completion tokens.
    tokens: u64,
}

impl SceneProgress {
    /// A line for scene `id` drawn on stderr, or `None` drawing (`shown` false) for a run nobody
    /// watches: the logs still go out.
    pub fn new(id: &str, shown: bool) -> Self {
        let bar = if shown {
            let bar = ProgressBar::new_spinner();
            bar.enable_steady_tick(Duration::from_millis(200));
            bar
        } else {
            ProgressBar::hidden()
        };
        let style = ProgressStyle::with_template("{spinner} {prefix} [{elapsed}] {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner());
        bar.set_style(style);
        bar.set_prefix(id.to_string());
        bar.set_message("planning");
        SceneProgress {
            bar,
            state: Mutex::new(State {
                stage: "planning".into(),
                ..State::default()
            }),
        }
    }

    /// Takes in one event of the trace: updates the line and logs it.
    pub fn observe(&self, e: &TraceEvent) {
        log(e);
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        match e.kind {
            TraceKind::Reply if e.role == "planner" => {
                s.groups = e.detail["groups"].as_array().map(Vec::len);
            }
            TraceKind::Stage => {
                let stage = e.detail["stage"].as_str().unwrap_or("?");
                if stage == "design" {
                    s.group += 1;
                }
                s.stage = match e.detail["round"].as_u64() {
                    Some(round) => format!("{stage} (round {round})"),
                    None => stage.to_string(),
                };
            }
            TraceKind::ModelCall => {
                s.calls += 1;
                let tokens = |k: &str| e.detail[k].as_u64().unwrap_or(0);
                s.tokens += tokens("prompt_tokens") + tokens("completion_tokens");
            }
            _ => return,
        }
        self.bar.set_message(s.line());
    }

    /// The line as it stands (without the spinner, the scene and the time).
    #[cfg(test)]
    fn message(&self) -> String {
        self.bar.message()
    }

    /// Takes the line off the terminal.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl State {
    /// `group 2 of 5, evaluate (round 1), 7 model calls, 5120 tokens`.
    fn line(&self) -> String {
        let mut parts = Vec::new();
        if self.group > 0 {
            parts.push(match self.groups {
                Some(n) => format!("group {} of {n}", self.group.min(n)),
                None => format!("group {}", self.group),
            });
        }
        parts.push(self.stage.clone());
        if self.calls > 0 {
            parts.push(format!(
                "{} model calls, {} tokens",
                self.calls, self.tokens
            ));
        }
        parts.join(", ")
    }
}

/// `-v`: the supervisor's decisions (stages log themselves in the scene loop); `-vv`: each
/// model call and each answer.
fn log(e: &TraceEvent) {
    match e.kind {
        TraceKind::Fallback | TraceKind::Restart | TraceKind::Timeout | TraceKind::Error => {
            tracing::info!(scene = %e.scene, role = %e.role, "{:?}: {}", e.kind, e.detail)
        }
        TraceKind::Done => tracing::info!(scene = %e.scene, "done"),
        TraceKind::ModelCall => {
            tracing::debug!(scene = %e.scene, role = %e.role, "model call {}", e.detail)
        }
        TraceKind::Reply => {
            tracing::debug!(scene = %e.scene, role = %e.role, ms = ?e.ms, usage = ?e.usage, "reply")
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::{Value, json};

    fn event(role: &str, kind: TraceKind, detail: Value) -> TraceEvent {
        TraceEvent {
            t_ms: 0,
            scene: "bedroom-01".into(),
            role: role.into(),
            implementation: "vlm".into(),
            kind,
            ms: None,
            usage: None,
            detail,
        }
    }

    #[test]
    fn the_line_follows_groups_stages_and_model_calls() {
        let p = SceneProgress::new("bedroom-01", false);
        assert_eq!(p.message(), "planning");
        p.observe(&event(
            "planner",
            TraceKind::Reply,
            json!({"groups": [{}, {}, {}]}),
        ));
        p.observe(&event(
            "supervisor",
            TraceKind::Stage,
            json!({"stage": "design", "group": ["bed-0"]}),
        ));
        assert_eq!(p.message(), "group 1 of 3, design");
        let call =
            json!({"purpose": "designer: group 1", "prompt_tokens": 900, "completion_tokens": 100});
        p.observe(&event("designer", TraceKind::ModelCall, call.clone()));
        p.observe(&event("designer", TraceKind::ModelCall, call));
        p.observe(&event(
            "supervisor",
            TraceKind::Stage,
            json!({"stage": "evaluate", "round": 1}),
        ));
        assert_eq!(
            p.message(),
            "group 1 of 3, evaluate (round 1), 2 model calls, 2000 tokens"
        );
        p.finish();
    }
}
