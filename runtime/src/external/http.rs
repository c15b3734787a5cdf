//! `impl = "http"`: an agent served over HTTP. Each request is POSTed as a JSON body to the
//! agent's `url`; the response body is the reply.

use std::time::Duration;

use async_trait::async_trait;

use super::Transport;
use disco_core::roles::RoleError;

/// The longest piece of an error page quoted in a message.
const QUOTED: usize = 200;

/// A role served by an HTTP endpoint.
pub struct HttpTransport {
    url: String,
    deadline: Duration,
    client: reqwest::Client,
}

impl HttpTransport {
    /// A transport that POSTs to `url` and waits at most `deadline` for each reply.
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
            client,
        })
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
        let body = response.text().await.map_err(|e| match e.is_timeout() {
            true => RoleError::Deadline(self.deadline.as_secs_f64()),
            false => RoleError::Failed(format!("POST {}: reading the reply: {e}", self.url)),
        })?;
        if !status.is_success() {
            let quoted: String = body.chars().take(QUOTED).collect();
            return Err(RoleError::Failed(format!(
                "POST {} answered {status}: {quoted}",
                self.url
            )));
        }
        Ok(body)
    }

    async fn discard(&self) {}
}
