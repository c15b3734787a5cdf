//! The settings of one model server, as written in an agent graph's `[models.NAME]` section.

use serde::Deserialize;

/// A model server shared by every scene of the process.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelConfig {
    /// Base URL of an OpenAI-compatible API.
    #[serde(default)]
    pub base_url: Option<String>,
    /// Model name sent with each request.
    #[serde(default)]
    pub model: Option<String>,
    /// Environment variable holding the API key.
    #[serde(default)]
    pub api_key_env: Option<String>,
    /// Requests in flight at once, across all scenes.
    #[serde(default = "default_in_flight")]
    pub max_in_flight: usize,
    /// Requests started per second at most, across all scenes.
    #[serde(default)]
    pub rate_per_s: Option<f64>,
    /// Whether the model sees images.
    #[serde(default = "default_true")]
    pub vision: bool,
    /// Implementation-specific settings (latency of a fake server, sampling, ...).
    #[serde(default)]
    pub options: toml::Table,
}

fn default_in_flight() -> usize {
    4
}
fn default_true() -> bool {
    true
}
