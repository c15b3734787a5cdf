//! Roles without Rust: an agent of any role served by a child process (`impl = "process"`) or an
//! HTTP endpoint (`impl = "http"`), speaking the JSON protocol of [`protocol`].
//!
//! An [`ExternalAgent`] implements every role trait; the registry wraps it in the role its agent
//! plays. It runs under the same supervision as the built-in roles: a reply that is not JSON, is
//! for another request or does not fit the role's schema is a [`RoleError::Failed`] (retried,
//! then the fallback), a process that exits is a [`RoleError::Panicked`] (the supervisor restarts
//! the role), one that hangs is killed at the deadline.
//!
//! Nothing an agent sends is read without a bound ([`capped`]): a reply over `max_reply_bytes`
//! (default 8 MiB) or not UTF-8 is an unusable answer, a stderr line is cut, and a reply keeps
//! at most [`MAX_NOTES`] notes of at most [`MAX_NOTE_CHARS`] characters. A process agent runs in
//! a process group of its own, killed as a whole ([`group`]).

pub mod capped;
pub mod group;
pub mod http;
pub mod process;
pub mod protocol;

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use async_trait::async_trait;
use base64::Engine;
use serde::Serialize;
use serde::de::DeserializeOwned;

use disco_core::layout::PlacedObject;
use disco_core::plan::Plan;
use disco_core::roles::{
    Answer, DesignRequest, Designer, EvalRequest, Evaluator, Infeasible, Move, Output,
    PatchRequest, Patcher, PhysicalRefinerRole, Planner, PrtRequest, Question, Refined, RoleError,
    RoleImpl, RoleKind, RoleResult, SemanticRefiner, SrtRequest,
};
use disco_core::scene::SceneSpec;
use protocol::{PROTOCOL_VERSION, Poses, Reply, Request};

/// The `options` keys of `process` and `http`: `render = true` sends renders.
pub const OPTIONS: &[&str] = &["render"];

/// The longest piece of a bad reply quoted in an error.
const QUOTED: usize = 120;

/// The most notes one reply adds to the layout; the rest are counted in one last note.
pub const MAX_NOTES: usize = 32;

/// The longest note kept, in characters; a longer one is cut.
pub const MAX_NOTE_CHARS: usize = 500;

/// An agent's notes, bounded: at most [`MAX_NOTES`], each at most [`MAX_NOTE_CHARS`]
/// characters, and a last note saying how many were left out.
pub fn bounded_notes(notes: Vec<String>) -> Vec<String> {
    let total = notes.len();
    let mut kept: Vec<String> = notes
        .into_iter()
        .take(MAX_NOTES)
        .map(|n| match n.chars().nth(MAX_NOTE_CHARS) {
            None => n,
            Some(_) => n
                .chars()
                .take(MAX_NOTE_CHARS)
                .chain("...".chars())
                .collect(),
        })
        .collect();
    if total > MAX_NOTES {
        kept.push(format!(
            "{} more notes of the agent left out (at most {MAX_NOTES} per reply)",
            total - MAX_NOTES
        ));
    }
    kept
}

/// Carries one request to an agent and its reply back.
#[async_trait]
pub trait Transport: Send + Sync {
    /// Sends `line` (one JSON object, no newline) and returns the agent's reply text.
    async fn exchange(&self, line: String) -> Result<String, RoleError>;
    /// Forgets the connection after a reply that broke the protocol, so the next call starts
    /// afresh (a process is killed and started again).
    async fn discard(&self);
}

/// An agent outside the binary, playing one role.
pub struct ExternalAgent {
    agent: String,
    role: RoleKind,
    transport: Box<dyn Transport>,
    next_id: AtomicU64,
    render: bool,
}

impl ExternalAgent {
    /// Agent `agent` playing `role` over `transport`; `render` sends it renders.
    pub fn new(agent: &str, role: RoleKind, transport: Box<dyn Transport>, render: bool) -> Self {
        ExternalAgent {
            agent: agent.to_string(),
            role,
            transport,
            next_id: AtomicU64::new(0),
            render,
        }
    }

    /// The agent as the implementation of its role.
    pub fn into_role_impl(self) -> RoleImpl {
        let me = Arc::new(self);
        match me.role {
            RoleKind::Planner => RoleImpl::Planner(me),
            RoleKind::Designer => RoleImpl::Designer(me),
            RoleKind::Evaluator => RoleImpl::Evaluator(me),
            RoleKind::Srt => RoleImpl::Srt(me),
            RoleKind::Prt => RoleImpl::Prt(me),
            RoleKind::Patch => RoleImpl::Patch(me),
        }
    }

    /// One exchange: the request out, the reply checked against the protocol.
    pub async fn call<B: Serialize, R: DeserializeOwned>(&self, body: B) -> RoleResult<R> {
        let id = self.next_id.fetch_add(1, Ordering::Relaxed) + 1;
        let request = Request {
            protocol: PROTOCOL_VERSION,
            id,
            agent: self.agent.clone(),
            role: self.role,
            request: body,
        };
        let line = serde_json::to_string(&request)
            .map_err(|e| RoleError::Failed(format!("cannot write request {id}: {e}")))?;
        let text = self.transport.exchange(line).await?;
        match read_reply(self.role, id, &text) {
            Ok(Ok(out)) => Ok(out),
            Ok(Err(said)) => Err(said),
            Err(broken) => {
                self.transport.discard().await;
                Err(broken)
            }
        }
    }

    fn render_for(&self, png: &Option<Arc<Vec<u8>>>) -> Option<String> {
        png.as_ref()
            .filter(|_| self.render)
            .map(|p| base64::engine::general_purpose::STANDARD.encode(p.as_slice()))
    }
}

/// Reads the reply to request `id`. The outer `Err` breaks the protocol (not JSON, another id or
/// version, a shape that does not fit); the inner one is the agent's own `error`.
fn read_reply<R: DeserializeOwned>(
    role: RoleKind,
    id: u64,
    text: &str,
) -> Result<RoleResult<R>, RoleError> {
    let quoted = || text.chars().take(QUOTED).collect::<String>();
    let broken =
        |why: String| RoleError::Failed(format!("the {role} agent broke the protocol: {why}"));
    let value: serde_json::Value = serde_json::from_str(text)
        .map_err(|e| broken(format!("its reply is not JSON ({e}): {:?}", quoted())))?;
    match value.get("id").and_then(|v| v.as_u64()) {
        Some(got) if got == id => {}
        Some(got) => {
            return Err(broken(format!(
                "it answered request {got} where request {id} was due"
            )));
        }
        None => {
            return Err(broken(format!(
                "its reply has no numeric \"id\": {:?}",
                quoted()
            )));
        }
    }
    let version = value.get("protocol").and_then(|v| v.as_u64());
    if version != Some(PROTOCOL_VERSION as u64) {
        return Err(broken(format!(
            "its reply says protocol {version:?}, expected {PROTOCOL_VERSION}"
        )));
    }
    let reply: Reply<R> = serde_json::from_value(value).map_err(|e| {
        broken(format!(
            "its reply to request {id} does not fit the {role} reply schema: {e}"
        ))
    })?;
    if let Some(error) = reply.error {
        return Ok(Err(RoleError::Failed(format!(
            "the {role} agent said: {error}"
        ))));
    }
    let Some(value) = reply.reply else {
        return Err(broken(format!(
            "its reply to request {id} has neither \"reply\" nor \"error\""
        )));
    };
    let mut out = Output::free(value);
    out.notes = bounded_notes(reply.notes);
    Ok(Ok(out))
}

/// Poses as placed objects of `scene`; a reply that names an object the scene does not have
/// is refused, as every reply's acceptance refuses unknown names (retried, then the fallback).
fn placed(scene: &SceneSpec, out: Output<Poses>) -> RoleResult<Vec<PlacedObject>> {
    let mut unknown = Vec::new();
    let out = out.map(|p| {
        let (objects, ghosts) = protocol::place(scene, p.objects);
        unknown = ghosts;
        objects
    });
    refuse_unknown(&unknown)?;
    Ok(out)
}

/// A protocol error naming the objects a reply gave that the scene does not have.
fn refuse_unknown(unknown: &[String]) -> Result<(), RoleError> {
    if unknown.is_empty() {
        return Ok(());
    }
    let shown: Vec<String> = unknown.iter().take(5).map(|n| format!("{n:?}")).collect();
    Err(RoleError::Refused(format!(
        "it names {} object(s) the scene does not have: {}",
        unknown.len(),
        shown.join(", ")
    )))
}

#[async_trait]
impl Planner for ExternalAgent {
    async fn plan(&self, scene: &SceneSpec) -> RoleResult<Plan> {
        self.call(protocol::PlanBody {
            scene: scene.clone(),
        })
        .await
    }
}

#[async_trait]
impl Designer for ExternalAgent {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        let body = protocol::DesignBody {
            scene: (*req.ctx.scene).clone(),
            plan: (*req.ctx.plan).clone(),
            group: req.group.clone(),
            placed: req.placed.clone(),
            moved: req.ctx.moved.clone(),
            render_png_base64: self.render_for(&req.render),
        };
        placed(&req.ctx.scene, self.call(body).await?)
    }

    fn wants_render(&self) -> bool {
        self.render
    }
}

impl ExternalAgent {
    async fn evaluate(
        &self,
        req: &EvalRequest,
        questions: &[Question],
    ) -> RoleResult<protocol::EvaluateReply> {
        let body = protocol::EvaluateBody {
            scene: (*req.ctx.scene).clone(),
            plan: (*req.ctx.plan).clone(),
            layout: req.layout.clone(),
            group: req.group.clone(),
            questions: questions.to_vec(),
            moved: req.ctx.moved.clone(),
            render_png_base64: self.render_for(&req.render),
        };
        let mut out: Output<protocol::EvaluateReply> = self.call(body).await?;
        let unmeetable = std::mem::take(&mut out.value.infeasible);
        out.infeasible = infeasible_of(questions, unmeetable);
        Ok(out)
    }
}

/// The constraints behind the questions an agent called infeasible (by id); an id that names no
/// structured question is passed over.
fn infeasible_of(questions: &[Question], said: Vec<protocol::Unmeetable>) -> Vec<Infeasible> {
    said.into_iter()
        .filter_map(|u| {
            let q = questions.iter().find(|q| q.id == u.id)?;
            Some(Infeasible {
                subject: q.subject.clone()?,
                constraint: q.constraint.clone()?,
                reason: u.reason,
            })
        })
        .collect()
}

#[async_trait]
impl Evaluator for ExternalAgent {
    async fn answer(&self, req: &EvalRequest, questions: &[Question]) -> RoleResult<Vec<Answer>> {
        Ok(self.evaluate(req, questions).await?.map(|r| r.answers))
    }

    async fn needs_physical(&self, req: &EvalRequest) -> RoleResult<bool> {
        Ok(self.evaluate(req, &[]).await?.map(|r| r.needs_physical))
    }

    fn wants_render(&self) -> bool {
        self.render
    }
}

#[async_trait]
impl SemanticRefiner for ExternalAgent {
    async fn refine(&self, req: &SrtRequest) -> RoleResult<Vec<PlacedObject>> {
        let failed = req
            .failed
            .iter()
            .map(|(question, answer)| protocol::Failed {
                question: question.clone(),
                answer: answer.clone(),
            })
            .collect();
        let body = protocol::SrtBody {
            scene: (*req.ctx.scene).clone(),
            plan: (*req.ctx.plan).clone(),
            layout: req.layout.clone(),
            failed,
            movable: req.movable.clone(),
            moved: req.ctx.moved.clone(),
            render_png_base64: self.render_for(&req.render),
        };
        let mut out: Output<protocol::SrtReply> = self.call(body).await?;
        let asked: Vec<Question> = req.failed.iter().map(|(q, _)| q.clone()).collect();
        let unmeetable = std::mem::take(&mut out.value.infeasible);
        out.infeasible = infeasible_of(&asked, unmeetable);
        placed(&req.ctx.scene, out.map(|r| Poses { objects: r.objects }))
    }

    fn wants_render(&self) -> bool {
        self.render
    }
}

#[async_trait]
impl PhysicalRefinerRole for ExternalAgent {
    async fn refine(&self, req: &PrtRequest) -> RoleResult<Refined> {
        let mut settled: Vec<String> = req.settled.iter().cloned().collect();
        settled.sort();
        let body = protocol::PrtBody {
            scene: (*req.ctx.scene).clone(),
            plan: (*req.ctx.plan).clone(),
            layout: req.layout.clone(),
            settled,
        };
        let Output {
            value: reply,
            usage,
            calls,
            notes,
            infeasible,
        } = self.call::<_, protocol::PrtReply>(body).await?;
        let (objects, unknown) = protocol::place(&req.ctx.scene, reply.objects);
        refuse_unknown(&unknown)?;
        let moves = objects
            .iter()
            .map(|o| Move::between(&req.layout.objects, o))
            .collect();
        let refined = Refined {
            objects,
            dropped: reply.dropped,
            moves,
            notes: bounded_notes(reply.notes),
        };
        Ok(Output {
            value: refined,
            usage,
            calls,
            notes,
            infeasible,
        })
    }
}

#[async_trait]
impl Patcher for ExternalAgent {
    async fn patch(&self, req: &PatchRequest) -> RoleResult<Vec<PlacedObject>> {
        let body = protocol::PatchBody {
            scene: (*req.ctx.scene).clone(),
            plan: (*req.ctx.plan).clone(),
            layout: req.layout.clone(),
            group: req.group.clone(),
            moved: req.ctx.moved.clone(),
        };
        placed(&req.ctx.scene, self.call(body).await?)
    }
}

#[cfg(test)]
mod tests;
