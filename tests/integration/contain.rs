//! Agents are contained: an agent that never stops talking costs a bounded read and its fallback
//! finishes the room; what an agent forks ends with it; SIGTERM or SIGINT to disco kills every
//! agent, keeps what is finished and exits 143 or 130.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

use crate::harness::{examples, layouts_in, stderr, trace_events, write};

/// A graph whose designer is `designer` (the lines of its `[agents.designer]` section after
/// `impl`), with the rules designer as its fallback.
fn graph_with_designer(dir: &Path, designer: &str) -> String {
    let graph = format!(
        "[run]\nbackoff_ms = 1\n\n[pipeline]\nround = [\"evaluate\", \"srt\", \"prt\"]\n\n\
         [agents.planner]\nimpl = \"rules\"\n\n\
         [agents.designer]\n{designer}\nretries = 1\nfallback = \"rules\"\n\n\
         [agents.evaluator]\nimpl = \"rules\"\n[agents.srt]\nimpl = \"rules\"\n[agents.prt]\nimpl = \"grid\"\n"
    );
    write(dir, "graph.toml", &graph)
}

/// Runs `disco generate` on the bedroom with graph `config`; returns the layout and the trace.
fn generate_with(dir: &Path, config: &str) -> (Value, Vec<Value>) {
    let out = dir.join("room.json");
    let trace = dir.join("trace.jsonl");
    let o = crate::harness::generate(
        &examples().join("bedroom.json"),
        &out,
        &["--config", config, "--trace", trace.to_str().unwrap()],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let layout = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    (layout, trace_events(&trace))
}

/// How many assets the layout places or drops (the bedroom has 7).
fn furnished(layout: &Value) -> usize {
    ["objects", "dropped"]
        .iter()
        .map(|k| layout[*k].as_array().map_or(0, Vec::len))
        .sum()
}

/// What the trace's designer events say, as one text.
fn designer_said(events: &[Value]) -> String {
    events
        .iter()
        .filter(|e| e["role"] == "designer")
        .map(|e| format!("{} {}\n", e["kind"], e["detail"]))
        .collect()
}

/// A server on a free port that answers every connection with a 200 and a body that never
/// ends (until the client hangs up); returns its URL.
fn endless_http_server() -> String {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}/agent", listener.local_addr().unwrap());
    std::thread::spawn(move || {
        for mut socket in listener.incoming().flatten() {
            std::thread::spawn(move || {
                let mut buf = [0u8; 65536];
                let _ = socket.read(&mut buf);
                let head = "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\n\r\n";
                if socket.write_all(head.as_bytes()).is_err() {
                    return;
                }
                let chunk = vec![b'{'; 65536];
                while socket.write_all(&chunk).is_ok() {}
            });
        }
    });
    url
}

#[test]
fn an_agent_that_never_stops_talking_is_an_unusable_answer_and_the_fallback_finishes_the_room() {
    let url = endless_http_server();
    for designer in [
        "impl = \"process\"\ncommand = [\"cat\", \"/dev/zero\"]".to_string(),
        format!("impl = \"http\"\nurl = \"{url}\""),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let config = graph_with_designer(dir.path(), &designer);
        let (layout, events) = generate_with(dir.path(), &config);
        assert_eq!(furnished(&layout), 7, "{designer}: {layout}");
        let said = designer_said(&events);
        assert!(
            said.contains("its reply is over 8 MiB"),
            "{designer}: {said}"
        );
        assert!(said.contains("fallback"), "{designer}: {said}");
    }
}

/// The process ids an agent wrote to `file`, one per line, waiting up to 20 s for `n`.
fn pids_in(file: &Path, n: usize) -> Vec<u32> {
    let t0 = Instant::now();
    loop {
        let pids: Vec<u32> = std::fs::read_to_string(file)
            .unwrap_or_default()
            .lines()
            .filter_map(|l| l.trim().parse().ok())
            .collect();
        if pids.len() >= n || t0.elapsed() > Duration::from_secs(20) {
            return pids;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Whether process `pid` is gone (no entry, or a zombie waiting for its reaper), waiting up to
/// 5 s for it to go.
fn gone(pid: u32) -> bool {
    let t0 = Instant::now();
    while t0.elapsed() < Duration::from_secs(5) {
        let dead = match std::fs::read_to_string(format!("/proc/{pid}/stat")) {
            Err(_) => true,
            Ok(stat) => stat
                .rsplit_once(')')
                .is_some_and(|(_, r)| matches!(r.trim_start().chars().next(), Some('Z' | 'X'))),
        };
        if dead {
            return true;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    false
}

/// Writes `agent.sh` (run by `sh`, from `dir`) into `dir`; it records its pid and those of the
/// children it forks in `dir/pids`.
fn agent_script(dir: &Path, body: &str) -> String {
    let misbehaving =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/integration/agents/misbehaving.py");
    let text = format!(
        "cd \"$(dirname \"$0\")\"\necho $$ >> pids\nMISBEHAVING='{}'\n{body}\n",
        misbehaving.display()
    );
    write(dir, "agent.sh", &text)
}

#[test]
fn what_an_agent_forks_ends_with_its_scene() {
    let dir = tempfile::tempdir().unwrap();
    let script = agent_script(
        dir.path(),
        "sleep 300 &\necho $! >> pids\nexec python3 \"$MISBEHAVING\" good",
    );
    let config = graph_with_designer(
        dir.path(),
        &format!("impl = \"process\"\ncommand = [\"sh\", {script:?}]"),
    );
    let (layout, _) = generate_with(dir.path(), &config);
    assert_eq!(furnished(&layout), 7);
    let pids = pids_in(&dir.path().join("pids"), 2);
    assert_eq!(pids.len(), 2, "the agent and its child");
    for pid in pids {
        assert!(gone(pid), "process {pid} outlived its scene");
    }
}

/// Starts `disco ARGS` with stderr captured, waits until `ready` holds (at most 30 s), sends it
/// `signal` with kill(1), and returns its exit code and stderr (waiting at most 20 s).
fn signalled(args: &[&str], signal: &str, ready: impl Fn() -> bool) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_disco"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !ready() {
        assert!(t0.elapsed() < Duration::from_secs(30), "never ready");
        assert!(child.try_wait().unwrap().is_none(), "disco ended early");
        std::thread::sleep(Duration::from_millis(20));
    }
    let sent = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let t0 = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if t0.elapsed() > Duration::from_secs(20) {
            let _ = child.kill();
            panic!("disco did not exit after {signal}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    (status.code(), err)
}

/// The files of `dir` whose names start with `.disco-` (temporary files of atomic writes).
fn temp_files(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with(".disco-")
        })
        .collect()
}

#[test]
fn sigterm_or_sigint_stops_disco_and_every_agent_it_started() {
    for (signal, code) in [("TERM", 143), ("INT", 130)] {
        let dir = tempfile::tempdir().unwrap();
        let script = agent_script(dir.path(), "sleep 300 &\necho $! >> pids\nexec sleep 300");
        let config = graph_with_designer(
            dir.path(),
            &format!("impl = \"process\"\ncommand = [\"sh\", {script:?}]"),
        );
        let out = dir.path().join("room.json");
        let scene = examples().join("bedroom.json");
        let pids_file = dir.path().join("pids");
        let (got, err) = signalled(
            &[
                "generate",
                scene.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--config",
                &config,
            ],
            signal,
            || pids_in(&pids_file, 0).len() >= 2,
        );
        assert_eq!(got, Some(code), "SIG{signal}: {err}");
        assert!(err.contains(&format!("stopped by SIG{signal}")), "{err}");
        for pid in pids_in(&pids_file, 2) {
            assert!(gone(pid), "SIG{signal}: agent process {pid} outlived disco");
        }
        assert!(!out.exists(), "an unfinished layout is not written");
        assert!(temp_files(dir.path()).is_empty());
    }
}

#[test]
fn a_batch_stopped_by_sigterm_keeps_its_finished_scenes_whole() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = dir.path().join("scenes");
    std::fs::create_dir(&scenes).unwrap();
    let mut scene: Value =
        serde_json::from_str(&std::fs::read_to_string(examples().join("bedroom.json")).unwrap())
            .unwrap();
    for id in ["a-first", "b-second"] {
        scene["id"] = id.into();
        std::fs::write(scenes.join(format!("{id}.json")), scene.to_string()).unwrap();
    }
    // The first agent started answers; every later one hangs with a child of its own.
    let script = agent_script(
        dir.path(),
        "if mkdir answered 2>/dev/null; then exec python3 \"$MISBEHAVING\" good; fi\n\
         sleep 300 &\necho $! >> pids\nexec sleep 300",
    );
    let config = graph_with_designer(
        dir.path(),
        &format!("impl = \"process\"\ncommand = [\"sh\", {script:?}]\ndeadline_s = 120"),
    );
    let out = dir.path().join("out");
    let pids_file = dir.path().join("pids");
    let (got, err) = signalled(
        &[
            "batch",
            scenes.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--jobs",
            "1",
            "--config",
            &config,
            "-q",
        ],
        "TERM",
        || pids_in(&pids_file, 0).len() >= 3 && !layouts_in(&out).is_empty(),
    );
    assert_eq!(got, Some(143), "{err}");
    let written = layouts_in(&out);
    assert_eq!(written.len(), 1, "{written:?}");
    disco_layout::Layout::load(&written[0]).expect("the finished scene, whole");
    assert!(temp_files(&out).is_empty(), "{:?}", temp_files(&out));
    for pid in pids_in(&pids_file, 3) {
        assert!(gone(pid), "agent process {pid} outlived disco");
    }
}
