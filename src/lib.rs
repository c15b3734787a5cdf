//! # disco-layout
//!
//! Furnished rooms from a sentence and a list of 3D assets: every object placed and turned so the
//! room makes sense and is physically sound. An implementation of DisCo-Layout (ICLR 2026).
//!
//! This crate is the top of a workspace of layered crates, each depending only on those below it
//! (see ARCHITECTURE.md): `disco-core` <- `disco-llm`, `disco-tools` <- `disco-agents` <-
//! `disco-runtime` <- this crate (outputs, benchmark, the `disco` binary). It re-exports every
//! layer under one name, so a user needs only `disco_layout`. From the ground up:
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
//! - [`commands`]: what the `disco` commands compute apart from printing, shared with the Python
//!   package;
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

// The layers below, re-exported under one roof.
pub use disco_agents as agents;
pub use disco_core::{
    error, geometry, geometry3d, io, layout, metrics, placement, plan, relations, render, roles,
    scene, synth,
};
pub use disco_llm as llm;
pub use disco_llm::gateway;
pub use disco_runtime::{batch, config, registry, supervisor, trace};
pub use disco_tools as tools;
pub use disco_tools::refine;

/// The actor runtime (the `disco-runtime` crate).
pub mod runtime {
    pub use disco_runtime::*;
}

// What this crate adds on top: outputs, the benchmark, the VLM judge.
pub mod bench;
pub mod commands;
pub mod export;
pub mod judge;
pub mod outputs;
pub mod report;

pub use disco_core::{
    Asset, Dropped, Error, Footprint, Layout, Metrics, ObjectConstraints, PlacedObject, Plan,
    Relation, RelationSpec, Result, Room, SceneSpec, Stats, Wall,
};
pub use disco_runtime::Runtime;
pub use disco_tools::{PhysicalRefiner, PrtConfig, Refined};
