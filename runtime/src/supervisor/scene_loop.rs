//! The paper's loop for one scene, written against [`RoleCaller`] so that it runs the same over
//! actors or over plain calls:
//!
//! plan; then for each group in order: design -> render -> evaluate -> SRT if semantics failed ->
//! PRT if physics failed (and custom stages where configured) -> evaluate again, up to
//! `max_rounds`; then a final PRT pass over the whole layout (unless an ablation turns it off).
//!
//! Calls are retried with exponential backoff; after the last retry the role's fallback
//! implementation takes over (recorded in `stats.fallbacks`).

use std::collections::{HashMap, HashSet};
use std::sync::Arc;
use std::time::{Duration, Instant};

use async_trait::async_trait;
use backon::{ExponentialBuilder, Retryable};
use glam::DVec2;
use serde_json::json;

use super::messages::{EvalMode, EvaluateCall, PlanCall, RoleCall, RoleReply, RoleRequest};
use crate::config::{
    AgentConfig, AgentId, EvalModeConfig, GraphConfig, QuestionStyle, Stage, When,
};
use crate::trace::{Trace, TraceEvent, TraceKind};
use disco_core::layout::{Dropped, Layout, PlacedObject, PrtStats, Stats};
use disco_core::plan::Plan;
use disco_core::relations::{ConstraintCheck, constraints_of};
use disco_core::render::{RenderOptions, render_png};
use disco_core::roles::Refined;
use disco_core::roles::{
    Answer, DesignRequest, EvalRequest, Evaluation, Output, PatchRequest, PrtRequest, Question,
    RoleError, RoleKind, SceneContext, SrtRequest, Usage,
};
use disco_core::scene::SceneSpec;

/// How the loop reaches the roles.
#[async_trait]
pub trait RoleCaller: Send + Sync {
    /// Sends `request` to `agent` and waits at most `deadline` for the answer.
    async fn invoke(
        &self,
        agent: &AgentId,
        request: RoleRequest,
        deadline: Duration,
    ) -> Result<Output<RoleReply>, RoleError>;
    /// Swaps `agent` to implementation `fallback`; `Err` says why it could not.
    async fn swap(&self, agent: &AgentId, fallback: &str) -> Result<(), String>;
    /// The implementation currently serving `agent`.
    fn implementation(&self, agent: &AgentId) -> String;
    /// Whether the implementation serving `agent` looks at renders.
    fn wants_render(&self, agent: &AgentId) -> bool;
}

/// Why a scene could not be finished.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneFailure {
    /// The graph has no such agent.
    #[error("no agent {0:?} in the graph")]
    NoAgent(AgentId),
    /// The agent plays another role than the request needs.
    #[error("the {agent} is not a {expected} agent")]
    WrongRole {
        /// The agent.
        agent: AgentId,
        /// The role the request needs.
        expected: RoleKind,
    },
    /// An agent failed past its retries, with no fallback left.
    #[error("the {agent} ({implementation}) failed after {tries} tries: {source}")]
    RoleFailed {
        /// The agent.
        agent: AgentId,
        /// The implementation that failed last.
        implementation: String,
        /// Calls made, retries included.
        tries: u32,
        /// The last error.
        source: RoleError,
    },
    /// An agent failed and its fallback could not be started.
    #[error("the {agent} failed ({source}) and its fallback {fallback:?} could not start: {why}")]
    FallbackFailed {
        /// The agent.
        agent: AgentId,
        /// The fallback implementation.
        fallback: String,
        /// Why the agent failed.
        source: RoleError,
        /// Why the fallback could not start.
        why: String,
    },
    /// The scene ran past `run.scene_deadline_s`.
    #[error("the scene missed its deadline of {0:.0} s")]
    Deadline(f64),
    /// The supervisor stopped before the loop was done.
    #[error("the scene's supervisor stopped before the scene was done")]
    SupervisorStopped,
}

impl SceneFailure {
    /// The model server error behind the failure, when a model server is to blame.
    pub fn model_server(&self) -> Option<&RoleError> {
        match self {
            SceneFailure::RoleFailed { source, .. }
            | SceneFailure::FallbackFailed { source, .. }
                if source.is_model_server() =>
            {
                Some(source)
            }
            _ => None,
        }
    }
}

/// The layout as it grows, group by group.
struct Progress {
    plan: Arc<Plan>,
    placed: Vec<PlacedObject>,
    dropped: Vec<Dropped>,
    /// Objects of finished groups: the PRT gives them precedence.
    settled: HashSet<String>,
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
    rounds: u32,
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
        until: started + Duration::from_secs_f64(graph.run.scene_deadline_s),
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
        rounds: 0,
    };
    let mut layout = l.run().await?;
    layout.stats.llm_calls = l.usage.calls;
    layout.stats.prompt_tokens = l.usage.prompt_tokens;
    layout.stats.completion_tokens = l.usage.completion_tokens;
    layout.stats.wall_ms = started.elapsed().as_millis() as u64;
    layout.stats.fallbacks = l.fallbacks;
    layout.stats.model_failures = l.model_failures;
    layout.stats.notes.extend(l.notes);
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

    /// Records that a stage of the loop begins.
    fn stage(&self, detail: serde_json::Value) {
        self.event(None, TraceKind::Stage, None, None, detail);
    }

    /// Sends `call` to `agent`: with retries and backoff, then with its fallback. The reply is
    /// the one the request's type asks for; any other is a failure like an error.
    async fn call<C: RoleCall>(
        &mut self,
        agent: &AgentId,
        call: C,
    ) -> Result<C::Reply, SceneFailure> {
        let graph = self.graph;
        let config = graph
            .agents
            .get(agent.as_str())
            .ok_or_else(|| SceneFailure::NoAgent(agent.clone()))?;
        if graph.role_of(agent.as_str()) != Some(C::ROLE) {
            return Err(SceneFailure::WrongRole {
                agent: agent.clone(),
                expected: C::ROLE,
            });
        }
        let request = call.into_request();
        let model = config.model.as_ref().map(|m| m.get_ref().clone());
        let fallback = config.fallback.as_ref().map(|f| f.get_ref().clone());
        if let Some(fallback) = &fallback
            && !self.swapped.contains(agent)
        {
            let why = match &model {
                _ if self.late => Some("the scene is past its deadline".to_string()),
                Some(m) if self.down_models.contains(m) => {
                    Some(format!("model server {m:?} already failed in this scene"))
                }
                _ => None,
            };
            if let Some(why) = why {
                self.swap_early(agent, fallback, &why).await?;
            }
        }
        loop {
            match self.attempts::<C>(agent, &request, config).await {
                Ok(out) => return Ok(self.account(agent, out)),
                Err(_) if !self.late && self.time_left().is_zero() => {
                    return Err(SceneFailure::Deadline(self.graph.run.scene_deadline_s));
                }
                Err(e) if fallback.is_some() && !self.swapped.contains(agent) => {
                    if e.is_model_server() || matches!(e, RoleError::Deadline(_)) {
                        self.down_models.extend(model.clone());
                    }
                    self.fall_back(
                        agent,
                        fallback.clone().unwrap_or_default(),
                        e,
                        config.retries,
                    )
                    .await?;
                }
                Err(e) => {
                    return Err(SceneFailure::RoleFailed {
                        agent: agent.clone(),
                        implementation: self.caller.implementation(agent),
                        tries: config.retries + 1,
                        source: e,
                    });
                }
            }
        }
    }

    /// One call and its retries with exponential backoff, each traced.
    async fn attempts<C: RoleCall>(
        &self,
        agent: &AgentId,
        request: &RoleRequest,
        config: &AgentConfig,
    ) -> Result<Output<C::Reply>, RoleError> {
        let deadline = Duration::from_secs_f64(config.deadline_s).min(self.time_left());
        if deadline.is_zero() {
            return Err(RoleError::Deadline(0.0));
        }
        let backoff = ExponentialBuilder::default()
            .with_min_delay(Duration::from_millis(self.graph.run.backoff_ms))
            .with_max_delay(Duration::from_secs(10))
            .with_max_times(config.retries as usize);
        let attempt = || async {
            self.event(
                Some(agent),
                TraceKind::Request,
                None,
                None,
                request.summary(),
            );
            let t0 = Instant::now();
            let result = self.caller.invoke(agent, request.clone(), deadline).await;
            let ms = Some(t0.elapsed().as_secs_f64() * 1000.0);
            match &result {
                Ok(out) => self.event(
                    Some(agent),
                    TraceKind::Reply,
                    ms,
                    Some(out.usage),
                    out.value.summary(),
                ),
                Err(e @ RoleError::Deadline(_)) => self.event(
                    Some(agent),
                    TraceKind::Timeout,
                    ms,
                    None,
                    json!(e.to_string()),
                ),
                Err(e) => self.event(
                    Some(agent),
                    TraceKind::Error,
                    ms,
                    None,
                    json!(e.to_string()),
                ),
            }
            let out = result?;
            let reply = C::from_reply(out.value.clone())?;
            Ok(out.map(|_| reply))
        };
        attempt
            .retry(backoff)
            .when(|_| !self.time_left().is_zero())
            .await
    }

    /// Time left before the scene's deadline (or, once late, before the grace ends).
    fn time_left(&self) -> Duration {
        self.until.saturating_duration_since(Instant::now())
    }

    /// The scene's deadline passed: from now on what is left is finished by fallbacks, within
    /// [`LATE_GRACE`].
    fn go_late(&mut self) {
        if !self.late {
            self.late = true;
            self.until = Instant::now() + LATE_GRACE;
            self.notes.push(format!(
                "the scene missed its deadline of {:.0} s: what was left was finished by fallbacks and the final PRT",
                self.graph.run.scene_deadline_s
            ));
        }
    }

    /// Swaps `agent` to `fallback` before calling it, for `why`.
    async fn swap_early(
        &mut self,
        agent: &AgentId,
        fallback: &str,
        why: &str,
    ) -> Result<(), SceneFailure> {
        let from = self.caller.implementation(agent);
        self.caller
            .swap(agent, fallback)
            .await
            .map_err(|e| SceneFailure::FallbackFailed {
                agent: agent.clone(),
                fallback: fallback.to_string(),
                source: RoleError::Unavailable(why.to_string()),
                why: e,
            })?;
        let note = format!("{agent}: {from} -> {fallback} ({why})");
        self.event(Some(agent), TraceKind::Fallback, None, None, json!(note));
        self.fallbacks.push(note);
        self.swapped.insert(agent.clone());
        Ok(())
    }

    /// Adds an answer's costs, model calls and notes to the scene's; returns its value.
    fn account<T>(&mut self, agent: &AgentId, out: Output<T>) -> T {
        self.usage += out.usage;
        for call in &out.calls {
            self.event(
                Some(agent),
                TraceKind::ModelCall,
                Some(call.latency_ms),
                None,
                json!(call),
            );
        }
        self.notes
            .extend(out.notes.iter().map(|n| format!("{agent}: {n}")));
        out.value
    }

    /// Swaps `agent` to its `fallback` after it failed with `e`.
    async fn fall_back(
        &mut self,
        agent: &AgentId,
        fallback: String,
        e: RoleError,
        retries: u32,
    ) -> Result<(), SceneFailure> {
        let from = self.caller.implementation(agent);
        if let Err(why) = self.caller.swap(agent, &fallback).await {
            return Err(SceneFailure::FallbackFailed {
                agent: agent.clone(),
                fallback,
                source: e,
                why,
            });
        }
        let note = format!(
            "{agent}: {from} -> {fallback} after {} tries ({e})",
            retries + 1
        );
        self.event(Some(agent), TraceKind::Fallback, None, None, json!(note));
        if e.is_model_server() {
            self.model_failures.push(format!("{agent}: {e}"));
        }
        self.fallbacks.push(note);
        self.swapped.insert(agent.clone());
        Ok(())
    }

    fn ctx(&self, plan: &Arc<Plan>) -> SceneContext {
        SceneContext {
            scene: Arc::clone(&self.scene),
            plan: Arc::clone(plan),
        }
    }

    fn layout_of(&self, p: &Progress) -> Layout {
        Layout {
            id: self.scene.id.clone(),
            room: self.scene.room,
            objects: p.placed.clone(),
            dropped: p.dropped.clone(),
            plan: (*p.plan).clone(),
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
            p.settled.extend(group.iter().cloned());
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
            settled: HashSet::new(),
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
            ctx: self.ctx(&p.plan),
            group: group.to_vec(),
            placed: p.placed.clone(),
            render: self.render_for(&AgentId::DESIGNER, &self.layout_of(p)),
        };
        let poses = self.call(&AgentId::DESIGNER, request).await?;
        let proposed = self.accept_poses(group, poses, &AgentId::DESIGNER);
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
        let stages = self.graph.pipeline.stages();
        if stages.first() != Some(&Stage::Evaluate) {
            return Ok(());
        }
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
            for stage in stages.iter().skip(1) {
                if let Stage::Agent(agent) = stage {
                    self.run_stage(p, at, group, agent, &verdict).await?;
                }
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
        let questions = self.questions(&p.plan, group);
        let config = &self.graph.agents[AgentId::EVALUATOR.as_str()];
        let mode = match config.mode {
            EvalModeConfig::Parallel => EvalMode::Parallel {
                width: config.width,
            },
            EvalModeConfig::Batch => EvalMode::Batch,
        };
        let request = EvalRequest {
            ctx: self.ctx(&p.plan),
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
        agent: &AgentId,
        verdict: &Verdict,
    ) -> Result<(), SceneFailure> {
        let now = self.layout_of(p);
        match self.graph.role_of(agent.as_str()) {
            Some(RoleKind::Srt) if !verdict.failed.is_empty() => {
                self.stage(json!({"stage": agent}));
                let request = SrtRequest {
                    ctx: self.ctx(&p.plan),
                    render: self.render_for(agent, &now),
                    layout: now,
                    failed: verdict.failed.clone(),
                    movable: group.to_vec(),
                };
                let moves = self.call(agent, request).await?;
                let moves = self.accept_poses(group, moves, agent);
                apply(&mut p.placed, moves);
            }
            Some(RoleKind::Prt) if verdict.needs_physical => {
                self.stage(json!({"stage": agent}));
                let request = PrtRequest {
                    ctx: self.ctx(&p.plan),
                    layout: now,
                    settled: p.settled.clone(),
                };
                let refined = self.call(agent, request).await?;
                self.accept_refined(p, refined);
            }
            Some(RoleKind::Patch) if self.patch_due(agent, verdict) => {
                self.stage(json!({"stage": agent}));
                let request = PatchRequest {
                    ctx: self.ctx(&p.plan),
                    layout: now,
                    group: group.to_vec(),
                };
                let moves = self.call(agent, request).await?;
                let moves = self.accept_poses(group, moves, agent);
                apply(&mut p.placed, moves);
            }
            _ => return Ok(()),
        }
        self.snapshot(agent.as_str(), at, p);
        Ok(())
    }

    /// Whether custom stage `agent` runs after `verdict` (its `when` setting).
    fn patch_due(&self, agent: &AgentId, verdict: &Verdict) -> bool {
        match self.graph.agents[agent.as_str()].when {
            When::Always => true,
            When::SemanticFailed => !verdict.failed.is_empty(),
            When::PhysicalFailed => verdict.needs_physical,
        }
    }

    /// The PRT over the whole layout, so that the result is physically valid.
    async fn final_prt(&mut self, p: &mut Progress) -> Result<PrtStats, SceneFailure> {
        self.stage(json!({"stage": "final prt"}));
        let request = PrtRequest {
            ctx: self.ctx(&p.plan),
            layout: self.layout_of(p),
            settled: p.settled.clone(),
        };
        let refined = self.call(&AgentId::PRT, request).await?;
        let stats = refined.stats();
        self.accept_refined(p, refined);
        self.snapshot("final prt", Step { group: 0, round: 0 }, p);
        Ok(stats)
    }

    /// One question per constraint of the group's objects, or one open question.
    fn questions(&self, plan: &Plan, group: &[String]) -> Vec<Question> {
        if self.graph.agents[AgentId::EVALUATOR.as_str()].questions == QuestionStyle::Open {
            return vec![Question {
                id: 0,
                text: format!(
                    "Does the layout of {} look right for a {}?",
                    group.join(", "),
                    self.scene.room_type
                ),
                subject: None,
                constraint: None,
            }];
        }
        let mut out = Vec::new();
        for name in group {
            // Against-wall is a physical matter (the PRT's); the questions are the semantic ones.
            for kind in constraints_of(plan, name)
                .into_iter()
                .filter(|k| !matches!(k, disco_core::relations::ConstraintKind::AgainstWall))
            {
                let statement = ConstraintCheck {
                    subject: name.clone(),
                    kind: kind.clone(),
                    met: false,
                };
                out.push(Question {
                    id: out.len(),
                    text: format!("Is it true that {statement}?"),
                    subject: Some(name.clone()),
                    constraint: Some(kind),
                });
            }
        }
        out
    }

    /// Keeps the poses for objects of `group` only, once each, with finite numbers; the scene's
    /// sizes and categories always win. Objects of the group a designer left out start at the
    /// room centre (the PRT finds them a place), and the notes say so.
    fn accept_poses(
        &mut self,
        group: &[String],
        poses: Vec<PlacedObject>,
        who: &AgentId,
    ) -> Vec<PlacedObject> {
        let mut seen = HashSet::new();
        let mut out = Vec::new();
        for p in poses {
            let Some(asset) = self.scene.asset(&p.name) else {
                self.notes
                    .push(format!("{who}: ignored unknown object {:?}", p.name));
                continue;
            };
            if !group.contains(&p.name) || !seen.insert(p.name.clone()) {
                continue;
            }
            if !(p.position.iter().all(|v| v.is_finite()) && p.rotation.is_finite()) {
                self.notes
                    .push(format!("{who}: ignored non-finite pose for {:?}", p.name));
                seen.remove(&p.name);
                continue;
            }
            out.push(PlacedObject {
                name: asset.name.clone(),
                category: asset.category.clone(),
                size: asset.size,
                position: p.position,
                rotation: disco_core::geometry::normalize_degrees(p.rotation),
            });
        }
        if *who == AgentId::DESIGNER {
            let centre = DVec2::new(self.scene.room.width / 2.0, self.scene.room.depth / 2.0);
            for name in group.iter().filter(|n| !seen.contains(*n)) {
                if let Some(a) = self.scene.asset(name) {
                    self.notes.push(format!("designer did not place {name:?}"));
                    self.unplaced.insert(name.clone());
                    out.push(PlacedObject {
                        name: a.name.clone(),
                        category: a.category.clone(),
                        size: a.size,
                        position: [centre.x, centre.y],
                        rotation: 0.0,
                    });
                }
            }
        }
        out
    }

    /// Objects the designer left out start at the room centre when a PRT stage will find them a
    /// place; in a graph without one they are dropped, as a method without physical refinement
    /// would have to.
    fn park_or_drop(&self, poses: Vec<PlacedObject>) -> (Vec<PlacedObject>, Vec<Dropped>) {
        let graph = self.graph;
        let has_prt = graph.run.final_prt
            || graph
                .pipeline
                .round
                .iter()
                .any(|s| graph.role_of(s) == Some(RoleKind::Prt));
        if has_prt {
            return (poses, Vec::new());
        }
        let mut dropped = Vec::new();
        let kept = poses
            .into_iter()
            .filter(|p| {
                let unplaced = self.unplaced.contains(&p.name);
                if unplaced {
                    dropped.push(Dropped {
                        name: p.name.clone(),
                        reason: "the designer found no place for it and no PRT stage runs".into(),
                    });
                }
                !unplaced
            })
            .collect();
        (kept, dropped)
    }

    /// Takes the PRT's poses and drops; its notes go to the scene's.
    fn accept_refined(&mut self, p: &mut Progress, refined: Refined) {
        self.notes.extend(refined.notes);
        p.dropped.extend(refined.dropped);
        p.placed = refined.objects;
    }

    /// The final layout: objects in scene order; any asset neither placed nor dropped is dropped
    /// with a reason (never silently lost).
    fn finish(&self, p: Progress) -> Layout {
        let Progress {
            plan,
            placed,
            mut dropped,
            ..
        } = p;
        let mut by_name: HashMap<String, PlacedObject> =
            placed.into_iter().map(|o| (o.name.clone(), o)).collect();
        let mut objects = Vec::new();
        for a in &self.scene.assets {
            if let Some(o) = by_name.remove(&a.name) {
                objects.push(o);
            } else if !dropped.iter().any(|d| d.name == a.name) {
                dropped.push(Dropped {
                    name: a.name.clone(),
                    reason: "no stage produced a pose for it".into(),
                });
            }
        }
        Layout {
            id: self.scene.id.clone(),
            room: self.scene.room,
            objects,
            dropped,
            plan: (*plan).clone(),
            stats: Stats::default(),
        }
    }
}

fn apply(placed: &mut [PlacedObject], moves: Vec<PlacedObject>) {
    for m in moves {
        if let Some(o) = placed.iter_mut().find(|o| o.name == m.name) {
            o.position = m.position;
            o.rotation = m.rotation;
        }
    }
}

fn failed_questions(questions: &[Question], eval: &Evaluation) -> Vec<(Question, Answer)> {
    questions
        .iter()
        .filter_map(|q| {
            // A question the evaluator did not answer counts as failed: nothing is silently passed.
            let a = eval
                .answers
                .iter()
                .find(|a| a.id == q.id)
                .cloned()
                .unwrap_or(Answer {
                    id: q.id,
                    yes: false,
                    reason: "no answer".into(),
                });
            (!a.yes).then(|| (q.clone(), a))
        })
        .collect()
}

/// Makes any plan usable: unknown names are dropped from constraints and groups, each asset is
/// in exactly one group (the missing ones in a last group), and assets that fit the room in no
/// rotation are dropped up front with the reason.
pub fn sanitize_plan(
    scene: &SceneSpec,
    mut plan: Plan,
    notes: &mut Vec<String>,
) -> (Plan, Vec<Dropped>) {
    let known: HashSet<&str> = scene.assets.iter().map(|a| a.name.as_str()).collect();
    let before = plan.constraints.len();
    plan.constraints.retain(|k, _| known.contains(k.as_str()));
    for c in plan.constraints.values_mut() {
        c.relations.retain(|r| known.contains(r.target.as_str()));
        if c.facing.as_deref().is_some_and(|t| !known.contains(t)) {
            c.facing = None;
        }
    }
    if plan.constraints.len() < before {
        notes.push(format!(
            "plan: ignored constraints for {} unknown objects",
            before - plan.constraints.len()
        ));
    }
    let mut dropped = Vec::new();
    let mut misfits = HashSet::new();
    for a in &scene.assets {
        if let Some(why) = a.misfit(&scene.room) {
            dropped.push(Dropped {
                name: a.name.clone(),
                reason: why,
            });
            misfits.insert(a.name.clone());
        }
    }
    let mut seen: HashSet<String> = HashSet::new();
    let mut groups: Vec<Vec<String>> = Vec::new();
    for g in plan.groups {
        let g: Vec<String> = g
            .into_iter()
            .filter(|n| {
                known.contains(n.as_str()) && !misfits.contains(n) && seen.insert(n.clone())
            })
            .collect();
        if !g.is_empty() {
            groups.push(g);
        }
    }
    let rest: Vec<String> = scene
        .assets
        .iter()
        .filter(|a| !seen.contains(&a.name) && !misfits.contains(&a.name))
        .map(|a| a.name.clone())
        .collect();
    if !rest.is_empty() {
        notes.push(format!(
            "plan: {} objects were in no group; placed last",
            rest.len()
        ));
        groups.push(rest);
    }
    plan.groups = groups;
    (plan, dropped)
}
