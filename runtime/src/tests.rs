//! The runtime's tests: supervision (panics, failures, hangs), fallbacks, concurrency through the
//! gateway, parallel evaluation, ablations and custom stages — each asserted on the result and
//! the trace.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use async_trait::async_trait;

use super::{Runtime, SceneFailure};
use crate::config::{AgentId, GraphConfig};
use crate::registry::{BuildError, Registry};
use crate::supervisor::caller::SwapError;
use crate::trace::{Trace, TraceEvent, TraceKind};
use disco_agents::rules::{RuleDesigner, RuleEvaluator};
use disco_core::error::Error;
use disco_core::layout::{Dropped, Layout, PlacedObject};
use disco_core::metrics::measure;
use disco_core::roles::{
    Answer, DesignRequest, Designer, EvalRequest, Evaluator, Move, Output, PhysicalRefinerRole,
    PrtRequest, Question, Refined, RoleError, RoleImpl, RoleKind, RoleResult, SemanticRefiner,
    SrtRequest,
};
use disco_core::scene::SceneSpec;
use disco_core::synth;

mod off_floor;

fn bedroom() -> SceneSpec {
    synth::bedroom().0
}

fn graph(extra: &[&str]) -> GraphConfig {
    let sets: Vec<String> = extra.iter().map(|s| s.to_string()).collect();
    GraphConfig::load(None, &sets).unwrap()
}

fn events_of<'a>(events: &'a [TraceEvent], role: &str, kind: TraceKind) -> Vec<&'a TraceEvent> {
    events
        .iter()
        .filter(|e| e.role == role && e.kind == kind)
        .collect()
}

fn assert_complete(scene: &SceneSpec, layout: &Layout) {
    let m = measure(layout);
    assert_eq!(m.collision_pct, 0.0, "{:?}", m.colliding_pairs);
    assert_eq!(m.oob_pct, 0.0);
    let mut names: Vec<&str> = layout
        .objects
        .iter()
        .map(|o| o.name.as_str())
        .chain(layout.dropped.iter().map(|d| d.name.as_str()))
        .collect();
    names.sort_unstable();
    let mut expected: Vec<&str> = scene.assets.iter().map(|a| a.name.as_str()).collect();
    expected.sort_unstable();
    assert_eq!(names, expected, "every asset exactly once");
}

async fn run(
    graph: GraphConfig,
    registry: Registry,
    scene: SceneSpec,
) -> (Result<Layout, Error>, Vec<TraceEvent>) {
    let rt = Runtime::new(graph, registry).unwrap();
    let trace = Arc::new(Trace::default());
    let result = rt.generate(scene, Arc::clone(&trace)).await;
    (result, trace.events())
}

/// A designer that misbehaves as told, then (optionally) behaves like the rules.
struct Faulty {
    mode: Fault,
    tripped: Arc<AtomicBool>,
}

#[derive(Clone, Copy)]
enum Fault {
    PanicOnce,
    AlwaysFail,
    ServerDown,
    Hang,
}

#[async_trait]
impl Designer for Faulty {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        match self.mode {
            Fault::PanicOnce if !self.tripped.swap(true, Ordering::SeqCst) => {
                panic!("designer test double panics on its first call")
            }
            Fault::AlwaysFail => {
                return Err(RoleError::Failed("the test double always fails".into()));
            }
            Fault::ServerDown => {
                return Err(RoleError::ModelServer {
                    model: "test".into(),
                    reason: "cannot reach http://127.0.0.1:9/v1/chat/completions".into(),
                });
            }
            Fault::Hang => {
                tokio::time::sleep(Duration::from_secs(3600)).await;
            }
            _ => {}
        }
        RuleDesigner::new().design(req).await
    }
}

fn with_faulty(mode: Fault) -> Registry {
    let mut r = Registry::builtin();
    let tripped = Arc::new(AtomicBool::new(false));
    r.register(RoleKind::Designer, "faulty", move |_| {
        Ok(RoleImpl::Designer(Arc::new(Faulty {
            mode,
            tripped: Arc::clone(&tripped),
        })))
    });
    r
}

#[tokio::test]
async fn the_default_graph_furnishes_a_room_and_traces_every_role() {
    let scene = bedroom();
    let (result, events) = run(graph(&[]), Registry::builtin(), scene.clone()).await;
    let layout = result.unwrap();
    assert_complete(&scene, &layout);
    assert!(layout.dropped.is_empty());
    assert_eq!(events_of(&events, "planner", TraceKind::Reply).len(), 1);
    let groups = layout.plan.groups.len();
    assert_eq!(
        events_of(&events, "designer", TraceKind::Request).len(),
        groups
    );
    assert!(events_of(&events, "evaluator", TraceKind::Reply).len() >= groups);
    assert!(events.iter().all(|e| e.scene == scene.id));
    // Replies carry what the role decided.
    let design = events_of(&events, "designer", TraceKind::Reply)[0];
    assert!(
        design.detail["poses"]
            .as_array()
            .is_some_and(|p| !p.is_empty())
    );
    assert!(design.ms.is_some());
}

#[tokio::test]
async fn a_role_that_panics_is_restarted_and_the_scene_completes() {
    let scene = bedroom();
    let (result, events) = run(
        graph(&["agents.designer.impl=faulty"]),
        with_faulty(Fault::PanicOnce),
        scene.clone(),
    )
    .await;
    let layout = result.unwrap();
    assert_complete(&scene, &layout);
    assert_eq!(layout.stats.restarts, 1);
    assert!(
        layout.stats.fallbacks.is_empty(),
        "a retry sufficed: {:?}",
        layout.stats.fallbacks
    );
    let errors = events_of(&events, "designer", TraceKind::Error);
    assert!(
        errors[0]
            .detail
            .as_str()
            .unwrap()
            .contains("panicked: designer test double panics"),
        "{:?}",
        errors[0]
    );
    assert_eq!(events_of(&events, "designer", TraceKind::Restart).len(), 1);
}

#[tokio::test]
async fn a_role_that_always_fails_is_replaced_by_its_fallback() {
    let scene = bedroom();
    let g = graph(&[
        "agents.designer.impl=faulty",
        "agents.designer.fallback=rules",
        "agents.designer.retries=2",
    ]);
    let (result, events) = run(g, with_faulty(Fault::AlwaysFail), scene.clone()).await;
    let layout = result.unwrap();
    assert_complete(&scene, &layout);
    assert_eq!(layout.stats.fallbacks.len(), 1);
    assert!(
        layout.stats.fallbacks[0].starts_with("designer: faulty -> rules after 3 tries"),
        "{:?}",
        layout.stats.fallbacks
    );
    assert_eq!(events_of(&events, "designer", TraceKind::Error).len(), 3);
    assert_eq!(events_of(&events, "designer", TraceKind::Fallback).len(), 1);
    // After the swap, the rules designer answers.
    let replies = events_of(&events, "designer", TraceKind::Reply);
    assert!(!replies.is_empty() && replies.iter().all(|e| e.implementation == "rules"));
}

#[tokio::test]
async fn a_model_server_that_fails_is_a_model_error_not_a_scene_error() {
    // With a fallback the layout is complete, and the stats say a model server failed.
    let g = graph(&[
        "agents.designer.impl=faulty",
        "agents.designer.fallback=rules",
        "agents.designer.retries=0",
    ]);
    let scene = bedroom();
    let (result, _) = run(g, with_faulty(Fault::ServerDown), scene.clone()).await;
    let layout = result.unwrap();
    assert_complete(&scene, &layout);
    assert_eq!(layout.stats.model_failures.len(), 1, "{:?}", layout.stats);
    assert!(layout.stats.model_failures[0].contains("cannot reach"));
    // Without one the scene fails with the model's error (the CLI's exit code 3).
    let g = graph(&["agents.designer.impl=faulty", "agents.designer.retries=0"]);
    let (result, _) = run(g, with_faulty(Fault::ServerDown), bedroom()).await;
    match result.unwrap_err() {
        Error::Model { name, reason } => {
            assert_eq!(name, "test");
            assert!(reason.contains("cannot reach"), "{reason}");
        }
        other => panic!("expected a model error, got {other:?}"),
    }
    // Any other failure stays a scene error.
    let g = graph(&["agents.designer.impl=faulty", "agents.designer.retries=0"]);
    let (result, _) = run(g, with_faulty(Fault::AlwaysFail), bedroom()).await;
    assert!(matches!(result.unwrap_err(), Error::Scene { .. }));
}

#[tokio::test]
async fn without_a_fallback_the_scene_fails_with_a_clear_error() {
    let g = graph(&["agents.designer.impl=faulty", "agents.designer.retries=1"]);
    let (result, _) = run(g, with_faulty(Fault::AlwaysFail), bedroom()).await;
    let err = result.unwrap_err();
    let e = err.to_string();
    assert_eq!(
        e,
        "scene bedroom-synth: the designer (faulty) failed after 2 tries: the test double always fails"
    );
    // The failure is kept typed inside the error, not flattened into its text.
    let Error::Scene { id, failure } = &err else {
        panic!("expected a scene error, got {err:?}");
    };
    assert_eq!(id, "bedroom-synth");
    assert_eq!(
        failure.downcast_ref::<SceneFailure>(),
        Some(&SceneFailure::RoleFailed {
            agent: AgentId::DESIGNER,
            implementation: "faulty".into(),
            tries: 2,
            source: RoleError::Failed("the test double always fails".into()),
        })
    );
    let source = std::error::Error::source(&err).map(|s| s.to_string());
    assert_eq!(source.as_deref(), e.strip_prefix("scene bedroom-synth: "));
}

#[tokio::test]
async fn a_fallback_that_cannot_be_built_fails_the_scene_with_the_registrys_typed_error() {
    // `vlm` without a `model` key: its factory refuses when the swap asks for it.
    let g = graph(&[
        "agents.designer.impl=faulty",
        "agents.designer.retries=0",
        "agents.designer.fallback=vlm",
    ]);
    let (result, _) = run(g, with_faulty(Fault::AlwaysFail), bedroom()).await;
    let err = result.unwrap_err();
    let Error::Scene { failure, .. } = &err else {
        panic!("expected a scene error, got {err:?}");
    };
    let Some(SceneFailure::FallbackFailed { fallback, why, .. }) =
        failure.downcast_ref::<SceneFailure>()
    else {
        panic!("expected a fallback failure, got {failure:?}");
    };
    assert_eq!(fallback, "vlm");
    let SwapError::Build(built) = why else {
        panic!("expected a build error, got {why:?}");
    };
    let BuildError::Factory {
        agent,
        implementation,
        reason,
    } = built.as_ref()
    else {
        panic!("expected a factory's refusal, got {why:?}");
    };
    assert_eq!(
        (agent, implementation.as_str()),
        (&AgentId::DESIGNER, "vlm")
    );
    assert!(reason.contains("needs `model"), "{reason}");
    assert!(
        err.to_string()
            .contains("could not start: agents.designer: cannot build \"vlm\": "),
        "{err}"
    );
}

#[tokio::test]
async fn a_scene_past_its_deadline_is_finished_by_fallbacks_not_lost() {
    let scene = bedroom();
    let g = graph(&[
        "agents.designer.impl=faulty",
        "agents.designer.deadline_s=3600",
        "agents.designer.fallback=rules",
        "run.scene_deadline_s=1",
    ]);
    let t0 = std::time::Instant::now();
    let (result, _) = run(g, with_faulty(Fault::Hang), scene.clone()).await;
    let layout = result.unwrap();
    assert!(t0.elapsed() < Duration::from_secs(10), "{:?}", t0.elapsed());
    assert_complete(&scene, &layout);
    assert!(layout.stats.deadline_missed);
    assert!(layout.dropped.is_empty(), "{:?}", layout.dropped);
    let m = measure(&layout);
    assert_eq!((m.collision_pct, m.oob_pct), (0.0, 0.0));
    assert!(
        layout
            .stats
            .fallbacks
            .iter()
            .any(|f| f.contains("designer: faulty -> rules")),
        "{:?}",
        layout.stats.fallbacks
    );
}

#[tokio::test]
async fn once_a_model_server_failed_its_other_agents_fall_back_at_once() {
    // Planner and designer share a (test) model; the planner's server fails, so the designer
    // goes to its fallback without a call of its own.
    let mut registry = with_faulty(Fault::AlwaysFail);
    registry.register(RoleKind::Planner, "faulty", |_| {
        Ok(RoleImpl::Planner(Arc::new(DownPlanner)))
    });
    let g = graph(&[
        "agents.planner.impl=faulty",
        "agents.planner.model=test",
        "agents.planner.retries=0",
        "agents.planner.fallback=rules",
        "agents.designer.impl=faulty",
        "agents.designer.model=test",
        "agents.designer.fallback=rules",
        "models.test.base_url=http://127.0.0.1:9/v1",
    ]);
    let scene = bedroom();
    let (result, events) = run(g, registry, scene.clone()).await;
    let layout = result.unwrap();
    assert_complete(&scene, &layout);
    assert!(
        events_of(&events, "designer", TraceKind::Request)
            .iter()
            .all(|e| e.implementation == "rules"),
        "the designer never asked the failed server"
    );
    assert!(
        layout
            .stats
            .fallbacks
            .iter()
            .any(|f| f
                .starts_with("designer: faulty -> rules (model server \"test\" already failed")),
        "{:?}",
        layout.stats.fallbacks
    );
    assert_eq!(layout.stats.model_failures.len(), 1);
}

/// A planner whose model server is down.
struct DownPlanner;

#[async_trait]
impl disco_core::roles::Planner for DownPlanner {
    async fn plan(&self, _: &SceneSpec) -> RoleResult<disco_core::plan::Plan> {
        Err(RoleError::ModelServer {
            model: "test".into(),
            reason: "down".into(),
        })
    }
}

#[tokio::test]
async fn a_role_that_hangs_is_cut_off_at_its_deadline() {
    let scene = bedroom();
    let g = graph(&[
        "agents.designer.impl=faulty",
        "agents.designer.deadline_s=0.2",
        "agents.designer.retries=1",
        "agents.designer.fallback=rules",
    ]);
    let t0 = std::time::Instant::now();
    let (result, events) = run(g, with_faulty(Fault::Hang), scene.clone()).await;
    let layout = result.unwrap();
    assert_complete(&scene, &layout);
    assert!(t0.elapsed() < Duration::from_secs(10), "{:?}", t0.elapsed());
    let timeouts = events_of(&events, "designer", TraceKind::Timeout);
    assert_eq!(timeouts.len(), 2);
    assert!(timeouts.iter().all(|e| e.ms.unwrap() >= 200.0));
    assert!(
        !events_of(&events, "designer", TraceKind::Restart).is_empty(),
        "the hung actor was restarted"
    );
    assert_eq!(layout.stats.fallbacks.len(), 1);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_hundred_scenes_share_one_bounded_gateway() {
    // A designer behind a fake model of 50 ms latency, 8 requests in flight at most.
    let rt = crate::simulated::simulated_model_runtime(Duration::from_millis(50), 8).unwrap();
    let trace = Arc::new(Trace::default());
    let scenes: Vec<SceneSpec> = (0..200)
        .map(|i| {
            let mut s = bedroom();
            s.id = format!("bedroom-{i}");
            s
        })
        .collect();
    let runs = scenes.into_iter().map(|s| {
        let rt = rt.clone();
        let trace = Arc::clone(&trace);
        async move { rt.generate(s, trace).await }
    });
    let results = futures::future::join_all(runs).await;
    assert_eq!(results.len(), 200);
    for r in &results {
        let layout = r.as_ref().unwrap();
        assert_eq!(layout.stats.llm_calls, layout.plan.groups.len() as u64);
        assert_eq!(
            layout.stats.prompt_tokens,
            100 * layout.plan.groups.len() as u64
        );
    }
    let gw = rt.gateways().get("fake").unwrap();
    assert_eq!(
        gw.peak_in_flight(),
        8,
        "the gateway was saturated but never exceeded"
    );
    assert_eq!(gw.in_flight(), 0);
}

/// An evaluator that counts how many of its calls run at once.
struct Counting {
    now: Arc<AtomicUsize>,
    peak: Arc<AtomicUsize>,
    calls: Arc<AtomicUsize>,
}

#[async_trait]
impl Evaluator for Counting {
    async fn answer(&self, req: &EvalRequest, questions: &[Question]) -> RoleResult<Vec<Answer>> {
        self.calls.fetch_add(1, Ordering::SeqCst);
        let n = self.now.fetch_add(1, Ordering::SeqCst) + 1;
        self.peak.fetch_max(n, Ordering::SeqCst);
        tokio::time::sleep(Duration::from_millis(20)).await;
        self.now.fetch_sub(1, Ordering::SeqCst);
        RuleEvaluator.answer(req, questions).await
    }
    async fn needs_physical(&self, req: &EvalRequest) -> RoleResult<bool> {
        RuleEvaluator.needs_physical(req).await
    }
}

async fn evaluator_concurrency(sets: &[&str]) -> (usize, usize, usize) {
    let (now, peak, calls) = (
        Arc::new(AtomicUsize::new(0)),
        Arc::new(AtomicUsize::new(0)),
        Arc::new(AtomicUsize::new(0)),
    );
    let mut registry = Registry::builtin();
    let (p, c, n) = (Arc::clone(&peak), Arc::clone(&calls), Arc::clone(&now));
    registry.register(RoleKind::Evaluator, "counting", move |_| {
        Ok(RoleImpl::Evaluator(Arc::new(Counting {
            now: Arc::clone(&n),
            peak: Arc::clone(&p),
            calls: Arc::clone(&c),
        })))
    });
    let mut all = vec!["agents.evaluator.impl=counting"];
    all.extend(sets);
    // A dining room: one group with six chairs, two questions each.
    let scene = SceneSpec::from_json(
        Path::new("dining.json"),
        include_str!("../../examples/scenes/dining-room.json"),
    )
    .unwrap();
    let (result, events) = run(graph(&all), registry, scene).await;
    result.unwrap();
    let questions: usize = events_of(&events, "evaluator", TraceKind::Request)
        .iter()
        .map(|e| e.detail["questions"].as_array().map_or(0, Vec::len))
        .sum();
    (
        peak.load(Ordering::SeqCst),
        calls.load(Ordering::SeqCst),
        questions,
    )
}

#[tokio::test]
async fn evaluator_questions_go_out_in_parallel_up_to_the_width() {
    let (peak, calls, questions) = evaluator_concurrency(&["agents.evaluator.width=3"]).await;
    assert_eq!(peak, 3);
    assert_eq!(calls, questions, "one call per question");
    let (peak, calls, questions) =
        evaluator_concurrency(&["agents.evaluator.mode=\"batch\""]).await;
    assert_eq!(peak, 1);
    assert!(
        calls < questions,
        "batched: {calls} calls for {questions} questions"
    );
}

async fn ablation(file: &str) -> (Layout, Vec<TraceEvent>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(file);
    let g = GraphConfig::load(Some(&path), &["agents.designer.impl=noisy".into()]).unwrap();
    let scene = SceneSpec::from_json(
        Path::new("living.json"),
        include_str!("../../examples/scenes/living-room.json"),
    )
    .unwrap();
    let (result, events) = run(g, Registry::builtin(), scene).await;
    (result.unwrap(), events)
}

#[tokio::test]
async fn each_ablation_really_removes_its_stage() {
    let (_, full) = ablation("config/default.toml").await;
    assert!(
        !events_of(&full, "srt", TraceKind::Request).is_empty(),
        "the noisy designer gives the SRT work"
    );
    assert!(!events_of(&full, "prt", TraceKind::Request).is_empty());

    let (_, no_srt) = ablation("config/ablations/no-srt.toml").await;
    assert!(events_of(&no_srt, "srt", TraceKind::Request).is_empty());
    assert!(!events_of(&no_srt, "prt", TraceKind::Request).is_empty());

    let (layout, no_prt) = ablation("config/ablations/no-prt.toml").await;
    assert!(events_of(&no_prt, "prt", TraceKind::Request).is_empty());
    assert!(!events_of(&no_prt, "srt", TraceKind::Request).is_empty());
    assert!(layout.stats.prt.is_none());

    let (_, none) = ablation("config/ablations/no-refine.toml").await;
    for role in ["evaluator", "srt", "prt"] {
        assert!(
            events_of(&none, role, TraceKind::Request).is_empty(),
            "{role}"
        );
    }

    let (_, open) = ablation("config/ablations/open-vqa.toml").await;
    let asks = events_of(&open, "evaluator", TraceKind::Request);
    assert!(!asks.is_empty());
    assert!(
        asks.iter()
            .all(|e| e.detail["questions"].as_array().unwrap().len() == 1)
    );
    assert!(
        asks.iter()
            .all(|e| e.detail["questions"][0]["subject"].is_null())
    );
}

async fn baseline(file: &str, scene: SceneSpec) -> (Layout, Vec<TraceEvent>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(file);
    let g = GraphConfig::load(Some(&path), &[]).unwrap();
    let (result, events) = run(g, Registry::builtin(), scene).await;
    (result.unwrap(), events)
}

fn living_room() -> SceneSpec {
    SceneSpec::from_json(
        Path::new("living.json"),
        include_str!("../../examples/scenes/living-room.json"),
    )
    .unwrap()
}

#[tokio::test]
async fn the_baselines_are_configs_one_design_call_and_no_refinement() {
    for file in [
        "config/baselines/layoutgpt.toml",
        "config/baselines/holodeck.toml",
    ] {
        let (layout, events) = baseline(file, living_room()).await;
        assert_eq!(
            events_of(&events, "designer", TraceKind::Request).len(),
            1,
            "{file}: the whole room in one designer call"
        );
        for role in ["evaluator", "srt", "prt"] {
            assert!(
                events_of(&events, role, TraceKind::Request).is_empty(),
                "{file}: {role}"
            );
        }
        assert!(layout.stats.prt.is_none(), "{file}");
    }
    // The grid search's hard constraints hold on their own; the noisy one-shot design does not.
    let (grid, _) = baseline("config/baselines/holodeck.toml", living_room()).await;
    assert_complete(&living_room(), &grid);
    let (noisy, _) = baseline("config/baselines/layoutgpt.toml", living_room()).await;
    let m = measure(&noisy);
    assert!(m.collision_pct > 0.0 || m.oob_pct > 0.0, "{m:?}");
}

#[tokio::test]
async fn without_a_prt_what_the_designer_cannot_place_is_dropped_with_its_reason() {
    let mut scene = living_room();
    let mut huge = scene.assets[0].clone();
    huge.name = "second sofa".into();
    huge.size = [scene.room.width - 10.0, scene.room.depth - 10.0, 80.0];
    scene.assets.push(huge);
    let (layout, _) = baseline("config/baselines/holodeck.toml", scene.clone()).await;
    assert_complete(&scene, &layout);
    let dropped = layout
        .dropped
        .iter()
        .find(|d| d.name == "second sofa")
        .unwrap();
    assert!(dropped.reason.contains("no PRT"), "{}", dropped.reason);
}

#[tokio::test]
async fn a_custom_stage_runs_in_the_loop() {
    let (layout, events) = ablation("config/experiments/clearance.toml").await;
    let asks = events_of(&events, "clearance", TraceKind::Request);
    assert!(!asks.is_empty(), "the clearance keeper was called");
    assert!(asks.iter().all(|e| e.implementation == "clearance"));
    assert!(!events_of(&events, "clearance", TraceKind::Reply).is_empty());
    assert_eq!(measure(&layout).collision_pct, 0.0);
}

#[test]
fn config_errors_name_the_file_line_and_key() {
    let g = graph(&["agents.designer.impl=vlmm"]);
    let e = Runtime::new(g, Registry::builtin())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains(
            "agents.designer.impl: unknown designer implementation \"vlmm\"; known: grid-search, http, noisy, process, rules, vlm; did you mean vlm?"
        ),
        "{e}"
    );
    assert!(e.starts_with("--set agents.designer.impl=vlmm: "), "{e}");
    let g = graph(&["agents.srt.fallback=magic"]);
    let e = Runtime::new(g, Registry::builtin())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("agents.srt.fallback: unknown srt implementation \"magic\""),
        "{e}"
    );
}

#[test]
fn a_call_sent_to_an_implementation_of_another_role_is_an_error_not_a_panic() {
    use crate::supervisor::messages::{PlanCall, RoleCall};
    let rt = tokio::runtime::Runtime::new().unwrap();
    let imp = RoleImpl::Evaluator(Arc::new(RuleEvaluator));
    let call = PlanCall(Arc::new(bedroom()));
    let err = rt.block_on(call.run(&imp)).unwrap_err();
    assert_eq!(
        err,
        RoleError::WrongRequest {
            role: RoleKind::Evaluator,
            request: "plan"
        }
    );
    assert_eq!(err.to_string(), "a evaluator cannot answer a plan request");
    let _ = Output::free(());
}

/// A planner with a fixed plan: the chair (group 1) faces the table (group 2).
struct ChairBeforeTable;

#[async_trait]
impl disco_core::roles::Planner for ChairBeforeTable {
    async fn plan(&self, _: &SceneSpec) -> RoleResult<disco_core::plan::Plan> {
        let mut plan = disco_core::plan::Plan::default();
        plan.constraints.insert(
            "chair-0".into(),
            disco_core::plan::ObjectConstraints {
                facing: Some("table-0".into()),
                ..Default::default()
            },
        );
        plan.groups = vec![vec!["chair-0".into()], vec!["table-0".into()]];
        Ok(Output::free(plan))
    }
}

#[tokio::test]
async fn a_constraint_is_asked_about_only_once_both_objects_are_placed() {
    let scene = SceneSpec {
        id: "defer".into(),
        prompt: "a chair at a table".into(),
        room_type: "dining room".into(),
        room: disco_core::scene::Room::rect(400.0, 400.0),
        assets: vec![
            disco_core::scene::Asset::new("chair-0", "chair", [45.0, 50.0, 90.0]),
            disco_core::scene::Asset::new("table-0", "table", [120.0, 80.0, 75.0]),
        ],
    };
    let mut registry = Registry::builtin();
    registry.register(RoleKind::Planner, "fixed", |_| {
        Ok(RoleImpl::Planner(Arc::new(ChairBeforeTable)))
    });
    let (result, events) = run(graph(&["agents.planner.impl=fixed"]), registry, scene).await;
    result.unwrap();
    let asked: Vec<String> = events_of(&events, "evaluator", TraceKind::Request)
        .iter()
        .map(|e| e.detail["questions"].to_string())
        .collect();
    assert!(asked.len() >= 2, "{asked:?}");
    // Group 1 (the chair alone): nothing about the absent table.
    assert!(!asked[0].contains("table-0"), "{}", asked[0]);
    // Group 2 (the table): the chair's deferred question comes now.
    assert!(
        asked
            .iter()
            .skip(1)
            .any(|q| q.contains("chair-0") && q.contains("table-0")),
        "{asked:?}"
    );
}

/// How a PRT test double lies (each as a broken or hostile external PRT was seen to).
#[derive(Clone, Copy, Debug)]
enum Lie {
    /// Every object at (-500, -500).
    FarAway,
    /// Every object at (1e308, 1e308).
    Huge,
    /// Every object both placed and dropped, and a ghost dropped.
    Both,
    /// Everything dropped with an empty reason.
    Silent,
    /// A ghost placed among the real objects.
    Ghost,
    /// Every object at the room's centre, on top of one another.
    Piled,
}

/// A PRT that answers as `Lie` says.
struct LyingPrt(Lie);

#[async_trait]
impl PhysicalRefinerRole for LyingPrt {
    async fn refine(&self, req: &PrtRequest) -> RoleResult<Refined> {
        let given = &req.layout.objects;
        let room = &req.ctx.scene.room;
        let at = |position: [f64; 2]| -> Vec<PlacedObject> {
            given
                .iter()
                .map(|o| PlacedObject {
                    position,
                    ..o.clone()
                })
                .collect()
        };
        let drops = |reason: &str| -> Vec<Dropped> {
            given
                .iter()
                .map(|o| Dropped {
                    name: o.name.clone(),
                    reason: reason.into(),
                })
                .collect()
        };
        let ghost = |o: &PlacedObject| PlacedObject {
            name: "ghost".into(),
            ..o.clone()
        };
        let (objects, dropped) = match self.0 {
            Lie::FarAway => (at([-500.0, -500.0]), Vec::new()),
            Lie::Huge => (at([1e308, 1e308]), Vec::new()),
            Lie::Both => {
                let mut dropped = drops("no room for it");
                dropped.push(Dropped {
                    name: "ghost".into(),
                    reason: "it is not there".into(),
                });
                (given.clone(), dropped)
            }
            Lie::Silent => (Vec::new(), drops("")),
            Lie::Ghost => {
                let mut objects = given.clone();
                objects.extend(given.first().map(ghost));
                (objects, Vec::new())
            }
            Lie::Piled => (at([room.width / 2.0, room.depth / 2.0]), Vec::new()),
        };
        let moves = objects
            .iter()
            .map(|o| Move {
                name: o.name.clone(),
                displacement_cm: 0.0,
                rotated: false,
            })
            .collect();
        Ok(Output::free(Refined {
            objects,
            dropped,
            moves,
            notes: Vec::new(),
        }))
    }
}

fn with_liar(lie: Lie) -> Registry {
    let mut r = Registry::builtin();
    r.register(RoleKind::Prt, "liar", move |_| {
        Ok(RoleImpl::Prt(Arc::new(LyingPrt(lie))))
    });
    r
}

/// The stats' entry saying the built-in grid PRT answered for the `prt` agent, if it did.
fn last_word(layout: &Layout) -> Option<&String> {
    layout
        .stats
        .fallbacks
        .iter()
        .find(|f| f.starts_with("prt: the built-in grid PRT answered instead"))
}

#[tokio::test]
async fn a_prt_whose_replies_lie_is_refused_and_the_built_in_prt_has_the_last_word() {
    let scene = bedroom();
    for lie in [
        Lie::FarAway,
        Lie::Huge,
        Lie::Both,
        Lie::Silent,
        Lie::Ghost,
        Lie::Piled,
    ] {
        let g = graph(&["agents.prt.impl=liar", "agents.prt.retries=1"]);
        let (result, events) = run(g, with_liar(lie), scene.clone()).await;
        let layout = result.unwrap();
        assert_complete(&scene, &layout);
        assert!(layout.dropped.is_empty(), "{lie:?}: {:?}", layout.dropped);
        let said = last_word(&layout).unwrap_or_else(|| panic!("{lie:?}: {:?}", layout.stats));
        assert!(
            said.contains("the prt (liar) failed after 2 tries: its reply was refused: "),
            "{lie:?}: {said}"
        );
        // Refused twice (a try and its retry), then never asked again in this scene.
        let refusals = events_of(&events, "prt", TraceKind::Error)
            .into_iter()
            .filter(|e| e.detail.as_str().unwrap().contains("its reply was refused"))
            .count();
        assert_eq!(refusals, 2, "{lie:?}");
        assert_eq!(
            events_of(&events, "prt", TraceKind::Request).len(),
            2,
            "{lie:?}"
        );
        assert!(layout.stats.prt.is_some());
    }
}

#[tokio::test]
async fn a_refused_prt_reply_goes_to_the_fallback_first() {
    let scene = bedroom();
    let g = graph(&[
        "agents.prt.impl=liar",
        "agents.prt.retries=0",
        "agents.prt.fallback=grid",
    ]);
    let (result, _) = run(g, with_liar(Lie::FarAway), scene.clone()).await;
    let layout = result.unwrap();
    assert_complete(&scene, &layout);
    assert_eq!(
        layout.stats.fallbacks.len(),
        1,
        "{:?}",
        layout.stats.fallbacks
    );
    assert!(
        layout.stats.fallbacks[0].starts_with(
            "prt: liar -> grid after 1 tries (its reply was refused: \"bed-0\" at [-500, -500] is far outside"
        ),
        "{:?}",
        layout.stats.fallbacks
    );
    assert!(last_word(&layout).is_none());
}

/// An external PRT (a `process` agent) that places everything at (-500, -500) (`far`), or lists
/// every object as placed and as dropped without a reason, plus a dropped ghost (`both`).
const LYING_PRT: &str = r#"
import json, sys
mode = sys.argv[1]
for line in sys.stdin:
    req = json.loads(line)
    objects = req["request"]["layout"]["objects"]
    poses = [{"name": o["name"], "position": o["position"], "rotation": o["rotation"]} for o in objects]
    if mode == "far":
        reply = {"objects": [dict(p, position=[-500, -500]) for p in poses]}
    else:
        dropped = [{"name": o["name"], "reason": ""} for o in objects]
        reply = {"objects": poses, "dropped": dropped + [{"name": "ghost", "reason": "boo"}]}
    print(json.dumps({"protocol": 1, "id": req["id"], "reply": reply}), flush=True)
"#;

#[tokio::test]
async fn an_external_prt_that_lies_is_refused_and_the_layout_stays_valid() {
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("lying_prt.py");
    std::fs::write(&script, LYING_PRT).unwrap();
    let scene = bedroom();
    for (mode, why) in [
        ("far", "at [-500, -500] is far outside"),
        ("both", "is both placed and dropped"),
    ] {
        let command = format!(
            "agents.prt.command=[\"python3\", {:?}, \"{mode}\"]",
            script.to_string_lossy()
        );
        let g = graph(&["agents.prt.impl=process", &command, "agents.prt.retries=0"]);
        let (result, _) = run(g, Registry::builtin(), scene.clone()).await;
        let layout = result.unwrap();
        assert_complete(&scene, &layout);
        let said = last_word(&layout).unwrap_or_else(|| panic!("{mode}: {:?}", layout.stats));
        assert!(said.contains(why), "{mode}: {said}");
    }
}

/// An SRT with nothing to move.
struct Content;

#[async_trait]
impl SemanticRefiner for Content {
    async fn refine(&self, _: &SrtRequest) -> RoleResult<Vec<PlacedObject>> {
        Ok(Output::free(Vec::new()))
    }
}

#[tokio::test]
async fn an_empty_move_list_is_a_valid_reply() {
    let mut registry = Registry::builtin();
    registry.register(RoleKind::Srt, "content", |_| {
        Ok(RoleImpl::Srt(Arc::new(Content)))
    });
    let g = GraphConfig::load(
        Some(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../config/default.toml")),
        &[
            "agents.designer.impl=noisy".into(),
            "agents.srt.impl=content".into(),
            "agents.srt.retries=0".into(),
        ],
    )
    .unwrap();
    let (result, events) = run(g, registry, living_room()).await;
    let layout = result.unwrap();
    assert!(
        !events_of(&events, "srt", TraceKind::Reply).is_empty(),
        "the noisy designer gives the SRT work"
    );
    assert!(events_of(&events, "srt", TraceKind::Error).is_empty());
    assert!(
        layout.stats.fallbacks.is_empty(),
        "{:?}",
        layout.stats.fallbacks
    );
}

#[tokio::test]
async fn absurd_deadlines_mean_no_deadline_not_a_panic() {
    // However they got into the graph (the parser bounds them too), 1e300 seconds and NaN do not
    // panic the loop or a worker.
    let mut g = graph(&[]);
    g.run.scene_deadline_s = 1e300;
    g.run.restart_window_s = f64::NAN;
    for agent in g.agents.values_mut() {
        agent.config.deadline_s = 1e300;
    }
    let scene = bedroom();
    let (result, _) = run(g, Registry::builtin(), scene.clone()).await;
    let layout = result.unwrap();
    assert_complete(&scene, &layout);
    assert!(!layout.stats.deadline_missed);
    assert_eq!(
        crate::supervisor::scene_loop::seconds(1e300),
        crate::supervisor::scene_loop::LONGEST_WAIT
    );
    assert_eq!(crate::supervisor::scene_loop::seconds(-1.0), Duration::ZERO);
}

#[test]
fn a_plan_with_endless_repeats_is_bounded_by_the_scene() {
    use disco_core::plan::{ObjectConstraints, Plan, Relation, RelationSpec};
    let scene = bedroom();
    let mut plan = Plan::default();
    let near_desk = RelationSpec {
        relation: Relation::Near,
        target: "desk-0".into(),
    };
    plan.constraints.insert(
        "chair-0".into(),
        ObjectConstraints {
            relations: vec![near_desk; 100_000],
            ..Default::default()
        },
    );
    plan.groups = vec![vec!["chair-0".to_string(); 100_000]];
    let mut notes = Vec::new();
    let (plan, _) = crate::supervisor::scene_loop::sanitize_plan(&scene, plan, &mut notes);
    assert_eq!(plan.constraints["chair-0"].relations.len(), 1);
    assert!(
        notes.contains(&"plan: ignored 99999 repeated relations".to_string()),
        "{notes:?}"
    );
    assert_eq!(plan.groups.concat().len(), scene.assets.len());
}
