//! The model path against a scripted fault server: the faults a real server will not produce on
//! demand (429 with Retry-After, 500s, hangs, garbage, endless, trickling and cut bodies, redirect
//! loops, a key refused mid-run, empty choices) and the answers a
//! bad model gives (truncated JSON, invented and repeated names, missing objects, NaN), each
//! handled and each asserted.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use axum::Router;
use axum::extract::State;
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use serde_json::{Value, json};

use crate::vlm::{VlmBase, VlmDesigner, VlmEvaluator};
use disco_core::plan::{Plan, Relation};
use disco_core::relations::ConstraintKind;
use disco_core::roles::{DesignRequest, Designer, EvalRequest, Evaluator, Question, SceneContext};
use disco_llm::ModelConfig;
use disco_llm::Prompts;
use disco_llm::{ChatClient, LlmError, Message};

/// One scripted answer of the fault server.
#[derive(Clone)]
enum Reply {
    /// A status with headers and a raw body.
    Raw(u16, Vec<(&'static str, String)>, String),
    /// A chat completion whose message content is this text.
    Content(String),
    /// No answer for this long.
    Hang(Duration),
    /// 200 and a body that never ends.
    Endless,
    /// 200, the start of a body, then the connection breaks.
    Cut,
    /// 200 and a body that comes one byte every 100 ms, for ever.
    Trickle,
    /// 302 back to the same address, for ever.
    RedirectLoop,
}

#[derive(Default)]
struct Script {
    replies: Mutex<VecDeque<Reply>>,
    requests: Mutex<Vec<Value>>,
}

async fn complete(State(s): State<Arc<Script>>, body: axum::Json<Value>) -> Response {
    s.requests.lock().unwrap().push(body.0);
    let next = s.replies.lock().unwrap().pop_front();
    match next {
        Some(Reply::Raw(status, headers, body)) => {
            let mut h = HeaderMap::new();
            for (k, v) in headers {
                h.insert(k, v.parse().unwrap());
            }
            (StatusCode::from_u16(status).unwrap(), h, body).into_response()
        }
        Some(Reply::Content(text)) => axum::Json(json!({
            "choices": [{"index": 0, "message": {"role": "assistant", "content": text}}],
            "usage": {"prompt_tokens": 10, "completion_tokens": 5}
        }))
        .into_response(),
        Some(Reply::Hang(d)) => {
            tokio::time::sleep(d).await;
            StatusCode::GATEWAY_TIMEOUT.into_response()
        }
        Some(Reply::Endless) => {
            let chunk = axum::body::Bytes::from(vec![b' '; 64 * 1024]);
            let body = futures::stream::repeat_with(move || Ok::<_, std::io::Error>(chunk.clone()));
            axum::body::Body::from_stream(body).into_response()
        }
        Some(Reply::Cut) => {
            let parts = vec![
                Ok(axum::body::Bytes::from_static(b"{\"choices\": [")),
                Err(std::io::Error::other("the server went away")),
            ];
            // The break comes after the headers and the first bytes are on the wire.
            let body = futures::StreamExt::then(futures::stream::iter(parts), |part| async move {
                if part.is_err() {
                    tokio::time::sleep(Duration::from_millis(300)).await;
                }
                part
            });
            axum::body::Body::from_stream(body).into_response()
        }
        Some(Reply::Trickle) => {
            let body = futures::stream::unfold((), |()| async {
                tokio::time::sleep(Duration::from_millis(100)).await;
                Some((
                    Ok::<_, std::io::Error>(axum::body::Bytes::from_static(b" ")),
                    (),
                ))
            });
            axum::body::Body::from_stream(body).into_response()
        }
        Some(Reply::RedirectLoop) => {
            // Every later request is sent back here too.
            s.replies.lock().unwrap().push_front(Reply::RedirectLoop);
            let mut h = HeaderMap::new();
            h.insert("location", "/v1/chat/completions".parse().unwrap());
            (StatusCode::TEMPORARY_REDIRECT, h).into_response()
        }
        None => (StatusCode::INTERNAL_SERVER_ERROR, "script exhausted").into_response(),
    }
}

/// Starts the fault server with `replies`; returns its base URL and the script.
async fn serve(replies: Vec<Reply>) -> (String, Arc<Script>) {
    let script = Arc::new(Script {
        replies: Mutex::new(replies.into()),
        requests: Mutex::default(),
    });
    let app = Router::new()
        .route("/v1/chat/completions", post(complete))
        .route(
            "/v1/models",
            get(|| async { axum::Json(json!({"data": []})) }),
        )
        .with_state(Arc::clone(&script));
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    tokio::spawn(async move { axum::serve(listener, app).await.unwrap() });
    (format!("http://{addr}/v1"), script)
}

fn client(url: &str, options: &[(&str, toml::Value)]) -> ChatClient {
    let mut o = toml::Table::new();
    o.insert("backoff_ms".into(), toml::Value::Integer(10));
    for (k, v) in options {
        o.insert(k.to_string(), v.clone());
    }
    let m = ModelConfig {
        base_url: Some(url.into()),
        model: Some("test".into()),
        api_key_env: None,
        max_in_flight: 4,
        rate_per_s: None,
        vision: false,
        options: o,
    };
    ChatClient::from_config("test", &m, None, None).unwrap()
}

fn hi() -> Vec<Message> {
    vec![Message::text("user", "hi")]
}

#[tokio::test]
async fn too_many_requests_waits_as_told_then_succeeds() {
    let (url, _) = serve(vec![
        Reply::Raw(429, vec![("retry-after", "1".into())], "slow down".into()),
        Reply::Content("ok".into()),
    ])
    .await;
    let t0 = Instant::now();
    let r = client(&url, &[]).chat("t", &hi(), None).await.unwrap();
    assert_eq!(r.content, "ok");
    assert_eq!(r.record.attempts, 2);
    assert!(
        t0.elapsed() >= Duration::from_millis(950),
        "honours Retry-After"
    );
    assert_eq!(
        (r.record.prompt_tokens, r.record.completion_tokens),
        (10, 5)
    );
}

#[tokio::test]
async fn a_server_error_is_retried_and_a_bad_request_is_not() {
    let (url, _) = serve(vec![
        Reply::Raw(500, vec![], "boom".into()),
        Reply::Content("ok".into()),
    ])
    .await;
    let r = client(&url, &[]).chat("t", &hi(), None).await.unwrap();
    assert_eq!(r.record.attempts, 2);

    let (url, script) = serve(vec![Reply::Raw(400, vec![], "bad schema".into())]).await;
    let (e, record) = client(&url, &[]).chat("t", &hi(), None).await.unwrap_err();
    assert!(matches!(e, LlmError::Status { status: 400, ref body, .. } if body == "bad schema"));
    assert_eq!(record.attempts, 1);
    assert_eq!(script.requests.lock().unwrap().len(), 1);
}

#[tokio::test]
async fn a_hang_times_out() {
    let (url, _) = serve(vec![Reply::Hang(Duration::from_secs(5))]).await;
    let c = client(
        &url,
        &[
            ("timeout_s", toml::Value::Float(0.3)),
            ("retries", toml::Value::Integer(0)),
        ],
    );
    let t0 = Instant::now();
    let (e, _) = c.chat("t", &hi(), None).await.unwrap_err();
    assert!(matches!(e, LlmError::Timeout { .. }), "{e}");
    assert!(t0.elapsed() < Duration::from_secs(3));
}

#[tokio::test]
async fn garbage_and_empty_choices_keep_the_raw_body() {
    let (url, _) = serve(vec![
        Reply::Raw(200, vec![], "<html>proxy error</html>".into()),
        Reply::Raw(200, vec![], r#"{"choices": []}"#.into()),
    ])
    .await;
    let c = client(&url, &[]);
    let (e, _) = c.chat("t", &hi(), None).await.unwrap_err();
    assert!(e.to_string().contains("<html>proxy error</html>"), "{e}");
    let (e, _) = c.chat("t", &hi(), None).await.unwrap_err();
    assert!(e.to_string().contains("`choices` is empty"), "{e}");
}

#[tokio::test]
async fn a_server_that_is_down_fails_the_preflight_clearly() {
    let c = client("http://127.0.0.1:9/v1", &[]);
    let e = c.preflight().await.unwrap_err();
    assert!(
        e.to_string()
            .starts_with("cannot reach http://127.0.0.1:9/v1/models"),
        "{e}"
    );
}

fn bedroom_request(url: &str, group: &[&str]) -> (VlmDesigner, DesignRequest) {
    let (scene, _) = disco_core::synth::bedroom();
    let designer = VlmDesigner::new(VlmBase {
        client: client(url, &[]),
        prompts: Prompts::default(),
    });
    let req = DesignRequest {
        ctx: SceneContext::new(Arc::new(scene), Arc::new(Plan::default())),
        group: group.iter().map(|s| s.to_string()).collect(),
        placed: Vec::new(),
        render: None,
    };
    (designer, req)
}

#[tokio::test]
async fn truncated_json_is_asked_again_with_the_reason() {
    let (url, script) = serve(vec![
        Reply::Content(r#"{"objects": [{"name": "bed-0", "posi"#.into()),
        Reply::Content(
            r#"```json
{"objects": [{"name": "bed-0", "position": [200, 105], "rotation": 0}]}
```"#
                .into(),
        ),
    ])
    .await;
    let (designer, req) = bedroom_request(&url, &["bed-0"]);
    let out = designer.design(&req).await.unwrap();
    assert_eq!(out.value.len(), 1);
    assert_eq!(out.value[0].position, [200.0, 105.0]);
    assert_eq!(out.usage.calls, 2);
    let requests = script.requests.lock().unwrap();
    let reask = requests[1]["messages"].as_array().unwrap().last().unwrap();
    assert!(
        reask["content"].as_str().unwrap().contains("cut short"),
        "{reask}"
    );
}

#[tokio::test]
async fn invented_repeated_and_nan_entries_are_refused_and_missing_objects_placed_by_rules() {
    let first = json!({"objects": [
        {"name": "Bed 0", "position": [200, 105], "rotation": 91},
        {"name": "bed-0", "position": [10, 10], "rotation": 0},
        {"name": "sofa-9", "position": [50, 50], "rotation": 0},
        {"name": "nightstand-0", "position": ["NaN", 20], "rotation": 0}
    ]});
    let (url, script) = serve(vec![
        Reply::Content(first.to_string()),
        // Asked for the nightstand again: still nothing usable, three times.
        Reply::Content(r#"{"objects": []}"#.into()),
        Reply::Content("I am sorry, I cannot help.".into()),
        Reply::Content(r#"{"objects": [{"name": "ghost", "position": [1, 1]}]}"#.into()),
    ])
    .await;
    let (designer, req) = bedroom_request(&url, &["bed-0", "nightstand-0"]);
    let out = designer.design(&req).await.unwrap();
    let names: Vec<&str> = out.value.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["bed-0", "nightstand-0"]);
    assert_eq!(out.value[0].rotation, 90.0, "rotation snapped");
    assert_eq!(out.usage.calls, 4);
    let notes = out.notes.join("\n");
    assert!(notes.contains("\"sofa-9\""), "{notes}");
    assert!(
        notes.contains("no usable position for \"nightstand-0\""),
        "{notes}"
    );
    assert!(
        notes.contains("the model did not place nightstand-0; the rules designer placed them"),
        "{notes}"
    );
    // The second request asked only for what was missing.
    let requests = script.requests.lock().unwrap();
    let enum_names = &requests[1]["response_format"]["json_schema"]["schema"]["properties"]["objects"]
        ["items"]["properties"]["name"]["enum"];
    assert_eq!(enum_names, &json!(["nightstand-0"]));
}

/// A VLM evaluator over `url` with `options`, and a request about the synthetic bedroom.
fn bedroom_evaluation(url: &str, options: &[(&str, &str)]) -> (VlmEvaluator, EvalRequest) {
    let (scene, layout) = disco_core::synth::bedroom();
    let mut table = toml::Table::new();
    for (k, v) in options {
        table.insert((*k).into(), toml::Value::String((*v).into()));
    }
    let evaluator = VlmEvaluator::new(
        VlmBase {
            client: client(url, &[]),
            prompts: Prompts::default(),
        },
        &table,
    )
    .unwrap();
    let req = EvalRequest {
        ctx: SceneContext::new(Arc::new(scene), Arc::clone(&layout.plan)),
        layout,
        group: vec![],
        render: None,
    };
    (evaluator, req)
}

/// `subject` `relation` `target` as a question.
fn relation_question(id: usize, subject: &str, relation: Relation, target: &str) -> Question {
    Question {
        id,
        text: format!(
            "Is it true that {subject} is {} {target}?",
            relation.words()
        ),
        subject: Some(subject.into()),
        constraint: Some(ConstraintKind::Relation {
            relation,
            target: target.into(),
        }),
    }
}

#[tokio::test]
async fn unanswered_questions_get_the_geometric_answer() {
    let (url, _) = serve(vec![
        // Batch: one answer for an unknown id, one good.
        Reply::Content(
            r#"{"answers": [{"id": 7, "answer": "yes", "reason": ""}, {"id": 0, "answer": "No.", "reason": "far"}]}"#
                .into(),
        ),
    ])
    .await;
    let (evaluator, req) = bedroom_evaluation(&url, &[("ask", "all")]);
    let open = Question {
        id: 0,
        text: "Does the bedroom look right?".into(),
        subject: None,
        constraint: None,
    };
    let wall = Question {
        id: 1,
        text: "question 1".into(),
        subject: Some("bed-0".into()),
        constraint: Some(ConstraintKind::AgainstWall),
    };
    let out = evaluator.answer(&req, &[open, wall]).await.unwrap();
    assert_eq!(out.value.len(), 2);
    assert!(!out.value[0].yes, "the model's own answer is kept");
    assert_eq!(out.value[1].id, 1);
    assert!(
        out.notes[0].contains("geometry answered"),
        "{:?}",
        out.notes
    );
}

/// By default a question the metric's predicate settles is not sent: the geometry answers it
/// with the measured values, and no model call is made (the physical verdict included).
#[tokio::test]
async fn questions_the_geometry_settles_are_not_sent() {
    let (url, script) = serve(vec![]).await;
    let (evaluator, req) = bedroom_evaluation(&url, &[]);
    let questions = [
        relation_question(0, "wardrobe-0", Relation::Near, "bed-0"),
        relation_question(1, "nightstand-0", Relation::SideOf, "bed-0"),
    ];
    let out = evaluator.answer(&req, &questions).await.unwrap();
    let physical = evaluator.needs_physical(&req).await.unwrap();
    assert_eq!(script.requests.lock().unwrap().len(), 0, "nothing sent");
    assert_eq!(out.usage.calls + physical.usage.calls, 0);
    assert!(!out.value[0].yes, "the wardrobe's gap to the bed is 60 cm");
    assert_eq!(out.value[0].reason, "no: measured: gap 60 cm");
    assert!(out.value[1].yes, "{}", out.value[1].reason);
    assert!(!physical.value, "the synthetic bedroom is valid");
}

/// With `ask = "all"` every question goes out stating the predicate and the measured values; an
/// answer that contradicts the geometry is noted and the geometry's answer counts.
#[tokio::test]
async fn a_verdict_contradicting_the_geometry_is_noted_and_the_geometry_counts() {
    let (url, script) = serve(vec![Reply::Content(
        r#"{"answers": [{"id": 0, "answer": "yes", "reason": "it is close enough"}, {"id": 1, "answer": "yes", "reason": "right beside"}]}"#
            .into(),
    )])
    .await;
    let (evaluator, req) = bedroom_evaluation(&url, &[("ask", "all")]);
    let questions = [
        relation_question(0, "wardrobe-0", Relation::Near, "bed-0"),
        relation_question(1, "nightstand-0", Relation::SideOf, "bed-0"),
    ];
    let out = evaluator.answer(&req, &questions).await.unwrap();
    assert!(!out.value[0].yes, "the geometry's no counts");
    assert!(
        out.value[0]
            .reason
            .contains("the model said yes (it is close enough)")
            && out.value[0].reason.contains("gap 60 cm"),
        "{}",
        out.value[0].reason
    );
    assert!(out.value[1].yes);
    assert_eq!(out.notes.len(), 1, "{:?}", out.notes);
    assert!(
        out.notes[0]
            .contains("the model answered yes to \"Is it true that wardrobe-0 is near bed-0?\""),
        "{:?}",
        out.notes
    );
    let requests = script.requests.lock().unwrap();
    let user = requests[0]["messages"].as_array().unwrap().last().unwrap()["content"].to_string();
    assert!(user.contains("at most 50 cm"), "{user}");
    assert!(
        user.contains("Measured on this layout: gap 60 cm."),
        "{user}"
    );
}

#[tokio::test]
async fn an_endless_body_is_an_unusable_answer_not_an_abort() {
    let (url, _) = serve(vec![Reply::Endless]).await;
    let t0 = Instant::now();
    let (e, _) = client(&url, &[("retries", toml::Value::Integer(0))])
        .chat("t", &hi(), None)
        .await
        .unwrap_err();
    assert!(
        matches!(&e, LlmError::Malformed { reason, .. } if reason.contains("over 8 MiB")),
        "{e}"
    );
    assert!(t0.elapsed() < Duration::from_secs(30));
}

#[tokio::test]
async fn a_body_cut_short_is_not_called_unreachable() {
    let (url, _) = serve(vec![Reply::Cut]).await;
    let (e, _) = client(&url, &[("retries", toml::Value::Integer(0))])
        .chat("t", &hi(), None)
        .await
        .unwrap_err();
    assert!(
        matches!(&e, LlmError::Malformed { reason, .. } if reason.contains("cut off")),
        "{e}"
    );
    assert!(!e.to_string().contains("cannot reach"), "{e}");
}

#[tokio::test]
async fn a_trickling_body_ends_at_the_request_timeout() {
    let (url, _) = serve(vec![Reply::Trickle]).await;
    let t0 = Instant::now();
    let (e, _) = client(
        &url,
        &[
            ("retries", toml::Value::Integer(0)),
            ("timeout_s", toml::Value::Float(1.0)),
        ],
    )
    .chat("t", &hi(), None)
    .await
    .unwrap_err();
    let waited = t0.elapsed();
    assert!(waited >= Duration::from_millis(900), "{waited:?}: {e}");
    assert!(waited < Duration::from_secs(10), "{waited:?}: {e}");
    assert!(e.to_string().contains("did not answer within 1 s"), "{e}");
}

#[tokio::test]
async fn a_redirect_loop_is_a_clear_error_not_a_hang() {
    let (url, script) = serve(vec![Reply::RedirectLoop]).await;
    let t0 = Instant::now();
    let (e, _) = client(&url, &[("retries", toml::Value::Integer(0))])
        .chat("t", &hi(), None)
        .await
        .unwrap_err();
    assert!(t0.elapsed() < Duration::from_secs(10));
    assert!(e.to_string().contains("redirect"), "{e}");
    // The loop is cut after a bounded number of hops.
    assert!(script.requests.lock().unwrap().len() <= 11);
}

#[tokio::test]
async fn a_key_refused_mid_run_is_the_model_servers_failure() {
    // The first call is answered, the second refused: the designer reports a model-server
    // failure (the runtime falls back and the CLI exits 3), not an unusable answer to re-ask.
    let (url, _) = serve(vec![
        Reply::Content(
            r#"{"objects": [{"name": "bed-0", "position": [200, 105], "rotation": 0}]}"#.into(),
        ),
        Reply::Raw(401, vec![], "invalid api key".into()),
    ])
    .await;
    let (designer, req) = bedroom_request(&url, &["bed-0"]);
    assert!(designer.design(&req).await.is_ok());
    let e = designer.design(&req).await.unwrap_err();
    assert!(e.is_model_server(), "{e}");
    assert!(e.to_string().contains("401"), "{e}");
}

/// A prompt-only stage (`impl = "vlm"`, role patch): its template file is the whole prompt, and
/// the model's moves come back only for the stage's group; a name outside it is refused.
#[tokio::test]
async fn a_prompt_only_stage_renders_its_own_template_and_moves_only_its_group() {
    let template = std::env::temp_dir().join(format!("disco-critic-{}.j2", std::process::id()));
    std::fs::write(
        &template,
        "Free the walkways. Move only: {{ group | join(', ') }}.",
    )
    .unwrap();
    let (url, script) = serve(vec![Reply::Content(
        r#"{"objects": [{"name": "bed-0", "position": [210, 110], "rotation": 0},
                        {"name": "wardrobe-0", "position": [50, 50], "rotation": 90}]}"#
            .into(),
    )])
    .await;
    let stage = crate::vlm::VlmPatch::new(
        VlmBase {
            client: client(&url, &[]),
            prompts: Prompts::default()
                .with_file(crate::vlm::patch::TEMPLATE, &template)
                .unwrap(),
        },
        "critic",
    );
    let (scene, layout) = disco_core::synth::bedroom();
    let req = disco_core::roles::PatchRequest {
        ctx: SceneContext::new(Arc::new(scene), Arc::new(Plan::default())),
        layout,
        group: vec!["bed-0".into()],
    };
    let out = disco_core::roles::Patcher::patch(&stage, &req)
        .await
        .unwrap();
    std::fs::remove_file(&template).ok();
    assert_eq!(out.value.len(), 1, "only the group moves: {:?}", out.value);
    assert_eq!(out.value[0].name, "bed-0");
    assert_eq!(out.value[0].position, [210.0, 110.0]);
    let requests = script.requests.lock().unwrap();
    let user = requests[0]["messages"].as_array().unwrap().last().unwrap();
    assert!(
        user["content"]
            .to_string()
            .contains("Free the walkways. Move only: bed-0."),
        "{user}"
    );
}
