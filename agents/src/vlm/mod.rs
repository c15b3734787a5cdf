//! The `vlm` implementations of planner, designer, evaluator and SRT, over any OpenAI-compatible
//! server, plus the VLM judge.
//!
//! Each role renders its prompt template, asks with a JSON schema (and the top-down render for
//! vision models), and reads the answer leniently. An answer that cannot be used is asked for
//! again with the exact reason, at most [`REASKS`] times; what the model still gets wrong is
//! made good by the rules and said in the notes, so no answer a model gives breaks a run. Only
//! a server that cannot be reached fails the call (the runtime then retries and falls back).

mod designer;
mod evaluator;
#[cfg(test)]
mod fault_tests;
pub mod judge;
pub mod patch;
mod planner;
pub mod room_words;
pub mod schema;
mod srt;

use std::sync::Arc;

use serde_json::{Value, json};

pub use designer::VlmDesigner;
pub use evaluator::VlmEvaluator;
pub use patch::VlmPatch;
pub use planner::VlmPlanner;
pub use srt::VlmSrt;

use disco_core::layout::PlacedObject;
use disco_core::relations::ConstraintKind;
use disco_core::roles::{Output, RoleError};
use disco_core::scene::SceneSpec;
use disco_llm::{ChatClient, Message, Prompts, Schema, extract};

/// Times an unusable answer is asked for again, with the reason, before the rules step in.
pub const REASKS: usize = 2;

/// What every VLM role holds: the client and the prompts.
#[derive(Debug, Clone)]
pub struct VlmBase {
    /// The model client.
    pub client: ChatClient,
    /// The templates.
    pub prompts: Prompts,
}

impl VlmBase {
    /// Asks `user` (rendered from template `template` with `vars`), with the system prompt and,
    /// for vision models, `image`; reads the answer with `read`. An answer `read` refuses is
    /// asked for again with its reason, [`REASKS`] times at most. `Ok(Err(reason))`: the model
    /// never gave a usable answer (the usage still counts). `Err`: the server failed.
    pub async fn ask<T>(
        &self,
        purpose: &str,
        template: &str,
        vars: &Value,
        image: Option<Arc<Vec<u8>>>,
        schema: &Schema,
        mut read: impl FnMut(&Value) -> Result<T, String>,
    ) -> Result<Output<Result<T, String>>, RoleError> {
        let system = self
            .prompts
            .render("system", vars)
            .map_err(RoleError::Failed)?;
        let user = self
            .prompts
            .render(template, vars)
            .map_err(RoleError::Failed)?;
        let mut messages = vec![
            Message::text("system", system),
            Message {
                role: "user".into(),
                text: user,
                image_png: image.filter(|_| self.client.vision),
            },
        ];
        let mut out = Output::free(Err(String::new()));
        for _ in 0..=REASKS {
            let reply = match self.client.chat(purpose, &messages, Some(schema)).await {
                Ok(r) => r,
                Err((e, record)) => {
                    out.calls.push(record);
                    // A server that answers nonsense is the model's fault: ask again. One that
                    // cannot be reached is the runtime's to retry.
                    if !matches!(e, disco_llm::LlmError::Malformed { .. }) {
                        return Err(RoleError::ModelServer {
                            model: self.client.name().to_string(),
                            reason: e.to_string(),
                        });
                    }
                    out.value = Err(e.to_string());
                    continue;
                }
            };
            out.usage.calls += 1;
            out.usage.prompt_tokens += reply.record.prompt_tokens;
            out.usage.completion_tokens += reply.record.completion_tokens;
            out.calls.push(reply.record);
            let parsed = extract::extract_json(&reply.content).and_then(|v| read(&v));
            match parsed {
                Ok(v) => {
                    out.value = Ok(v);
                    return Ok(out);
                }
                Err(reason) => {
                    tracing::debug!(purpose, %reason, "model answer refused");
                    out.value = Err(reason.clone());
                    messages.push(Message::text("assistant", reply.content));
                    messages.push(Message::text(
                        "user",
                        format!(
                            "That answer could not be used: {reason}. Answer again with the complete JSON in the requested shape, using only the names given."
                        ),
                    ));
                }
            }
        }
        Ok(out)
    }
}

/// The scene, as prompt variables: `id`, `prompt`, `room_type`, `room`, `assets`. `room` has
/// `width` and `depth` (of the bounding box), and `outline`, the outline and openings in words,
/// only when the room is not a plain rectangle without openings.
pub fn scene_vars(scene: &SceneSpec) -> Value {
    let mut room = json!({"width": round(scene.room.width), "depth": round(scene.room.depth)});
    if let Some(words) = room_words::describe_room(&scene.room) {
        room["outline"] = json!(words);
    }
    json!({
        "id": scene.id,
        "prompt": scene.prompt,
        "room_type": scene.room_type,
        "room": room,
        "assets": scene.assets.iter().map(|a| json!({
            "name": a.name, "category": a.category, "size": a.size.map(round),
        })).collect::<Vec<_>>(),
    })
}

/// Objects as prompt variables: name, category, size, position, rotation, rounded to 1 cm.
pub fn object_vars(objects: &[PlacedObject]) -> Vec<Value> {
    objects
        .iter()
        .map(|o| {
            json!({
                "name": o.name, "category": o.category, "size": o.size.map(round),
                "position": o.position.map(round), "rotation": round(o.rotation),
            })
        })
        .collect()
}

/// A constraint in words, from the subject's point of view: `against a wall`, `side of bed-0`.
pub fn describe(kind: &ConstraintKind) -> String {
    match kind {
        ConstraintKind::AgainstWall => "against a wall".into(),
        ConstraintKind::Relation { relation, target } => format!("{} {target}", relation.words()),
        ConstraintKind::Facing { target } => format!("facing {target}"),
        ConstraintKind::Place(place) => place.to_string(),
    }
}

/// Whole numbers print without a fraction, so prompts read `[160, 210]`.
fn round(v: f64) -> Value {
    let r = (v * 10.0).round() / 10.0;
    if r.fract() == 0.0 && r.abs() < 1e12 {
        json!(r as i64)
    } else {
        json!(r)
    }
}

/// A yes/no answer read leniently: `"yes"`, `"Yes."`, `true`, `"no"`, `false`.
pub fn yes_no(v: &Value) -> Option<bool> {
    match v {
        Value::Bool(b) => Some(*b),
        Value::String(s) => {
            let s = s.trim().to_lowercase();
            if s.starts_with("yes") || s == "true" || s == "y" {
                Some(true)
            } else if s.starts_with("no") || s == "false" || s == "n" {
                Some(false)
            } else {
                None
            }
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every prompt rendered for the synthetic bedroom: a change to a template or to what it is
    /// given shows up as a snapshot diff (`cargo insta review`).
    #[test]
    fn prompts_for_a_fixed_scene() {
        let (scene, layout) = disco_core::synth::bedroom();
        let prompts = Prompts::default();
        let mut vars = scene_vars(&scene);
        vars["objects"] = json!(object_vars(&layout.objects[..3]));
        vars["placed"] = json!(object_vars(&layout.objects[..1]));
        vars["group"] = json!([{
            "name": "nightstand-0", "category": "nightstand", "size": [50, 40, 55],
            "constraints": ["against a wall", "side of bed-0"],
        }]);
        vars["question"] = json!("Is nightstand-0 beside bed-0?");
        vars["questions"] = json!([
            {"id": 0, "text": "Is nightstand-0 beside bed-0?"},
            {"id": 1, "text": "Does wardrobe-0 stand against a wall?"},
        ]);
        vars["failed"] =
            json!([{"question": "Is nightstand-0 beside bed-0?", "reason": "it is 2 m away"}]);
        vars["movable"] = json!(["nightstand-0"]);
        vars["has_image"] = json!(true);
        for (name, _) in disco_llm::BUILTIN_PROMPTS {
            let text = prompts.render(name, &vars).unwrap();
            insta::assert_snapshot!(format!("prompt_{name}"), text);
        }
    }

    /// A polygon room with a door and a window: every prompt states the outline and the
    /// openings; the rectangular snapshot above stays as it was.
    #[test]
    fn prompts_for_a_polygon_room_state_its_outline() {
        let (mut scene, layout) = disco_core::synth::bedroom();
        let mut room = disco_core::scene::Room::from_polygon(vec![
            [0.0, 0.0],
            [480.0, 0.0],
            [480.0, 280.0],
            [320.0, 280.0],
            [320.0, 420.0],
            [0.0, 420.0],
        ]);
        room.doors.push(disco_core::room::Door::new(0, 400.0, 80.0));
        scene.room = room;
        let mut vars = scene_vars(&scene);
        vars["objects"] = json!(object_vars(&layout.objects[..3]));
        vars["placed"] = json!(object_vars(&layout.objects[..1]));
        vars["group"] = json!([]);
        let prompts = Prompts::default();
        for (name, _) in disco_llm::BUILTIN_PROMPTS {
            let text = prompts.render(name, &vars).unwrap();
            if name == "system" {
                assert!(text.contains("outline and openings are given"), "{text}");
                assert!(!text.contains("rectangular"), "{text}");
            } else {
                assert!(text.contains("(320, 280)"), "{name}: {text}");
                assert!(text.contains("- door 0 in wall 0"), "{name}: {text}");
            }
        }
    }

    #[test]
    fn yes_no_leniently() {
        assert_eq!(yes_no(&json!("Yes.")), Some(true));
        assert_eq!(yes_no(&json!(false)), Some(false));
        assert_eq!(yes_no(&json!("maybe")), None);
    }
}
