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
pub mod formation;
pub mod judge;
pub mod measure;
pub mod mount;
pub mod patch;
mod planner;
pub mod room_words;
pub mod schema;
mod srt;
#[cfg(test)]
mod test_server;

use std::sync::Arc;

use serde_json::{Value, json};

pub use designer::VlmDesigner;
pub use evaluator::VlmEvaluator;
pub use patch::VlmPatch;
pub use planner::VlmPlanner;
pub use srt::VlmSrt;

use disco_core::layout::PlacedObject;
use disco_core::plan::Plan;
use disco_core::relations::ConstraintKind;
use disco_core::roles::{Output, RoleError, SceneContext};
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

/// The scene, as prompt variables: `id`, `prompt`, `room_type`, `a_room_type` (with its article:
/// `an office`), `room`, `assets`. `room` has `width` and `depth` (of the bounding box), and
/// `outline`, the outline and openings in words, only when the room is not a plain rectangle
/// without openings.
pub fn scene_vars(scene: &SceneSpec) -> Value {
    let mut room = json!({"width": round(scene.room.width), "depth": round(scene.room.depth)});
    if let Some(words) = room_words::describe_room(&scene.room) {
        room["outline"] = json!(words);
    }
    // The angles beyond the right angles a pose may take: those of the slanted walls.
    let slanted: Vec<i64> = schema::allowed_turns(&scene.room)
        .into_iter()
        .filter(|t| t % 90.0 != 0.0)
        .map(|t| t as i64)
        .collect();
    if !slanted.is_empty() {
        room["turns"] = json!(slanted);
    }
    json!({
        "id": scene.id,
        "prompt": scene.prompt,
        "room_type": scene.room_type,
        "a_room_type": with_article(&scene.room_type),
        "room": room,
        // The walkway the reach check needs (cm), as the prompts state it.
        "walkway_cm": disco_core::metrics::AGENT_WIDTH_CM as i64,
        "assets": scene.assets.iter().map(|a| json!({
            "name": a.name, "category": a.category, "size": a.size.map(round),
        })).collect::<Vec<_>>(),
    })
}

/// The off-floor parts of the prompt variables, for a request made under `plan` about
/// `objects`, when either takes something off the floor ([`mount::plan_leaves_floor`]):
/// `off_floor` is set, and a plain rectangle's walls are listed by index as `room.outline`
/// (with `room.walls_only`, so the system prompt still calls the room rectangular), so the
/// model can name the wall a piece hangs on. Floor-only requests are left exactly as they were.
pub fn off_floor_vars(vars: &mut Value, scene: &SceneSpec, plan: &Plan, objects: &[PlacedObject]) {
    if !mount::plan_leaves_floor(plan, objects) {
        return;
    }
    vars["off_floor"] = json!(true);
    if vars["room"].get("outline").is_none() {
        vars["room"]["outline"] = json!(room_words::describe_walls(&scene.room));
        vars["room"]["walls_only"] = json!(true);
    }
}

/// `a bedroom`, `an office`: the indefinite article by the first letter's sound (a vowel).
pub fn with_article(noun: &str) -> String {
    let vowel = noun
        .trim()
        .chars()
        .next()
        .is_some_and(|c| "aeiouAEIOU".contains(c));
    format!("{} {}", if vowel { "an" } else { "a" }, noun.trim())
}

/// What a tool moved since the agent's last request, one line each, as prompt variable
/// `moved` (empty when nothing moved).
pub fn moved_vars(ctx: &SceneContext) -> Vec<String> {
    ctx.moved.iter().map(ToString::to_string).collect()
}

/// The rules the plan and the room set for one piece, in words: against a wall; for a piece
/// that stands on a wall, which windows it may stand under (no taller than the sill) and which
/// it must keep clear of (a free-standing piece needs only the rule the room states once per
/// window); and what the piece is for ([`crate::uses::use_words`]: a counter's staff side, a
/// table's seats).
pub fn piece_rules(ctx: &SceneContext, name: &str, height: f64) -> Vec<String> {
    let mut rules = Vec::new();
    if ctx.plan.wants_wall(name) {
        rules.push("its back must touch a wall".to_string());
    }
    // A piece hung on a wall or standing on a top is judged by the openings themselves.
    if on_a_wall(&ctx.plan, name) && ctx.plan.support_of(name).is_none() {
        rules.extend(room_words::window_rules(&ctx.scene.room, height));
    }
    if let Some(a) = ctx.scene.asset(name) {
        rules.extend(crate::uses::use_words(
            &crate::knowledge::Knowledge::builtin(),
            a,
        ));
    }
    rules
}

/// Whether the plan puts `name` where a window's sill concerns it: against a wall, on a wall of
/// some role, or under a window.
pub fn on_a_wall(plan: &disco_core::plan::Plan, name: &str) -> bool {
    plan.constraints.get(name).is_some_and(|c| {
        c.against_wall
            || c.place
                .as_ref()
                .is_some_and(|p| p.wall.is_some() || p.under_window)
    })
}

/// Objects as prompt variables: name, category, size, position, rotation, rounded to 1 cm; and
/// for an object off the floor, `held`: what holds it and how high ([`mount::held_words`]).
pub fn object_vars(objects: &[PlacedObject]) -> Vec<Value> {
    objects
        .iter()
        .map(|o| {
            let mut v = json!({
                "name": o.name, "category": o.category, "size": o.size.map(round),
                "position": o.position.map(round), "rotation": round(o.rotation),
            });
            if let Some(held) = mount::held_words(o) {
                v["held"] = json!(held);
            }
            v
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
            "rules": ["it is no taller than window 0's sill (85 cm): it may stand under window 0"],
        }]);
        vars["words"] = json!([
            "against a wall means its back edge lies on a wall",
            "beside means its centre lies past bed-0's left or right edge",
        ]);
        vars["moved"] = json!([disco_core::roles::ToolMove {
            name: "wardrobe-0".into(),
            by: "prt".into(),
            from: [30.0, 100.0],
            from_rotation: 90.0,
            to: [30.0, 120.0],
            to_rotation: 90.0,
            why: "it overlapped desk-0".into(),
        }
        .to_string()]);
        vars["rules"] = json!(["nightstand-0: its back must touch a wall"]);
        vars["against_wall"] = json!(["bed-0", "nightstand-0"]);
        vars["question"] = json!("Is nightstand-0 beside bed-0?");
        let beside = disco_core::relations::ConstraintKind::Relation {
            relation: disco_core::plan::Relation::SideOf,
            target: "bed-0".into(),
        };
        vars["means"] = json!(measure::meaning(&beside));
        vars["measured"] = json!(
            measure::measure(&layout, "nightstand-0", &beside)
                .unwrap()
                .values
        );
        vars["questions"] = json!([
            {"id": 0, "text": "Is nightstand-0 beside bed-0?", "means": vars["means"], "measured": vars["measured"]},
            {"id": 1, "text": "Does the bedroom look right?", "means": null, "measured": null},
        ]);
        vars["failed"] = json!([{
            "id": 0, "question": "Is nightstand-0 beside bed-0?", "reason": "it is 2 m away",
            "means": vars["means"], "measured": vars["measured"],
        }]);
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

    /// A layout with a lamp on a nightstand and a painting on a wall: every prompt that lists
    /// objects says what holds them, the walls of the plain rectangle are listed by index, the
    /// system prompt still calls the room rectangular and says what leaving the floor means,
    /// and the physical question counts floating and hanging over openings.
    #[test]
    fn prompts_off_the_floor_name_the_walls_and_what_holds_each_piece() {
        let (mut scene, mut layout) = disco_core::synth::bedroom();
        scene.assets.push(disco_core::scene::Asset::new(
            "lamp-0",
            "table lamp",
            [30.0, 30.0, 50.0],
        ));
        let stand = layout.object("nightstand-0").unwrap().clone();
        layout.objects.push(PlacedObject {
            name: "lamp-0".into(),
            category: "table lamp".into(),
            size: [30.0, 30.0, 50.0],
            position: stand.position,
            rotation: stand.rotation,
            elevation: 55.0,
            on: Some("nightstand-0".into()),
            wall: None,
        });
        let mut vars = scene_vars(&scene);
        off_floor_vars(&mut vars, &scene, &layout.plan, &layout.objects);
        vars["objects"] = json!(object_vars(&layout.objects));
        vars["placed"] = vars["objects"].clone();
        vars["group"] = json!([]);
        vars["failed"] = json!([]);
        vars["movable"] = json!(["lamp-0"]);
        vars["held"] = json!(["lamp-0"]);
        let prompts = Prompts::default();
        let system = prompts.render("system", &vars).unwrap();
        assert!(system.contains("rectangular room"), "{system}");
        assert!(
            system.contains("The room spans x from 0 to 400"),
            "{system}"
        );
        assert!(system.contains("Some objects leave the floor"), "{system}");
        for name in [
            "designer",
            "evaluator",
            "evaluator_batch",
            "physical",
            "srt",
            "judge",
        ] {
            let text = prompts.render(name, &vars).unwrap();
            assert!(
                text.contains("- wall 2: from (400, 350) to (0, 350), 350 cm long")
                    || text.contains("- wall 2: from (400, 350) to (0, 350), 400 cm long"),
                "{name}: {text}"
            );
            assert!(
                text.contains(
                    "rotation 180, on top of nightstand-0, its bottom 55 cm above the floor"
                ),
                "{name}: {text}"
            );
        }
        let physical = prompts.render("physical", &vars).unwrap();
        assert!(physical.contains("float with nothing holding it, hang over a door or a window"));
        let srt = prompts.render("srt", &vars).unwrap();
        assert!(
            srt.contains("For lamp-0, which leaves the floor, give instead what should hold it")
        );
        // The same layout without the lamp is a floor-only request: none of it appears.
        layout.objects.pop();
        let mut vars = scene_vars(&scene);
        off_floor_vars(&mut vars, &scene, &layout.plan, &layout.objects);
        assert!(vars.get("off_floor").is_none());
        assert!(vars["room"].get("outline").is_none());
    }

    #[test]
    fn articles_and_piece_rules() {
        assert_eq!(with_article("office"), "an office");
        assert_eq!(with_article("bedroom"), "a bedroom");
        let (mut scene, layout) = disco_core::synth::bedroom();
        scene.room.windows.push(disco_core::room::Window {
            wall: 0,
            at: 200.0,
            width: 100.0,
            sill: 85.0,
            height: 120.0,
        });
        let ctx = SceneContext::new(
            std::sync::Arc::new(scene),
            std::sync::Arc::clone(&layout.plan),
        );
        let wardrobe = piece_rules(&ctx, "wardrobe-0", 200.0);
        assert_eq!(wardrobe.len(), 2, "{wardrobe:?}");
        assert_eq!(wardrobe[0], "its back must touch a wall");
        assert_eq!(
            wardrobe[1],
            "it is too tall for under window 0 (sill 85 cm): keep it 40 cm clear"
        );
        // A rug stands on no wall: the window's rule, stated once with the room, is all it needs.
        let rug = piece_rules(&ctx, "rug-0", 1.0);
        assert!(rug.is_empty(), "{rug:?}");
        assert_eq!(
            room_words::window_rules(&ctx.scene.room, 1.0).as_deref(),
            Some("it may stand under window 0 (sill 85 cm)")
        );
    }

    #[test]
    fn yes_no_leniently() {
        assert_eq!(yes_no(&json!("Yes.")), Some(true));
        assert_eq!(yes_no(&json!(false)), Some(false));
        assert_eq!(yes_no(&json!("maybe")), None);
    }
}
