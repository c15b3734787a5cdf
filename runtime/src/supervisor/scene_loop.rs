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

use super::messages::{EvalMode, RoleReply, RoleRequest};
use crate::config::{EvalModeConfig, GraphConfig, QuestionStyle, When};
use crate::trace::{Trace, TraceEvent, TraceKind};
use disco_core::layout::{Dropped, Layout, PlacedObject, Stats};
use disco_core::plan::Plan;
use disco_core::relations::{ConstraintCheck, constraints_of};
use disco_core::render::{RenderOptions, render_png};
use disco_core::roles::Refined;
use disco_core::roles::{
    Answer, DesignRequest, EvalRequest, Evaluation, Output, PatchRequest, PrtRequest, Question,
    RoleError, SceneContext, SrtRequest, Usage,
};
use disco_core::scene::SceneSpec;

/// How the loop reaches the roles.
#[async_trait]
pub trait RoleCaller: Send + Sync {
    /// Sends `request` to agent `role` and waits at most `deadline` for the answer.
    async fn invoke(
        &self,
        role: &str,
        request: RoleRequest,
        deadline: Duration,
    ) -> Result<Output<RoleReply>, RoleError>;
    /// Swaps agent `role` to implementation `fallback`; `Err` says why it could not.
    async fn swap(&self, role: &str, fallback: &str) -> Result<(), String>;
    /// The implementation currently serving `role`.
    fn implementation(&self, role: &str) -> String;
    /// Whether the implementation serving `role` looks at renders.
    fn wants_render(&self, role: &str) -> bool;
}

/// Why a scene could not be finished.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct SceneFailure(pub String);

struct Loop<'a> {
    scene: Arc<SceneSpec>,
    graph: &'a GraphConfig,
    caller: &'a dyn RoleCaller,
    trace: &'a Trace,
    usage: Usage,
    fallbacks: Vec<String>,
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
        graph,
        caller,
        trace,
        usage: Usage::default(),
        fallbacks: Vec::new(),
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
    layout.stats.notes.extend(l.notes);
    layout.stats.rounds = l.rounds;
    Ok(layout)
}

impl Loop<'_> {
    fn event(
        &self,
        role: &str,
        kind: TraceKind,
        ms: Option<f64>,
        usage: Option<Usage>,
        detail: serde_json::Value,
    ) {
        self.trace.record(TraceEvent {
            t_ms: 0,
            scene: self.scene.id.clone(),
            role: role.to_string(),
            implementation: self.caller.implementation(role),
            kind,
            ms,
            usage,
            detail,
        });
    }

    /// Records that a stage of the loop begins.
    /// Records the layout after a step, when the trace keeps snapshots.
    fn snapshot(
        &self,
        step: &str,
        group: usize,
        round: u32,
        placed: &[PlacedObject],
        dropped: &[Dropped],
    ) {
        if self.trace.wants_snapshots() {
            self.event(
                "supervisor",
                TraceKind::Snapshot,
                None,
                None,
                json!({"step": step, "group": group, "round": round, "objects": placed, "dropped": dropped}),
            );
        }
    }

    fn stage(&self, detail: serde_json::Value) {
        self.event("supervisor", TraceKind::Stage, None, None, detail);
    }

    /// Calls `role` with retries and backoff, then with its fallback.
    async fn call(&mut self, role: &str, request: RoleRequest) -> Result<RoleReply, SceneFailure> {
        let agent = self
            .graph
            .agents
            .get(role)
            .ok_or_else(|| SceneFailure(format!("no agent {role:?} in the graph")))?;
        let deadline = Duration::from_secs_f64(agent.deadline_s);
        let backoff = ExponentialBuilder::default()
            .with_min_delay(Duration::from_millis(self.graph.run.backoff_ms))
            .with_max_delay(Duration::from_secs(10))
            .with_max_times(agent.retries as usize);
        let mut swapped = false;
        loop {
            let attempt = || async {
                self.event(role, TraceKind::Request, None, None, request.summary());
                let t0 = Instant::now();
                let result = self.caller.invoke(role, request.clone(), deadline).await;
                let ms = Some(t0.elapsed().as_secs_f64() * 1000.0);
                match &result {
                    Ok(out) => self.event(
                        role,
                        TraceKind::Reply,
                        ms,
                        Some(out.usage),
                        out.value.summary(),
                    ),
                    Err(RoleError::Deadline(_)) => self.event(
                        role,
                        TraceKind::Timeout,
                        ms,
                        None,
                        json!(result.as_ref().err().map(|e| e.to_string())),
                    ),
                    Err(e) => self.event(role, TraceKind::Error, ms, None, json!(e.to_string())),
                }
                result
            };
            match attempt.retry(backoff).await {
                Ok(out) => {
                    self.usage += out.usage;
                    for call in &out.calls {
                        self.event(
                            role,
                            TraceKind::ModelCall,
                            Some(call.latency_ms),
                            None,
                            json!(call),
                        );
                    }
                    self.notes
                        .extend(out.notes.iter().map(|n| format!("{role}: {n}")));
                    return Ok(out.value);
                }
                Err(e) => {
                    let fallback = agent.fallback.as_ref().map(|f| f.get_ref().clone());
                    match fallback {
                        Some(f) if !swapped => {
                            let from = self.caller.implementation(role);
                            self.caller.swap(role, &f).await.map_err(|why| {
                                SceneFailure(format!("the {role} failed ({e}) and its fallback {f:?} could not start: {why}"))
                            })?;
                            let note = format!(
                                "{role}: {from} -> {f} after {} tries ({e})",
                                agent.retries + 1
                            );
                            self.event(role, TraceKind::Fallback, None, None, json!(note));
                            self.fallbacks.push(note);
                            swapped = true;
                        }
                        _ => {
                            return Err(SceneFailure(format!(
                                "the {role} ({}) failed after {} tries: {e}",
                                self.caller.implementation(role),
                                agent.retries + 1
                            )));
                        }
                    }
                }
            }
        }
    }

    fn ctx(&self, plan: &Arc<Plan>) -> SceneContext {
        SceneContext {
            scene: Arc::clone(&self.scene),
            plan: Arc::clone(plan),
        }
    }

    fn layout_of(&self, objects: Vec<PlacedObject>, dropped: Vec<Dropped>, plan: &Plan) -> Layout {
        Layout {
            id: self.scene.id.clone(),
            room: self.scene.room,
            objects,
            dropped,
            plan: plan.clone(),
            stats: Stats::default(),
        }
    }

    fn render_for(&self, role: &str, layout: &Layout) -> Option<Arc<Vec<u8>>> {
        if !self.caller.wants_render(role) {
            return None;
        }
        render_png(layout, &RenderOptions::default())
            .ok()
            .map(Arc::new)
    }

    async fn run(&mut self) -> Result<Layout, SceneFailure> {
        let graph = self.graph;
        let reply = self
            .call("planner", RoleRequest::Plan(Arc::clone(&self.scene)))
            .await?;
        let RoleReply::Plan(raw_plan) = reply else {
            return Err(SceneFailure(
                "the planner answered something other than a plan".into(),
            ));
        };
        let (mut plan, mut dropped) = sanitize_plan(&self.scene, raw_plan, &mut self.notes);
        if graph.run.single_shot && plan.groups.len() > 1 {
            plan.groups = vec![plan.groups.concat()];
        }
        let plan = Arc::new(plan);

        let mut placed: Vec<PlacedObject> = Vec::new();
        let mut settled: HashSet<String> = HashSet::new();
        for (gi, group) in plan.groups.clone().into_iter().enumerate() {
            let gi = gi + 1;
            self.stage(json!({"stage": "design", "group": group}));
            let so_far = self.layout_of(placed.clone(), dropped.clone(), &plan);
            let request = DesignRequest {
                ctx: self.ctx(&plan),
                group: group.clone(),
                placed: placed.clone(),
                render: self.render_for("designer", &so_far),
            };
            let RoleReply::Design(poses) =
                self.call("designer", RoleRequest::Design(request)).await?
            else {
                return Err(SceneFailure(
                    "the designer answered something other than poses".into(),
                ));
            };
            let proposed = self.accept_poses(&group, poses, "designer");
            let (proposed, unplaced) = self.park_or_drop(proposed);
            dropped.extend(unplaced);
            placed.extend(proposed);
            self.snapshot("design", gi, 0, &placed, &dropped);

            for round in 0..graph.run.max_rounds {
                if graph.pipeline.round.first().map(String::as_str) != Some("evaluate") {
                    break;
                }
                self.rounds += 1;
                let current = self.layout_of(placed.clone(), dropped.clone(), &plan);
                let questions = self.questions(&plan, &group);
                let agent = &graph.agents["evaluator"];
                let mode = match agent.mode {
                    EvalModeConfig::Parallel => EvalMode::Parallel { width: agent.width },
                    EvalModeConfig::Batch => EvalMode::Batch,
                };
                let request = EvalRequest {
                    ctx: self.ctx(&plan),
                    render: self.render_for("evaluator", &current),
                    layout: current.clone(),
                    group: group.clone(),
                };
                self.stage(json!({"stage": "evaluate", "round": round + 1}));
                let RoleReply::Evaluate(eval) = self
                    .call(
                        "evaluator",
                        RoleRequest::Evaluate(request, questions.clone(), mode),
                    )
                    .await?
                else {
                    return Err(SceneFailure(
                        "the evaluator answered something other than an evaluation".into(),
                    ));
                };
                let failed = failed_questions(&questions, &eval);
                if failed.is_empty() && !eval.needs_physical {
                    break;
                }
                for stage in graph.pipeline.round.iter().skip(1) {
                    let role = graph.role_of(stage);
                    let now = self.layout_of(placed.clone(), dropped.clone(), &plan);
                    match role {
                        Some(disco_core::roles::RoleKind::Srt) if !failed.is_empty() => {
                            self.stage(json!({"stage": stage}));
                            let request = SrtRequest {
                                ctx: self.ctx(&plan),
                                render: self.render_for(stage, &now),
                                layout: now,
                                failed: failed.clone(),
                                movable: group.clone(),
                            };
                            if let RoleReply::Srt(moves) =
                                self.call(stage, RoleRequest::Srt(request)).await?
                            {
                                let moves = self.accept_poses(&group, moves, stage);
                                apply(&mut placed, moves);
                                self.snapshot(stage, gi, round + 1, &placed, &dropped);
                            }
                        }
                        Some(disco_core::roles::RoleKind::Prt) if eval.needs_physical => {
                            self.stage(json!({"stage": stage}));
                            let request = PrtRequest {
                                ctx: self.ctx(&plan),
                                layout: now,
                                settled: settled.clone(),
                            };
                            if let RoleReply::Prt(refined) =
                                self.call(stage, RoleRequest::Prt(request)).await?
                            {
                                (placed, dropped) = self.accept_refined(refined, dropped);
                                self.snapshot(stage, gi, round + 1, &placed, &dropped);
                            }
                        }
                        Some(disco_core::roles::RoleKind::Patch) => {
                            let when = graph.agents[stage.as_str()].when;
                            let due = match when {
                                When::Always => true,
                                When::SemanticFailed => !failed.is_empty(),
                                When::PhysicalFailed => eval.needs_physical,
                            };
                            if due {
                                self.stage(json!({"stage": stage}));
                                let request = PatchRequest {
                                    ctx: self.ctx(&plan),
                                    layout: now,
                                    group: group.clone(),
                                };
                                if let RoleReply::Patch(moves) =
                                    self.call(stage, RoleRequest::Patch(request)).await?
                                {
                                    let moves = self.accept_poses(&group, moves, stage);
                                    apply(&mut placed, moves);
                                    self.snapshot(stage, gi, round + 1, &placed, &dropped);
                                }
                            }
                        }
                        _ => {}
                    }
                }
            }
            settled.extend(group.iter().cloned());
        }

        if graph.run.final_prt {
            self.stage(json!({"stage": "final prt"}));
            let request = PrtRequest {
                ctx: self.ctx(&plan),
                layout: self.layout_of(placed.clone(), dropped.clone(), &plan),
                settled,
            };
            if let RoleReply::Prt(refined) = self.call("prt", RoleRequest::Prt(request)).await? {
                let stats = refined.stats();
                (placed, dropped) = self.accept_refined(refined, dropped);
                self.snapshot("final prt", 0, 0, &placed, &dropped);
                let mut layout = self.finish(placed, dropped, &plan);
                layout.stats.prt = Some(stats);
                return Ok(layout);
            }
        }
        Ok(self.finish(placed, dropped, &plan))
    }

    /// One question per constraint of the group's objects, or one open question.
    fn questions(&self, plan: &Plan, group: &[String]) -> Vec<Question> {
        if self.graph.agents["evaluator"].questions == QuestionStyle::Open {
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
        who: &str,
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
        if who == "designer" {
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
                .any(|s| graph.role_of(s) == Some(disco_core::roles::RoleKind::Prt));
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

    fn accept_refined(
        &mut self,
        refined: Refined,
        mut dropped: Vec<Dropped>,
    ) -> (Vec<PlacedObject>, Vec<Dropped>) {
        self.notes.extend(refined.notes);
        dropped.extend(refined.dropped);
        (refined.objects, dropped)
    }

    /// The final layout: objects in scene order; any asset neither placed nor dropped is dropped
    /// with a reason (never silently lost).
    fn finish(&self, placed: Vec<PlacedObject>, mut dropped: Vec<Dropped>, plan: &Plan) -> Layout {
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
        self.layout_of(objects, dropped, plan)
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
