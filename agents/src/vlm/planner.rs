//! The VLM planner: constraints and groups from the model; what it leaves out, from the rules.

use std::collections::BTreeMap;

use async_trait::async_trait;
use serde_json::Value;

use super::schema::{self, list};
use super::{VlmBase, scene_vars};
use crate::rules::RulePlanner;
use disco_core::plan::{ObjectConstraints, Plan, RelationSpec};
use disco_core::roles::{Planner, RoleResult};
use disco_core::scene::SceneSpec;
use disco_llm::extract::NameMap;

/// Plans with a model.
pub struct VlmPlanner {
    base: VlmBase,
}

impl VlmPlanner {
    /// A planner over `base`.
    pub fn new(base: VlmBase) -> Self {
        VlmPlanner { base }
    }
}

/// Reads a plan: names mapped to the scene's, unknown relations and targets dropped (noted).
/// An error when no object at all is recognisable.
pub fn read_plan(v: &Value, scene: &SceneSpec) -> Result<(Plan, Vec<String>), String> {
    let names = NameMap::new(scene.assets.iter().map(|a| a.name.clone()));
    let mut notes = Vec::new();
    let mut constraints = BTreeMap::new();
    for item in list(v, "objects")? {
        let written = item.get("name").and_then(Value::as_str).unwrap_or("");
        let Some(name) = names.resolve(written) else {
            notes.push(format!("plan names an unknown object {written:?}"));
            continue;
        };
        let mut c = ObjectConstraints {
            against_wall: item
                .get("against_wall")
                .and_then(super::yes_no)
                .unwrap_or(false),
            ..Default::default()
        };
        for r in item
            .get("relations")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
        {
            let target = r
                .get("target")
                .and_then(Value::as_str)
                .and_then(|t| names.resolve(t));
            match (r.get("relation").and_then(schema::relation), target) {
                (Some(relation), Some(target)) if target != name => {
                    c.relations.push(RelationSpec { relation, target })
                }
                _ => notes.push(format!("ignored relation {r} of {name}")),
            }
        }
        c.facing = item
            .get("facing")
            .and_then(Value::as_str)
            .and_then(|t| names.resolve(t))
            .filter(|t| *t != name);
        constraints.entry(name).or_insert(c);
    }
    if constraints.is_empty() {
        return Err("the plan names none of the objects".into());
    }
    let groups = v
        .get("groups")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(Value::as_array)
        .map(|g| {
            g.iter()
                .filter_map(Value::as_str)
                .filter_map(|n| names.resolve(n))
                .collect::<Vec<_>>()
        })
        .filter(|g| !g.is_empty())
        .collect();
    Ok((
        Plan {
            constraints,
            groups,
            formations: Vec::new(),
        },
        notes,
    ))
}

#[async_trait]
impl Planner for VlmPlanner {
    async fn plan(&self, scene: &SceneSpec) -> RoleResult<Plan> {
        let names: Vec<String> = scene.assets.iter().map(|a| a.name.clone()).collect();
        let vars = scene_vars(scene);
        let mut out = self
            .base
            .ask(
                "planner",
                "planner",
                &vars,
                None,
                &schema::plan(&names),
                |v| read_plan(v, scene),
            )
            .await?;
        let rules = RulePlanner::new().make_plan(scene);
        let plan = match std::mem::replace(&mut out.value, Err(String::new())) {
            Ok((mut plan, notes)) => {
                out.notes.extend(notes);
                // Objects the model said nothing about keep the rules' constraints.
                let missing: Vec<String> = names
                    .iter()
                    .filter(|n| !plan.constraints.contains_key(*n))
                    .cloned()
                    .collect();
                if !missing.is_empty() {
                    out.notes.push(format!(
                        "the model planned nothing for {}; rules constraints used",
                        missing.join(", ")
                    ));
                    for n in &missing {
                        if let Some(c) = rules.constraints.get(n) {
                            plan.constraints.insert(n.clone(), c.clone());
                        }
                    }
                }
                plan
            }
            Err(reason) => {
                out.notes.push(format!(
                    "no usable plan from the model ({reason}); rules plan used"
                ));
                rules
            }
        };
        Ok(out.map(|_| plan))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::plan::Relation;
    use serde_json::json;

    #[test]
    fn a_sloppy_plan_is_read() {
        let scene = disco_core::synth::bedroom().0;
        let v = json!({"objects": [
            {"name": "Bed-0", "against_wall": "yes", "relations": [], "facing": null},
            {"name": "nightstand-0", "against_wall": true, "relations": [
                {"relation": "beside", "target": "bed 0"},
                {"relation": "levitating", "target": "bed-0"},
                {"relation": "near", "target": "unicorn-3"}], "facing": "nightstand-0"},
            {"name": "dragon-1", "against_wall": false, "relations": [], "facing": null}
        ], "groups": [["bed-0", "nightstand-0", "ghost"], []]});
        let (plan, notes) = read_plan(&v, &scene).unwrap();
        assert!(plan.constraints["bed-0"].against_wall);
        let ns = &plan.constraints["nightstand-0"];
        assert_eq!(ns.relations.len(), 1);
        assert_eq!(ns.relations[0].relation, Relation::SideOf);
        assert_eq!(ns.facing, None, "an object does not face itself");
        assert_eq!(plan.groups, vec![vec!["bed-0", "nightstand-0"]]);
        assert_eq!(notes.len(), 3, "{notes:?}");
        assert!(read_plan(&json!({"objects": [{"name": "x"}]}), &scene).is_err());
        assert!(read_plan(&json!("no"), &scene).is_err());
    }
}
