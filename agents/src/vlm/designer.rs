//! The VLM designer: poses for one group from the model, with the render of the layout so far;
//! objects it leaves out are asked for once more, then placed by the rules.

use async_trait::async_trait;
use serde_json::json;

use super::schema::{self, read_poses};
use super::{VlmBase, describe, measure, moved_vars, object_vars, room_words, scene_vars};
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
        let mut names = NameMap::new(req.group.iter().cloned());
        let mut out: Output<Vec<PlacedObject>> = Output::free(Vec::new());
        let mut wanted = req.group.clone();
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
                        "rules": room_words::window_rules(&scene.room, a.size[2])
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
        Ok(out)
    }

    fn wants_render(&self) -> bool {
        self.base.client.vision
    }
}
