//! Test support for the model-backed agents: a local OpenAI-compatible server whose every answer
//! is a fixed text, and the agents' base pointed at it.

use std::sync::{Arc, Mutex};

use axum::Router;
use axum::routing::post;
use serde_json::{Value, json};

use super::VlmBase;
use disco_llm::{ChatClient, ModelConfig, Prompts};

/// A model server whose every answer is `content`: its URL, and every request body it was sent.
pub(crate) async fn model_answering(content: &'static str) -> (String, Arc<Mutex<Vec<Value>>>) {
    let seen: Arc<Mutex<Vec<Value>>> = Arc::default();
    let log = Arc::clone(&seen);
    let app = Router::new().route(
        "/v1/chat/completions",
        post(move |axum::Json(body): axum::Json<Value>| {
            log.lock().unwrap().push(body);
            async move {
                axum::Json(json!({
                    "choices": [{"index": 0, "message": {"role": "assistant", "content": content}}],
                    "usage": {"prompt_tokens": 10, "completion_tokens": 5}
                }))
            }
        }),
    );
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    tokio::spawn(async move { axum::serve(listener, app).await.unwrap() });
    (format!("http://{addr}/v1"), seen)
}

/// The agents' base (client and built-in prompts) for a model server at `url`, text only.
pub(crate) fn base(url: String) -> VlmBase {
    let model = ModelConfig {
        base_url: Some(url),
        model: Some("test".into()),
        api_key_env: None,
        max_in_flight: 1,
        rate_per_s: None,
        vision: false,
        options: toml::Table::new(),
    };
    VlmBase {
        client: ChatClient::from_config("test", &model, None, None).unwrap(),
        prompts: Prompts::default(),
    }
}
