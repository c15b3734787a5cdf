//! Reading an answer's body from a model server: chunk by chunk, capped, so a runaway or
//! hostile server costs a bounded amount of memory and its answer counts as unusable.

use super::{LlmError, cut, error_chain};

/// The longest answer body read from a model server; a longer one (a runaway or hostile server)
/// is an unusable answer, not a reason to run out of memory.
pub const MAX_BODY_BYTES: usize = 8 * 1024 * 1024;

/// Why a body could not be read.
pub(super) enum BodyError {
    /// The connection timed out while the body came (the runtime's to retry).
    Transport(reqwest::Error),
    /// The body cannot be used: cut short, or over the limit.
    Unusable(LlmError),
}

/// Reads an answer's body, at most [`MAX_BODY_BYTES`]: a body cut short or over the limit is an
/// unusable answer (the agents ask again), a timeout is the transport's.
pub(super) async fn read_answer(resp: reqwest::Response, url: &str) -> Result<String, BodyError> {
    match read_capped(resp, MAX_BODY_BYTES).await {
        Ok(text) => Ok(text),
        Err(Capped::Transport(e)) if e.is_timeout() => Err(BodyError::Transport(e)),
        Err(Capped::Transport(e)) => Err(BodyError::Unusable(LlmError::Malformed {
            url: url.into(),
            reason: format!("the answer was cut off: {}", error_chain(&e)),
            body: String::new(),
        })),
        Err(Capped::TooLarge(head)) => Err(BodyError::Unusable(LlmError::Malformed {
            url: url.into(),
            reason: format!(
                "the answer is over {} MiB; no chat completion is that long",
                MAX_BODY_BYTES / (1024 * 1024)
            ),
            body: cut(&head),
        })),
    }
}

/// Why a capped read stopped.
enum Capped {
    /// The connection failed or timed out while the body came.
    Transport(reqwest::Error),
    /// The body passed the limit; what had come so far.
    TooLarge(String),
}

/// Reads a response body of at most `limit` bytes, chunk by chunk, so an endless body costs
/// `limit` bytes of memory and no more.
async fn read_capped(mut resp: reqwest::Response, limit: usize) -> Result<String, Capped> {
    let mut body: Vec<u8> = Vec::new();
    while let Some(chunk) = resp.chunk().await.map_err(Capped::Transport)? {
        if body.len() + chunk.len() > limit {
            body.truncate(4096);
            return Err(Capped::TooLarge(
                String::from_utf8_lossy(&body).into_owned(),
            ));
        }
        body.extend_from_slice(&chunk);
    }
    Ok(String::from_utf8_lossy(&body).into_owned())
}
