//! The paper's loop for one scene, written against [`RoleCaller`] so that it runs the same over
//! actors or over plain calls:
//!
//! plan; then for each group in order: design -> render -> evaluate -> SRT if semantics failed ->
//! PRT if physics failed (and custom stages where configured) -> evaluate again, up to
//! `max_rounds`; then a final PRT pass over the whole layout (unless an ablation turns it off).
//!
//! Every reply is checked by its call's acceptance before the loop takes it (see `accept`).
//! Calls are retried with exponential backoff; after the last retry the role's fallback
//! implementation takes over (recorded in `stats.fallbacks`); a PRT call that still fails is
//! answered by the built-in grid PRT, the last word. See `calls` for how a call is made and
//! `intake` for what the loop takes from the roles.

mod calls;
mod intake;
pub mod moved;
#[cfg(test)]
mod tests;

use std::collections::{HashMap, HashSet};
use std::sync::Arc;
use std::time::{Duration, Instant};

use serde_json::json;

use super::accept::cap_scene_notes;
pub use super::caller::{RoleCaller, SceneFailure, SwapError};
use super::messages::{EvalMode, EvaluateCall, PlanCall};
use crate::config::{AgentId, EvalModeConfig, GraphConfig, Stage, When};
use crate::trace::{Trace, TraceEvent, TraceKind};
use disco_agents::vlm::formation::posed_by_formation;
use disco_core::layout::{Dropped, Layout, PlacedObject, PrtStats, Stats};
use disco_core::plan::Plan;
use disco_core::render::{RenderOptions, render_png};
use disco_core::roles::{
    Answer, DesignRequest, EvalRequest, Infeasible, PatchRequest, PrtRequest, Question, Refined,
    SceneContext, SrtRequest, ToolMove, Usage,
};
use disco_core::scene::SceneSpec;
pub use intake::sanitize_plan;
use intake::{apply, failed_questions, srt_key};
use moved::carry_formations;

/// The layout as it grows, group by group.
struct Progress {
    plan: Arc<Plan>,
    placed: Vec<PlacedObject>,
    dropped: Vec<Dropped>,
    /// Objects of finished groups: the PRT gives them precedence (shared with its requests).
    settled: Arc<HashSet<String>>,
}

impl Progress {
    /// Whether every object of `group` is placed or dropped already.
    fn has_all(&self, group: &[String]) -> bool {
        group.iter().all(|n| {
            self.placed.iter().any(|o| &o.name == n) || self.dropped.iter().any(|d| &d.name == n)
        })
    }
}

/// Where the loop is: group (from 1; 0 for the final pass) and round (0 for the design).
#[derive(Debug, Clone, Copy)]
struct Step {
    group: usize,
    round: u32,
}

/// What one evaluation found.
struct Verdict {
    /// Questions answered "no" (or not answered), with the answers.
    failed: Vec<(Question, Answer)>,
    /// Whether the evaluator asked for physical refinement.
    needs_physical: bool,
}

/// How long a scene past its deadline gets to finish with fallbacks and the final PRT.
pub const LATE_GRACE: Duration = Duration::from_secs(60);

/// The longest time the supervisor waits for anything (ten years): a deadline or window of more
/// seconds than that, however it got into the graph, means "no deadline", not a panic.
pub const LONGEST_WAIT: Duration = Duration::from_secs(10 * 365 * 24 * 3600);

/// `s` seconds as a duration: negative or not a number is zero, more than [`LONGEST_WAIT`] is
/// [`LONGEST_WAIT`] (`Duration::from_secs_f64` would panic on 1e300).
pub fn seconds(s: f64) -> Duration {
    match s {
        s if s.is_nan() || s <= 0.0 => Duration::ZERO,
        s if s >= LONGEST_WAIT.as_secs_f64() => LONGEST_WAIT,
        s => Duration::from_secs_f64(s),
    }
}

struct Loop<'a> {
    scene: Arc<SceneSpec>,
    /// When the scene's time is up (moved by [`LATE_GRACE`] once it was).
    until: Instant,
    /// The scene's deadline passed: what is left is finished by fallbacks, without rounds.
    late: bool,
    /// Agents swapped to their fallback in this scene.
    swapped: HashSet<AgentId>,
    /// Model servers that failed in this scene: their other agents go straight to a fallback.
    down_models: HashSet<String>,
    graph: &'a GraphConfig,
    caller: &'a dyn RoleCaller,
    trace: &'a Trace,
    usage: Usage,
    fallbacks: Vec<String>,
    model_failures: Vec<String>,
    notes: Vec<String>,
    /// Objects a designer left out (parked at the room centre for the PRT, or dropped).
    unplaced: HashSet<String>,
    /// PRT agents that failed past their fallback: the built-in grid PRT answers for them.
    built_in_prt: HashSet<AgentId>,
    rounds: u32,
    /// Everything a tool moved unasked, in order.
    tool_moves: Vec<ToolMove>,
    /// How many of `tool_moves` each agent has been told of.
    told: HashMap<AgentId, usize>,
    /// Constraints a role reported cannot be met: not asked about again.
    infeasible: Vec<Infeasible>,
    /// The SRT requests sent so far (a hash of layout and failed checks): none goes out twice.
    srt_sent: HashSet<u64>,
}

/// Runs the whole loop for `scene` and returns its layout.
pub async fn run_scene(
    scene: Arc<SceneSpec>,
    graph: &GraphConfig,
    caller: &dyn RoleCaller,
    trace: &Trace,
) -> Result<Layout, SceneFailure> {
    let started = Instant::now();
    let mut l = Loop {
        scene,
        until: started + seconds(graph.run.scene_deadline_s),
        late: false,
        swapped: HashSet::new(),
        down_models: HashSet::new(),
        graph,
        caller,
        trace,
        usage: Usage::default(),
        fallbacks: Vec::new(),
        model_failures: Vec::new(),
        notes: Vec::new(),
        unplaced: HashSet::new(),
        built_in_prt: HashSet::new(),
        rounds: 0,
        tool_moves: Vec::new(),
        told: HashMap::new(),
        infeasible: Vec::new(),
        srt_sent: HashSet::new(),
    };
    let mut layout = l.run().await?;
    layout.stats.llm_calls = l.usage.calls;
    layout.stats.prompt_tokens = l.usage.prompt_tokens;
    layout.stats.completion_tokens = l.usage.completion_tokens;
    layout.stats.wall_ms = started.elapsed().as_millis() as u64;
    layout.stats.fallbacks = l.fallbacks;
    layout.stats.model_failures = l.model_failures;
    layout.stats.notes.extend(l.notes);
    cap_scene_notes(&mut layout.stats.notes);
    layout.stats.rounds = l.rounds;
    layout.stats.deadline_missed = l.late;
    Ok(layout)
}

impl Loop<'_> {
    /// Records an event of `agent` (`None`: the supervisor itself).
    fn event(
        &self,
        agent: Option<&AgentId>,
        kind: TraceKind,
        ms: Option<f64>,
        usage: Option<Usage>,
        detail: serde_json::Value,
    ) {
        if !self.trace.keeps_events() {
            return;
        }
        let (role, implementation) = match agent {
            Some(a) => (a.to_string(), self.caller.implementation(a)),
            None => ("supervisor".to_string(), "supervisor".to_string()),
        };
        self.trace.record(TraceEvent {
            t_ms: 0,
            scene: self.scene.id.clone(),
            role,
            implementation,
            kind,
            ms,
            usage,
            detail,
        });
    }

    /// Records the layout after a step, when the trace keeps snapshots.
    fn snapshot(&self, step: &str, at: Step, p: &Progress) {
        if self.trace.wants_snapshots() {
            self.event(
                None,
                TraceKind::Snapshot,
                None,
                None,
                json!({"step": step, "group": at.group, "round": at.round, "objects": p.placed, "dropped": p.dropped}),
            );
        }
    }

    /// Records that a stage of the loop begins (and logs it at info level, `-v`).
    fn stage(&self, detail: serde_json::Value) {
        tracing::info!(scene = %self.scene.id, "stage {detail}");
        self.event(None, TraceKind::Stage, None, None, detail);
    }

    /// The context of a request to `agent`: scene, plan, and what a tool moved since its last
    /// request (then counted as told).
    fn ctx(&mut self, agent: &AgentId, plan: &Arc<Plan>) -> SceneContext {
        let mut ctx = SceneContext::new(Arc::clone(&self.scene), Arc::clone(plan));
        let told = self.told.entry(agent.clone()).or_default();
        ctx.moved = self.tool_moves[(*told).min(self.tool_moves.len())..].to_vec();
        *told = self.tool_moves.len();
        ctx
    }

    fn layout_of(&self, p: &Progress) -> Layout {
        Layout {
            id: self.scene.id.clone(),
            room: self.scene.room.clone(),
            objects: p.placed.clone(),
            dropped: p.dropped.clone(),
            plan: Arc::clone(&p.plan),
            stats: Stats::default(),
        }
    }

    fn render_for(&self, agent: &AgentId, layout: &Layout) -> Option<Arc<Vec<u8>>> {
        if !self.caller.wants_render(agent) {
            return None;
        }
        render_png(layout, &RenderOptions::default())
            .ok()
            .map(Arc::new)
    }

    /// The paper's loop: plan; design, evaluate and refine each group; a final PRT.
    /// Past the scene's deadline, the loop goes on with fallbacks and without rounds, so the
    /// scene still ends in a complete, physically valid layout (`stats.deadline_missed`).
    async fn run(&mut self) -> Result<Layout, SceneFailure> {
        let mut p = match self.plan().await {
            Err(SceneFailure::Deadline(_)) => {
                self.go_late();
                self.plan().await?
            }
            r => r?,
        };
        let groups = p.plan.groups.clone();
        for (i, group) in groups.iter().enumerate() {
            let group_no = i + 1;
            let on_time = match self.late {
                true => Err(SceneFailure::Deadline(self.graph.run.scene_deadline_s)),
                false => self.design_and_refine(&mut p, group_no, group).await,
            };
            match on_time {
                Err(SceneFailure::Deadline(_)) => {
                    self.go_late();
                    if !p.has_all(group) {
                        self.design_group(&mut p, group_no, group).await?;
                    }
                }
                r => r?,
            }
            Arc::make_mut(&mut p.settled).extend(group.iter().cloned());
        }
        let prt = match self.graph.run.final_prt {
            true => Some(self.final_prt(&mut p).await?),
            false => None,
        };
        let mut layout = self.finish(p);
        layout.stats.prt = prt;
        Ok(layout)
    }

    /// Designs one group, then its evaluate-and-refine rounds.
    async fn design_and_refine(
        &mut self,
        p: &mut Progress,
        group_no: usize,
        group: &[String],
    ) -> Result<(), SceneFailure> {
        self.design_group(p, group_no, group).await?;
        self.refine_group(p, group_no, group).await
    }

    /// Asks the planner, and makes its plan usable.
    async fn plan(&mut self) -> Result<Progress, SceneFailure> {
        let raw = self
            .call(&AgentId::PLANNER, PlanCall(Arc::clone(&self.scene)))
            .await?;
        let (mut plan, dropped) = sanitize_plan(&self.scene, raw, &mut self.notes);
        if self.graph.run.single_shot && plan.groups.len() > 1 {
            plan.groups = vec![plan.groups.concat()];
        }
        Ok(Progress {
            plan: Arc::new(plan),
            placed: Vec::new(),
            dropped,
            settled: Arc::default(),
        })
    }

    /// Asks the designer to pose one group, seeing what is placed so far.
    async fn design_group(
        &mut self,
        p: &mut Progress,
        group_no: usize,
        group: &[String],
    ) -> Result<(), SceneFailure> {
        self.stage(json!({"stage": "design", "group": group}));
        let request = DesignRequest {
            ctx: self.ctx(&AgentId::DESIGNER, &p.plan),
            group: group.to_vec(),
            placed: p.placed.clone(),
            // The layout is copied only when the designer sees a render of it.
            render: match self.caller.wants_render(&AgentId::DESIGNER) {
                true => self.render_for(&AgentId::DESIGNER, &self.layout_of(p)),
                false => None,
            },
        };
        let poses = self.call(&AgentId::DESIGNER, request).await?;
        let proposed = self.park_missing(group, poses);
        let (proposed, unplaced) = self.park_or_drop(proposed);
        p.dropped.extend(unplaced);
        p.placed.extend(proposed);
        self.snapshot(
            "design",
            Step {
                group: group_no,
                round: 0,
            },
            p,
        );
        Ok(())
    }

    /// Evaluate-and-refine rounds for one group, until the evaluator is content or the rounds
    /// run out.
    async fn refine_group(
        &mut self,
        p: &mut Progress,
        group_no: usize,
        group: &[String],
    ) -> Result<(), SceneFailure> {
        let graph = self.graph;
        let Some((Stage::Evaluate, stages)) = graph.round().split_first() else {
            return Ok(());
        };
        for round in 0..self.graph.run.max_rounds {
            self.rounds += 1;
            let verdict = self.evaluate(p, group, round).await?;
            if verdict.failed.is_empty() && !verdict.needs_physical {
                break;
            }
            let at = Step {
                group: group_no,
                round: round + 1,
            };
            let before = p.placed.clone();
            for stage in stages {
                self.run_stage(p, at, group, stage, &verdict).await?;
            }
            // Nothing moved: another round would ask the same questions of the same layout.
            if p.placed == before {
                self.notes.push(format!(
                    "group {group_no}: round {} moved nothing; no further rounds",
                    round + 1
                ));
                break;
            }
        }
        Ok(())
    }

    /// Asks the evaluator the group's questions and for its physical verdict.
    async fn evaluate(
        &mut self,
        p: &Progress,
        group: &[String],
        round: u32,
    ) -> Result<Verdict, SceneFailure> {
        let current = self.layout_of(p);
        let Some(evaluator) = self.graph.agent(&AgentId::EVALUATOR) else {
            return Err(SceneFailure::NoAgent(AgentId::EVALUATOR));
        };
        let config = evaluator.config();
        let questions = self.questions(&p.plan, group, p, config.questions);
        let mode = match config.mode {
            EvalModeConfig::Parallel => EvalMode::Parallel {
                width: config.width,
            },
            EvalModeConfig::Batch => EvalMode::Batch,
        };
        let request = EvalRequest {
            ctx: self.ctx(&AgentId::EVALUATOR, &p.plan),
            render: self.render_for(&AgentId::EVALUATOR, &current),
            layout: current,
            group: group.to_vec(),
        };
        self.stage(json!({"stage": "evaluate", "round": round + 1}));
        let call = EvaluateCall {
            request,
            questions: questions.clone(),
            mode,
        };
        let eval = self.call(&AgentId::EVALUATOR, call).await?;
        Ok(Verdict {
            failed: failed_questions(&questions, &eval),
            needs_physical: eval.needs_physical,
        })
    }

    /// Runs one refinement stage of a round when the verdict calls for it: an SRT when questions
    /// failed, a PRT when physics failed, a custom stage as its `when` says.
    async fn run_stage(
        &mut self,
        p: &mut Progress,
        at: Step,
        group: &[String],
        stage: &Stage,
        verdict: &Verdict,
    ) -> Result<(), SceneFailure> {
        // The layout is copied only for a stage that runs.
        let agent = match stage {
            Stage::Srt(agent) if !verdict.failed.is_empty() => {
                // The same layout and the same failed checks: the same request again. Not sent.
                if !self.srt_sent.insert(srt_key(&p.placed, &verdict.failed)) {
                    self.notes.push(format!(
                        "{agent}: the same layout and failed checks as a request already sent; not sent again"
                    ));
                    return Ok(());
                }
                self.stage(json!({"stage": agent}));
                let now = self.layout_of(p);
                let request = SrtRequest {
                    ctx: self.ctx(agent, &p.plan),
                    render: self.render_for(agent, &now),
                    layout: now,
                    failed: verdict.failed.clone(),
                    // A formation's members move only with it, as a whole (below).
                    movable: group
                        .iter()
                        .filter(|n| !posed_by_formation(&p.plan, n))
                        .cloned()
                        .collect(),
                };
                let moves = self.call(agent, request).await?;
                self.apply_moves(p, moves, agent);
                agent
            }
            Stage::Prt(agent) if verdict.needs_physical => {
                self.stage(json!({"stage": agent}));
                let refined = self.refine_physically(agent, p, false).await?;
                self.take_refined(p, refined, agent.as_str());
                agent
            }
            Stage::Patch { agent, when } if patch_due(*when, verdict) => {
                self.stage(json!({"stage": agent}));
                let request = PatchRequest {
                    ctx: self.ctx(agent, &p.plan),
                    layout: self.layout_of(p),
                    group: group.to_vec(),
                };
                let moves = self.call(agent, request).await?;
                self.apply_moves(p, moves, agent);
                agent
            }
            _ => return Ok(()),
        };
        self.snapshot(agent.as_str(), at, p);
        Ok(())
    }

    /// Applies a refiner's moves; the members of a formation whose focus moved move with it.
    fn apply_moves(&mut self, p: &mut Progress, moves: Vec<PlacedObject>, agent: &AgentId) {
        let before = p.placed.clone();
        apply(&mut p.placed, moves);
        let carried = carry_formations(&p.plan, &before, &mut p.placed);
        if !carried.is_empty() {
            self.notes.push(format!(
                "{agent}: {} moved with their formation's focus, as a whole",
                carried.join(", ")
            ));
        }
    }

    /// The PRT over the whole layout, so that the result is physically valid.
    async fn final_prt(&mut self, p: &mut Progress) -> Result<PrtStats, SceneFailure> {
        self.stage(json!({"stage": "final prt"}));
        let refined = self.refine_physically(&AgentId::PRT, p, true).await?;
        let stats = refined.stats();
        self.take_refined(p, refined, "final prt");
        self.snapshot("final prt", Step { group: 0, round: 0 }, p);
        Ok(stats)
    }

    /// What a PRT is asked: the layout so far, earlier groups settled.
    fn prt_request(&self, p: &Progress) -> PrtRequest {
        PrtRequest {
            ctx: SceneContext::new(Arc::clone(&self.scene), Arc::clone(&p.plan)),
            layout: self.layout_of(p),
            settled: Arc::clone(&p.settled),
        }
    }

    /// Asks PRT `agent` to make the layout physically valid. When it fails past its retries and
    /// fallback (its replies refused, say), the built-in grid PRT answers instead, now and for the
    /// rest of the scene: the last word, so that a PRT swapped in by the graph cannot leave the
    /// layout invalid. A missed scene deadline still ends a round's PRT (the loop goes late), but
    /// not the `last_pass`.
    async fn refine_physically(
        &mut self,
        agent: &AgentId,
        p: &Progress,
        last_pass: bool,
    ) -> Result<Refined, SceneFailure> {
        if !self.built_in_prt.contains(agent) {
            match self.call(agent, self.prt_request(p)).await {
                Ok(refined) => return Ok(refined),
                Err(SceneFailure::Deadline(s)) if !last_pass => {
                    return Err(SceneFailure::Deadline(s));
                }
                Err(failure) => {
                    let note =
                        format!("{agent}: the built-in grid PRT answered instead ({failure})");
                    self.event(Some(agent), TraceKind::Fallback, None, None, json!(note));
                    self.fallbacks.push(note);
                    self.built_in_prt.insert(agent.clone());
                }
            }
        }
        let request = self.prt_request(p);
        let refiner = disco_tools::prt::PhysicalRefiner::new(disco_tools::prt::PrtConfig {
            grid_step_cm: self.graph.run.grid_step_cm,
            ..Default::default()
        });
        Ok(refiner.refine_settled(
            &self.scene.room,
            &request.layout.objects,
            &request.layout.plan,
            &request.settled,
        ))
    }
}

/// Whether a custom stage that runs `when` runs after `verdict`.
fn patch_due(when: When, verdict: &Verdict) -> bool {
    match when {
        When::Always => true,
        When::SemanticFailed => !verdict.failed.is_empty(),
        When::PhysicalFailed => verdict.needs_physical,
    }
}
