//! # disco-layout
//!
//! Furnished rooms from a sentence and a list of 3D assets: every object placed and turned so the
//! room makes sense and is physically sound. An implementation of DisCo-Layout (ICLR 2026).
//!
//! The crate is one library with a thin `disco` binary. Its modules, from the ground up:
//!
//! - [`scene`], [`plan`], [`layout`]: the input spec, the planner's constraints and the output layout;
//! - [`geometry`]: oriented footprints, overlap, containment, walls (parry2d + glam);
//! - [`relations`]: one geometric predicate per word of the plan vocabulary;
//! - [`tools`]: the refinement tools, starting with the Physical Refinement Tool ([`PhysicalRefiner`]);
//! - [`metrics`]: Col, OOB, constraint satisfaction, reach, dropped, displacement;
//! - [`render`]: top-down PNGs for people and vision models;
//! - [`roles`]: the five roles as plain async traits; [`agents`] and [`tools`] implement them;
//! - [`config`], [`registry`]: TOML agent graphs and implementations by name;
//! - [`runtime`]: roles as ractor actors under a per-scene supervisor; [`gateway`], [`trace`];
//! - [`llm`]: the OpenAI-compatible chat client, prompts, record/replay, lenient JSON reading;
//! - [`export`]: the layout as a binary glTF for Blender, three.js and game engines;
//! - [`report`]: step-by-step renders, contact sheets and self-contained HTML reports;
//! - [`mod@bench`]: the benchmark's tables, suites of methods and speed figures;
//! - [`io`]: JSON reading with field-level errors and atomic writes.
//!
//! Generating a room from Rust (the whole program is `examples/furnish.rs`):
//!
//! ```no_run
//! # async fn demo() -> anyhow::Result<()> {
//! use std::sync::Arc;
//! use disco_layout::{Runtime, SceneSpec, config::GraphConfig, registry::Registry, trace::Trace};
//!
//! let scene = SceneSpec::load("examples/scenes/bedroom.json".as_ref())?;
//! let runtime = Runtime::new(GraphConfig::load(None, &[])?, Registry::builtin())?;
//! let layout = runtime.generate(scene, Arc::new(Trace::default())).await?;
//! let m = disco_layout::metrics::measure(&layout);
//! println!("{} placed, {:.1}% of constraints met", m.placed, m.constraint_pct);
//! # Ok(()) }
//! ```
#![deny(missing_docs)]

#[path = "../agents/mod.rs"]
pub mod agents;
pub mod bench;
pub mod config;
pub mod error;
pub mod export;
pub mod gateway;
pub mod geometry;
pub mod io;
pub mod judge;
pub mod layout;
pub mod llm;
pub mod metrics;
pub mod plan;
pub mod refine;
pub mod registry;
pub mod relations;
pub mod render;
pub mod report;
pub mod roles;
pub mod runtime;
pub mod scene;
pub mod synth;
#[path = "../tools/mod.rs"]
pub mod tools;
pub mod trace;

pub use error::{Error, Result};
pub use geometry::{Footprint, Wall};
pub use layout::{Dropped, Layout, PlacedObject, Stats};
pub use metrics::Metrics;
pub use plan::{ObjectConstraints, Plan, Relation, RelationSpec};
pub use runtime::Runtime;
pub use scene::{Asset, Room, SceneSpec};
pub use tools::prt::{PhysicalRefiner, PrtConfig, Refined};
