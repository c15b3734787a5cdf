//! The VLM agents against a real local model server, and the errors when no server can be used.

use std::path::Path;
use std::process::Command;

use serde_json::Value;

use crate::harness::local_model::local_llm;
use crate::harness::{disco_env, stderr, stdout, write};

/// Two pieces in a bedroom: small enough for a 135M model to answer about quickly.
const TWO_PIECES: &str = r#"{"id": "vlm-small", "prompt": "a bedroom", "room_type": "bedroom",
  "room": {"width": 400, "depth": 350},
  "assets": [{"name": "bed-0", "category": "bed", "size": [160, 210, 100]},
             {"name": "nightstand-0", "category": "nightstand", "size": [50, 40, 55]}]}"#;

/// The whole VLM pipeline (planner, designer, evaluator, SRT) on a real 135M model: whatever it
/// answers, the layout is valid and the stats count the real calls and tokens; recorded with
/// `--cache`, the run replays identically with the server gone.
#[test]
fn vlm_pipeline_on_a_real_local_llama_cpp_server() {
    let server = local_llm();
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "scene.json", TWO_PIECES);
    let out = dir.path().join("out.json");
    let cache = dir.path().join("cache");
    let trace = dir.path().join("trace.jsonl");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("config/local-llm.toml");
    let args = |out: &Path| {
        vec![
            "generate".to_string(),
            scene.clone(),
            "-o".into(),
            out.to_string_lossy().into_owned(),
            "--config".into(),
            config.to_string_lossy().into_owned(),
            "--set".into(),
            "run.max_rounds=1".into(),
            // Every question to the model, even those the geometry settles: the point here is
            // the model's answers going through.
            "--set".into(),
            "agents.evaluator.options.ask=all".into(),
            "--cache".into(),
            cache.to_string_lossy().into_owned(),
            "--trace".into(),
            trace.to_string_lossy().into_owned(),
            "--json".into(),
        ]
    };
    let a = args(&out);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let o = disco_env(&a, &[("DISCO_LOCAL_LLM_URL", &server.url)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let m: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(m["collision_pct"], 0.0);
    assert_eq!(m["oob_pct"], 0.0);
    let layout: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let placed = layout["objects"].as_array().unwrap().len();
    let dropped = layout["dropped"].as_array().unwrap();
    assert_eq!(placed + dropped.len(), 2, "every asset placed or dropped");
    assert!(
        dropped
            .iter()
            .all(|d| !d["reason"].as_str().unwrap().is_empty())
    );
    let stats = &layout["stats"];
    let calls = stats["llm_calls"].as_u64().unwrap();
    // Planner, designer (one call per group at least), evaluator questions and physical verdict.
    assert!(calls >= 4, "{stats}");
    assert!(
        stats["prompt_tokens"].as_u64().unwrap() > 100 * calls,
        "{stats}"
    );
    assert!(
        stats["completion_tokens"].as_u64().unwrap() >= calls,
        "{stats}"
    );
    let events = std::fs::read_to_string(&trace).unwrap();
    let model_calls = events
        .lines()
        .filter(|l| l.contains("\"model_call\""))
        .count();
    assert!(model_calls as u64 >= calls, "every call traced");
    for role in ["planner", "designer", "evaluator"] {
        assert!(
            events.lines().any(
                |l| l.contains("\"model_call\"") && l.contains(&format!("\"role\":\"{role}\""))
            ),
            "{role} called the model"
        );
    }

    assert_the_models_own_answers_shaped_the_layout(&events, &layout);

    // The benchmark's judge columns come from the same server.
    let bench_out = dir.path().join("bench");
    let scenes = dir.path().join("judged");
    std::fs::create_dir(&scenes).unwrap();
    std::fs::copy(&scene, scenes.join("scene.json")).unwrap();
    let o = disco_env(
        &[
            "bench",
            "--scenes",
            scenes.to_str().unwrap(),
            "--out",
            bench_out.to_str().unwrap(),
            "--judge",
            config.to_str().unwrap(),
            "--json",
        ],
        &[("DISCO_LOCAL_LLM_URL", &server.url)],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let run: Value = serde_json::from_str(&stdout(&o)).unwrap();
    let judge = &run["results"][0]["judge"];
    for k in ["positional", "rotational"] {
        let v = judge[k].as_f64().unwrap_or(-1.0);
        assert!((0.0..=100.0).contains(&v), "{k}: {judge}");
    }
    assert!(run["table"]["rows"][0]["judge_positional"].is_number());

    // Replay: the server is gone, the recorded answers give the same layout.
    drop(server);
    let replay = dir.path().join("replay.json");
    let a = args(&replay);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let o = disco_env(&a, &[("DISCO_LOCAL_LLM_URL", "http://127.0.0.1:9/v1")]);
    assert!(o.status.success(), "{}", stderr(&o));
    let again: Value = serde_json::from_str(&std::fs::read_to_string(&replay).unwrap()).unwrap();
    assert_eq!(again["objects"], layout["objects"]);
    assert_eq!(again["stats"]["llm_calls"], layout["stats"]["llm_calls"]);
}

#[test]
fn a_model_server_that_is_down_or_a_missing_key_is_one_clear_error_at_start() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "scene.json", TWO_PIECES);
    let out = dir.path().join("out.json");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let local = root.join("config/local-llm.toml");
    let o = disco_env(
        &[
            "generate",
            &scene,
            "-o",
            &out.to_string_lossy(),
            "--config",
            &local.to_string_lossy(),
        ],
        &[("DISCO_LOCAL_LLM_URL", "http://127.0.0.1:9/v1")],
    );
    assert_eq!(
        o.status.code(),
        Some(3),
        "exit 3: a model server could not be used"
    );
    let err = stderr(&o);
    assert!(
        err.contains("model main: cannot reach http://127.0.0.1:9/v1/models"),
        "{err}"
    );
    assert!(err.contains("scripts/local-llm start"), "{err}");
    assert_eq!(
        err.lines().count(),
        1,
        "one error, no stack of retries: {err}"
    );
    assert!(!out.exists(), "nothing written");

    let openai = root.join("config/openai.toml");
    let mut c = Command::new(env!("CARGO_BIN_EXE_disco"));
    c.args([
        "generate",
        &scene,
        "-o",
        &out.to_string_lossy(),
        "--config",
        &openai.to_string_lossy(),
    ])
    .env_remove("OPENAI_API_KEY");
    let o = c.output().unwrap();
    assert_eq!(
        o.status.code(),
        Some(1),
        "a missing key is a configuration error"
    );
    assert!(
        stderr(&o).contains("the API key variable OPENAI_API_KEY is not set"),
        "{}",
        stderr(&o)
    );
}

/// A model server that answers the preflight and the first chat request, then goes away: the
/// run finishes with the fallbacks, writes its layout, and exits 3.
#[test]
fn a_model_server_that_dies_mid_run_exits_3_and_still_writes_the_layout() {
    use std::io::{BufRead, BufReader, Read, Write};
    use std::net::TcpListener;
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}/v1", listener.local_addr().unwrap());
    // Two answers (GET /v1/models, then one chat completion), then the listener is dropped:
    // every later connection is refused.
    let server = std::thread::spawn(move || {
        for _ in 0..2 {
            let (mut conn, _) = listener.accept().unwrap();
            let mut reader = BufReader::new(conn.try_clone().unwrap());
            let mut length = 0usize;
            loop {
                let mut line = String::new();
                reader.read_line(&mut line).unwrap();
                if let Some(v) = line.to_ascii_lowercase().strip_prefix("content-length:") {
                    length = v.trim().parse().unwrap();
                }
                if line == "\r\n" || line.is_empty() {
                    break;
                }
            }
            let mut body = vec![0; length];
            reader.read_exact(&mut body).unwrap();
            let answer = r#"{"data": [], "choices": [{"index": 0, "message": {"role": "assistant", "content": "{}"}}], "usage": {"prompt_tokens": 5, "completion_tokens": 1}}"#;
            write!(
                conn,
                "HTTP/1.1 200 OK\r\ncontent-type: application/json\r\ncontent-length: {}\r\nconnection: close\r\n\r\n{answer}",
                answer.len()
            )
            .unwrap();
        }
    });
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "scene.json", TWO_PIECES);
    let out = dir.path().join("out.json");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("config/local-llm.toml");
    let o = disco_env(
        &[
            "generate",
            &scene,
            "-o",
            out.to_str().unwrap(),
            "--config",
            config.to_str().unwrap(),
            "--set",
            "run.max_rounds=1",
        ],
        &[("DISCO_LOCAL_LLM_URL", &url)],
    );
    server.join().unwrap();
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("a model server failed"),
        "{}",
        stderr(&o)
    );
    let layout: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let placed = layout["objects"].as_array().unwrap().len();
    assert_eq!(placed + layout["dropped"].as_array().unwrap().len(), 2);
    assert!(
        !layout["stats"]["model_failures"]
            .as_array()
            .unwrap()
            .is_empty(),
        "{}",
        layout["stats"]
    );
}

/// What the model's own answers did, beyond the fallbacks: its structured answers (the server
/// constrains them to the schema) were taken, the delivered plan is the model's plan, and every
/// part of an answer the agents refused is named in the layout's notes.
fn assert_the_models_own_answers_shaped_the_layout(trace: &str, layout: &Value) {
    let events: Vec<Value> = trace
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let fell_back: Vec<&Value> = events.iter().filter(|e| e["kind"] == "fallback").collect();
    let model_reply = |role: &str| {
        events
            .iter()
            .find(|e| e["role"] == role && e["kind"] == "reply" && e["implementation"] == "vlm")
    };
    let plan = model_reply("planner").unwrap_or_else(|| {
        panic!("the planner's answer came from the model, not a fallback: {fell_back:?}")
    });
    // The plan delivered is the model's: each delivered group is one the model proposed, with
    // any name it repeated taken out.
    let proposed: Vec<Vec<&str>> = plan["detail"]["groups"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| {
            g.as_array()
                .unwrap()
                .iter()
                .map(|n| n.as_str().unwrap())
                .collect()
        })
        .collect();
    for group in layout["plan"]["groups"].as_array().unwrap() {
        let names: Vec<&str> = group
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap())
            .collect();
        assert!(
            proposed.iter().any(|p| names.iter().all(|n| p.contains(n))),
            "delivered group {names:?} is not among the model's {proposed:?}"
        );
    }
    // The designer's model answer placed the group's own objects, or the notes say why not.
    let design = model_reply("designer").expect("the designer asked the model");
    let notes = layout["stats"]["notes"].to_string();
    for pose in design["detail"]["poses"].as_array().unwrap() {
        let name = pose["name"].as_str().unwrap();
        assert!(
            layout["objects"]
                .as_array()
                .unwrap()
                .iter()
                .any(|o| o["name"] == name)
                || notes.contains(name),
            "the model's pose for {name} neither placed nor explained: {notes}"
        );
    }
}
