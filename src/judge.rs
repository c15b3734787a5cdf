//! The VLM judge wired to an agent graph: which model judges, and the call itself.

use std::sync::Arc;

use crate::agents::vlm::VlmBase;
use crate::agents::vlm::judge::{Scores, judge};
use crate::config::{AgentId, GraphConfig};
use crate::error::{Error, Result};
use crate::gateway::Gateways;
use crate::layout::Layout;
use crate::llm::{Cache, Prompts};
use crate::render::{RenderOptions, render_png};
use crate::scene::SceneSpec;

/// The model that judges: `[judge]`'s, else the designer's, else the graph's only model.
pub fn judge_model(graph: &GraphConfig) -> Option<String> {
    let of = |agent: &AgentId| {
        graph
            .agent(agent)
            .and_then(|a| a.config().model.as_ref())
            .map(|m| m.get_ref().clone())
    };
    graph
        .judge
        .model
        .as_ref()
        .map(|m| m.get_ref().clone())
        .or_else(|| of(&AgentId::DESIGNER))
        .or_else(|| (graph.models.len() == 1).then(|| graph.models.keys().next().cloned())?)
}

/// Scores `layout` with the graph's judge model (see [`judge_model`]), with the prompt of
/// `[judge]` if it names one.
pub async fn judge_layout(
    graph: &GraphConfig,
    scene: &SceneSpec,
    layout: &Layout,
) -> Result<Scores> {
    let name = judge_model(graph).ok_or_else(|| {
        Error::invalid(
            &graph.source,
            "judge",
            "the judge needs a model: add [judge] with model = \"NAME\" (a [models.NAME] section), or use a preset such as --config config/local-llm.toml",
        )
    })?;
    let model_err = |reason: String| Error::Model {
        name: name.clone(),
        reason,
    };
    let cache = match &graph.run.cache {
        Some(dir) => Some(Arc::new(Cache::open(std::path::Path::new(dir))?)),
        None => None,
    };
    let gateways = Gateways::for_models(&graph.models);
    let client = graph.model_client(&name, gateways.get(&name), cache)?;
    if graph.run.cache.is_none() {
        client
            .preflight()
            .await
            .map_err(|e| model_err(e.to_string()))?;
    }
    let mut prompts = Prompts::default();
    if let Some(p) = &graph.judge.prompt {
        prompts = prompts.with_file("judge", &graph.resolve_path(p.get_ref()))?;
    }
    let png = render_png(layout, &RenderOptions::default())?;
    let base = VlmBase { client, prompts };
    judge(&base, scene, layout, Some(Arc::new(png)))
        .await
        .map_err(|e| model_err(e.to_string()))
}
