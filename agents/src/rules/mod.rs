//! The offline rule-based agents: good enough to be the default, and the baseline every model run
//! is compared with.

mod designer;
mod evaluator;
mod mounting;
mod planner;
mod seating;

pub use designer::RuleDesigner;
pub use evaluator::RuleEvaluator;
pub use planner::RulePlanner;
