//! The actors: one [`RoleActor`] per agent of a scene, under one [`SceneSupervisor`] per scene.
//!
//! The supervisor owns the scene: it spawns the role actors (unnamed, so scenes never clash),
//! forwards requests to them, restarts one that panics or misses its deadline (one-for-one, at
//! most `max_restarts` in `restart_window_s`), swaps in a fallback implementation when asked, and
//! runs the scene's loop in a task of its own so that its mailbox stays free for supervision
//! events. A role actor answers each request from a spawned task, so a long model call never
//! blocks its mailbox.

use std::collections::{HashMap, VecDeque};
use std::panic::AssertUnwindSafe;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use async_trait::async_trait;
use futures::FutureExt;
use ractor::{Actor, ActorProcessingErr, ActorRef, RpcReplyPort, SupervisionEvent};
use serde_json::json;
use tokio::sync::oneshot;
use tokio::task::AbortHandle;

use super::caller::SwapError;
use super::messages::Job;
use super::scene_loop::{LATE_GRACE, RoleCaller, SceneFailure, run_scene, seconds};
use crate::config::{AgentId, GraphConfig};
use crate::registry::Registry;
use crate::trace::{Trace, TraceEvent, TraceKind};
use disco_core::layout::Layout;
use disco_core::roles::{RoleError, RoleImpl};
use disco_core::scene::SceneSpec;
use disco_llm::Gateways;

/// How long the loop waits for the supervisor to swap in a fallback.
const SWAP_TIMEOUT: Duration = Duration::from_secs(30);

/// How long past the loop's own deadline and [`LATE_GRACE`] the hard stop comes.
const HARD_STOP_SLACK: Duration = Duration::from_secs(10);

/// Messages to a role actor.
pub enum RoleMsg {
    /// Carry out a call; its answer goes back on the call's own channel.
    Invoke(Arc<dyn Job>),
    /// The implementation panicked while answering: fail, so the supervisor restarts us.
    Crashed(String),
}

/// Runs one role implementation.
pub struct RoleActor;

/// A role actor's state: its implementation and the tasks answering requests.
pub struct RoleState {
    imp: RoleImpl,
    tasks: Vec<AbortHandle>,
}

fn panic_text(p: Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

impl Actor for RoleActor {
    type Msg = RoleMsg;
    type State = RoleState;
    type Arguments = RoleImpl;

    async fn pre_start(
        &self,
        _myself: ActorRef<RoleMsg>,
        imp: RoleImpl,
    ) -> Result<RoleState, ActorProcessingErr> {
        Ok(RoleState {
            imp,
            tasks: Vec::new(),
        })
    }

    async fn handle(
        &self,
        myself: ActorRef<RoleMsg>,
        msg: RoleMsg,
        state: &mut RoleState,
    ) -> Result<(), ActorProcessingErr> {
        match msg {
            RoleMsg::Invoke(job) => {
                let imp = state.imp.clone();
                let task = tokio::spawn(async move {
                    match AssertUnwindSafe(Arc::clone(&job).run(imp))
                        .catch_unwind()
                        .await
                    {
                        Ok(None) => {}
                        // An external agent whose process died reports it as a panic: the
                        // role is restarted the same way.
                        Ok(Some(text)) => {
                            let _ = myself.cast(RoleMsg::Crashed(text));
                        }
                        Err(p) => {
                            let text = panic_text(p);
                            job.fail(RoleError::Panicked(text.clone()));
                            let _ = myself.cast(RoleMsg::Crashed(text));
                        }
                    }
                });
                state.tasks.retain(|t| !t.is_finished());
                state.tasks.push(task.abort_handle());
                Ok(())
            }
            RoleMsg::Crashed(text) => Err(format!("the implementation panicked: {text}").into()),
        }
    }

    async fn post_stop(
        &self,
        _myself: ActorRef<RoleMsg>,
        state: &mut RoleState,
    ) -> Result<(), ActorProcessingErr> {
        // A cut-off call must not run on in the background.
        for t in &state.tasks {
            t.abort();
        }
        Ok(())
    }
}

/// Messages to a scene supervisor.
pub enum SupervisorMsg {
    /// Forward a call to `agent` (its answer goes back on the call's own channel).
    Invoke {
        /// The agent.
        agent: AgentId,
        /// The call.
        job: Arc<dyn Job>,
    },
    /// The agent missed its deadline: cut it off and restart it.
    DeadlineMissed(AgentId),
    /// Swap an agent to implementation `fallback`.
    Swap {
        /// The agent.
        agent: AgentId,
        /// The implementation to swap in.
        fallback: String,
        /// `Err` says why it could not.
        reply: RpcReplyPort<Result<(), SwapError>>,
    },
    /// The scene's loop is done.
    Finished(Box<Result<Layout, SceneFailure>>),
}

/// Everything a supervisor needs to run a scene.
pub struct SupervisorArgs {
    /// What the scene runs with.
    pub run: SceneRun,
    /// Where the result goes.
    pub done: oneshot::Sender<Result<Layout, SceneFailure>>,
}

/// The scene and what it runs with: graph, implementations, gateways, trace.
pub struct SceneRun {
    /// The scene.
    pub scene: Arc<SceneSpec>,
    /// The agent graph.
    pub graph: Arc<GraphConfig>,
    /// Implementations by name.
    pub registry: Arc<Registry>,
    /// Shared model gateways.
    pub gateways: Arc<Gateways>,
    /// Where events go.
    pub trace: Arc<Trace>,
}

/// What serves an agent now, as the supervisor shares it with its loop's caller (for the trace and
/// render decisions).
struct Serving {
    implementation: String,
    wants_render: bool,
}

/// The state the supervisor shares with the caller its loop uses.
#[derive(Default)]
struct Shared {
    serving: HashMap<AgentId, Serving>,
}

struct Slot {
    actor: Option<ActorRef<RoleMsg>>,
    implementation: String,
    restarts: VecDeque<Instant>,
    broken: Option<String>,
}

/// Supervises one scene.
pub struct SceneSupervisor;

/// A supervisor's state.
pub struct SupervisorState {
    args: SceneRun,
    slots: HashMap<AgentId, Slot>,
    shared: Arc<Mutex<Shared>>,
    done: Option<oneshot::Sender<Result<Layout, SceneFailure>>>,
    restarts: u32,
    driver: Option<AbortHandle>,
}

impl SupervisorState {
    fn event(&self, agent: &AgentId, kind: TraceKind, detail: serde_json::Value) {
        let implementation = self
            .slots
            .get(agent)
            .map(|s| s.implementation.clone())
            .unwrap_or_default();
        self.args.trace.record(TraceEvent {
            t_ms: 0,
            scene: self.args.scene.id.clone(),
            role: agent.to_string(),
            implementation,
            kind,
            ms: None,
            usage: None,
            detail,
        });
    }

    async fn spawn_role(
        &mut self,
        myself: &ActorRef<SupervisorMsg>,
        agent: &AgentId,
        implementation: &str,
    ) -> Result<(), SwapError> {
        let imp = self
            .args
            .registry
            .build(&self.args.graph, &self.args.gateways, agent, implementation)
            .map_err(|e| SwapError::Build(Box::new(e)))?;
        let wants_render = imp.wants_render();
        let (actor, _) = Actor::spawn_linked(None, RoleActor, imp, myself.get_cell())
            .await
            .map_err(|e| SwapError::Spawn {
                agent: agent.clone(),
                reason: e.to_string(),
            })?;
        let slot = self.slots.entry(agent.clone()).or_insert_with(|| Slot {
            actor: None,
            implementation: implementation.to_string(),
            restarts: VecDeque::new(),
            broken: None,
        });
        if let Some(old) = slot.actor.replace(actor) {
            old.stop(Some("replaced".into()));
        }
        slot.implementation = implementation.to_string();
        slot.broken = None;
        self.shared
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .serving
            .insert(
                agent.clone(),
                Serving {
                    implementation: implementation.to_string(),
                    wants_render,
                },
            );
        Ok(())
    }

    /// Restarts `agent` if it has restarts left in the window; otherwise marks it broken.
    async fn restart(&mut self, myself: &ActorRef<SupervisorMsg>, agent: &AgentId, why: &str) {
        let window = seconds(self.args.graph.run.restart_window_s);
        let max = self.args.graph.run.max_restarts as usize;
        let Some(slot) = self.slots.get_mut(agent) else {
            return;
        };
        let now = Instant::now();
        while slot
            .restarts
            .front()
            .is_some_and(|t| now.duration_since(*t) > window)
        {
            slot.restarts.pop_front();
        }
        if let Some(old) = slot.actor.take() {
            old.stop(Some(why.to_string()));
        }
        if slot.restarts.len() >= max {
            let broken = format!(
                "restarted {max} times within {:.0} s; last: {why}",
                window.as_secs_f64()
            );
            slot.broken = Some(broken.clone());
            self.event(agent, TraceKind::Error, json!({ "broken": broken }));
            return;
        }
        slot.restarts.push_back(now);
        let implementation = slot.implementation.clone();
        self.restarts += 1;
        self.event(agent, TraceKind::Restart, json!({"reason": why}));
        if let Err(e) = self.spawn_role(myself, agent, &implementation).await
            && let Some(slot) = self.slots.get_mut(agent)
        {
            slot.broken = Some(e.to_string());
        }
    }
}

/// The [`RoleCaller`] a scene's loop uses: every call goes through the supervisor.
struct ActorCaller {
    supervisor: ActorRef<SupervisorMsg>,
    shared: Arc<Mutex<Shared>>,
}

#[async_trait]
impl RoleCaller for ActorCaller {
    fn send(&self, agent: &AgentId, job: Arc<dyn Job>) {
        let sent = self.supervisor.cast(SupervisorMsg::Invoke {
            agent: agent.clone(),
            job: Arc::clone(&job),
        });
        if let Err(e) = sent {
            job.fail(RoleError::Unavailable(format!(
                "the supervisor is gone: {e}"
            )));
        }
    }

    fn missed(&self, agent: &AgentId) {
        let _ = self
            .supervisor
            .cast(SupervisorMsg::DeadlineMissed(agent.clone()));
    }

    async fn swap(&self, agent: &AgentId, fallback: &str) -> Result<(), SwapError> {
        let (agent, fallback) = (agent.clone(), fallback.to_string());
        match self
            .supervisor
            .call(
                |reply| SupervisorMsg::Swap {
                    agent,
                    fallback,
                    reply,
                },
                Some(SWAP_TIMEOUT),
            )
            .await
        {
            Ok(ractor::rpc::CallResult::Success(r)) => r,
            _ => Err(SwapError::NoAnswer),
        }
    }

    fn implementation(&self, agent: &AgentId) -> String {
        self.shared
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .serving
            .get(agent)
            .map(|s| s.implementation.clone())
            .unwrap_or_else(|| "supervisor".into())
    }

    fn wants_render(&self, agent: &AgentId) -> bool {
        self.shared
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .serving
            .get(agent)
            .is_some_and(|s| s.wants_render)
    }
}

impl Actor for SceneSupervisor {
    type Msg = SupervisorMsg;
    type State = SupervisorState;
    type Arguments = SupervisorArgs;

    async fn pre_start(
        &self,
        myself: ActorRef<SupervisorMsg>,
        args: SupervisorArgs,
    ) -> Result<SupervisorState, ActorProcessingErr> {
        let mut state = SupervisorState {
            args: args.run,
            slots: HashMap::new(),
            shared: Arc::new(Mutex::new(Shared::default())),
            done: Some(args.done),
            restarts: 0,
            driver: None,
        };
        let agents: Vec<(AgentId, String)> = state
            .args
            .graph
            .agents()
            .iter()
            .map(|(id, a)| (id.clone(), a.config().impl_name().to_string()))
            .collect();
        for (agent, implementation) in agents {
            state
                .spawn_role(&myself, &agent, &implementation)
                .await
                .map_err(ActorProcessingErr::from)?;
        }
        Ok(state)
    }

    async fn post_start(
        &self,
        myself: ActorRef<SupervisorMsg>,
        state: &mut SupervisorState,
    ) -> Result<(), ActorProcessingErr> {
        let caller = ActorCaller {
            supervisor: myself.clone(),
            shared: Arc::clone(&state.shared),
        };
        let (scene, graph, trace) = (
            Arc::clone(&state.args.scene),
            Arc::clone(&state.args.graph),
            Arc::clone(&state.args.trace),
        );
        // The loop keeps its own deadline and finishes late scenes with fallbacks; this is the
        // hard stop behind it, for a loop that cannot even do that.
        let deadline = seconds(graph.run.scene_deadline_s) + LATE_GRACE + HARD_STOP_SLACK;
        let driver = tokio::spawn(async move {
            let result =
                match tokio::time::timeout(deadline, run_scene(scene, &graph, &caller, &trace))
                    .await
                {
                    Ok(r) => r,
                    Err(_) => Err(SceneFailure::Deadline(deadline.as_secs_f64())),
                };
            let _ = myself.cast(SupervisorMsg::Finished(Box::new(result)));
        });
        state.driver = Some(driver.abort_handle());
        Ok(())
    }

    async fn handle(
        &self,
        myself: ActorRef<SupervisorMsg>,
        msg: SupervisorMsg,
        state: &mut SupervisorState,
    ) -> Result<(), ActorProcessingErr> {
        match msg {
            SupervisorMsg::Invoke { agent, job } => {
                let Some(slot) = state.slots.get(&agent) else {
                    job.fail(RoleError::Unavailable(format!("no agent {agent:?}")));
                    return Ok(());
                };
                if let Some(why) = &slot.broken {
                    job.fail(RoleError::Unavailable(why.clone()));
                    return Ok(());
                }
                let restarting = || RoleError::Unavailable(format!("the {agent} is restarting"));
                match &slot.actor {
                    Some(actor) => {
                        if actor
                            .send_message(RoleMsg::Invoke(Arc::clone(&job)))
                            .is_err()
                        {
                            job.fail(restarting());
                        }
                    }
                    None => job.fail(restarting()),
                }
            }
            SupervisorMsg::DeadlineMissed(agent) => {
                state.restart(&myself, &agent, "missed its deadline").await;
            }
            SupervisorMsg::Swap {
                agent,
                fallback,
                reply,
            } => {
                if let Some(old) = state.slots.get_mut(&agent).and_then(|s| s.actor.take()) {
                    old.stop(Some(format!("replaced by {fallback}")));
                }
                let result = state.spawn_role(&myself, &agent, &fallback).await;
                if result.is_ok()
                    && let Some(slot) = state.slots.get_mut(&agent)
                {
                    slot.restarts.clear();
                }
                let _ = reply.send(result);
            }
            SupervisorMsg::Finished(result) => {
                let result = result.map(|mut layout| {
                    layout.stats.restarts = state.restarts;
                    layout
                });
                if let Some(done) = state.done.take() {
                    let _ = done.send(result);
                }
                myself.stop_children(Some("scene finished".into()));
                myself.stop(Some("scene finished".into()));
            }
        }
        Ok(())
    }

    /// Restarts a failed role instead of the default (which stops the supervisor with it).
    async fn handle_supervisor_evt(
        &self,
        myself: ActorRef<SupervisorMsg>,
        event: SupervisionEvent,
        state: &mut SupervisorState,
    ) -> Result<(), ActorProcessingErr> {
        if let SupervisionEvent::ActorFailed(cell, err) = event {
            let agent = state
                .slots
                .iter()
                .find(|(_, s)| {
                    s.actor
                        .as_ref()
                        .is_some_and(|a| a.get_id() == cell.get_id())
                })
                .map(|(a, _)| a.clone());
            if let Some(agent) = agent {
                state.restart(&myself, &agent, &err.to_string()).await;
            }
        }
        Ok(())
    }

    async fn post_stop(
        &self,
        _myself: ActorRef<SupervisorMsg>,
        state: &mut SupervisorState,
    ) -> Result<(), ActorProcessingErr> {
        if let Some(d) = &state.driver {
            d.abort();
        }
        if let Some(done) = state.done.take() {
            let _ = done.send(Err(SceneFailure::SupervisorStopped));
        }
        Ok(())
    }
}
