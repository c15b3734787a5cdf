//! A chat-completions client for any OpenAI-compatible server (OpenAI, vLLM, Ollama, llama.cpp,
//! LM Studio): text and image parts, JSON-schema structured output, retries that honour
//! `Retry-After`, a bounded gateway per server, and lenient reading of what servers send back.

use std::sync::Arc;
use std::time::{Duration, Instant};

use backon::{BackoffBuilder, ExponentialBuilder};
use base64::Engine;

use serde_json::{Value, json};

use super::cache::Cache;
use crate::ModelConfig;
use crate::gateway::ModelGateway;
pub use body::MAX_BODY_BYTES;
use body::{BodyError, read_answer};
pub use disco_core::roles::CallRecord;

/// What went wrong talking to a model server. Each variant keeps what the server said.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LlmError {
    /// The server answered with an error status.
    #[error("{url} answered HTTP {status}: {body}")]
    Status {
        /// The endpoint.
        url: String,
        /// HTTP status.
        status: u16,
        /// The raw body (cut to 2000 characters).
        body: String,
    },
    /// No connection, or the connection broke.
    #[error("cannot reach {url}: {reason}")]
    Connect {
        /// The endpoint.
        url: String,
        /// Why.
        reason: String,
    },
    /// No answer within the timeout.
    #[error("{url} did not answer within {seconds:.0} s")]
    Timeout {
        /// The endpoint.
        url: String,
        /// The timeout.
        seconds: f64,
    },
    /// The body is not a chat completion we can read.
    #[error("unreadable answer from {url}: {reason}; body: {body}")]
    Malformed {
        /// The endpoint.
        url: String,
        /// What is wrong with it.
        reason: String,
        /// The raw body (cut to 2000 characters).
        body: String,
    },
    /// The configuration cannot work (no key, no base URL).
    #[error("{0}")]
    Config(String),
}

impl LlmError {
    /// Whether trying again may help (429, 5xx, broken connections, timeouts).
    pub fn is_transient(&self) -> bool {
        match self {
            LlmError::Status { status, .. } => *status == 429 || *status >= 500,
            LlmError::Connect { .. } | LlmError::Timeout { .. } => true,
            LlmError::Malformed { .. } | LlmError::Config(_) => false,
        }
    }
}

/// A JSON schema the answer must follow.
#[derive(Debug, Clone, PartialEq)]
pub struct Schema {
    /// A short name (letters, digits, underscores).
    pub name: String,
    /// The schema.
    pub schema: Value,
}

/// One message of a conversation.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    /// `system`, `user` or `assistant`.
    pub role: String,
    /// The text.
    pub text: String,
    /// A PNG shown with the text (user messages, vision models only).
    pub image_png: Option<Arc<Vec<u8>>>,
}

impl Message {
    /// A message with text only.
    pub fn text(role: &str, text: impl Into<String>) -> Self {
        Message {
            role: role.into(),
            text: text.into(),
            image_png: None,
        }
    }
}

/// A successful answer.
#[derive(Debug, Clone, PartialEq)]
pub struct ChatReply {
    /// The assistant's text.
    pub content: String,
    /// The call's record.
    pub record: CallRecord,
}

/// Sampling and transport settings, from a model's `options` table.
#[derive(Debug, Clone, PartialEq)]
pub struct ClientSettings {
    /// Send `strict: true` with the JSON schema (servers that support it enforce it).
    pub strict_schema: bool,
    /// Send the schema at all (`response_format`); off for servers that reject it.
    pub structured_output: bool,
    /// Sampling temperature.
    pub temperature: f64,
    /// Sampling seed, for servers that honour one.
    pub seed: Option<u64>,
    /// Most tokens per answer.
    pub max_tokens: u32,
    /// Timeout of one HTTP attempt.
    pub timeout: Duration,
    /// Retries after a transient failure.
    pub retries: u32,
    /// First retry delay (doubling), unless the server says `Retry-After`.
    pub backoff: Duration,
    /// Longest `Retry-After` honoured.
    pub max_retry_after: Duration,
    /// Server-specific request fields merged into every request body (e.g. llama.cpp's
    /// `repeat_penalty`, OpenAI's `frequency_penalty`).
    pub extra: serde_json::Map<String, Value>,
}

impl Default for ClientSettings {
    fn default() -> Self {
        ClientSettings {
            strict_schema: true,
            structured_output: true,
            temperature: 0.2,
            seed: Some(7),
            max_tokens: 1024,
            timeout: Duration::from_secs(120),
            retries: 3,
            backoff: Duration::from_millis(500),
            max_retry_after: Duration::from_secs(60),
            extra: serde_json::Map::new(),
        }
    }
}

impl ClientSettings {
    /// Reads the settings from a model's `options` table; unknown keys are an error.
    pub fn from_options(options: &toml::Table) -> Result<Self, String> {
        let mut s = ClientSettings::default();
        for (key, value) in options {
            let float = || {
                value
                    .as_float()
                    .or_else(|| value.as_integer().map(|i| i as f64))
                    .filter(|v| v.is_finite() && *v >= 0.0)
                    .ok_or_else(|| format!("options.{key} must be a non-negative number"))
            };
            let boolean = || {
                value
                    .as_bool()
                    .ok_or_else(|| format!("options.{key} must be true or false"))
            };
            match key.as_str() {
                "strict_schema" => s.strict_schema = boolean()?,
                "structured_output" => s.structured_output = boolean()?,
                "temperature" => s.temperature = float()?,
                "seed" => s.seed = Some(float()? as u64),
                "max_tokens" => s.max_tokens = float()?.max(1.0) as u32,
                "timeout_s" => s.timeout = Duration::from_secs_f64(float()?.max(0.001)),
                "retries" => s.retries = float()? as u32,
                "backoff_ms" => s.backoff = Duration::from_millis(float()? as u64),
                "max_retry_after_s" => s.max_retry_after = Duration::from_secs_f64(float()?),
                "extra" => {
                    let table = value
                        .as_table()
                        .ok_or("options.extra must be a table of request fields")?;
                    let json = serde_json::to_value(table).map_err(|e| e.to_string())?;
                    s.extra = json.as_object().cloned().unwrap_or_default();
                }
                other => {
                    return Err(format!(
                        "unknown model option {other:?}; known: strict_schema, structured_output, temperature, seed, max_tokens, timeout_s, retries, backoff_ms, max_retry_after_s, extra"
                    ));
                }
            }
        }
        Ok(s)
    }
}

/// A client of one model on one server.
#[derive(Debug, Clone)]
pub struct ChatClient {
    name: String,
    http: reqwest::Client,
    base_url: String,
    model: String,
    api_key: Option<String>,
    /// Whether the model sees images.
    pub vision: bool,
    settings: ClientSettings,
    gateway: Option<Arc<ModelGateway>>,
    cache: Option<Arc<Cache>>,
}

/// Expands `${VAR}` and `${VAR:-default}` in a config string from the environment.
pub fn expand_env(s: &str) -> String {
    let mut out = String::new();
    let mut rest = s;
    while let Some(start) = rest.find("${") {
        out.push_str(&rest[..start]);
        let Some(end) = rest[start..].find('}') else {
            out.push_str(&rest[start..]);
            return out;
        };
        let inner = &rest[start + 2..start + end];
        let (var, default) = match inner.split_once(":-") {
            Some((v, d)) => (v, d),
            None => (inner, ""),
        };
        match std::env::var(var) {
            Ok(v) if !v.is_empty() => out.push_str(&v),
            _ => out.push_str(default),
        }
        rest = &rest[start + end + 1..];
    }
    out.push_str(rest);
    out
}

/// Makes ring the process's TLS provider. reqwest is built without one of its own (see
/// Cargo.toml: aws-lc is a long C build), so call this before building any `reqwest::Client`.
/// A provider installed earlier, by a host application, is kept; calling it again does nothing.
pub fn install_tls_provider() {
    let _ = rustls::crypto::ring::default_provider().install_default();
}

impl ChatClient {
    /// The model's name in the graph (`[models.NAME]`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// A client for the model `name` of the graph. Fails when its key variable is unset or it
    /// has no base URL.
    pub fn from_config(
        name: &str,
        model: &ModelConfig,
        gateway: Option<Arc<ModelGateway>>,
        cache: Option<Arc<Cache>>,
    ) -> Result<Self, LlmError> {
        let base_url = model
            .base_url
            .as_deref()
            .map(expand_env)
            .filter(|u| !u.is_empty())
            .ok_or_else(|| LlmError::Config(format!("models.{name}: no base_url")))?;
        let api_key = match &model.api_key_env {
            Some(var) => match std::env::var(var) {
                Ok(k) if !k.trim().is_empty() => Some(k.trim().to_string()),
                _ => {
                    return Err(LlmError::Config(format!(
                        "models.{name}: the API key variable {var} is not set (export {var}=...)"
                    )));
                }
            },
            None => None,
        };
        let settings = ClientSettings::from_options(&model.options)
            .map_err(|e| LlmError::Config(format!("models.{name}: {e}")))?;
        install_tls_provider();
        Ok(ChatClient {
            name: name.to_string(),
            http: reqwest::Client::builder()
                .connect_timeout(Duration::from_secs(10))
                .build()
                .map_err(|e| LlmError::Config(e.to_string()))?,
            base_url: base_url.trim_end_matches('/').to_string(),
            model: model
                .model
                .as_deref()
                .map(expand_env)
                .unwrap_or_else(|| "default".into()),
            api_key,
            vision: model.vision,
            settings,
            gateway,
            cache,
        })
    }

    /// The server's base URL.
    pub fn base_url(&self) -> &str {
        &self.base_url
    }

    /// The settings in use.
    pub fn settings(&self) -> &ClientSettings {
        &self.settings
    }

    /// Checks once, quickly, that the server answers (`GET /models`) and accepts the key, so a
    /// wrong URL or key is one clear error at start instead of a stack of retries.
    pub async fn preflight(&self) -> Result<(), LlmError> {
        let url = format!("{}/models", self.base_url);
        let mut req = self.http.get(&url).timeout(Duration::from_secs(10));
        if let Some(k) = &self.api_key {
            req = req.bearer_auth(k);
        }
        match req.send().await {
            Err(e) => Err(LlmError::Connect {
                url,
                reason: error_chain(&e),
            }),
            Ok(r) if r.status() == 401 || r.status() == 403 => Err(LlmError::Status {
                url,
                status: r.status().as_u16(),
                body: cut(&r.text().await.unwrap_or_default()),
            }),
            // Some servers lack /models; any other answer means the server is there.
            Ok(_) => Ok(()),
        }
    }

    /// The request body for `messages`.
    pub fn body(&self, messages: &[Message], schema: Option<&Schema>) -> Value {
        let msgs: Vec<Value> = messages
            .iter()
            .map(|m| match (&m.image_png, self.vision) {
                (Some(png), true) => {
                    let data = base64::engine::general_purpose::STANDARD.encode(png.as_slice());
                    json!({"role": m.role, "content": [
                        {"type": "text", "text": m.text},
                        {"type": "image_url", "image_url": {"url": format!("data:image/png;base64,{data}")}}
                    ]})
                }
                _ => json!({"role": m.role, "content": m.text}),
            })
            .collect();
        let mut body = json!({
            "model": self.model,
            "messages": msgs,
            "temperature": self.settings.temperature,
            "max_tokens": self.settings.max_tokens,
        });
        if let Some(seed) = self.settings.seed {
            body["seed"] = json!(seed);
        }
        for (k, v) in &self.settings.extra {
            body[k.as_str()] = v.clone();
        }
        if let (Some(s), true) = (schema, self.settings.structured_output) {
            body["response_format"] = json!({
                "type": "json_schema",
                "json_schema": {"name": s.name, "strict": self.settings.strict_schema, "schema": s.schema}
            });
        }
        body
    }

    /// One chat completion, with retries on transient failures.
    pub async fn chat(
        &self,
        purpose: &str,
        messages: &[Message],
        schema: Option<&Schema>,
    ) -> Result<ChatReply, (LlmError, CallRecord)> {
        let body = self.body(messages, schema);
        let mut record = CallRecord {
            purpose: purpose.to_string(),
            ..Default::default()
        };
        if let Some(cache) = &self.cache
            && let Some(raw) = cache.get(&body)
        {
            record.cached = true;
            return reply_of("cache", &raw, record);
        }
        let url = format!("{}/chat/completions", self.base_url);
        let mut delays = ExponentialBuilder::default()
            .with_min_delay(self.settings.backoff)
            .with_max_delay(Duration::from_secs(30))
            .with_max_times(self.settings.retries as usize)
            .build();
        let t0 = Instant::now();
        loop {
            record.attempts += 1;
            let (result, retry_after) = self.attempt(&url, &body).await;
            match result {
                Ok(raw) => {
                    record.latency_ms = t0.elapsed().as_secs_f64() * 1000.0;
                    let reply = reply_of(&url, &raw, record);
                    if let Ok(r) = &reply {
                        if let Some(cache) = &self.cache {
                            cache.put(&body, &raw);
                        }
                        let (p, c) = (r.record.prompt_tokens, r.record.completion_tokens);
                        tracing::debug!(purpose, ms = r.record.latency_ms, p, c, "model call");
                    }
                    return reply;
                }
                Err(e) => {
                    let next = if e.is_transient() {
                        delays.next()
                    } else {
                        None
                    };
                    match next {
                        Some(delay) => {
                            let wait = retry_after
                                .map(|d| d.min(self.settings.max_retry_after))
                                .unwrap_or(delay);
                            tracing::info!(purpose, error = %e, wait_ms = wait.as_millis() as u64, "model call failed; retrying");
                            tokio::time::sleep(wait).await;
                        }
                        None => {
                            record.latency_ms = t0.elapsed().as_secs_f64() * 1000.0;
                            record.error = Some(e.to_string());
                            return Err((e, record));
                        }
                    }
                }
            }
        }
    }

    /// One HTTP attempt: the parsed JSON body, or an error and the server's `Retry-After`.
    async fn attempt(
        &self,
        url: &str,
        body: &Value,
    ) -> (Result<Value, LlmError>, Option<Duration>) {
        let _permit = match &self.gateway {
            Some(g) => Some(g.acquire().await),
            None => None,
        };
        let mut req = self
            .http
            .post(url)
            .json(body)
            .timeout(self.settings.timeout);
        if let Some(k) = &self.api_key {
            req = req.bearer_auth(k);
        }
        let transport = |e: reqwest::Error| {
            if e.is_timeout() {
                LlmError::Timeout {
                    url: url.into(),
                    seconds: self.settings.timeout.as_secs_f64(),
                }
            } else {
                LlmError::Connect {
                    url: url.into(),
                    reason: error_chain(&e),
                }
            }
        };
        let resp = match req.send().await {
            Ok(r) => r,
            Err(e) => return (Err(transport(e)), None),
        };
        let status = resp.status();
        let retry_after = resp
            .headers()
            .get(reqwest::header::RETRY_AFTER)
            .and_then(|v| v.to_str().ok())
            .and_then(|v| v.trim().parse::<f64>().ok())
            .filter(|s| s.is_finite() && *s >= 0.0)
            .map(Duration::from_secs_f64);
        let text = match read_answer(resp, url).await {
            Ok(t) => t,
            Err(BodyError::Transport(e)) => return (Err(transport(e)), None),
            Err(BodyError::Unusable(e)) => return (Err(e), None),
        };
        if !status.is_success() {
            return (
                Err(LlmError::Status {
                    url: url.into(),
                    status: status.as_u16(),
                    body: cut(&text),
                }),
                retry_after,
            );
        }
        match serde_json::from_str::<Value>(&text) {
            Ok(v) => (Ok(v), None),
            Err(e) => (
                Err(LlmError::Malformed {
                    url: url.into(),
                    reason: format!("not JSON ({e})"),
                    body: cut(&text),
                }),
                None,
            ),
        }
    }
}

/// The reply in `raw` (from `source`: a URL or the cache), or why it is unusable; the record
/// takes the token counts or the error.
#[allow(clippy::result_large_err)]
fn reply_of(
    source: &str,
    raw: &Value,
    mut record: CallRecord,
) -> Result<ChatReply, (LlmError, CallRecord)> {
    match read_completion(raw) {
        Ok((content, p, c)) => {
            record.prompt_tokens = p;
            record.completion_tokens = c;
            Ok(ChatReply { content, record })
        }
        Err(reason) => {
            let e = LlmError::Malformed {
                url: source.into(),
                reason,
                body: cut(&raw.to_string()),
            };
            record.error = Some(e.to_string());
            Err((e, record))
        }
    }
}

/// The text and token counts of a chat completion, read leniently: `content` as a string or as a
/// list of text parts, `reasoning_content` when `content` is empty, usage when present.
pub fn read_completion(raw: &Value) -> Result<(String, u64, u64), String> {
    if let Some(err) = raw.get("error") {
        return Err(format!("the server reported an error: {err}"));
    }
    let choices = raw
        .get("choices")
        .and_then(Value::as_array)
        .ok_or("no `choices` in the answer")?;
    let first = choices.first().ok_or("`choices` is empty")?;
    let message = first
        .get("message")
        .or_else(|| first.get("delta"))
        .ok_or("the first choice has no `message`")?;
    let text = match message.get("content") {
        Some(Value::String(s)) => s.clone(),
        Some(Value::Array(parts)) => parts
            .iter()
            .filter_map(|p| p.get("text").and_then(Value::as_str))
            .collect::<Vec<_>>()
            .join(""),
        _ => String::new(),
    };
    let text = if text.trim().is_empty() {
        message
            .get("reasoning_content")
            .and_then(Value::as_str)
            .unwrap_or_default()
            .to_string()
    } else {
        text
    };
    if text.trim().is_empty() {
        return Err("the answer's text is empty".into());
    }
    let usage = |k: &str| {
        raw.get("usage")
            .and_then(|u| u.get(k))
            .and_then(Value::as_u64)
            .unwrap_or(0)
    };
    Ok((text, usage("prompt_tokens"), usage("completion_tokens")))
}

fn cut(s: &str) -> String {
    const MAX: usize = 2000;
    if s.chars().count() <= MAX {
        s.to_string()
    } else {
        let head: String = s.chars().take(MAX).collect();
        format!("{head}... ({} characters in all)", s.chars().count())
    }
}

/// An error with its sources, e.g. `error sending request: connection refused`.
fn error_chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut cur = e.source();
    while let Some(c) = cur {
        let t = c.to_string();
        if !s.contains(&t) {
            s.push_str(": ");
            s.push_str(&t);
        }
        cur = c.source();
    }
    s
}

mod body;
#[cfg(test)]
mod tests;
