//! The refinement tools the evaluator can call: the Physical Refinement Tool (grid matching).

pub mod prt;

pub use prt::{Move, PhysicalRefiner, PrtConfig, Refined};
pub mod srt;
