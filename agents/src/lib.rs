//! The agents: rule-based implementations of planner, designer and evaluator (the offline
//! default), model-backed ones (`vlm`), the `noisy` designer used by ablations, the `grid-search`
//! designer of the Holodeck-shaped baseline, and an example of a role the paper lacks.
//!
//! Agents implement the role traits of `disco-core` and may use the tools (`disco-tools`) and the
//! model client (`disco-llm`); they know nothing of actors or of agent graphs.
#![deny(missing_docs)]

pub mod arrangement;
pub mod clearance;
#[cfg(test)]
mod fixtures;
pub mod grid_search;
pub mod hanging;
pub mod hints;
pub mod kinship;
pub mod knowledge;
pub mod noisy;
pub mod options;
pub mod requests;
pub mod rules;
pub mod uses;
pub mod vlm;
