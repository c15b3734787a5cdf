//! # disco-core
//!
//! The ground floor of disco-layout: what a room, a furniture list, a plan and a layout are, and
//! everything that can be said about them without an agent, a model or an actor.
//!
//! - [`scene`], [`plan`], [`layout`]: the input spec, the planner's constraints and the output;
//! - [`room`]: the floor outline (rectangle or polygon), its walls, doors and windows, and the
//!   zones they keep clear;
//! - [`geometry`]: oriented footprints, overlap, containment, walls (parry2d + glam);
//! - [`relations`]: one geometric predicate per word of the plan vocabulary;
//! - [`placement`]: poses that satisfy a relation (shared by the rule designer and the SRT);
//! - [`metrics`]: Col, OOB, constraint satisfaction, reach, dropped, displacement;
//! - [`render`]: top-down PNGs for people and vision models;
//! - [`roles`]: the five roles of the method as plain async traits, with their requests and
//!   answers: the contract between the agents and tools (which implement it) and the runtime
//!   (which calls it);
//! - [`units`]: size limits, the floor-covering height, angles, numbers as people read them;
//! - [`io`], [`error`]: JSON reading with field-level errors, atomic writes, the error type;
//! - [`synth`]: small synthetic scenes for tests, examples and benchmarks.
//!
//! This crate depends on no other crate of the workspace.
#![deny(missing_docs)]

pub mod error;
pub mod geometry;
pub mod geometry3d;
pub mod io;
pub mod layout;
pub mod metrics;
pub mod placement;
pub mod plan;
pub mod polygon;
pub mod relations;
pub mod render;
pub mod roles;
pub mod room;
pub mod scene;
pub mod synth;
pub mod targets;
pub mod units;

pub use error::{Error, Result};
pub use geometry::{Footprint, Wall};
pub use layout::{Dropped, Layout, PlacedObject, Stats};
pub use metrics::Metrics;
pub use plan::{ObjectConstraints, Plan, Relation, RelationSpec};
pub use roles::{Move, Refined};
pub use scene::{Asset, Room, SceneSpec};
