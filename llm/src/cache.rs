//! Record and replay: each request's answer stored under a hash of the request, so a run can be
//! reproduced, and re-run without the server.

use std::path::{Path, PathBuf};

use serde_json::{Value, json};
use sha2::{Digest, Sha256};

/// A folder of recorded answers, one JSON file per distinct request.
#[derive(Debug)]
pub struct Cache {
    dir: PathBuf,
}

impl Cache {
    /// A cache in `dir` (created when missing).
    pub fn open(dir: &Path) -> disco_core::Result<Self> {
        std::fs::create_dir_all(dir).map_err(|source| disco_core::Error::Write {
            path: dir.to_path_buf(),
            source,
        })?;
        Ok(Cache {
            dir: dir.to_path_buf(),
        })
    }

    /// The key of a request body: SHA-256 of its JSON text (object keys are sorted by
    /// serde_json, so equal requests have equal keys).
    pub fn key(body: &Value) -> String {
        let digest = Sha256::digest(body.to_string().as_bytes());
        digest.iter().map(|b| format!("{b:02x}")).collect()
    }

    fn path(&self, body: &Value) -> PathBuf {
        self.dir.join(format!("{}.json", Self::key(body)))
    }

    /// The recorded answer to `body`, if any.
    pub fn get(&self, body: &Value) -> Option<Value> {
        let text = std::fs::read_to_string(self.path(body)).ok()?;
        let v: Value = serde_json::from_str(&text).ok()?;
        v.get("response").cloned()
    }

    /// Records `response` as the answer to `body` (atomically; a failure only logs).
    pub fn put(&self, body: &Value, response: &Value) {
        let entry = json!({"request": body, "response": response});
        if let Err(e) = disco_core::io::write_json(&self.path(body), &entry) {
            tracing::warn!("could not record a model answer: {e}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_and_replays_by_request() {
        let dir = tempfile::tempdir().unwrap();
        let c = Cache::open(dir.path()).unwrap();
        let a = json!({"model": "m", "messages": [{"role": "user", "content": "hi"}]});
        let b = json!({"model": "m", "messages": [{"role": "user", "content": "ho"}]});
        assert!(c.get(&a).is_none());
        c.put(&a, &json!({"choices": []}));
        assert_eq!(c.get(&a), Some(json!({"choices": []})));
        assert!(c.get(&b).is_none());
        assert_ne!(Cache::key(&a), Cache::key(&b));
    }
}
