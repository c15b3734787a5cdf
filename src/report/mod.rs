//! What a run leaves for people to look at: the steps drawn one by one ([`mod@steps`]) and a
//! self-contained HTML report ([`html`]).

pub mod html;
mod room;
pub mod steps;

pub use steps::{Step, steps, write_step_renders};
