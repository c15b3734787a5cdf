//! The VLM designer: poses for one group from the model, with the render of the layout so far;
//! objects it leaves out are asked for once more, then placed by the rules. Members of a
//! formation are not asked for: the formation's shape poses them about what the model placed
//! (see [`formation`]); a group of nothing but such members makes no model call.

use async_trait::async_trait;
use serde_json::json;

use super::schema::{self, read_poses};
use super::{
    VlmBase, describe, formation, measure, moved_vars, object_vars, on_a_wall, room_words,
    scene_vars,
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
        // The group, then a second request for what the first answer left out.
        for round in 0..2 {
            if wanted.is_empty() {
                break;
            }
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
                    json!({
                        "name": a.name, "category": a.category, "size": a.size.map(|v| v.round() as i64),
                        "constraints": constraints.iter().map(describe).collect::<Vec<_>>(),
                        // The windows concern a piece only where it could stand under one:
                        // on a wall (each window's rule is stated once, with the room).
                        "rules": on_a_wall(plan, &a.name)
                            .then(|| room_words::window_rules(&scene.room, a.size[2]))
                            .flatten()
                            .into_iter()
                            .chain(crate::uses::use_words(&crate::knowledge::Knowledge::builtin(), a))
                            .collect::<Vec<_>>(),
                    })
                })
                .collect();
            let mut placed = req.placed.clone();
            placed.extend(out.value.iter().cloned());
            let mut vars = scene_vars(scene);
            vars["group"] = json!(group);
            vars["formations"] = json!(formations);
            vars["words"] = json!(words);
            vars["moved"] = json!(moved_vars(&req.ctx));
            vars["placed"] = json!(object_vars(&placed));
            vars["has_image"] = json!(self.base.client.vision && req.render.is_some());
            let purpose = format!("designer: {}", wanted.join(", "));
            let asked = self
                .base
                .ask(
                    &purpose,
                    "designer",
                    &vars,
                    req.render.clone(),
                    &schema::poses(&wanted),
                    |v| {
                        // Read against a copy, so a refused answer takes no names.
                        let mut trial = names.clone();
                        read_poses(v, &mut trial, &scene.room).map(|r| (r, trial))
                    },
                )
                .await?;
            match out.absorb(asked) {
                Ok(((poses, notes), taken)) => {
                    names = taken;
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
        Ok(out)
    }

    fn wants_render(&self) -> bool {
        self.base.client.vision
    }
}

#[cfg(test)]
mod tests {
    use std::sync::{Arc, Mutex};

    use axum::Router;
    use axum::routing::post;
    use serde_json::{Value, json};

    use super::*;
    use disco_core::plan::{Formation, FormationShape, Plan};
    use disco_core::roles::SceneContext;
    use disco_core::scene::{Room, SceneSpec};
    use disco_llm::{ChatClient, ModelConfig, Prompts};

    /// A model server that places the piano and records every request body.
    async fn model_placing_the_piano() -> (String, Arc<Mutex<Vec<Value>>>) {
        let seen: Arc<Mutex<Vec<Value>>> = Arc::default();
        let log = Arc::clone(&seen);
        let app = Router::new().route(
            "/v1/chat/completions",
            post(move |axum::Json(body): axum::Json<Value>| {
                log.lock().unwrap().push(body);
                async move {
                    axum::Json(json!({
                        "choices": [{"index": 0, "message": {"role": "assistant",
                            "content": r#"{"objects": [{"name": "piano-0", "position": [300, 100], "rotation": 0}]}"#}}],
                        "usage": {"prompt_tokens": 10, "completion_tokens": 5}
                    }))
                }
            }),
        );
        let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        tokio::spawn(async move { axum::serve(listener, app).await.unwrap() });
        (format!("http://{addr}/v1"), seen)
    }

    fn designer(url: String) -> VlmDesigner {
        let model = ModelConfig {
            base_url: Some(url),
            model: Some("test".into()),
            api_key_env: None,
            max_in_flight: 1,
            rate_per_s: None,
            vision: false,
            options: toml::Table::new(),
        };
        VlmDesigner::new(VlmBase {
            client: ChatClient::from_config("test", &model, None, None).unwrap(),
            prompts: Prompts::default(),
        })
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
}
