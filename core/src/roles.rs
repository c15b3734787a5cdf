//! The five roles of the method as plain async traits, with their typed requests and answers.
//!
//! A role knows nothing about actors, retries or configuration: it takes a request and answers it.
//! The runtime (the `disco-runtime` crate) wraps each implementation in an actor, supervises it and feeds
//! it; the same implementations can be called directly in tests.

use std::collections::HashSet;
use std::fmt;
use std::sync::Arc;

use async_trait::async_trait;
use serde::{Deserialize, Serialize};

use crate::layout::{Dropped, PrtStats};
use crate::layout::{Layout, PlacedObject};
use crate::plan::Plan;
use crate::relations::ConstraintKind;
use crate::scene::SceneSpec;

/// One model call's record: what it cost and how long it took.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct CallRecord {
    /// What the call was for, e.g. `designer: group 2`.
    pub purpose: String,
    /// Wall time in milliseconds (0 for a cache hit).
    pub latency_ms: f64,
    /// Prompt tokens the server reported.
    pub prompt_tokens: u64,
    /// Completion tokens the server reported.
    pub completion_tokens: u64,
    /// HTTP attempts made (retries included).
    pub attempts: u32,
    /// Answered from the record/replay cache.
    pub cached: bool,
    /// The error, when the call failed.
    pub error: Option<String>,
}

/// How one object moved.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Move {
    /// The object's name.
    pub name: String,
    /// Distance between its old and new centre, in cm.
    pub displacement_cm: f64,
    /// Whether its rotation changed.
    pub rotated: bool,
}

impl Move {
    /// How `o` moved from its pose in `before` (not at all when it was not there): the distance
    /// between the centres, and whether it turned by more than a millionth of a degree (a full
    /// turn is no turn).
    pub fn between(
        before: &[crate::layout::PlacedObject],
        o: &crate::layout::PlacedObject,
    ) -> Move {
        let old = before.iter().find(|b| b.name == o.name);
        Move {
            name: o.name.clone(),
            displacement_cm: old.map_or(0.0, |b| {
                (b.position[0] - o.position[0]).hypot(b.position[1] - o.position[1])
            }),
            rotated: old.is_some_and(|b| {
                let turn = crate::geometry::normalize_degrees(b.rotation - o.rotation);
                turn.min(360.0 - turn) > 1e-6
            }),
        }
    }
}

/// The outcome of one refinement.
#[derive(Debug, Clone, PartialEq)]
pub struct Refined {
    /// Placed objects, in input order.
    pub objects: Vec<PlacedObject>,
    /// Objects with no valid pose anywhere, with the reason.
    pub dropped: Vec<Dropped>,
    /// One entry per placed object.
    pub moves: Vec<Move>,
    /// Requirements that could not be met (an against-wall object away from walls, a turn to fit).
    pub notes: Vec<String>,
}

impl Refined {
    /// A summary for the layout's `stats`.
    pub fn stats(&self) -> PrtStats {
        let n = self.moves.len().max(1) as f64;
        PrtStats {
            moved: self
                .moves
                .iter()
                .filter(|m| m.displacement_cm > 1e-9 || m.rotated)
                .count(),
            mean_displacement_cm: self.moves.iter().map(|m| m.displacement_cm).sum::<f64>() / n,
            max_displacement_cm: self
                .moves
                .iter()
                .map(|m| m.displacement_cm)
                .fold(0.0, f64::max),
            notes: self.notes.clone(),
        }
    }
}

/// What a role can report as failure. Every variant says what happened in words.
#[derive(Debug, Clone, PartialEq, thiserror::Error, Serialize)]
pub enum RoleError {
    /// The implementation could not do its job (a prompt that does not render, a search that
    /// found nothing, ...).
    #[error("{0}")]
    Failed(String),
    /// The model server behind the role could not be used: unreachable, refused the request or
    /// the key, or did not answer in time. Answers that are merely unusable are not this: the
    /// agents ask again and make good.
    #[error("model server {model:?}: {reason}")]
    ModelServer {
        /// The model's name in the graph (`[models.NAME]`).
        model: String,
        /// What went wrong, with what the server said.
        reason: String,
    },
    /// The implementation panicked; the runtime restarts it.
    #[error("panicked: {0}")]
    Panicked(String),
    /// The call took longer than the role's deadline.
    #[error("missed its deadline of {0:.1} s")]
    Deadline(f64),
    /// The role's actor was down (restarting, or out of restarts).
    #[error("unavailable: {0}")]
    Unavailable(String),
    /// The reply failed its call's acceptance (an unknown or repeated name, a number out of
    /// bounds, a drop without a reason, a layout left invalid, ...): a protocol error, retried,
    /// then handed to the fallback.
    #[error("its reply was refused: {0}")]
    Refused(String),
    /// The role was sent a request of another role.
    #[error("a {role} cannot answer a {request} request")]
    WrongRequest {
        /// The role that got it.
        role: RoleKind,
        /// The request's kind.
        request: &'static str,
    },
}

impl RoleError {
    /// Whether the failure is the model server's (see [`RoleError::ModelServer`]).
    pub fn is_model_server(&self) -> bool {
        matches!(self, RoleError::ModelServer { .. })
    }
}

/// Model usage of one answer (zero for rule-based roles).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Usage {
    /// Model calls made.
    pub calls: u64,
    /// Prompt tokens.
    pub prompt_tokens: u64,
    /// Completion tokens.
    pub completion_tokens: u64,
}

impl std::ops::AddAssign for Usage {
    fn add_assign(&mut self, o: Usage) {
        self.calls += o.calls;
        self.prompt_tokens += o.prompt_tokens;
        self.completion_tokens += o.completion_tokens;
    }
}

/// An answer plus the model usage it cost.
#[derive(Debug, Clone, PartialEq)]
pub struct Output<T> {
    /// The answer.
    pub value: T,
    /// What it cost.
    pub usage: Usage,
    /// Each model call made for it.
    pub calls: Vec<CallRecord>,
    /// What the implementation wants the layout's stats to say (e.g. an object it could not get
    /// from the model and placed by rules).
    pub notes: Vec<String>,
    /// Constraints it reports cannot be met in this room, with the reason: the loop stops
    /// asking about them.
    pub infeasible: Vec<Infeasible>,
}

/// A constraint a role reports cannot be met, with the reason (`two bookshelves side by side on
/// a wall near the desk: no wall stretch near the desk holds both`).
#[derive(Debug, Clone, PartialEq)]
pub struct Infeasible {
    /// The object the constraint is about.
    pub subject: String,
    /// What it asks.
    pub constraint: ConstraintKind,
    /// Why it cannot be met, in words.
    pub reason: String,
}

impl<T> Output<T> {
    /// An answer that cost no model call.
    pub fn free(value: T) -> Self {
        Output {
            value,
            usage: Usage::default(),
            calls: Vec::new(),
            notes: Vec::new(),
            infeasible: Vec::new(),
        }
    }

    /// The same costs, calls and notes with another value.
    pub fn map<U>(self, f: impl FnOnce(T) -> U) -> Output<U> {
        Output {
            value: f(self.value),
            usage: self.usage,
            calls: self.calls,
            notes: self.notes,
            infeasible: self.infeasible,
        }
    }

    /// Adds the costs, calls and notes of `other` (whose value is dropped) to these.
    pub fn absorb<U>(&mut self, other: Output<U>) -> U {
        self.usage += other.usage;
        self.calls.extend(other.calls);
        self.notes.extend(other.notes);
        self.infeasible.extend(other.infeasible);
        other.value
    }
}

/// The result type of every role.
pub type RoleResult<T> = Result<Output<T>, RoleError>;

/// What the roles share about the scene being furnished.
#[derive(Debug, Clone)]
pub struct SceneContext {
    /// The scene.
    pub scene: Arc<SceneSpec>,
    /// The plan (empty until the planner answered).
    pub plan: Arc<Plan>,
    /// What a tool moved since this agent's last request (the PRT's repairs, and what moved
    /// with them): nothing moves without the next request saying so.
    pub moved: Vec<ToolMove>,
}

impl SceneContext {
    /// The context of `scene` under `plan`, with nothing moved.
    pub fn new(scene: Arc<SceneSpec>, plan: Arc<Plan>) -> Self {
        SceneContext {
            scene,
            plan,
            moved: Vec::new(),
        }
    }
}

/// An object a tool moved, not at a model's request: from where to where, by which step and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ToolMove {
    /// The object.
    pub name: String,
    /// The step that moved it: `prt` (a round's physical refinement), `final prt`, or `with
    /// desk-0` (a dependent carried along with the object its plan ties it to).
    pub by: String,
    /// Its centre before, in cm.
    pub from: [f64; 2],
    /// Its rotation before, in degrees.
    pub from_rotation: f64,
    /// Its centre after, in cm.
    pub to: [f64; 2],
    /// Its rotation after, in degrees.
    pub to_rotation: f64,
    /// Why, in words (`it overlapped desk-0`, `it stood in window 0's keep-clear zone`), with
    /// the plan's constraints the move broke, if any.
    pub why: String,
}

impl fmt::Display for ToolMove {
    /// `desk-0 from [120, 40] rotation 0 to [210, 40] rotation 0 (prt): it stood in ...`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = |v: f64| v.round() as i64;
        write!(
            f,
            "{} moved from [{}, {}] rotation {} to [{}, {}] rotation {} ({}): {}",
            self.name,
            r(self.from[0]),
            r(self.from[1]),
            r(self.from_rotation),
            r(self.to[0]),
            r(self.to[1]),
            r(self.to_rotation),
            self.by,
            self.why
        )
    }
}

/// The designer's task: pose one group, given what is already placed.
#[derive(Debug, Clone)]
pub struct DesignRequest {
    /// Scene and plan.
    pub ctx: SceneContext,
    /// Names of the objects to pose now.
    pub group: Vec<String>,
    /// Objects placed by earlier groups.
    pub placed: Vec<PlacedObject>,
    /// A top-down PNG of `placed`, for roles that look.
    pub render: Option<Arc<Vec<u8>>>,
}

/// One yes/no question the evaluator answers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Question {
    /// Index within one evaluation.
    pub id: usize,
    /// The question in words, e.g. `Is chair-0 around table-0?`.
    pub text: String,
    /// The object the question is about (for structured questions).
    pub subject: Option<String>,
    /// The constraint behind the question; `None` for an open-ended question.
    #[serde(skip)]
    pub constraint: Option<ConstraintKind>,
}

/// The evaluator's answer to one question.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Answer {
    /// The question's id.
    pub id: usize,
    /// Yes (the layout meets it) or no.
    pub yes: bool,
    /// Why, in words.
    pub reason: String,
}

/// What the evaluator looks at.
#[derive(Debug, Clone)]
pub struct EvalRequest {
    /// Scene and plan.
    pub ctx: SceneContext,
    /// The layout so far, including the group being placed.
    pub layout: Layout,
    /// The group being placed.
    pub group: Vec<String>,
    /// A top-down PNG of `layout`, for roles that look.
    pub render: Option<Arc<Vec<u8>>>,
}

/// The evaluator's full verdict.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluation {
    /// One answer per question.
    pub answers: Vec<Answer>,
    /// Whether the layout needs physical refinement.
    pub needs_physical: bool,
}

/// The Semantic Refinement Tool's task: fix the failed questions with small moves.
#[derive(Debug, Clone)]
pub struct SrtRequest {
    /// Scene and plan.
    pub ctx: SceneContext,
    /// The layout to adjust.
    pub layout: Layout,
    /// The questions answered "no", with the evaluator's reasons.
    pub failed: Vec<(Question, Answer)>,
    /// Objects that may move (the current group).
    pub movable: Vec<String>,
    /// A top-down PNG of `layout`, for roles that look.
    pub render: Option<Arc<Vec<u8>>>,
}

/// The Physical Refinement Tool's task.
#[derive(Debug, Clone)]
pub struct PrtRequest {
    /// Scene and plan.
    pub ctx: SceneContext,
    /// The layout to make valid.
    pub layout: Layout,
    /// Objects that keep precedence (earlier groups); shared, as the scene loop keeps it.
    pub settled: Arc<HashSet<String>>,
}

/// A custom stage's task: look at the layout, return objects to move.
#[derive(Debug, Clone)]
pub struct PatchRequest {
    /// Scene and plan.
    pub ctx: SceneContext,
    /// The layout so far.
    pub layout: Layout,
    /// The group being placed (the objects the stage may move).
    pub group: Vec<String>,
}

/// Makes the plan: constraints for every asset and ordered groups.
#[async_trait]
pub trait Planner: Send + Sync + 'static {
    /// Plans `scene`.
    async fn plan(&self, scene: &SceneSpec) -> RoleResult<Plan>;
}

/// Poses the objects of one group.
#[async_trait]
pub trait Designer: Send + Sync + 'static {
    /// Poses for (some or all of) `req.group`.
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>>;
    /// Whether it wants a render of the layout so far.
    fn wants_render(&self) -> bool {
        false
    }
}

/// Answers yes/no questions about a layout, and says whether it needs physical refinement.
#[async_trait]
pub trait Evaluator: Send + Sync + 'static {
    /// Answers `questions` (one, or a batch) about `req.layout`.
    async fn answer(&self, req: &EvalRequest, questions: &[Question]) -> RoleResult<Vec<Answer>>;
    /// True when the layout needs physical refinement (collisions, out of bounds, off its wall).
    async fn needs_physical(&self, req: &EvalRequest) -> RoleResult<bool>;
    /// Whether it wants a render of the layout.
    fn wants_render(&self) -> bool {
        false
    }
}

/// The Semantic Refinement Tool: small pose changes that fix failed constraints.
#[async_trait]
pub trait SemanticRefiner: Send + Sync + 'static {
    /// New poses for the objects it moves (others stay).
    async fn refine(&self, req: &SrtRequest) -> RoleResult<Vec<PlacedObject>>;
    /// Whether it wants a render of the layout.
    fn wants_render(&self) -> bool {
        false
    }
}

/// The Physical Refinement Tool role.
#[async_trait]
pub trait PhysicalRefinerRole: Send + Sync + 'static {
    /// A physically valid version of `req.layout`.
    async fn refine(&self, req: &PrtRequest) -> RoleResult<Refined>;
}

/// A custom stage (a role the paper lacks): reads the layout, returns objects to move.
#[async_trait]
pub trait Patcher: Send + Sync + 'static {
    /// New poses for the objects it moves.
    async fn patch(&self, req: &PatchRequest) -> RoleResult<Vec<PlacedObject>>;
}

/// The kind of a role, which fixes its trait and message types.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    Serialize,
    Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum RoleKind {
    /// [`Planner`].
    Planner,
    /// [`Designer`].
    Designer,
    /// [`Evaluator`].
    Evaluator,
    /// [`SemanticRefiner`].
    Srt,
    /// [`PhysicalRefinerRole`].
    Prt,
    /// [`Patcher`]: a custom stage.
    Patch,
}

impl fmt::Display for RoleKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            RoleKind::Planner => "planner",
            RoleKind::Designer => "designer",
            RoleKind::Evaluator => "evaluator",
            RoleKind::Srt => "srt",
            RoleKind::Prt => "prt",
            RoleKind::Patch => "patch",
        })
    }
}

/// One implementation of one role, behind the matching trait object.
#[derive(Clone)]
pub enum RoleImpl {
    /// A planner.
    Planner(Arc<dyn Planner>),
    /// A designer.
    Designer(Arc<dyn Designer>),
    /// An evaluator.
    Evaluator(Arc<dyn Evaluator>),
    /// A semantic refiner.
    Srt(Arc<dyn SemanticRefiner>),
    /// A physical refiner.
    Prt(Arc<dyn PhysicalRefinerRole>),
    /// A custom stage.
    Patch(Arc<dyn Patcher>),
}

impl RoleImpl {
    /// The role this implements.
    pub fn kind(&self) -> RoleKind {
        match self {
            RoleImpl::Planner(_) => RoleKind::Planner,
            RoleImpl::Designer(_) => RoleKind::Designer,
            RoleImpl::Evaluator(_) => RoleKind::Evaluator,
            RoleImpl::Srt(_) => RoleKind::Srt,
            RoleImpl::Prt(_) => RoleKind::Prt,
            RoleImpl::Patch(_) => RoleKind::Patch,
        }
    }

    /// Whether this implementation looks at renders.
    pub fn wants_render(&self) -> bool {
        match self {
            RoleImpl::Designer(d) => d.wants_render(),
            RoleImpl::Evaluator(e) => e.wants_render(),
            RoleImpl::Srt(s) => s.wants_render(),
            _ => false,
        }
    }
}

impl fmt::Debug for RoleImpl {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "RoleImpl({})", self.kind())
    }
}
