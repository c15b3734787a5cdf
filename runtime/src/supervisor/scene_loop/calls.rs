//! Calling one role from the scene loop: the typed call out, its typed answer back and checked by
//! the call's acceptance, retries with backoff within the role's and the scene's deadlines, the
//! fallback swap (early, when the model server already failed or the scene is late), and the
//! answer's costs and (capped) notes into the scene's.

use std::sync::Arc;
use std::time::{Duration, Instant};

use backon::{ExponentialBuilder, Retryable};
use serde_json::json;

use super::super::accept::{MAX_TEXT_CHARS, cap_notes, clip};
use super::super::caller::SceneFailure;
use super::super::messages::{RoleCall, pending};
use super::{LATE_GRACE, Loop, seconds};

/// The longest pause between two tries of a call.
const MAX_BACKOFF: Duration = Duration::from_secs(10);
use crate::config::{AgentConfig, AgentId};
use crate::trace::TraceKind;
use disco_core::relations::ConstraintCheck;
use disco_core::roles::{Output, RoleError, RoleResult};

impl Loop<'_> {
    /// Sends `call` to `agent`: with retries and backoff, then with its fallback. The reply is
    /// the one the call's type asks for, taken only once the call accepted it; a refused reply
    /// is a failure like an error. The loop names only agents the graph's check settled for the
    /// call's role (the method's own agents, and the agents of the round's typed stages).
    pub(super) async fn call<C: RoleCall>(
        &mut self,
        agent: &AgentId,
        call: C,
    ) -> Result<C::Reply, SceneFailure> {
        let graph = self.graph;
        let Some(found) = graph.agent(agent) else {
            return Err(SceneFailure::NoAgent(agent.clone()));
        };
        let config = found.config();
        // Shared by every try, so that a retry does not copy the layout again.
        let call = Arc::new(call);
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
            match self.attempts(agent, &call, config).await {
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

    /// One call and its retries with exponential backoff, each traced; a reply its call refuses
    /// is traced as an error and retried.
    pub(super) async fn attempts<C: RoleCall>(
        &self,
        agent: &AgentId,
        call: &Arc<C>,
        config: &AgentConfig,
    ) -> Result<Output<C::Reply>, RoleError> {
        let backoff = ExponentialBuilder::default()
            .with_min_delay(Duration::from_millis(self.graph.run.backoff_ms))
            .with_max_delay(MAX_BACKOFF)
            .with_max_times(config.retries as usize);
        let attempt = || async {
            // Each try gets what is left of the scene's time, at most the agent's deadline.
            let deadline = seconds(config.deadline_s).min(self.time_left());
            if deadline.is_zero() {
                return Err(RoleError::Deadline(0.0));
            }
            let keep = self.trace.keeps_events();
            if keep {
                self.event(Some(agent), TraceKind::Request, None, None, call.summary());
            }
            let t0 = Instant::now();
            let result = self.once(agent, call, deadline).await;
            let ms = Some(t0.elapsed().as_secs_f64() * 1000.0);
            match &result {
                _ if !keep => {}
                Ok(out) => self.event(
                    Some(agent),
                    TraceKind::Reply,
                    ms,
                    Some(out.usage),
                    C::reply_summary(&out.value),
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
            let Output {
                value,
                usage,
                calls,
                notes,
                infeasible,
            } = result?;
            let value = call.accept(value).inspect_err(|e| {
                self.event(
                    Some(agent),
                    TraceKind::Error,
                    None,
                    None,
                    json!(e.to_string()),
                );
            })?;
            Ok(Output {
                value,
                usage,
                calls,
                notes: cap_notes(notes),
                infeasible,
            })
        };
        attempt
            .retry(backoff)
            .when(|_| !self.time_left().is_zero())
            .await
    }

    /// One try: `call` to `agent`'s actor and its answer back, within `deadline` (past it the
    /// agent is cut off and restarted).
    async fn once<C: RoleCall>(
        &self,
        agent: &AgentId,
        call: &Arc<C>,
        deadline: Duration,
    ) -> RoleResult<C::Reply> {
        let (job, answer) = pending(Arc::clone(call));
        self.caller.send(agent, job);
        match tokio::time::timeout(deadline, answer).await {
            Ok(Ok(result)) => result,
            Ok(Err(_)) => Err(RoleError::Unavailable(format!(
                "the {agent} dropped the request"
            ))),
            Err(_) => {
                self.caller.missed(agent);
                Err(RoleError::Deadline(deadline.as_secs_f64()))
            }
        }
    }

    /// Time left before the scene's deadline (or, once late, before the grace ends).
    pub(super) fn time_left(&self) -> Duration {
        self.until.saturating_duration_since(Instant::now())
    }

    /// The scene's deadline passed: from now on what is left is finished by fallbacks, within
    /// [`LATE_GRACE`].
    pub(super) fn go_late(&mut self) {
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
    pub(super) async fn swap_early(
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
    pub(super) fn account<T>(&mut self, agent: &AgentId, out: Output<T>) -> T {
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
        for i in out.infeasible {
            let what = ConstraintCheck {
                subject: i.subject.clone(),
                kind: i.constraint.clone(),
                met: false,
            };
            if self
                .infeasible
                .iter()
                .any(|k| k.subject == i.subject && k.constraint == i.constraint)
            {
                continue;
            }
            let note = format!(
                "{agent}: reports \"{what}\" cannot be met ({}); it is not asked about again",
                clip(&i.reason, MAX_TEXT_CHARS)
            );
            self.event(
                Some(agent),
                TraceKind::Stage,
                None,
                None,
                json!({"infeasible": note}),
            );
            self.notes.push(note);
            self.infeasible.push(i);
        }
        out.value
    }

    /// Swaps `agent` to its `fallback` after it failed with `e`.
    pub(super) async fn fall_back(
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
}
