//! The actor runtime: each role of a scene runs as its own ractor actor under a per-scene
//! supervisor; scenes run concurrently and share one bounded gateway per model server.
//!
//! ```no_run
//! # async fn demo() -> disco_layout::Result<()> {
//! use std::sync::Arc;
//! use disco_layout::{SceneSpec, config::GraphConfig, registry::Registry, runtime::Runtime, trace::Trace};
//!
//! let runtime = Runtime::new(GraphConfig::load(None, &[])?, Registry::builtin())?;
//! let scene = SceneSpec::load("examples/scenes/bedroom.json".as_ref())?;
//! let layout = runtime.generate(scene, Arc::new(Trace::default())).await?;
//! println!("{} objects placed", layout.objects.len());
//! # Ok(()) }
//! ```

mod actors;
pub mod batch;
pub mod messages;
pub mod scene_loop;

use std::sync::Arc;

use ractor::Actor;
use tokio::sync::oneshot;

pub use actors::{RoleActor, RoleMsg, SceneSupervisor, SupervisorArgs, SupervisorMsg};

use crate::config::GraphConfig;
use crate::error::{Error, Result};
use crate::gateway::Gateways;
use crate::layout::Layout;
use crate::registry::Registry;
use crate::scene::SceneSpec;
use crate::trace::Trace;

/// A configured runtime: the agent graph, the implementations and the shared model gateways.
/// Cheap to share; every [`generate`](Runtime::generate) call runs one scene under its own
/// supervisor.
#[derive(Clone)]
pub struct Runtime {
    graph: Arc<GraphConfig>,
    registry: Arc<Registry>,
    gateways: Arc<Gateways>,
}

impl Runtime {
    /// Checks the graph against the registry (every implementation named exists and can be
    /// built) and sets up the gateways.
    pub fn new(graph: GraphConfig, registry: Registry) -> Result<Self> {
        registry.check(&graph)?;
        let gateways = Gateways::for_graph(&graph);
        for (name, agent) in &graph.agents {
            registry.build(&graph, &gateways, name, agent.impl_name())?;
        }
        Ok(Runtime {
            graph: Arc::new(graph),
            registry: Arc::new(registry),
            gateways: Arc::new(gateways),
        })
    }

    /// The agent graph.
    pub fn graph(&self) -> &GraphConfig {
        &self.graph
    }

    /// The shared model gateways.
    pub fn gateways(&self) -> &Gateways {
        &self.gateways
    }

    /// Furnishes one scene. Events go to `trace`. A failing scene returns an error naming it and
    /// the reason; it never affects other scenes.
    pub async fn generate(&self, scene: SceneSpec, trace: Arc<Trace>) -> Result<Layout> {
        let id = scene.id.clone();
        let (done, result) = oneshot::channel();
        let args = SupervisorArgs {
            scene: Arc::new(scene),
            graph: Arc::clone(&self.graph),
            registry: Arc::clone(&self.registry),
            gateways: Arc::clone(&self.gateways),
            trace,
            done,
        };
        let scene_err = |reason: String| Error::Scene {
            id: id.clone(),
            reason,
        };
        Actor::spawn(None, SceneSupervisor, args)
            .await
            .map_err(|e| scene_err(format!("could not start its supervisor: {e}")))?;
        match result.await {
            Ok(Ok(layout)) => Ok(layout),
            Ok(Err(failure)) => Err(scene_err(failure.0)),
            Err(_) => Err(scene_err("its supervisor stopped without an answer".into())),
        }
    }
}

#[cfg(test)]
mod tests;
