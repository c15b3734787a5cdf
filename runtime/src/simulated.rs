//! A model server simulated by latency alone: a benchmark instrument for what the runtime costs
//! around real model time (`disco perf`, the gateway tests), with no server and no network.

use std::sync::Arc;
use std::time::Duration;

use async_trait::async_trait;
use disco_agents::rules::RuleDesigner;
use disco_core::Result;
use disco_core::layout::PlacedObject;
use disco_core::roles::{DesignRequest, Designer, RoleImpl, RoleKind, RoleResult, Usage};
use disco_llm::ModelGateway;

use crate::Runtime;
use crate::config::GraphConfig;
use crate::registry::Registry;

/// A designer standing in for a model: it waits for the gateway, sleeps a fixed latency, counts
/// one call of 100 prompt and 20 completion tokens, and answers with the rules designer's poses.
/// Throughput runs (`disco perf`, the runtime's tests) use it to see what the runtime adds
/// around real model time.
pub struct SimulatedModelDesigner {
    /// The gateway of the fake model server.
    pub gateway: Arc<ModelGateway>,
    /// The latency of one call.
    pub latency: Duration,
}

#[async_trait]
impl Designer for SimulatedModelDesigner {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        let _permit = self.gateway.acquire().await;
        tokio::time::sleep(self.latency).await;
        let mut out = RuleDesigner::new().design(req).await?;
        out.usage = Usage {
            calls: 1,
            prompt_tokens: 100,
            completion_tokens: 20,
        };
        Ok(out)
    }
}

/// A runtime whose designer is a [`SimulatedModelDesigner`] behind a gateway of `in_flight`.
pub fn simulated_model_runtime(latency: Duration, in_flight: usize) -> Result<Runtime> {
    let mut registry = Registry::builtin();
    registry.register(RoleKind::Designer, "simulated-model", move |ctx| {
        let gateway = ctx.gateway.clone().ok_or("needs a model")?;
        Ok(RoleImpl::Designer(Arc::new(SimulatedModelDesigner {
            gateway,
            latency,
        })))
    });
    let sets = [
        "agents.designer.impl=simulated-model".to_string(),
        "agents.designer.model=fake".to_string(),
        format!("models.fake.max_in_flight={in_flight}"),
    ];
    Runtime::new(GraphConfig::load(None, &sets)?, registry)
}
