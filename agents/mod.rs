//! The agents: rule-based implementations of planner, designer and evaluator (the offline
//! default), model-backed ones (`vlm`), the `noisy` designer used by ablations, and an example of a role the paper lacks.

pub mod clearance;
pub mod hints;
pub mod knowledge;
pub mod noisy;
pub mod rules;
pub mod vlm;
