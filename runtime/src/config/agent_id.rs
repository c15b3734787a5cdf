//! Agents and round stages of a graph, as types: the scene loop names agents by [`AgentId`],
//! finds their settled role and settings in an [`Agent`], and walks a round as [`Stage`]s, never
//! by bare strings.

use std::fmt;

use super::{AgentConfig, When};
use disco_core::roles::RoleKind;

/// The name of an agent of the graph (`[agents.NAME]`). The agents of the five roles of the method
/// have fixed names ([`AgentId::PLANNER`], ...); a graph may add stages of its own under any name.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct AgentId(std::borrow::Cow<'static, str>);

impl AgentId {
    /// The planner.
    pub const PLANNER: AgentId = AgentId(std::borrow::Cow::Borrowed("planner"));
    /// The designer.
    pub const DESIGNER: AgentId = AgentId(std::borrow::Cow::Borrowed("designer"));
    /// The evaluator.
    pub const EVALUATOR: AgentId = AgentId(std::borrow::Cow::Borrowed("evaluator"));
    /// The Semantic Refinement Tool.
    pub const SRT: AgentId = AgentId(std::borrow::Cow::Borrowed("srt"));
    /// The Physical Refinement Tool (also the final pass over the whole layout).
    pub const PRT: AgentId = AgentId(std::borrow::Cow::Borrowed("prt"));

    /// The agent named `name` in the graph.
    pub fn new(name: impl Into<String>) -> Self {
        AgentId(std::borrow::Cow::Owned(name.into()))
    }

    /// The name as written in the graph.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl fmt::Display for AgentId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl serde::Serialize for AgentId {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(&self.0)
    }
}

impl std::borrow::Borrow<str> for AgentId {
    fn borrow(&self) -> &str {
        &self.0
    }
}

/// An agent of a checked graph: its id, its role (written, or implied by its name) and its
/// section as written. Made only by the graph's check.
#[derive(Debug, Clone, PartialEq)]
pub struct Agent {
    pub(crate) id: AgentId,
    pub(crate) role: RoleKind,
    pub(crate) config: AgentConfig,
}

impl Agent {
    /// The agent `id` of role `role`, set up by `config`.
    pub(super) fn new(id: AgentId, role: RoleKind, config: AgentConfig) -> Self {
        Agent { id, role, config }
    }

    /// Its id, the name of its section.
    pub fn id(&self) -> &AgentId {
        &self.id
    }

    /// The role it plays.
    pub fn role(&self) -> RoleKind {
        self.role
    }

    /// Its settings: implementation, model, deadline, retries, fallback, options...
    pub fn config(&self) -> &AgentConfig {
        &self.config
    }
}

/// One stage of an evaluate-and-refine round, as `[pipeline] round` lists them, with what the
/// graph's check settled: each agent exists and plays the role of its stage.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Stage {
    /// The evaluator answers the group's questions (always first).
    Evaluate,
    /// An SRT agent: runs when some question was answered "no".
    Srt(AgentId),
    /// A PRT agent: runs when the evaluator asked for physical refinement.
    Prt(AgentId),
    /// A custom (patch) stage: runs as its `when` says.
    Patch {
        /// The agent.
        agent: AgentId,
        /// When it runs.
        when: When,
    },
}

impl Stage {
    /// The stage's agent (`None` for [`Stage::Evaluate`], which is the evaluator's).
    pub fn agent(&self) -> Option<&AgentId> {
        match self {
            Stage::Evaluate => None,
            Stage::Srt(agent) | Stage::Prt(agent) | Stage::Patch { agent, .. } => Some(agent),
        }
    }
}
