//! The actor runtime: each role of a scene runs as its own ractor actor under a per-scene
//! supervisor; scenes run concurrently and share one bounded gateway per model server.
//!
//! ```no_run
//! # async fn demo() -> disco_core::Result<()> {
//! use std::sync::Arc;
//! use disco_core::SceneSpec;
//! use disco_runtime::{Runtime, config::GraphConfig, registry::Registry, trace::Trace};
//!
//! let runtime = Runtime::new(GraphConfig::load(None, &[])?, Registry::builtin())?;
//! let scene = SceneSpec::load("examples/scenes/bedroom.json".as_ref())?;
//! let layout = runtime.generate(scene, Arc::new(Trace::default())).await?;
//! println!("{} objects placed", layout.objects.len());
//! # Ok(()) }
//! ```
#![deny(missing_docs)]
// A stderr whose reader is gone must not panic: messages go through `disco_core::io::to_stderr`.
#![deny(clippy::print_stderr)]

pub mod batch;
pub mod config;
pub mod external;
pub mod registry;
pub mod shard;
pub mod simulated;
pub mod supervisor;
pub mod trace;

use std::sync::Arc;

use ractor::Actor;
use tokio::sync::oneshot;

pub use supervisor::{
    RoleActor, RoleMsg, SceneFailure, SceneRun, SceneSupervisor, SupervisorArgs, SupervisorMsg,
};

use crate::config::GraphConfig;
use crate::registry::Registry;
use crate::trace::Trace;
use disco_core::error::{Error, Result};
use disco_core::layout::Layout;
use disco_core::roles::RoleError;
use disco_core::scene::SceneSpec;
use disco_llm::Gateways;

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
        let gateways = Gateways::for_models(&graph.models);
        for (id, agent) in graph.agents() {
            registry
                .build(&graph, &gateways, id, agent.config().impl_name())
                .map_err(|e| e.in_graph(&graph))?;
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

    /// Checks once, before any scene runs, that every model server the graph uses answers and
    /// accepts its key: a wrong URL or key is one clear error, not a stack of retries. With a
    /// record/replay folder (`run.cache`) an unreachable server is only a warning, so recorded
    /// runs replay offline.
    pub async fn preflight(&self) -> Result<()> {
        let mut models: Vec<&str> = self
            .graph
            .agents()
            .values()
            .filter_map(|a| a.config().model.as_ref().map(|m| m.get_ref().as_str()))
            .collect();
        models.sort_unstable();
        models.dedup();
        for name in models {
            if !self.graph.models.contains_key(name) {
                continue;
            }
            let client = self.graph.model_client(name, None, None)?;
            if let Err(e) = client.preflight().await {
                if self.graph.run.cache.is_some() {
                    tracing::warn!("model {name}: {e}; replaying recorded answers only");
                } else {
                    return Err(Error::Model {
                        name: name.to_string(),
                        reason: format!(
                            "{e} (is the server running? for the local one: `export DISCO_LOCAL_LLM_URL=$(scripts/local-llm start)`)"
                        ),
                    });
                }
            }
        }
        Ok(())
    }

    /// The shared model gateways.
    pub fn gateways(&self) -> &Gateways {
        &self.gateways
    }

    /// Furnishes one scene. Events go to `trace`. A failing scene returns an error naming it and
    /// the reason; it never affects other scenes.
    pub async fn generate(&self, scene: SceneSpec, trace: Arc<Trace>) -> Result<Layout> {
        let id = scene.id.clone();
        let digest = scene.digest();
        let (done, result) = oneshot::channel();
        let args = SupervisorArgs {
            run: SceneRun {
                scene: Arc::new(scene),
                graph: Arc::clone(&self.graph),
                registry: Arc::clone(&self.registry),
                gateways: Arc::clone(&self.gateways),
                trace,
            },
            done,
        };
        let scene_err = |failure: SceneFailure| Error::Scene {
            id: id.clone(),
            failure: Box::new(failure),
        };
        Actor::spawn(None, SceneSupervisor, args)
            .await
            .map_err(|e| scene_err(SceneFailure::NotStarted(e.to_string())))?;
        match result.await {
            Ok(Ok(mut layout)) => {
                layout.stats.scene_sha256 = Some(digest);
                Ok(layout)
            }
            Ok(Err(failure)) => Err(match failure.model_server() {
                Some(RoleError::ModelServer { model, reason }) => Error::Model {
                    name: model.clone(),
                    reason: format!("scene {id}: {reason}"),
                },
                _ => scene_err(failure),
            }),
            Err(_) => Err(scene_err(SceneFailure::NoAnswer)),
        }
    }
}

#[cfg(test)]
mod tests;
