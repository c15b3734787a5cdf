//! The VLM designer: poses for one group from the model, with the render of the layout so far;
//! objects it leaves out are asked for once more, then placed by the rules. Members of a
//! formation are not asked for: the formation's shape poses them about what the model placed
//! (see [`formation`]); a group of nothing but such members makes no model call.

use std::collections::HashSet;

use async_trait::async_trait;
use serde_json::json;

use super::mount::{self, ReadMount};
use super::schema::{self, read_poses};
use super::{
    VlmBase, describe, formation, measure, moved_vars, object_vars, off_floor_vars, on_a_wall,
    room_words, scene_vars,
};
use crate::rules::RuleDesigner;
use disco_core::layout::PlacedObject;
use disco_core::relations::constraints_of;
use disco_core::roles::{DesignRequest, Designer, Output, RoleResult};
use disco_core::scene::Asset;
use disco_llm::extract::NameMap;

/// Poses groups with a model.
pub struct VlmDesigner {
    base: VlmBase,
}

impl VlmDesigner {
    /// A designer over `base`.
    pub fn new(base: VlmBase) -> Self {
        VlmDesigner { base }
    }
}

fn placed_object(a: &Asset, position: [f64; 2], rotation: f64) -> PlacedObject {
    PlacedObject {
        name: a.name.clone(),
        category: a.category.clone(),
        size: a.size,
        position,
        rotation,
        ..Default::default()
    }
}

#[async_trait]
impl Designer for VlmDesigner {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        let scene = &req.ctx.scene;
        let plan = &req.ctx.plan;
        let mut out: Output<Vec<PlacedObject>> = Output::free(Vec::new());
        // Members of a formation (and the chairs of desks in rows or pods) are posed by the
        // formation's exact shape once the model has placed the rest; the model is told so.
        let (shaped, mut wanted): (Vec<String>, Vec<String>) = req
            .group
            .iter()
            .cloned()
            .partition(|n| formation::posed_by_formation(plan, n));
        let formations: Vec<String> = plan
            .formations
            .iter()
            .filter(|f| f.members.iter().any(|m| shaped.contains(m)))
            .map(|f| formation::describe_formation(scene, f))
            .collect();
        let mut names = NameMap::new(wanted.iter().cloned());
        // Pieces the plan takes off the floor: the model names what holds them, and code poses
        // them last, once everything that could hold them stands.
        let held: HashSet<String> = wanted
            .iter()
            .filter(|n| plan.support_of(n).is_some())
            .cloned()
            .collect();
        let scene_names = NameMap::new(scene.assets.iter().map(|a| a.name.clone()));
        let walls = scene.room.walls().len();
        let mut mounts: Vec<ReadMount> = Vec::new();
        // The group, then a second request for what the first answer left out.
        for round in 0..2 {
            if wanted.is_empty() {
                break;
            }
            let mut placed = req.placed.clone();
            placed.extend(out.value.iter().cloned());
            let mut words: Vec<String> = Vec::new();
            let group: Vec<_> = wanted
                .iter()
                .filter_map(|n| scene.asset(n))
                .map(|a| {
                    let constraints = constraints_of(plan, &a.name);
                    for c in &constraints {
                        let m = measure::meaning(c);
                        if !words.contains(&m) {
                            words.push(m);
                        }
                    }
                    let mut entry = json!({
                        "name": a.name, "category": a.category, "size": a.size.map(|v| v.round() as i64),
                        "constraints": constraints.iter().map(describe).collect::<Vec<_>>(),
                        // The windows concern a piece only where it could stand under one:
                        // on a wall (each window's rule is stated once, with the room); a piece
                        // hung on a wall keeps clear of the openings themselves.
                        "rules": (on_a_wall(plan, &a.name) && !held.contains(&a.name))
                            .then(|| room_words::window_rules(&scene.room, a.size[2]))
                            .flatten()
                            .into_iter()
                            .chain(crate::uses::use_words(&crate::knowledge::Knowledge::builtin(), a))
                            .collect::<Vec<_>>(),
                    });
                    if let Some(h) = mount::held_request(scene, plan, &a.name, &placed) {
                        entry["held"] = json!(h);
                    }
                    entry
                })
                .collect();
            let mut vars = scene_vars(scene);
            off_floor_vars(&mut vars, scene, plan, &placed);
            let held_now: Vec<String> = wanted
                .iter()
                .filter(|n| held.contains(*n))
                .cloned()
                .collect();
            if !held_now.is_empty() {
                vars["held"] = json!(held_now);
                vars["all_held"] = json!(held_now.len() == wanted.len());
            }
            vars["group"] = json!(group);
            vars["formations"] = json!(formations);
            vars["words"] = json!(words);
            vars["moved"] = json!(moved_vars(&req.ctx));
            vars["placed"] = json!(object_vars(&placed));
            vars["has_image"] = json!(self.base.client.vision && req.render.is_some());
            let purpose = format!("designer: {}", wanted.join(", "));
            let schema = match held_now.is_empty() {
                true => schema::poses(&wanted),
                false => {
                    let targets: Vec<String> =
                        scene.assets.iter().map(|a| a.name.clone()).collect();
                    schema::poses_off_floor(&wanted, &held_now, &targets, walls)
                }
            };
            let schema = schema::with_turns(schema, &scene.room);
            let asked = self
                .base
                .ask(
                    &purpose,
                    "designer",
                    &vars,
                    req.render.clone(),
                    &schema,
                    |v| {
                        // Read against a copy, so a refused answer takes no names.
                        let mut trial = names.clone();
                        if held_now.is_empty() {
                            return read_poses(v, &mut trial, &scene.room)
                                .map(|r| ((r, Vec::new()), trial));
                        }
                        let (rest, mounts, mut notes) =
                            mount::read_mounts(v, &mut trial, &held, &scene_names, walls)?;
                        let poses = match read_poses(&rest, &mut trial, &scene.room) {
                            Ok((poses, more)) => {
                                notes.extend(more);
                                poses
                            }
                            // Only pieces off the floor were asked for, or answered.
                            Err(_) if !mounts.is_empty() => Vec::new(),
                            Err(e) => return Err(e),
                        };
                        Ok((((poses, notes), mounts), trial))
                    },
                )
                .await?;
            match out.absorb(asked) {
                Ok((((poses, notes), read), taken)) => {
                    names = taken;
                    mounts.extend(read);
                    out.notes.extend(notes);
                    for p in poses {
                        if let Some(a) = scene.asset(&p.name) {
                            out.value.push(placed_object(a, p.position, p.rotation));
                        }
                    }
                }
                Err(reason) => out
                    .notes
                    .push(format!("no usable poses (round {}): {reason}", round + 1)),
            }
            wanted = names.missing();
        }
        if !wanted.is_empty() {
            out.notes.push(format!(
                "the model did not place {}; the rules designer placed them",
                wanted.join(", ")
            ));
            let assets: Vec<&Asset> = wanted.iter().filter_map(|n| scene.asset(n)).collect();
            let mut placed = req.placed.clone();
            placed.extend(out.value.iter().cloned());
            let by_rules = RuleDesigner::new().design_group(scene, plan, &assets, &placed);
            out.value.extend(by_rules);
        }
        if !shaped.is_empty() {
            let members: Vec<&Asset> = shaped.iter().filter_map(|n| scene.asset(n)).collect();
            let mut placed = req.placed.clone();
            placed.extend(out.value.iter().cloned());
            let posed = formation::pose_members(scene, plan, &members, &placed);
            out.notes.push(format!(
                "{} posed by their formation's shape",
                shaped.join(", ")
            ));
            out.value.extend(posed);
        }
        // Last, what leaves the floor, by the model's words, among everything that stands.
        for m in &mounts {
            let Some(asset) = scene.asset(&m.name) else {
                continue;
            };
            let mut placed = req.placed.clone();
            placed.extend(out.value.iter().cloned());
            let (posed, note) = mount::pose_held(scene, plan, asset, m, &placed);
            out.notes.extend(note);
            out.value.push(posed);
        }
        Ok(out)
    }

    fn wants_render(&self) -> bool {
        self.base.client.vision
    }
}

#[cfg(test)]
mod tests {
    use std::sync::{Arc, Mutex};

    use serde_json::{Value, json};

    use super::*;
    use crate::vlm::test_server::{base, model_answering};
    use disco_core::plan::{
        Formation, FormationShape, ObjectConstraints, Plan, Relation, RelationSpec,
    };
    use disco_core::roles::SceneContext;
    use disco_core::scene::Support;
    use disco_core::scene::{Room, SceneSpec};

    /// A model server that places the piano and records every request body.
    async fn model_placing_the_piano() -> (String, Arc<Mutex<Vec<Value>>>) {
        model_answering(
            r#"{"objects": [{"name": "piano-0", "position": [300, 100], "rotation": 0}]}"#,
        )
        .await
    }

    fn designer(url: String) -> VlmDesigner {
        VlmDesigner::new(base(url))
    }

    #[tokio::test]
    async fn the_model_poses_the_focus_and_the_formation_poses_its_members() {
        let (url, seen) = model_placing_the_piano().await;
        let members: Vec<String> = (0..3).map(|i| format!("chair-{i}")).collect();
        let mut assets = vec![Asset::new("piano-0", "piano", [150.0, 150.0, 100.0])];
        assets.extend(
            members
                .iter()
                .map(|m| Asset::new(m, "chair", [50.0, 50.0, 90.0])),
        );
        let scene = SceneSpec {
            id: "t".into(),
            prompt: "chairs in an arc facing the piano".into(),
            room_type: "music room".into(),
            room: Room::rect(600.0, 500.0),
            assets,
        };
        let mut plan = Plan::default();
        plan.formations.push(Formation {
            shape: FormationShape::Arc,
            focus: Some("piano-0".into()),
            members: members.clone(),
            count: None,
            of: Vec::new(),
        });
        // As planners write it: each member faces the focus.
        for m in &members {
            plan.constraints.insert(
                m.clone(),
                disco_core::plan::ObjectConstraints {
                    facing: Some("piano-0".into()),
                    ..Default::default()
                },
            );
        }
        let mut group = vec!["piano-0".to_string()];
        group.extend(members.iter().cloned());
        plan.groups = vec![group.clone()];
        let req = DesignRequest {
            ctx: SceneContext::new(Arc::new(scene), Arc::new(plan)),
            group,
            placed: Vec::new(),
            render: None,
        };
        let out = designer(url.clone()).design(&req).await.unwrap();
        let bodies = seen.lock().unwrap().clone();
        assert_eq!(bodies.len(), 1, "one call: the piano");
        let text = bodies[0].to_string();
        assert!(
            text.contains("an arc of chair-0, chair-1, chair-2 (50 x 50 cm each) about piano-0"),
            "{text}"
        );
        let asked = &bodies[0]["response_format"]["json_schema"]["schema"]["properties"]["objects"]
            ["items"]["properties"]["name"]["enum"];
        assert_eq!(asked, &json!(["piano-0"]), "only the focus is asked for");
        assert_eq!(out.value.len(), 4, "{:?}", out.value);
        let piano = out.value.iter().find(|o| o.name == "piano-0").unwrap();
        assert_eq!(piano.position, [300.0, 100.0], "the model's pose, verbatim");
        for m in &members {
            let chair = out.value.iter().find(|o| &o.name == m).unwrap();
            assert!(
                disco_core::relations::facing(&chair.footprint(), &piano.footprint()),
                "{chair:?} faces the piano"
            );
        }

        // A group of nothing but members, about a focus that stands: no model call at all.
        let mut only = req.clone();
        only.group = members.clone();
        only.placed = vec![piano.clone()];
        let out = designer(url).design(&only).await.unwrap();
        assert_eq!(seen.lock().unwrap().len(), 1, "no call for members alone");
        assert_eq!(out.value.len(), 3);
        assert_eq!(out.usage.calls, 0);
    }

    #[tokio::test]
    async fn the_model_names_what_holds_a_piece_and_code_poses_it_exactly() {
        let (url, seen) = model_answering(
            r#"{"objects": [{"name": "lamp-0", "on": "nightstand-1"}, {"name": "painting-0", "wall": 2, "above": "bed-0"}]}"#,
        )
        .await;
        let (mut scene, layout) = disco_core::synth::bedroom();
        scene.assets.extend([
            Asset::new("lamp-0", "table lamp", [30.0, 30.0, 50.0]),
            Asset::new("painting-0", "framed painting", [100.0, 4.0, 70.0]),
        ]);
        let mut plan = (*layout.plan).clone();
        for (name, support, relation, target) in [
            ("lamp-0", Support::Surface, Relation::On, "nightstand-0"),
            ("painting-0", Support::Wall, Relation::Above, "bed-0"),
        ] {
            plan.constraints.insert(
                name.into(),
                ObjectConstraints {
                    support: Some(support),
                    relations: vec![RelationSpec {
                        relation,
                        target: target.into(),
                    }],
                    ..Default::default()
                },
            );
        }
        let group = vec!["lamp-0".to_string(), "painting-0".to_string()];
        plan.groups.push(group.clone());
        let req = DesignRequest {
            ctx: SceneContext::new(Arc::new(scene), Arc::new(plan)),
            group,
            placed: layout.objects.clone(),
            render: None,
        };
        let out = designer(url).design(&req).await.unwrap();
        let bodies = seen.lock().unwrap().clone();
        assert_eq!(bodies.len(), 1);
        let user = bodies[0]["messages"][1]["content"].as_str().unwrap();
        let system = bodies[0]["messages"][0]["content"].as_str().unwrap();
        assert!(system.contains("rectangular room"), "{system}");
        assert!(system.contains("Some objects leave the floor"), "{system}");
        assert!(
            user.contains(
                "- wall 2: from (400, 350) to (0, 350), 400 cm long, the room lies below it"
            ),
            "the walls by index: {user}"
        );
        assert!(
            user.contains("- lamp-0: table lamp, 30 x 30 cm, 50 cm tall; on top of nightstand-0; it leaves the floor: answer \"on\": \"nightstand-0\" (its top: 50 x 40 cm, 55 cm high)"),
            "{user}"
        );
        assert!(
            user.contains("For lamp-0, painting-0, which leave the floor, give no rotation"),
            "{user}"
        );
        assert!(
            !user.contains("Give every"),
            "nothing here takes a position: {user}"
        );
        let items = &bodies[0]["response_format"]["json_schema"]["schema"]["properties"]["objects"]
            ["items"];
        assert_eq!(items["anyOf"][0]["required"], json!(["name"]), "{items}");
        assert!(out.notes.is_empty(), "{:?}", out.notes);
        // The model's words, posed exactly: the other nightstand, at its top; above the bed.
        let lamp = out.value.iter().find(|o| o.name == "lamp-0").unwrap();
        let stand = layout.object("nightstand-1").unwrap();
        assert_eq!(lamp.on.as_deref(), Some("nightstand-1"));
        assert_eq!(lamp.elevation, stand.top());
        assert!(disco_core::geometry3d::surface_problem(lamp, stand).is_none());
        let painting = out.value.iter().find(|o| o.name == "painting-0").unwrap();
        assert_eq!(painting.wall, Some(2));
        assert_eq!(painting.elevation, 120.0);
        assert!((painting.position[0] - 200.0).abs() < 1e-6, "{painting:?}");
    }
}
