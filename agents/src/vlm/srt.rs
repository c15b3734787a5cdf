//! The VLM Semantic Refinement Tool: the model proposes small moves for the objects whose
//! questions failed; only objects of the current group move.

use std::collections::HashSet;

use async_trait::async_trait;
use serde_json::{Value, json};

use super::schema::{self, ReadPose, read_infeasible, read_poses};
use super::{
    VlmBase, measure, mount, moved_vars, object_vars, off_floor_vars, piece_rules, scene_vars,
};
use disco_core::layout::{Layout, PlacedObject};
use disco_core::roles::{Infeasible, Output, RoleResult, SemanticRefiner, SrtRequest};
use disco_core::scene::Room;
use disco_llm::extract::NameMap;

/// Refines with a model.
pub struct VlmSrt {
    base: VlmBase,
}

impl VlmSrt {
    /// An SRT over `base`.
    pub fn new(base: VlmBase) -> Self {
        VlmSrt { base }
    }
}

#[async_trait]
impl SemanticRefiner for VlmSrt {
    async fn refine(&self, req: &SrtRequest) -> RoleResult<Vec<PlacedObject>> {
        if req.failed.is_empty() || req.movable.is_empty() {
            return Ok(Output::free(Vec::new()));
        }
        let scene = &req.ctx.scene;
        let mut vars = scene_vars(scene);
        vars["objects"] = json!(object_vars(&req.layout.objects));
        vars["failed"] = json!(
            req.failed
                .iter()
                .enumerate()
                .map(|(i, (q, a))| {
                    let measured = q
                        .subject
                        .as_deref()
                        .zip(q.constraint.as_ref())
                        .and_then(|(s, k)| measure::measure(&req.layout, s, k));
                    json!({
                        "id": i,
                        "question": q.text,
                        "reason": a.reason,
                        "means": q.constraint.as_ref().map(measure::meaning),
                        "measured": measured.map(|m| m.values),
                    })
                })
                .collect::<Vec<_>>()
        );
        vars["movable"] = json!(req.movable);
        vars["rules"] = json!(
            req.movable
                .iter()
                .filter_map(|n| {
                    let o = req.layout.object(n)?;
                    let mut rules = piece_rules(&req.ctx, n, o.size[2]);
                    for f in super::formation::formations_about(&req.ctx.plan, n) {
                        rules.push(format!(
                            "{} move with it as a whole (a formation about it)",
                            f.members.join(", ")
                        ));
                    }
                    (!rules.is_empty()).then(|| format!("{n}: {}", rules.join("; ")))
                })
                .collect::<Vec<_>>()
        );
        vars["moved"] = json!(moved_vars(&req.ctx));
        vars["has_image"] = json!(self.base.client.vision && req.render.is_some());
        off_floor_vars(&mut vars, scene, &req.ctx.plan, &req.layout.objects);
        // Movable pieces off the floor are moved by naming what holds them (see `mount`).
        let held: HashSet<String> = req
            .movable
            .iter()
            .filter(|n| {
                req.ctx.plan.support_of(n).is_some()
                    || req.layout.object(n).is_some_and(|o| !o.on_floor())
            })
            .cloned()
            .collect();
        let held_list: Vec<String> = req
            .movable
            .iter()
            .filter(|n| held.contains(*n))
            .cloned()
            .collect();
        let walls = scene.room.walls().len();
        let schema = match held.is_empty() {
            true => schema::moves(&req.movable),
            false => {
                vars["held"] = json!(held_list);
                let targets: Vec<String> = scene.assets.iter().map(|a| a.name.clone()).collect();
                schema::moves_off_floor(&req.movable, &held_list, &targets, walls)
            }
        };
        let schema = schema::with_turns(schema, &scene.room);
        let scene_names = NameMap::new(scene.assets.iter().map(|a| a.name.clone()));
        let names = NameMap::new(req.movable.iter().cloned());
        let count = req.failed.len();
        let out = self
            .base
            .ask("srt", "srt", &vars, req.render.clone(), &schema, |v| {
                let infeasible = read_infeasible(v, count);
                let mut trial = names.clone();
                let (rest, mounts, mut notes) = match held.is_empty() {
                    true => (v.clone(), Vec::new(), Vec::new()),
                    false => mount::read_mounts(v, &mut trial, &held, &scene_names, walls)?,
                };
                match read_moves(&rest, &mut trial, &scene.room) {
                    Ok((moves, more)) => {
                        notes.extend(more);
                        Ok(((moves, notes), mounts, infeasible))
                    }
                    // Nothing to move because nothing can be done: a valid answer.
                    Err(_) if !infeasible.is_empty() || !mounts.is_empty() => {
                        Ok(((Vec::new(), notes), mounts, infeasible))
                    }
                    Err(e) => Err(e),
                }
            })
            .await?;
        let mut reported = Vec::new();
        let mut mounts = Vec::new();
        let out = out.map(|r| {
            r.map(|(moves, read, infeasible)| {
                reported = infeasible;
                mounts = read;
                moves
            })
        });
        let mut moves = into_moves(out, &req.layout);
        // The pieces off the floor last, among the layout as the floor moves leave it.
        for m in &mounts {
            let Some(asset) = scene.asset(&m.name) else {
                continue;
            };
            let now: Vec<PlacedObject> = req
                .layout
                .objects
                .iter()
                .filter(|o| o.name != m.name)
                .map(|o| {
                    moves
                        .value
                        .iter()
                        .find(|n| n.name == o.name)
                        .unwrap_or(o)
                        .clone()
                })
                .collect();
            let (posed, note) = mount::pose_held(scene, &req.ctx.plan, asset, m, &now);
            moves.notes.extend(note);
            moves.value.push(posed);
        }
        for (i, reason) in reported {
            let Some((q, _)) = req.failed.get(i) else {
                continue;
            };
            if let (Some(subject), Some(constraint)) = (&q.subject, &q.constraint) {
                moves.infeasible.push(Infeasible {
                    subject: subject.clone(),
                    constraint: constraint.clone(),
                    reason,
                });
            }
        }
        Ok(moves)
    }

    fn wants_render(&self) -> bool {
        self.base.client.vision
    }
}

/// What reading a model's poses gives: the poses and notes, or why none was usable.
pub(super) type PosesRead = Result<(Vec<ReadPose>, Vec<String>), String>;

/// Moves read from a model's answer, as [`read_poses`] reads poses, except that an empty list
/// (`{"objects": []}`) is a valid answer: nothing needs to move. (A designer must pose something;
/// a refiner or custom stage may well leave the layout as it is.)
pub(super) fn read_moves(v: &Value, names: &mut NameMap, room: &Room) -> PosesRead {
    let objects = v.get("objects").and_then(Value::as_array).or(v.as_array());
    if objects.is_some_and(Vec::is_empty) {
        return Ok((Vec::new(), Vec::new()));
    }
    read_poses(v, names, room)
}

/// The model's poses as moves of objects already in `layout` (names it does not hold are
/// skipped); an unusable answer moves nothing and says so in the notes.
pub(super) fn into_moves(mut out: Output<PosesRead>, layout: &Layout) -> Output<Vec<PlacedObject>> {
    let moves = match std::mem::replace(&mut out.value, Err(String::new())) {
        Ok((poses, notes)) => {
            out.notes.extend(notes);
            poses
                .into_iter()
                .filter_map(|p| {
                    let o = layout.object(&p.name)?;
                    Some(PlacedObject {
                        position: p.position,
                        rotation: p.rotation,
                        ..o.clone()
                    })
                })
                .collect()
        }
        Err(reason) => {
            out.notes.push(format!(
                "no usable moves from the model ({reason}); nothing moved"
            ));
            Vec::new()
        }
    };
    out.map(|_| moves)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::vlm::test_server::{base, model_answering};
    use disco_core::roles::{Answer, Question, SceneContext};

    #[tokio::test]
    async fn an_empty_move_list_is_a_valid_answer_not_asked_again() {
        let (url, calls) = model_answering(r#"{"objects": []}"#).await;
        let srt = VlmSrt::new(base(url));
        let (scene, layout) = disco_core::synth::bedroom();
        let question = Question {
            id: 0,
            text: "Is it true that nightstand-0 is next to bed-0?".into(),
            subject: Some("nightstand-0".into()),
            constraint: None,
        };
        let answer = Answer {
            id: 0,
            yes: false,
            reason: "it is across the room".into(),
        };
        let req = SrtRequest {
            ctx: SceneContext::new(Arc::new(scene), Arc::clone(&layout.plan)),
            layout,
            failed: vec![(question, answer)],
            movable: vec!["nightstand-0".into()],
            render: None,
        };
        let out = srt.refine(&req).await.unwrap();
        assert!(out.value.is_empty());
        assert_eq!(calls.lock().unwrap().len(), 1, "one question, one answer");
        assert!(
            out.notes.iter().all(|n| !n.contains("no usable")),
            "{:?}",
            out.notes
        );
    }

    #[tokio::test]
    async fn a_piece_off_the_floor_is_moved_by_naming_what_holds_it() {
        let (url, calls) = model_answering(
            r#"{"objects": [{"name": "painting-0", "wall": 2, "above": "bed-0"}], "infeasible": []}"#,
        )
        .await;
        let srt = VlmSrt::new(base(url));
        let (mut scene, mut layout) = disco_core::synth::bedroom();
        scene.assets.push(disco_core::scene::Asset::new(
            "painting-0",
            "framed painting",
            [100.0, 4.0, 70.0],
        ));
        // Hung on the wrong wall: the bottom one, far from the bed (whose head is on wall 2).
        layout.objects.push(PlacedObject {
            name: "painting-0".into(),
            category: "framed painting".into(),
            size: [100.0, 4.0, 70.0],
            position: [100.0, 2.1],
            rotation: 0.0,
            elevation: 120.0,
            on: None,
            wall: Some(0),
        });
        let mut plan = (*layout.plan).clone();
        plan.constraints.insert(
            "painting-0".into(),
            disco_core::plan::ObjectConstraints {
                support: Some(disco_core::scene::Support::Wall),
                relations: vec![disco_core::plan::RelationSpec {
                    relation: disco_core::plan::Relation::Above,
                    target: "bed-0".into(),
                }],
                ..Default::default()
            },
        );
        let question = Question {
            id: 0,
            text: "Is painting-0 hung above bed-0?".into(),
            subject: Some("painting-0".into()),
            constraint: None,
        };
        let answer = Answer {
            id: 0,
            yes: false,
            reason: "it hangs on the other wall".into(),
        };
        let req = SrtRequest {
            ctx: SceneContext::new(Arc::new(scene), Arc::new(plan)),
            layout,
            failed: vec![(question, answer)],
            movable: vec!["painting-0".into()],
            render: None,
        };
        let out = srt.refine(&req).await.unwrap();
        assert_eq!(calls.lock().unwrap().len(), 1);
        assert_eq!(out.value.len(), 1, "{:?}", out.notes);
        let p = &out.value[0];
        assert_eq!(p.wall, Some(2), "{p:?}");
        assert!(
            (p.position[0] - 200.0).abs() < 1e-6,
            "centred over the bed: {p:?}"
        );
        assert_eq!(p.elevation, 120.0, "20 cm over the bed's 100 cm top");
    }
}
