//! Agents and round stages of a graph, as types: the scene loop names agents by [`AgentId`] and
//! walks a round as [`Stage`]s, never by bare strings.

use std::fmt;

use super::PipelineConfig;

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

/// One stage of an evaluate-and-refine round, as `[pipeline] round` lists them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Stage {
    /// The evaluator answers the group's questions (always first).
    Evaluate,
    /// An agent of role srt, prt or patch.
    Agent(AgentId),
}

impl PipelineConfig {
    /// The round's stages, typed (the graph's check has made sure each names a fitting agent).
    pub fn stages(&self) -> Vec<Stage> {
        self.round
            .iter()
            .map(|s| match s.as_str() {
                "evaluate" => Stage::Evaluate,
                name => Stage::Agent(AgentId::new(name)),
            })
            .collect()
    }
}
