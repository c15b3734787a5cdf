use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use super::process::ProcessTransport;
use super::protocol::{self, Poses};
use super::*;
use disco_core::roles::SceneContext;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn bedroom() -> SceneSpec {
    SceneSpec::load(&repo().join("examples/scenes/bedroom.json")).unwrap()
}

fn design_request() -> DesignRequest {
    let scene = bedroom();
    let group = scene.assets.iter().map(|a| a.name.clone()).collect();
    DesignRequest {
        ctx: SceneContext {
            scene: Arc::new(scene),
            plan: Arc::new(Plan::default()),
        },
        group,
        placed: Vec::new(),
        render: None,
    }
}

fn python(script: &str, args: &[&str]) -> Vec<String> {
    let mut c = vec![
        "python3".to_string(),
        repo().join(script).to_string_lossy().into_owned(),
    ];
    c.extend(args.iter().map(|a| a.to_string()));
    c
}

fn misbehaving(mode: &str, deadline: Duration) -> (Arc<ProcessTransport>, ExternalAgent) {
    let command = python("tests/integration/agents/misbehaving.py", &[mode]);
    let t = Arc::new(ProcessTransport::new("designer", command, deadline).unwrap());
    struct Shared(Arc<ProcessTransport>);
    #[async_trait]
    impl Transport for Shared {
        async fn exchange(&self, line: String) -> Result<String, RoleError> {
            self.0.exchange(line).await
        }
        async fn discard(&self) {
            self.0.discard().await
        }
    }
    let agent = ExternalAgent::new(
        "designer",
        RoleKind::Designer,
        Box::new(Shared(Arc::clone(&t))),
        false,
    );
    (t, agent)
}

fn alive(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok()
}

#[test]
fn a_reply_is_read_only_when_it_answers_this_request_in_this_protocol() {
    let read = |text: &str| read_reply::<Poses>(RoleKind::Designer, 7, text);
    let good = read(
        r#"{"protocol":1,"id":7,"reply":{"objects":[{"name":"a","position":[1,2],"rotation":90}]},"notes":["n"]}"#,
    );
    let out = good.unwrap().unwrap();
    assert_eq!(out.value.objects[0].position, [1.0, 2.0]);
    assert_eq!(out.notes, ["n"]);
    let said = read(r#"{"protocol":1,"id":7,"error":"no room"}"#)
        .unwrap()
        .unwrap_err();
    assert_eq!(said.to_string(), "the designer agent said: no room");
    let broken = |text: &str| read(text).unwrap_err().to_string();
    assert!(
        broken("hello").contains("its reply is not JSON"),
        "{}",
        broken("hello")
    );
    assert!(
        broken(r#"{"protocol":1,"id":8,"reply":{"objects":[]}}"#)
            .ends_with("it answered request 8 where request 7 was due")
    );
    assert!(
        broken(r#"{"protocol":2,"id":7,"reply":{"objects":[]}}"#)
            .contains("protocol Some(2), expected 1")
    );
    assert!(
        broken(r#"{"protocol":1,"id":7,"reply":{"poses":[]}}"#)
            .contains("does not fit the designer reply schema")
    );
    assert!(broken(r#"{"protocol":1,"id":7}"#).contains("neither"));
}

#[test]
fn the_committed_schemas_match_the_types() {
    let dir = repo().join("docs/protocol");
    let write = std::env::var_os("DISCO_WRITE_PROTOCOL_SCHEMAS").is_some();
    for (name, schema) in protocol::schemas() {
        let text = serde_json::to_string_pretty(&schema).unwrap() + "\n";
        let path = dir.join(&name);
        if write {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &text).unwrap();
            continue;
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            committed == text,
            "docs/protocol/{name} no longer matches the Rust types; regenerate with \
             `DISCO_WRITE_PROTOCOL_SCHEMAS=1 cargo test -p disco-runtime the_committed_schemas` \
             and review the diff"
        );
    }
}

#[tokio::test]
async fn a_python_designer_answers_and_its_process_is_reused() {
    let t = ProcessTransport::new(
        "designer",
        python("examples/agents/shelf_designer.py", &[]),
        Duration::from_secs(20),
    )
    .unwrap();
    let agent = ExternalAgent::new("designer", RoleKind::Designer, Box::new(t), false);
    let req = design_request();
    let first = agent.design(&req).await.unwrap();
    assert_eq!(first.value.len(), req.group.len());
    let bed = first.value.iter().find(|o| o.name == "bed-0").unwrap();
    assert_eq!(bed.size, [160.0, 210.0, 100.0], "sizes come from the scene");
    let second = agent.design(&req).await.unwrap();
    assert_eq!(first.value, second.value);
}

#[tokio::test]
async fn a_process_that_exits_is_a_crash_quoting_its_stderr() {
    let (_, agent) = misbehaving("crash-on-start", Duration::from_secs(10));
    let e = agent.design(&design_request()).await.unwrap_err();
    assert!(matches!(e, RoleError::Panicked(_)), "{e}");
    assert!(
        e.to_string().contains("giving up before the first request"),
        "{e}"
    );
    let (t, agent) = misbehaving("crash-mid-run", Duration::from_secs(10));
    agent.design(&design_request()).await.unwrap();
    let pid = t.last_pid().unwrap();
    let e = agent.design(&design_request()).await.unwrap_err();
    assert!(
        e.to_string()
            .contains("exited before answering (exit status: 4)"),
        "{e}"
    );
    assert!(!alive(pid), "the crashed process was reaped");
    agent
        .design(&design_request())
        .await
        .expect("the next call starts a new process");
}

#[tokio::test]
async fn a_hanging_process_is_killed_and_reaped_at_the_deadline() {
    let (t, agent) = misbehaving("hang", Duration::from_millis(500));
    let started = std::time::Instant::now();
    let e = agent.design(&design_request()).await.unwrap_err();
    assert_eq!(e, RoleError::Deadline(0.5));
    assert!(started.elapsed() < Duration::from_secs(3));
    let pid = t.last_pid().expect("a process was started");
    assert!(!alive(pid), "killed and reaped, no zombie");
    assert_eq!(t.pid().await, None);
}

#[tokio::test]
async fn garbage_or_a_wrong_id_is_a_clear_error_and_a_fresh_process() {
    for (mode, says) in [
        ("garbage", "its reply is not JSON"),
        ("wrong-id", "answered request 1001 where request 1 was due"),
    ] {
        let (t, agent) = misbehaving(mode, Duration::from_secs(10));
        let e = agent.design(&design_request()).await.unwrap_err();
        assert!(
            matches!(e, RoleError::Failed(_)) && e.to_string().contains(says),
            "{mode}: {e}"
        );
        assert_eq!(t.pid().await, None, "{mode}: the process was discarded");
    }
}

/// A minimal HTTP server on a free port answering each POSTed request with `answer(id)`; returns
/// its URL.
async fn http_agent(answer: fn(u64) -> String) -> String {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let url = format!("http://{}/agent", listener.local_addr().unwrap());
    tokio::spawn(async move {
        while let Ok((mut socket, _)) = listener.accept().await {
            let mut seen = Vec::new();
            let mut buf = [0u8; 65536];
            let body = loop {
                let n = socket.read(&mut buf).await.unwrap();
                seen.extend_from_slice(&buf[..n]);
                let text = String::from_utf8_lossy(&seen).into_owned();
                let Some(end) = text.find("\r\n\r\n") else {
                    continue;
                };
                let length: usize = text[..end]
                    .lines()
                    .find_map(|l| {
                        l.to_ascii_lowercase()
                            .strip_prefix("content-length:")
                            .map(|v| v.trim().parse().unwrap())
                    })
                    .unwrap();
                if seen.len() >= end + 4 + length {
                    break text[end + 4..].to_string();
                }
            };
            let request: serde_json::Value = serde_json::from_str(&body).unwrap();
            let reply = answer(request["id"].as_u64().unwrap());
            let response = format!(
                "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{reply}",
                reply.len()
            );
            socket.write_all(response.as_bytes()).await.unwrap();
        }
    });
    url
}

#[tokio::test]
async fn an_http_agent_answers_a_post_and_a_wrong_id_is_refused() {
    let url = http_agent(|id| {
        format!(r#"{{"protocol":1,"id":{id},"reply":{{"objects":[{{"name":"bed-0","position":[200,105],"rotation":0}}]}}}}"#)
    })
    .await;
    let t = super::http::HttpTransport::new(&url, Duration::from_secs(5)).unwrap();
    let agent = ExternalAgent::new("designer", RoleKind::Designer, Box::new(t), false);
    let out = agent.design(&design_request()).await.unwrap();
    assert_eq!(out.value.len(), 1);
    assert_eq!(out.value[0].category, "bed");
    let url = http_agent(|id| {
        format!(
            r#"{{"protocol":1,"id":{},"reply":{{"objects":[]}}}}"#,
            id + 1
        )
    })
    .await;
    let t = super::http::HttpTransport::new(&url, Duration::from_secs(5)).unwrap();
    let agent = ExternalAgent::new("designer", RoleKind::Designer, Box::new(t), false);
    let e = agent.design(&design_request()).await.unwrap_err();
    assert!(
        e.to_string()
            .contains("it answered request 2 where request 1 was due"),
        "{e}"
    );
}
