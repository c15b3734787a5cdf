//! A real local model server (llama.cpp serving SmolLM2-135M) for the VLM pipeline tests.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A real llama.cpp server (xllamacpp + SmolLM2-135M from PyPI): the one `DISCO_LOCAL_LLM_URL`
/// names (scripts/test starts it), else one `local_llm` starts and the value stops when dropped.
pub struct LocalLlm {
    /// The server's OpenAI-compatible base URL (`http://127.0.0.1:PORT/v1`).
    pub url: String,
    child: Option<std::process::Child>,
}

impl Drop for LocalLlm {
    fn drop(&mut self) {
        if let Some(c) = &mut self.child {
            let _ = c.kill();
            let _ = c.wait();
        }
    }
}

/// Whether a server on `port` answers `GET /health` with 200.
fn answers_health(port: u16) -> bool {
    use std::io::{Read, Write};
    let Ok(mut s) = std::net::TcpStream::connect(("127.0.0.1", port)) else {
        return false;
    };
    let _ = s.set_read_timeout(Some(std::time::Duration::from_secs(2)));
    if s.write_all(b"GET /health HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n")
        .is_err()
    {
        return false;
    }
    let mut buf = String::new();
    let _ = s.read_to_string(&mut buf);
    buf.starts_with("HTTP/1.1 200") || buf.starts_with("HTTP/1.0 200")
}

/// The local model server to test against: `DISCO_LOCAL_LLM_URL` if set, else a new one started
/// here (after `scripts/local-llm install`) and stopped when the returned value is dropped.
pub fn local_llm() -> LocalLlm {
    if let Ok(url) = std::env::var("DISCO_LOCAL_LLM_URL")
        && !url.is_empty()
    {
        return LocalLlm { url, child: None };
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let install = Command::new(root.join("scripts/local-llm"))
        .arg("install")
        .status()
        .expect("scripts/local-llm runs");
    assert!(install.success(), "scripts/local-llm install failed");
    let venv = std::env::var("DISCO_LLM_VENV")
        .map(PathBuf::from)
        .unwrap_or_else(|_| root.join(".venv-llm"));
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let child = Command::new(venv.join("bin/python"))
        .arg(root.join("scripts/llm_server.py"))
        .arg(port.to_string())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the llama.cpp server starts");
    let server = LocalLlm {
        url: format!("http://127.0.0.1:{port}/v1"),
        child: Some(child),
    };
    for _ in 0..240 {
        if answers_health(port) {
            return server;
        }
        std::thread::sleep(std::time::Duration::from_millis(500));
    }
    panic!("the local llama.cpp server did not come up on port {port}");
}
