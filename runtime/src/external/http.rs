//! `impl = "http"`: an agent served over HTTP. Each request is POSTed as a JSON body to the
//! agent's `url`; the response body is the reply, read chunk by chunk up to `max_reply_bytes`
//! (a longer one, or one that announces itself longer, is an unusable answer).

use std::time::Duration;

use async_trait::async_trait;

use super::Transport;
use super::capped::{self, MAX_REPLY_BYTES};
use disco_core::roles::RoleError;

/// The longest piece of an error page quoted in a message.
const QUOTED: usize = 200;

/// A role served by an HTTP endpoint.
pub struct HttpTransport {
    url: String,
    deadline: Duration,
    max_reply: usize,
    client: reqwest::Client,
}

/// Why a body could not be read.
enum BodyError {
    /// The connection failed or timed out while the body came.
    Transport(reqwest::Error),
    /// The body passed the cap.
    TooLong,
}

impl HttpTransport {
    /// A transport that POSTs to `url` and waits at most `deadline` for each reply, of at most
    /// [`MAX_REPLY_BYTES`].
    pub fn new(url: &str, deadline: Duration) -> Result<Self, String> {
        if !(url.starts_with("http://") || url.starts_with("https://")) {
            return Err(format!(
                "impl \"http\" needs `url = \"http://...\"`, got {url:?}"
            ));
        }
        disco_llm::install_tls_provider();
        let client = reqwest::Client::builder()
            .timeout(deadline)
            .build()
            .map_err(|e| format!("cannot set up an HTTP client: {e}"))?;
        Ok(HttpTransport {
            url: url.to_string(),
            deadline,
            max_reply: MAX_REPLY_BYTES,
            client,
        })
    }

    /// The same transport with replies capped at `bytes` (the agent's `max_reply_bytes`).
    pub fn with_max_reply(mut self, bytes: usize) -> Self {
        self.max_reply = bytes.max(1);
        self
    }

    /// Reads the body, at most `max_reply` bytes, chunk by chunk.
    async fn body(&self, mut response: reqwest::Response) -> Result<Vec<u8>, BodyError> {
        if response
            .content_length()
            .is_some_and(|n| n > self.max_reply as u64)
        {
            return Err(BodyError::TooLong);
        }
        let mut body = Vec::new();
        while let Some(chunk) = response.chunk().await.map_err(BodyError::Transport)? {
            if body.len() + chunk.len() > self.max_reply {
                return Err(BodyError::TooLong);
            }
            body.extend_from_slice(&chunk);
        }
        Ok(body)
    }
}

#[async_trait]
impl Transport for HttpTransport {
    async fn exchange(&self, line: String) -> Result<String, RoleError> {
        let sent = self
            .client
            .post(&self.url)
            .header(reqwest::header::CONTENT_TYPE, "application/json")
            .body(line)
            .send()
            .await;
        let response = match sent {
            Ok(r) => r,
            Err(e) if e.is_timeout() => {
                return Err(RoleError::Deadline(self.deadline.as_secs_f64()));
            }
            Err(e) => return Err(RoleError::Failed(format!("POST {}: {e}", self.url))),
        };
        let status = response.status();
        let body = self.body(response).await.map_err(|e| match e {
            BodyError::Transport(e) if e.is_timeout() => {
                RoleError::Deadline(self.deadline.as_secs_f64())
            }
            BodyError::Transport(e) => {
                RoleError::Failed(format!("POST {}: reading the reply: {e}", self.url))
            }
            BodyError::TooLong => RoleError::Failed(format!(
                "POST {}: {}",
                self.url,
                capped::too_long(self.max_reply)
            )),
        })?;
        if !status.is_success() {
            let quoted: String = String::from_utf8_lossy(&body)
                .chars()
                .take(QUOTED)
                .collect();
            return Err(RoleError::Failed(format!(
                "POST {} answered {status}: {quoted}",
                self.url
            )));
        }
        capped::utf8(body).map_err(|why| RoleError::Failed(format!("POST {}: {why}", self.url)))
    }

    async fn discard(&self) {}
}
