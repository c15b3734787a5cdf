//! # disco-tools
//!
//! The refinement tools the evaluator calls: the Physical Refinement Tool ([`prt`], grid matching:
//! wall alignment, out-of-bounds, collisions), the rule-based Semantic Refinement Tool ([`srt`]),
//! and [`refine`], which completes and repairs a layout made elsewhere; [`formation`] computes
//! group layouts with counts (rows, arcs, rings, pods, L and U workstations, a pair on each side)
//! exactly, for the designers and the plan.
//!
//! Tools depend on `disco-core` only; they never import an agent.
#![deny(missing_docs)]

pub mod formation;
pub mod prt;
pub mod refine;
pub mod srt;

#[cfg(test)]
mod fuzz_tests;

pub use disco_core::roles::{Move, Refined};
pub use prt::{PhysicalRefiner, PrtConfig};
