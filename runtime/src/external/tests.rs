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
        ctx: SceneContext::new(Arc::new(scene), Arc::new(Plan::default())),
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
    designer_of(
        python("tests/integration/agents/misbehaving.py", &[mode]),
        deadline,
    )
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

/// An agent of `command`, as a designer, with the process transport at hand.
fn designer_of(command: Vec<String>, deadline: Duration) -> (Arc<ProcessTransport>, ExternalAgent) {
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

fn sh(script: &str) -> Vec<String> {
    vec!["sh".into(), "-c".into(), script.into()]
}

/// Whether process `pid` is gone (no entry, or a zombie waiting for its reaper), waiting up to
/// 5 s for it to go.
fn gone(pid: u32) -> bool {
    let dead = || match std::fs::read_to_string(format!("/proc/{pid}/stat")) {
        Err(_) => true,
        // The state follows the command name in parentheses.
        Ok(stat) => stat
            .rsplit_once(')')
            .is_some_and(|(_, rest)| matches!(rest.trim_start().chars().next(), Some('Z' | 'X'))),
    };
    let t0 = std::time::Instant::now();
    while t0.elapsed() < Duration::from_secs(5) {
        if dead() {
            return true;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    false
}

/// The pids an agent wrote to `file`, one per line, waiting up to 10 s for `n` of them.
fn pids_in(file: &Path, n: usize) -> Vec<u32> {
    let t0 = std::time::Instant::now();
    loop {
        let pids: Vec<u32> = std::fs::read_to_string(file)
            .unwrap_or_default()
            .lines()
            .filter_map(|l| l.trim().parse().ok())
            .collect();
        if pids.len() >= n || t0.elapsed() > Duration::from_secs(10) {
            return pids;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[tokio::test]
async fn an_endless_reply_is_an_unusable_answer_read_no_further_than_the_cap() {
    let (t, agent) = designer_of(
        vec!["cat".into(), "/dev/zero".into()],
        Duration::from_secs(30),
    );
    let started = std::time::Instant::now();
    let e = agent.design(&design_request()).await.unwrap_err();
    assert!(
        matches!(e, RoleError::Failed(_)),
        "not a crash or an abort: {e}"
    );
    assert!(e.to_string().contains("its reply is over 8 MiB"), "{e}");
    assert!(e.to_string().contains("max_reply_bytes"), "{e}");
    assert!(started.elapsed() < Duration::from_secs(20));
    let pid = t.last_pid().unwrap();
    assert!(gone(pid), "the endless process was killed");
    assert_eq!(t.pid().await, None);

    // The cap is the agent's to set.
    let t = ProcessTransport::new(
        "designer",
        python("tests/integration/agents/misbehaving.py", &["good"]),
        Duration::from_secs(30),
    )
    .unwrap()
    .with_max_reply(20);
    let agent = ExternalAgent::new("designer", RoleKind::Designer, Box::new(t), false);
    let e = agent.design(&design_request()).await.unwrap_err();
    assert!(e.to_string().contains("its reply is over 20 bytes"), "{e}");
}

#[tokio::test]
async fn a_reply_that_is_not_utf8_says_so_and_is_no_crash() {
    let (t, agent) = misbehaving("not-utf8", Duration::from_secs(10));
    let e = agent.design(&design_request()).await.unwrap_err();
    assert!(matches!(e, RoleError::Failed(_)), "{e}");
    assert!(
        e.to_string()
            .contains("broke the protocol: its reply is not UTF-8 (byte 0xe9 at offset"),
        "{e}"
    );
    assert!(!e.to_string().contains("exited"), "{e}");
    assert_eq!(t.pid().await, None, "the process was discarded");
}

#[tokio::test]
async fn a_flood_of_stderr_without_a_newline_is_read_in_bounded_pieces() {
    // 30 MB on stderr in one line, then the process exits: the crash report quotes a cut line.
    let (_, agent) = designer_of(
        sh("head -c 30000000 /dev/zero | tr '\\0' x >&2; exit 3"),
        Duration::from_secs(30),
    );
    let e = agent.design(&design_request()).await.unwrap_err();
    let text = e.to_string();
    assert!(matches!(e, RoleError::Panicked(_)), "{text:.300}");
    assert!(text.contains("exit status: 3"), "{text:.300}");
    assert!(
        text.contains("more bytes of this line not shown"),
        "{text:.300}"
    );
    assert!(text.len() < 2000, "the report quotes {} bytes", text.len());
}

#[tokio::test]
async fn what_an_agent_forks_dies_with_it_at_the_end_of_its_scene_and_at_its_deadline() {
    let dir = tempfile::tempdir().unwrap();
    let pids = dir.path().join("pids");
    let script = format!(
        "sleep 300 & echo $! > '{}'; exec python3 '{}' \"$0\"",
        pids.display(),
        repo()
            .join("tests/integration/agents/misbehaving.py")
            .display()
    );
    // Scene end: the agent answers, then its role actor (and so the agent) is dropped.
    let mut command = sh(&script);
    command.push("good".into());
    let (t, agent) = designer_of(command, Duration::from_secs(10));
    agent.design(&design_request()).await.unwrap();
    let child = pids_in(&pids, 1)[0];
    assert!(
        !gone_now(child),
        "the forked child runs while the agent does"
    );
    let leader = t.last_pid().unwrap();
    assert!(super::group::live_count() > 0);
    drop(agent);
    drop(t);
    assert!(gone(leader), "the agent process was killed");
    assert!(gone(child), "the child it forked was killed with it");

    // Deadline: the agent hangs, and its whole group is killed.
    std::fs::remove_file(&pids).unwrap();
    let mut command = sh(&script);
    command.push("hang".into());
    let (t, agent) = designer_of(command, Duration::from_millis(700));
    let e = agent.design(&design_request()).await.unwrap_err();
    assert_eq!(e, RoleError::Deadline(0.7));
    let child = pids_in(&pids, 1)[0];
    assert!(gone(t.last_pid().unwrap()));
    assert!(
        gone(child),
        "the child it forked was killed at the deadline"
    );
}

/// Whether process `pid` is gone right now.
fn gone_now(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .map(|s| {
            s.rsplit_once(')')
                .is_some_and(|(_, r)| r.trim_start().starts_with('Z'))
        })
        .unwrap_or(true)
}

#[test]
fn notes_of_a_reply_are_bounded_in_number_and_length() {
    let notes: Vec<String> = (0..1000).map(|i| format!("note {i}")).collect();
    let mut with_long = notes.clone();
    with_long[0] = "x".repeat(100_000);
    let text = serde_json::json!({
        "protocol": 1, "id": 7, "reply": {"objects": []}, "notes": with_long
    })
    .to_string();
    let out = read_reply::<Poses>(RoleKind::Designer, 7, &text)
        .unwrap()
        .unwrap();
    assert_eq!(out.notes.len(), MAX_NOTES + 1);
    assert_eq!(out.notes[0].chars().count(), MAX_NOTE_CHARS + 3);
    assert_eq!(out.notes[1], "note 1");
    assert!(
        out.notes[MAX_NOTES].starts_with("968 more notes of the agent left out"),
        "{}",
        out.notes[MAX_NOTES]
    );
}

/// A server on a free port that answers every request with the bytes `response`, followed,
/// when `endless`, by a body that never ends (until the client hangs up); returns its URL.
async fn raw_http_agent(response: &'static [u8], endless: bool) -> String {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let url = format!("http://{}/agent", listener.local_addr().unwrap());
    tokio::spawn(async move {
        while let Ok((mut socket, _)) = listener.accept().await {
            tokio::spawn(async move {
                let mut buf = [0u8; 65536];
                let _ = socket.read(&mut buf).await;
                if socket.write_all(response).await.is_err() || !endless {
                    return;
                }
                let chunk = vec![b'x'; 65536];
                while socket.write_all(&chunk).await.is_ok() {}
            });
        }
    });
    url
}

#[tokio::test]
async fn an_endless_http_body_is_an_unusable_answer_read_no_further_than_the_cap() {
    for (head, endless) in [
        (
            &b"HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nConnection: close\r\n\r\n"[..],
            true,
        ),
        // One that says how long it is gets no further than its headers.
        (
            &b"HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: 100000000000\r\n\r\n"[..],
            false,
        ),
    ] {
        let url = raw_http_agent(head, endless).await;
        let t = super::http::HttpTransport::new(&url, Duration::from_secs(30)).unwrap();
        let agent = ExternalAgent::new("designer", RoleKind::Designer, Box::new(t), false);
        let started = std::time::Instant::now();
        let e = agent.design(&design_request()).await.unwrap_err();
        assert!(matches!(e, RoleError::Failed(_)), "{e}");
        assert!(e.to_string().contains("its reply is over 8 MiB"), "{e}");
        assert!(started.elapsed() < Duration::from_secs(20));
    }
}

#[tokio::test]
async fn an_http_reply_that_is_not_utf8_says_so() {
    let body = b"{\"protocol\":1,\"id\":1,\"reply\":{\"objects\":[]},\"notes\":[\"caf\xe9\"]}";
    let response: &'static [u8] = Box::leak(
        [
            format!(
                "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
                body.len()
            )
            .as_bytes(),
            &body[..],
        ]
        .concat()
        .into_boxed_slice(),
    );
    let url = raw_http_agent(response, false).await;
    let t = super::http::HttpTransport::new(&url, Duration::from_secs(5)).unwrap();
    let agent = ExternalAgent::new("designer", RoleKind::Designer, Box::new(t), false);
    let e = agent.design(&design_request()).await.unwrap_err();
    assert!(
        e.to_string()
            .contains("its reply is not UTF-8 (byte 0xe9 at offset"),
        "{e}"
    );
}

#[tokio::test]
async fn a_reply_naming_an_object_the_scene_lacks_is_refused_not_cleaned() {
    let (_t, agent) = misbehaving("ghost", Duration::from_secs(20));
    let err = agent.design(&design_request()).await.unwrap_err();
    assert!(matches!(err, RoleError::Refused(_)), "{err:?}");
    assert!(err.to_string().contains("unicorn-9"), "{err}");
}

/// A transport that keeps each request line and answers with `reply(id)`.
struct Recording {
    sent: std::sync::Mutex<Vec<String>>,
    reply: fn(u64) -> String,
}

#[async_trait]
impl Transport for Arc<Recording> {
    async fn exchange(&self, line: String) -> Result<String, RoleError> {
        let id = serde_json::from_str::<serde_json::Value>(&line).unwrap()["id"]
            .as_u64()
            .unwrap();
        self.sent.lock().unwrap().push(line);
        Ok((self.reply)(id))
    }
    async fn discard(&self) {}
}

fn recording(reply: fn(u64) -> String) -> Arc<Recording> {
    Arc::new(Recording {
        sent: std::sync::Mutex::new(Vec::new()),
        reply,
    })
}

#[tokio::test]
async fn requests_say_what_moved_and_replies_may_call_a_question_infeasible() {
    use disco_core::relations::ConstraintKind;
    use disco_core::roles::ToolMove;
    let scene = Arc::new(bedroom());
    let mut ctx = SceneContext::new(Arc::clone(&scene), Arc::new(Plan::default()));
    ctx.moved.push(ToolMove {
        name: "nightstand-0".into(),
        by: "prt".into(),
        from: [100.0, 20.0],
        from_rotation: 0.0,
        to: [60.0, 20.0],
        to_rotation: 0.0,
        why: "it overlapped bed-0".into(),
    });
    let layout = disco_core::layout::Layout {
        id: scene.id.clone(),
        room: scene.room.clone(),
        objects: Vec::new(),
        dropped: Vec::new(),
        plan: Arc::new(Plan::default()),
        stats: Default::default(),
    };
    let question = Question {
        id: 3,
        text: "Is it true that nightstand-0 is beside bed-0?".into(),
        subject: Some("nightstand-0".into()),
        constraint: Some(ConstraintKind::Relation {
            relation: disco_core::plan::Relation::SideOf,
            target: "bed-0".into(),
        }),
    };
    // The evaluator: `moved` goes out, `infeasible` comes back as the question's constraint.
    let t = recording(|id| {
        format!(
            r#"{{"protocol":1,"id":{id},"reply":{{"answers":[{{"id":3,"yes":false,"reason":"no room"}}],"infeasible":[{{"id":3,"reason":"the bed fills the wall"}},{{"id":9,"reason":"asked nothing"}}]}}}}"#
        )
    });
    let agent = ExternalAgent::new(
        "evaluator",
        RoleKind::Evaluator,
        Box::new(Arc::clone(&t)),
        false,
    );
    let req = EvalRequest {
        ctx: ctx.clone(),
        layout: layout.clone(),
        group: vec!["nightstand-0".into()],
        render: None,
    };
    let out = agent
        .answer(&req, std::slice::from_ref(&question))
        .await
        .unwrap();
    assert!(!out.value[0].yes);
    assert_eq!(out.infeasible.len(), 1, "an unknown id is passed over");
    assert_eq!(out.infeasible[0].subject, "nightstand-0");
    assert_eq!(
        out.infeasible[0].constraint,
        question.constraint.clone().unwrap()
    );
    assert_eq!(out.infeasible[0].reason, "the bed fills the wall");
    let sent: serde_json::Value = serde_json::from_str(&t.sent.lock().unwrap()[0]).unwrap();
    assert_eq!(sent["request"]["moved"][0]["name"], "nightstand-0");
    assert_eq!(sent["request"]["moved"][0]["why"], "it overlapped bed-0");
    // The srt: an empty move list with an infeasible question is a valid reply.
    let t = recording(|id| {
        format!(
            r#"{{"protocol":1,"id":{id},"reply":{{"objects":[],"infeasible":[{{"id":3,"reason":"no wall stretch holds both"}}]}}}}"#
        )
    });
    let agent = ExternalAgent::new("srt", RoleKind::Srt, Box::new(Arc::clone(&t)), false);
    let answer = Answer {
        id: 3,
        yes: false,
        reason: "no room".into(),
    };
    let req = SrtRequest {
        ctx: ctx.clone(),
        layout: layout.clone(),
        failed: vec![(question.clone(), answer)],
        movable: vec!["nightstand-0".into()],
        render: None,
    };
    let out = SemanticRefiner::refine(&agent, &req).await.unwrap();
    assert!(out.value.is_empty());
    assert_eq!(out.infeasible[0].reason, "no wall stretch holds both");
    let sent: serde_json::Value = serde_json::from_str(&t.sent.lock().unwrap()[0]).unwrap();
    assert_eq!(sent["request"]["moved"][0]["by"], "prt");
    // Nothing moved: the field is left out, so requests read as before.
    let t = recording(|id| format!(r#"{{"protocol":1,"id":{id},"reply":{{"objects":[]}}}}"#));
    let agent = ExternalAgent::new(
        "designer",
        RoleKind::Designer,
        Box::new(Arc::clone(&t)),
        false,
    );
    agent.design(&design_request()).await.unwrap();
    let sent: serde_json::Value = serde_json::from_str(&t.sent.lock().unwrap()[0]).unwrap();
    assert!(sent["request"].get("moved").is_none());
}
