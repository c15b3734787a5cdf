//! The wire protocol of external agents: one JSON request per line (or per HTTP POST) and one
//! JSON reply, each carrying the protocol version and the request's id.
//!
//! The bodies are built from the role request types of `disco_core::roles` and the scene, plan
//! and layout types; their JSON Schema, generated from these types, is committed in
//! `docs/protocol/` (see [`schemas`]) and explained in `docs/protocol/README.md`.

use std::collections::HashMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use disco_core::layout::{Dropped, Layout, PlacedObject};
use disco_core::plan::Plan;
use disco_core::roles::{Answer, Question, RoleKind, ToolMove};
use disco_core::scene::SceneSpec;

/// The protocol version every request carries and every reply must echo.
pub const PROTOCOL_VERSION: u32 = 1;

/// One request to an external agent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Request<B> {
    /// The protocol version (`1`).
    pub protocol: u32,
    /// The request's id, unique within the agent's process; the reply must echo it.
    pub id: u64,
    /// The agent's name in the graph (`designer`, `critic`, ...).
    pub agent: String,
    /// The role the agent plays, which fixes the shape of `request` and of the reply.
    pub role: RoleKind,
    /// What to do.
    pub request: B,
}

/// One reply of an external agent: `reply` when it did its job, `error` when it could not.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(bound(deserialize = "B: Deserialize<'de>"))]
pub struct Reply<B> {
    /// The protocol version (`1`).
    pub protocol: u32,
    /// The id of the request this answers.
    pub id: u64,
    /// The answer (absent when `error` is given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reply: Option<B>,
    /// Why the agent could not answer (then the runtime retries, then swaps in the fallback).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// What the layout's notes should say (e.g. an object it could not place).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

/// Where an object stands: the wire form of a pose (its size and category come from the scene).
///
/// An object off the floor also says what holds it: `elevation` (its bottom above the floor)
/// and `on` (the object whose top it stands on) or `wall` (the index of the wall it hangs on).
/// Each is left out when it has its default, so a pose on the floor reads and writes as
/// `{"name", "position", "rotation"}`, exactly as before objects left the floor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Pose {
    /// The asset's name.
    pub name: String,
    /// Footprint centre `[x, y]` in cm.
    pub position: [f64; 2],
    /// Degrees clockwise seen from above; 0 faces +y, 90 faces +x.
    pub rotation: f64,
    /// Height of the object's bottom above the floor, in cm (0, and left out, on the floor).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub elevation: f64,
    /// The name of the object whose top it stands on, when it stands on one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub on: Option<String>,
    /// The index of the wall it hangs on (its back on the wall), when it hangs on one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall: Option<usize>,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl Pose {
    /// The pose of a placed object, with what holds it when it is off the floor.
    pub fn of(o: &PlacedObject) -> Self {
        Pose {
            name: o.name.clone(),
            position: o.position,
            rotation: o.rotation,
            elevation: o.elevation,
            on: o.on.clone(),
            wall: o.wall,
        }
    }
}

/// Poses as placed objects, with the scene's size and category and the pose's `elevation`,
/// `on` and `wall` as sent (the reply's acceptance checks them); unknown names are left out and
/// returned apart, so that the caller can note them.
pub fn place(scene: &SceneSpec, poses: Vec<Pose>) -> (Vec<PlacedObject>, Vec<String>) {
    let assets: HashMap<&str, _> = scene.assets.iter().map(|a| (a.name.as_str(), a)).collect();
    let mut unknown = Vec::new();
    let mut placed = Vec::with_capacity(poses.len());
    for p in poses {
        match assets.get(p.name.as_str()) {
            Some(a) => placed.push(PlacedObject {
                name: p.name,
                category: a.category.clone(),
                size: a.size,
                position: p.position,
                rotation: p.rotation,
                elevation: p.elevation,
                on: p.on,
                wall: p.wall,
            }),
            None => unknown.push(p.name),
        }
    }
    (placed, unknown)
}

/// The planner's task: plan the scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PlanBody {
    /// The scene to plan.
    pub scene: SceneSpec,
}

/// The designer's task: pose the objects of `group`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DesignBody {
    /// The scene.
    pub scene: SceneSpec,
    /// The planner's constraints and groups.
    pub plan: Plan,
    /// Names of the objects to pose now.
    pub group: Vec<String>,
    /// Objects placed by earlier groups.
    pub placed: Vec<PlacedObject>,
    /// What a tool moved since this agent's last request, from where to where and why (the
    /// PRT's repairs, and what moved with them): nothing moves without the next request saying
    /// so. Left out when nothing moved.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub moved: Vec<ToolMove>,
    /// A top-down PNG of `placed`, base64, when the agent asked for renders.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub render_png_base64: Option<String>,
}

/// The evaluator's task: answer `questions` about `layout`, and say whether it needs physical
/// refinement. The runtime sends the physical question with an empty `questions` list.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct EvaluateBody {
    /// The scene.
    pub scene: SceneSpec,
    /// The plan.
    pub plan: Plan,
    /// The layout so far, including the group being placed.
    pub layout: Layout,
    /// The group being placed.
    pub group: Vec<String>,
    /// The yes/no questions to answer (empty: only `needs_physical` is read).
    pub questions: Vec<Question>,
    /// What a tool moved since this agent's last request (as in the designer's request).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub moved: Vec<ToolMove>,
    /// A top-down PNG of `layout`, base64, when the agent asked for renders.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub render_png_base64: Option<String>,
}

/// A question answered "no", with the evaluator's answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Failed {
    /// The question.
    pub question: Question,
    /// The evaluator's answer and reason.
    pub answer: Answer,
}

/// The semantic refiner's task: fix the failed questions by moving objects of `movable`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SrtBody {
    /// The scene.
    pub scene: SceneSpec,
    /// The plan.
    pub plan: Plan,
    /// The layout to adjust.
    pub layout: Layout,
    /// The questions answered "no".
    pub failed: Vec<Failed>,
    /// The objects that may move.
    pub movable: Vec<String>,
    /// What a tool moved since this agent's last request (as in the designer's request).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub moved: Vec<ToolMove>,
    /// A top-down PNG of `layout`, base64, when the agent asked for renders.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub render_png_base64: Option<String>,
}

/// The physical refiner's task: a layout without collisions, inside the room.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PrtBody {
    /// The scene.
    pub scene: SceneSpec,
    /// The plan.
    pub plan: Plan,
    /// The layout to make valid.
    pub layout: Layout,
    /// Objects that keep precedence (earlier groups), sorted.
    pub settled: Vec<String>,
}

/// A custom stage's task: look at `layout`, move objects of `group`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PatchBody {
    /// The scene.
    pub scene: SceneSpec,
    /// The plan.
    pub plan: Plan,
    /// The layout so far.
    pub layout: Layout,
    /// The group being placed: the objects the stage may move.
    pub group: Vec<String>,
    /// What a tool moved since this agent's last request (as in the designer's request).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub moved: Vec<ToolMove>,
}

/// The answer of a designer, semantic refiner or custom stage: new poses for the objects it
/// moves (the others stay where they are).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Poses {
    /// One pose per object moved or placed.
    pub objects: Vec<Pose>,
}

/// A question the agent says cannot be met in this room, by the question's id, with why: the
/// loop stops asking about it and the layout's notes say so.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Unmeetable {
    /// The id of the question (of `questions` for an evaluator, of `failed` for an srt).
    pub id: usize,
    /// Why it cannot be met, in words.
    pub reason: String,
}

/// The evaluator's answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct EvaluateReply {
    /// One answer per question asked (by id).
    #[serde(default)]
    pub answers: Vec<Answer>,
    /// Whether the layout needs physical refinement.
    #[serde(default)]
    pub needs_physical: bool,
    /// Questions that cannot be met in this room (answer them `no` too).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub infeasible: Vec<Unmeetable>,
}

/// The semantic refiner's answer: new poses for what it moves (an empty list moves nothing),
/// and the failed questions it finds cannot be met.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SrtReply {
    /// One pose per object moved.
    pub objects: Vec<Pose>,
    /// Failed questions that cannot be met in this room.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub infeasible: Vec<Unmeetable>,
}

/// The physical refiner's answer: every object of the layout, placed or dropped.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PrtReply {
    /// The placed objects.
    pub objects: Vec<Pose>,
    /// Objects with no valid pose anywhere, with the reason.
    #[serde(default)]
    pub dropped: Vec<Dropped>,
    /// Requirements it could not meet.
    #[serde(default)]
    pub notes: Vec<String>,
}

/// The request and reply schema of every role, as `(file name, schema)`: the files of
/// `docs/protocol/`.
pub fn schemas() -> Vec<(String, serde_json::Value)> {
    fn pair<Q: JsonSchema, R: JsonSchema>(role: &str) -> [(String, serde_json::Value); 2] {
        [
            (
                format!("{role}.request.json"),
                schemars::schema_for!(Request<Q>).to_value(),
            ),
            (
                format!("{role}.reply.json"),
                schemars::schema_for!(Reply<R>).to_value(),
            ),
        ]
    }
    [
        pair::<PlanBody, Plan>("planner"),
        pair::<DesignBody, Poses>("designer"),
        pair::<EvaluateBody, EvaluateReply>("evaluator"),
        pair::<SrtBody, SrtReply>("srt"),
        pair::<PrtBody, PrtReply>("prt"),
        pair::<PatchBody, Poses>("patch"),
    ]
    .into_iter()
    .flatten()
    .collect()
}
