//! How the scene loop reaches the roles ([`RoleCaller`]: over actors, or directly in tests), why
//! an agent could not be swapped ([`SwapError`]) and why a scene can fail ([`SceneFailure`]).

use std::sync::Arc;

use async_trait::async_trait;

use super::messages::Job;
use crate::config::AgentId;
use crate::registry::BuildError;
use disco_core::roles::RoleError;

/// How the loop reaches the roles.
#[async_trait]
pub trait RoleCaller: Send + Sync {
    /// Hands `job` to `agent`. The answer comes back on the job's own channel, or the job is
    /// failed (or dropped) when it cannot be carried out; the loop keeps the deadline.
    fn send(&self, agent: &AgentId, job: Arc<dyn Job>);
    /// `agent` missed its deadline on a call: cut it off and restart it.
    fn missed(&self, agent: &AgentId);
    /// Swaps `agent` to implementation `fallback`; `Err` says why it could not.
    async fn swap(&self, agent: &AgentId, fallback: &str) -> Result<(), SwapError>;
    /// The implementation currently serving `agent`.
    fn implementation(&self, agent: &AgentId) -> String;
    /// Whether the implementation serving `agent` looks at renders.
    fn wants_render(&self, agent: &AgentId) -> bool;
}

/// Why an agent could not be given an implementation (its fallback swapped in, or a restart).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SwapError {
    /// The implementation could not be built (the registry's error, boxed to keep
    /// [`SceneFailure`] small).
    #[error("{0}")]
    Build(Box<BuildError>),
    /// The actor to run it could not be started.
    #[error("cannot start the {agent} actor: {reason}")]
    Spawn {
        /// The agent.
        agent: AgentId,
        /// What the actor system said.
        reason: String,
    },
    /// The supervisor did not answer the swap in time, or is gone.
    #[error("the supervisor did not answer")]
    NoAnswer,
}

/// Why a scene could not be finished.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneFailure {
    /// The graph has no such agent (a graph changed after its check: `run.final_prt` turned
    /// on without a PRT agent, say).
    #[error("no agent {0:?} in the graph")]
    NoAgent(AgentId),
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
        why: SwapError,
    },
    /// The scene ran past `run.scene_deadline_s`.
    #[error("the scene missed its deadline of {0:.0} s")]
    Deadline(f64),
    /// The supervisor stopped before the loop was done.
    #[error("the scene's supervisor stopped before the scene was done")]
    SupervisorStopped,
    /// The scene's supervisor could not be started (what the actor system said).
    #[error("could not start its supervisor: {0}")]
    NotStarted(String),
    /// The scene's supervisor went away without sending the scene's result.
    #[error("its supervisor stopped without an answer")]
    NoAnswer,
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
