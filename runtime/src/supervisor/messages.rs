//! The role protocol: each call type is bound by [`RoleCall`] to its role and its reply, says how
//! it is carried out on an implementation (including the evaluator's parallel fan-out), and owns
//! the acceptance of what comes back. A call travels to its role actor as a [`Job`], and its
//! answer comes back on a channel of the reply's own type: there is no reply of another kind to
//! mistake for it.

use std::sync::{Arc, Mutex};

use async_trait::async_trait;
use futures::StreamExt;
use futures::future::BoxFuture;
use serde_json::{Value, json};
use tokio::sync::oneshot;

use super::accept;
use crate::external::protocol::Pose;
use disco_core::layout::PlacedObject;
use disco_core::plan::Plan;
use disco_core::roles::{
    Answer, DesignRequest, EvalRequest, Evaluation, Output, PatchRequest, PrtRequest, Question,
    Refined, RoleError, RoleImpl, RoleKind, RoleResult, SrtRequest,
};
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

/// A call of the role protocol, bound by type to the role that answers it and to its reply. The
/// scene loop sends a `RoleCall` and gets back exactly its `Reply`, and only once
/// [`accept`](RoleCall::accept) took it: a reply that fails acceptance is a protocol error
/// ([`RoleError::Refused`]), retried and then handed to the fallback like any other failure.
#[async_trait]
pub trait RoleCall: Send + Sync + 'static {
    /// What the role answers.
    type Reply: Send + 'static;
    /// The role that answers this call.
    const ROLE: RoleKind;
    /// The call's kind in one word (`plan`, `design`, ...).
    const NAME: &'static str;
    /// Carries the call out on `imp`; an implementation of another role is
    /// [`RoleError::WrongRequest`].
    async fn run(&self, imp: &RoleImpl) -> RoleResult<Self::Reply>;
    /// The call in brief, for the trace (renders are left out).
    fn summary(&self) -> Value;
    /// A reply in brief, for the trace: what the role said and decided.
    fn reply_summary(reply: &Self::Reply) -> Value;
    /// Checks `reply` against this call (its scene, its layout, what it may change): the reply as
    /// the loop takes it, or why it is refused.
    fn accept(&self, reply: Self::Reply) -> Result<Self::Reply, RoleError>;
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

fn wrong<T>(imp: &RoleImpl, request: &'static str) -> RoleResult<T> {
    Err(RoleError::WrongRequest {
        role: imp.kind(),
        request,
    })
}

/// Poses in brief, as the wire has them: name, position and rotation, and for an object off the
/// floor its elevation and what holds it (`on`, `wall`).
fn poses(objects: &[PlacedObject]) -> Value {
    objects
        .iter()
        .map(|o| serde_json::to_value(Pose::of(o)).unwrap_or(Value::Null))
        .collect()
}

#[async_trait]
impl RoleCall for PlanCall {
    type Reply = Plan;
    const ROLE: RoleKind = RoleKind::Planner;
    const NAME: &'static str = "plan";

    async fn run(&self, imp: &RoleImpl) -> RoleResult<Plan> {
        match imp {
            RoleImpl::Planner(p) => p.plan(&self.0).await,
            other => wrong(other, Self::NAME),
        }
    }

    fn summary(&self) -> Value {
        json!({"scene": self.0.id, "assets": self.0.assets.len()})
    }

    fn reply_summary(reply: &Plan) -> Value {
        serde_json::to_value(reply).unwrap_or(Value::Null)
    }

    /// Any plan is taken: `sanitize_plan` makes it usable (unknown names out, each asset in
    /// exactly one group), repairing rather than refusing, since a plan has no pose to check.
    fn accept(&self, reply: Plan) -> Result<Plan, RoleError> {
        Ok(reply)
    }
}

#[async_trait]
impl RoleCall for DesignRequest {
    type Reply = Vec<PlacedObject>;
    const ROLE: RoleKind = RoleKind::Designer;
    const NAME: &'static str = "design";

    async fn run(&self, imp: &RoleImpl) -> RoleResult<Vec<PlacedObject>> {
        match imp {
            RoleImpl::Designer(d) => d.design(self).await,
            other => wrong(other, Self::NAME),
        }
    }

    fn summary(&self) -> Value {
        json!({"group": self.group, "placed": self.placed.len()})
    }

    fn reply_summary(reply: &Vec<PlacedObject>) -> Value {
        json!({"poses": poses(reply)})
    }

    /// Poses for objects of the group, each once, bounded, sizes unchanged (see
    /// [`accept::poses`]); objects of the group left out are parked by the loop.
    fn accept(&self, reply: Vec<PlacedObject>) -> Result<Vec<PlacedObject>, RoleError> {
        accept::poses(&self.ctx.scene, &self.group, &self.placed, reply)
    }
}

#[async_trait]
impl RoleCall for EvaluateCall {
    type Reply = Evaluation;
    const ROLE: RoleKind = RoleKind::Evaluator;
    const NAME: &'static str = "evaluate";

    async fn run(&self, imp: &RoleImpl) -> RoleResult<Evaluation> {
        let RoleImpl::Evaluator(e) = imp else {
            return wrong(imp, Self::NAME);
        };
        let (answers, physical) = futures::join!(
            ask(e.as_ref(), &self.request, &self.questions, self.mode),
            e.needs_physical(&self.request)
        );
        let mut out = answers?;
        let needs_physical = out.absorb(physical?);
        Ok(out.map(|answers| Evaluation {
            answers,
            needs_physical,
        }))
    }

    fn summary(&self) -> Value {
        json!({"group": self.request.group, "questions": self.questions})
    }

    fn reply_summary(reply: &Evaluation) -> Value {
        serde_json::to_value(reply).unwrap_or(Value::Null)
    }

    /// Answers to questions asked, each at most once (see [`accept::answers`]).
    fn accept(&self, reply: Evaluation) -> Result<Evaluation, RoleError> {
        accept::answers(&self.questions, reply)
    }
}

#[async_trait]
impl RoleCall for SrtRequest {
    type Reply = Vec<PlacedObject>;
    const ROLE: RoleKind = RoleKind::Srt;
    const NAME: &'static str = "srt";

    async fn run(&self, imp: &RoleImpl) -> RoleResult<Vec<PlacedObject>> {
        match imp {
            RoleImpl::Srt(s) => s.refine(self).await,
            other => wrong(other, Self::NAME),
        }
    }

    fn summary(&self) -> Value {
        json!({"failed": self.failed.iter().map(|(q, a)| json!({"question": q.text, "reason": a.reason})).collect::<Vec<_>>()})
    }

    fn reply_summary(reply: &Vec<PlacedObject>) -> Value {
        json!({"poses": poses(reply)})
    }

    /// Moves of movable objects, each once, bounded, sizes unchanged; none is a valid answer
    /// (see [`accept::poses`]).
    fn accept(&self, reply: Vec<PlacedObject>) -> Result<Vec<PlacedObject>, RoleError> {
        accept::poses(&self.ctx.scene, &self.movable, &self.layout.objects, reply)
    }
}

#[async_trait]
impl RoleCall for PrtRequest {
    type Reply = Refined;
    const ROLE: RoleKind = RoleKind::Prt;
    const NAME: &'static str = "prt";

    async fn run(&self, imp: &RoleImpl) -> RoleResult<Refined> {
        match imp {
            RoleImpl::Prt(p) => p.refine(self).await,
            other => wrong(other, Self::NAME),
        }
    }

    fn summary(&self) -> Value {
        json!({"objects": self.layout.objects.len(), "settled": self.settled.len()})
    }

    fn reply_summary(r: &Refined) -> Value {
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

    /// Every object of the layout back exactly once, placed validly or dropped with a reason
    /// (see [`accept::refined`]).
    fn accept(&self, reply: Refined) -> Result<Refined, RoleError> {
        accept::refined(&self.ctx.scene, &self.layout.objects, reply)
    }
}

#[async_trait]
impl RoleCall for PatchRequest {
    type Reply = Vec<PlacedObject>;
    const ROLE: RoleKind = RoleKind::Patch;
    const NAME: &'static str = "patch";

    async fn run(&self, imp: &RoleImpl) -> RoleResult<Vec<PlacedObject>> {
        match imp {
            RoleImpl::Patch(p) => p.patch(self).await,
            other => wrong(other, Self::NAME),
        }
    }

    fn summary(&self) -> Value {
        json!({"group": self.group})
    }

    fn reply_summary(reply: &Vec<PlacedObject>) -> Value {
        json!({"poses": poses(reply)})
    }

    /// Moves of the group's objects, each once, bounded, sizes unchanged; none is a valid
    /// answer (see [`accept::poses`]).
    fn accept(&self, reply: Vec<PlacedObject>) -> Result<Vec<PlacedObject>, RoleError> {
        accept::poses(&self.ctx.scene, &self.group, &self.layout.objects, reply)
    }
}

/// A call on its way to a role actor, its reply type erased: the actor runs it on its
/// implementation, and the typed answer goes back on the call's own channel (see [`pending`]).
pub trait Job: Send + Sync {
    /// Carries the call out on `imp` and sends the answer back. Returns the text of a crash the
    /// actor must be restarted for (an external agent whose process died), if there was one.
    fn run(self: Arc<Self>, imp: RoleImpl) -> BoxFuture<'static, Option<String>>;
    /// Answers with `error` instead, when the call could not be carried out (the agent is
    /// restarting, the implementation panicked); a job already answered ignores it.
    fn fail(&self, error: RoleError);
}

/// The answer to a call, as the loop waits for it.
pub type Awaited<R> = oneshot::Receiver<RoleResult<R>>;

struct Pending<C: RoleCall> {
    call: Arc<C>,
    answer: Mutex<Option<oneshot::Sender<RoleResult<C::Reply>>>>,
}

impl<C: RoleCall> Pending<C> {
    fn send(&self, result: RoleResult<C::Reply>) {
        let sender = self.answer.lock().unwrap_or_else(|e| e.into_inner()).take();
        if let Some(sender) = sender {
            let _ = sender.send(result);
        }
    }
}

impl<C: RoleCall> Job for Pending<C> {
    fn run(self: Arc<Self>, imp: RoleImpl) -> BoxFuture<'static, Option<String>> {
        Box::pin(async move {
            let result = self.call.run(&imp).await;
            let crash = match &result {
                Err(RoleError::Panicked(text)) => Some(text.clone()),
                _ => None,
            };
            self.send(result);
            crash
        })
    }

    fn fail(&self, error: RoleError) {
        self.send(Err(error));
    }
}

/// `call` as a [`Job`] for a role actor, and where its answer will come. The call is shared, not
/// copied: a retry sends the same one again. When the job is dropped unanswered (its actor was
/// stopped), the receiver says so by closing.
pub fn pending<C: RoleCall>(call: Arc<C>) -> (Arc<dyn Job>, Awaited<C::Reply>) {
    let (sender, receiver) = oneshot::channel();
    let job = Arc::new(Pending {
        call,
        answer: Mutex::new(Some(sender)),
    });
    (job, receiver)
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
