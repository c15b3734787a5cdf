//! The typed messages between the scene supervisor and the role actors, and how a request is
//! carried out on a role implementation (including the evaluator's parallel fan-out).

use std::sync::Arc;

use futures::StreamExt;
use serde_json::{Value, json};

use disco_core::layout::PlacedObject;
use disco_core::plan::Plan;
use disco_core::roles::{
    Answer, DesignRequest, EvalRequest, Evaluation, Output, PatchRequest, PrtRequest, Question,
    RoleError, RoleImpl, SrtRequest,
};
use disco_core::roles::{Refined, RoleKind};
use disco_core::scene::SceneSpec;

/// How the evaluator's questions go out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EvalMode {
    /// One call per question, at most `width` at once.
    Parallel {
        /// Questions in flight at once.
        width: usize,
    },
    /// All questions in one call.
    Batch,
}

/// A request to a role.
#[derive(Debug, Clone)]
pub enum RoleRequest {
    /// Plan the scene.
    Plan(Arc<SceneSpec>),
    /// Pose a group.
    Design(DesignRequest),
    /// Answer questions and give the physical verdict.
    Evaluate(EvalRequest, Vec<Question>, EvalMode),
    /// Fix failed questions.
    Srt(SrtRequest),
    /// Make the layout physically valid.
    Prt(PrtRequest),
    /// Run a custom stage.
    Patch(PatchRequest),
}

/// A role's answer, matching its request.
#[derive(Debug, Clone)]
pub enum RoleReply {
    /// The plan.
    Plan(Plan),
    /// Poses for the group.
    Design(Vec<PlacedObject>),
    /// Answers and verdict.
    Evaluate(Evaluation),
    /// Moved objects.
    Srt(Vec<PlacedObject>),
    /// The refined layout.
    Prt(Refined),
    /// Moved objects.
    Patch(Vec<PlacedObject>),
}

fn poses(objects: &[PlacedObject]) -> Value {
    objects
        .iter()
        .map(|o| json!({"name": o.name, "position": o.position, "rotation": o.rotation}))
        .collect()
}

impl RoleRequest {
    /// The request in brief, for the trace (renders are left out).
    pub fn summary(&self) -> Value {
        match self {
            RoleRequest::Plan(scene) => json!({"scene": scene.id, "assets": scene.assets.len()}),
            RoleRequest::Design(r) => json!({"group": r.group, "placed": r.placed.len()}),
            RoleRequest::Evaluate(r, q, _) => json!({"group": r.group, "questions": q}),
            RoleRequest::Srt(r) => {
                json!({"failed": r.failed.iter().map(|(q, a)| json!({"question": q.text, "reason": a.reason})).collect::<Vec<_>>()})
            }
            RoleRequest::Prt(r) => {
                json!({"objects": r.layout.objects.len(), "settled": r.settled.len()})
            }
            RoleRequest::Patch(r) => json!({"group": r.group}),
        }
    }
}

impl RoleReply {
    /// The reply in brief, for the trace: what the role said and decided.
    pub fn summary(&self) -> Value {
        match self {
            RoleReply::Plan(p) => serde_json::to_value(p).unwrap_or(Value::Null),
            RoleReply::Design(o) | RoleReply::Srt(o) | RoleReply::Patch(o) => {
                json!({"poses": poses(o)})
            }
            RoleReply::Evaluate(e) => serde_json::to_value(e).unwrap_or(Value::Null),
            RoleReply::Prt(r) => {
                // The poses of what moved only (all, when the refiner did not say): the reply holds the
                // whole layout, and a big scene has one per group.
                let moved: Vec<PlacedObject> = match r.moves.len() == r.objects.len() {
                    true => r
                        .objects
                        .iter()
                        .zip(&r.moves)
                        .filter(|(o, m)| o.name == m.name && (m.displacement_cm > 0.0 || m.rotated))
                        .map(|(o, _)| o.clone())
                        .collect(),
                    false => r.objects.clone(),
                };
                json!({"objects": r.objects.len(), "poses": poses(&moved), "dropped": r.dropped, "notes": r.notes})
            }
        }
    }
}

/// A request of the role protocol, bound by type to the reply it expects: the scene loop sends a
/// `RoleCall` and gets back exactly its `Reply`, or an error. A role that answers with another
/// kind of reply has failed, wherever in the loop it happens (retried, then the fallback).
pub trait RoleCall: Clone + Send + 'static {
    /// What the role answers.
    type Reply: Send + 'static;
    /// The role that answers this request.
    const ROLE: RoleKind;
    /// The request as a message to a role actor.
    fn into_request(self) -> RoleRequest;
    /// The typed reply, or [`RoleError::WrongReply`] when the role answered something else.
    fn from_reply(reply: RoleReply) -> Result<Self::Reply, RoleError>;
}

/// Plan the scene.
#[derive(Debug, Clone)]
pub struct PlanCall(pub Arc<SceneSpec>);

/// Answer questions and give the physical verdict.
#[derive(Debug, Clone)]
pub struct EvaluateCall {
    /// What the evaluator looks at.
    pub request: EvalRequest,
    /// The questions to answer.
    pub questions: Vec<Question>,
    /// How the questions go out.
    pub mode: EvalMode,
}

/// Binds one request type to its [`RoleRequest`] and [`RoleReply`] variants.
macro_rules! role_call {
    ($call:ty, $role:ident, $reply:ty, |$c:ident| $request:expr, $variant:ident) => {
        impl RoleCall for $call {
            type Reply = $reply;
            const ROLE: RoleKind = RoleKind::$role;
            fn into_request(self) -> RoleRequest {
                let $c = self;
                $request
            }
            fn from_reply(reply: RoleReply) -> Result<$reply, RoleError> {
                match reply {
                    RoleReply::$variant(value) => Ok(value),
                    other => Err(RoleError::WrongReply {
                        expected: stringify!($variant),
                        got: other.kind_name(),
                    }),
                }
            }
        }
    };
}

role_call!(PlanCall, Planner, Plan, |c| RoleRequest::Plan(c.0), Plan);
role_call!(
    DesignRequest,
    Designer,
    Vec<PlacedObject>,
    |c| RoleRequest::Design(c),
    Design
);
role_call!(
    EvaluateCall,
    Evaluator,
    Evaluation,
    |c| RoleRequest::Evaluate(c.request, c.questions, c.mode),
    Evaluate
);
role_call!(
    SrtRequest,
    Srt,
    Vec<PlacedObject>,
    |c| RoleRequest::Srt(c),
    Srt
);
role_call!(PrtRequest, Prt, Refined, |c| RoleRequest::Prt(c), Prt);
role_call!(
    PatchRequest,
    Patch,
    Vec<PlacedObject>,
    |c| RoleRequest::Patch(c),
    Patch
);

/// Carries out `request` on `imp`. A request of the wrong kind for the implementation is an error.
pub async fn invoke(imp: &RoleImpl, request: &RoleRequest) -> Result<Output<RoleReply>, RoleError> {
    fn wrap<T>(
        r: Result<Output<T>, RoleError>,
        f: impl FnOnce(T) -> RoleReply,
    ) -> Result<Output<RoleReply>, RoleError> {
        r.map(|o| o.map(f))
    }
    match (imp, request) {
        (RoleImpl::Planner(p), RoleRequest::Plan(scene)) => {
            wrap(p.plan(scene).await, RoleReply::Plan)
        }
        (RoleImpl::Designer(d), RoleRequest::Design(r)) => {
            wrap(d.design(r).await, RoleReply::Design)
        }
        (RoleImpl::Evaluator(e), RoleRequest::Evaluate(r, questions, mode)) => {
            let (answers, physical) =
                futures::join!(ask(e.as_ref(), r, questions, *mode), e.needs_physical(r));
            let mut out = answers?;
            let needs_physical = out.absorb(physical?);
            Ok(out.map(|answers| {
                RoleReply::Evaluate(Evaluation {
                    answers,
                    needs_physical,
                })
            }))
        }
        (RoleImpl::Srt(s), RoleRequest::Srt(r)) => wrap(s.refine(r).await, RoleReply::Srt),
        (RoleImpl::Prt(p), RoleRequest::Prt(r)) => wrap(p.refine(r).await, RoleReply::Prt),
        (RoleImpl::Patch(p), RoleRequest::Patch(r)) => wrap(p.patch(r).await, RoleReply::Patch),
        (imp, req) => Err(RoleError::WrongRequest {
            role: imp.kind(),
            request: req.kind_name(),
        }),
    }
}

impl RoleRequest {
    /// The request's kind in one word (`plan`, `design`, ...).
    pub fn kind_name(&self) -> &'static str {
        match self {
            RoleRequest::Plan(_) => "plan",
            RoleRequest::Design(_) => "design",
            RoleRequest::Evaluate(..) => "evaluate",
            RoleRequest::Srt(_) => "srt",
            RoleRequest::Prt(_) => "prt",
            RoleRequest::Patch(_) => "patch",
        }
    }
}

impl RoleReply {
    /// The reply's kind in one word, as its variant is named.
    pub fn kind_name(&self) -> &'static str {
        match self {
            RoleReply::Plan(_) => "Plan",
            RoleReply::Design(_) => "Design",
            RoleReply::Evaluate(_) => "Evaluate",
            RoleReply::Srt(_) => "Srt",
            RoleReply::Prt(_) => "Prt",
            RoleReply::Patch(_) => "Patch",
        }
    }
}

/// Asks the questions, one call each up to `width` at once, or all in one call.
async fn ask(
    e: &dyn disco_core::roles::Evaluator,
    req: &EvalRequest,
    questions: &[Question],
    mode: EvalMode,
) -> Result<Output<Vec<Answer>>, RoleError> {
    if questions.is_empty() {
        return Ok(Output::free(Vec::new()));
    }
    match mode {
        EvalMode::Batch => e.answer(req, questions).await,
        EvalMode::Parallel { width } => {
            let calls: Vec<_> = questions
                .iter()
                .map(|q| e.answer(req, std::slice::from_ref(q)))
                .collect();
            let results: Vec<_> = futures::stream::iter(calls)
                .buffered(width.max(1))
                .collect()
                .await;
            let mut out = Output::free(Vec::with_capacity(questions.len()));
            for r in results {
                let answers = out.absorb(r?);
                out.value.extend(answers);
            }
            Ok(out)
        }
    }
}
