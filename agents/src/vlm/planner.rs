//! The VLM planner: constraints and groups from the model; what it leaves out, from the rules.

use std::collections::BTreeMap;

use async_trait::async_trait;
use serde_json::{Value, json};

use super::schema::{self, list};
use super::{VlmBase, mount, scene_vars};
use crate::rules::RulePlanner;
use disco_core::plan::{
    Formation, FormationShape, ObjectConstraints, Place, Plan, Relation, RelationSpec,
};
use disco_core::roles::{Planner, RoleResult};
use disco_core::scene::{SceneSpec, Support};
use disco_core::targets;
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
            let relation = r.get("relation").and_then(schema::relation);
            let target = r.get("target").and_then(Value::as_str).and_then(|t| {
                names.resolve(t).or_else(|| {
                    relation
                        .filter(|&rel| targets::takes_room_part(rel))
                        .and_then(|_| targets::room_part_name(&scene.room, t))
                })
            });
            match (relation, target) {
                (Some(relation), Some(target)) if target != name => {
                    c.relations.push(RelationSpec { relation, target })
                }
                _ => notes.push(format!("ignored relation {r} of {name}")),
            }
        }
        c.facing = item
            .get("facing")
            .and_then(Value::as_str)
            .and_then(|t| {
                names
                    .resolve(t)
                    .or_else(|| targets::room_part_name(&scene.room, t))
            })
            .filter(|t| *t != name);
        c.support = item.get("support").and_then(read_support);
        if let Some(p) = item.get("place").filter(|p| !p.is_null()) {
            match serde_json::from_value::<Place>(p.clone()) {
                Ok(place) if !place.is_empty() => c.place = Some(place),
                Ok(_) => {}
                Err(e) => notes.push(format!("ignored place {p} of {name}: {e}")),
            }
        }
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
    let formations = read_formations(v, &names, &mut notes);
    let mut plan = Plan {
        constraints,
        groups,
        formations,
    };
    settle_supports(&mut plan, scene, &mut notes);
    Ok((plan, notes))
}

/// A support read leniently: `surface`, `wall`, `floor`, and the usual words for them (`on a
/// top`, `on the wall`, `table top`, `shelf`); `floor` and anything unknown read as none.
fn read_support(v: &Value) -> Option<Support> {
    let s = v.as_str()?.trim().to_lowercase();
    if s.contains("wall") || s.contains("hang") {
        Some(Support::Wall)
    } else if ["surface", "top", "table", "shelf", "counter", "desk"]
        .iter()
        .any(|w| s.contains(w))
    {
        Some(Support::Surface)
    } else {
        None
    }
}

/// Makes the plan's supports agree with its relations and the scene: an `on` relation means a
/// surface, an `above` a wall; an asset's own `support` is obeyed (`floor` keeps it down, and
/// its `on` / `above` relations are dropped, noted); a piece off the floor placed in a group
/// before what holds it moves into that piece's group, after it (noted).
fn settle_supports(plan: &mut Plan, scene: &SceneSpec, notes: &mut Vec<String>) {
    for a in &scene.assets {
        let Some(c) = plan.constraints.get_mut(&a.name) else {
            continue;
        };
        let implied = c.relations.iter().find_map(|r| match r.relation {
            Relation::On => Some(Support::Surface),
            Relation::Above => Some(Support::Wall),
            _ => None,
        });
        c.support = c.support.or(implied);
        match a.support {
            Some(Support::Floor) => {
                let before = c.relations.len();
                c.relations.retain(|r| !r.relation.off_floor());
                if c.support.take().is_some() || c.relations.len() != before {
                    notes.push(format!(
                        "{} stays on the floor, as the scene says; its support in the plan is ignored",
                        a.name
                    ));
                }
            }
            Some(own) => c.support = Some(own),
            None => {}
        }
        // What holds it comes first: its support's target at the front of its relations.
        if let Some(i) = c.relations.iter().position(|r| r.relation.off_floor())
            && i > 0
        {
            let r = c.relations.remove(i);
            c.relations.insert(0, r);
        }
    }
    // A piece whose holder is placed in a later group joins that group, after it.
    let holders: Vec<(String, String)> = plan
        .constraints
        .iter()
        .filter(|(n, _)| plan.support_of(n).is_some())
        .filter_map(|(n, c)| {
            let r = c.relations.first().filter(|r| r.relation.off_floor())?;
            Some((n.clone(), r.target.clone()))
        })
        .collect();
    for (name, holder) in holders {
        let (Some(mine), Some(theirs)) = (plan.group_of(&name), plan.group_of(&holder)) else {
            continue;
        };
        if mine < theirs {
            plan.groups[mine].retain(|n| *n != name);
            plan.groups[theirs].push(name.clone());
            notes.push(format!(
                "{name} moved to the group of {holder}, which holds it"
            ));
        }
    }
    plan.groups.retain(|g| !g.is_empty());
}

/// The plan's formations, names mapped to the scene's; one with an unknown shape, or with no
/// member left, is dropped (noted).
fn read_formations(v: &Value, names: &NameMap, notes: &mut Vec<String>) -> Vec<Formation> {
    let resolve_all = |key: &str, f: &Value| -> Vec<String> {
        f.get(key)
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
            .filter_map(Value::as_str)
            .filter_map(|n| names.resolve(n))
            .collect()
    };
    let mut out = Vec::new();
    for f in v
        .get("formations")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
    {
        let shape = f
            .get("shape")
            .cloned()
            .and_then(|s| serde_json::from_value::<FormationShape>(s).ok());
        let members = resolve_all("members", f);
        let Some(shape) = shape.filter(|_| !members.is_empty()) else {
            notes.push(format!("ignored formation {f}"));
            continue;
        };
        out.push(Formation {
            shape,
            focus: f
                .get("focus")
                .and_then(Value::as_str)
                .and_then(|t| names.resolve(t)),
            members,
            count: f
                .get("count")
                .and_then(Value::as_u64)
                .and_then(|n| usize::try_from(n).ok())
                .filter(|n| (1..=1000).contains(n)),
            of: resolve_all("of", f),
        });
    }
    out
}

#[async_trait]
impl Planner for VlmPlanner {
    async fn plan(&self, scene: &SceneSpec) -> RoleResult<Plan> {
        let names: Vec<String> = scene.assets.iter().map(|a| a.name.clone()).collect();
        // Doors, windows and walls a relation may name, when the room lists them in words.
        let parts = if scene.room.is_rectangle() && !scene.room.has_openings() {
            Vec::new()
        } else {
            targets::room_parts(&scene.room)
        };
        let mut vars = scene_vars(scene);
        if !parts.is_empty() {
            vars["parts"] = json!(parts);
        }
        // Pieces the knowledge (or the scene) takes off the floor: the plan may say what holds
        // them. A scene with none gets the floor-only prompt and schema, as before.
        let off_floor = mount::leaves_floor(scene);
        let schema = if off_floor {
            vars["off_floor"] = json!(true);
            for (a, v) in scene
                .assets
                .iter()
                .zip(vars["assets"].as_array_mut().into_iter().flatten())
            {
                if let Some(words) = mount::leaving_words(scene, a) {
                    v["leaves"] = json!(words);
                }
            }
            schema::plan_off_floor(&names, &parts)
        } else {
            schema::plan(&names, &parts)
        };
        let mut out = self
            .base
            .ask("planner", "planner", &vars, None, &schema, |v| {
                read_plan(v, scene)
            })
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

    #[test]
    fn a_plan_may_name_doors_windows_and_walls_as_targets() {
        let mut scene = disco_core::synth::bedroom().0;
        scene
            .room
            .doors
            .push(disco_core::room::Door::new(0, 100.0, 80.0));
        let v = json!({"objects": [
            {"name": "bed-0", "against_wall": true, "relations": [
                {"relation": "opposite", "target": "door-0"}], "facing": "Window 7"},
            {"name": "nightstand-0", "against_wall": true, "relations": [
                {"relation": "near", "target": "door 0"},
                {"relation": "on", "target": "wall-1"},
                {"relation": "back_to_back", "target": "bed-0"}], "facing": "wall_2"}
        ], "groups": [["bed-0", "nightstand-0"]]});
        let (plan, notes) = read_plan(&v, &scene).unwrap();
        let bed = &plan.constraints["bed-0"];
        assert_eq!(bed.relations[0].target, "door-0");
        assert_eq!(bed.facing, None, "the room has no window 7");
        let ns = &plan.constraints["nightstand-0"];
        let got: Vec<(Relation, &str)> = ns
            .relations
            .iter()
            .map(|r| (r.relation, r.target.as_str()))
            .collect();
        assert_eq!(
            got,
            [(Relation::Near, "door-0"), (Relation::BackToBack, "bed-0")],
            "a wall has no top: `on wall-1` is ignored"
        );
        assert_eq!(ns.facing.as_deref(), Some("wall-2"));
        assert_eq!(notes.len(), 1, "{notes:?}");
        // The schema offers the parts as targets, never as subjects.
        let names = vec!["bed-0".to_string()];
        let parts = targets::room_parts(&scene.room);
        let s = schema::plan(&names, &parts).schema;
        let entry = &s["properties"]["objects"]["items"]["properties"];
        assert_eq!(entry["name"]["enum"], json!(["bed-0"]));
        let t = &entry["relations"]["items"]["properties"]["target"]["enum"];
        assert!(t.as_array().unwrap().contains(&json!("door-0")), "{t}");
    }

    #[test]
    fn a_model_may_name_places_and_formations() {
        let scene = disco_core::synth::bedroom().0;
        let v = json!({"objects": [
            {"name": "bed-0", "against_wall": true, "relations": [], "facing": null,
             "place": {"wall": "opposite_door"}},
            {"name": "nightstand-0", "against_wall": true, "relations": [], "facing": null,
             "place": {"wall": "the ceiling"}}
        ], "groups": [["bed-0", "nightstand-0"]],
        "formations": [
            {"shape": "per_side", "focus": "bed-0", "members": ["nightstand-0", "ghost"], "count": 1},
            {"shape": "spiral", "members": ["bed-0"]}
        ]});
        let (plan, notes) = read_plan(&v, &scene).unwrap();
        let place = plan.constraints["bed-0"].place.clone().unwrap();
        assert_eq!(place.wall, Some(disco_core::plan::WallRole::OppositeDoor));
        assert!(plan.constraints["nightstand-0"].place.is_none());
        assert_eq!(plan.formations.len(), 1, "{notes:?}");
        assert_eq!(plan.formations[0].members, ["nightstand-0"]);
        assert_eq!(plan.formations[0].focus.as_deref(), Some("bed-0"));
        assert!(notes.iter().any(|n| n.contains("the ceiling")), "{notes:?}");
        assert!(notes.iter().any(|n| n.contains("spiral")), "{notes:?}");
    }

    #[test]
    fn a_model_may_take_pieces_off_the_floor_and_the_plan_is_made_consistent() {
        let mut scene = disco_core::synth::bedroom().0;
        scene.assets.extend([
            disco_core::scene::Asset::new("lamp-0", "table lamp", [30.0, 30.0, 50.0]),
            disco_core::scene::Asset::new("painting-0", "framed painting", [100.0, 4.0, 70.0]),
        ]);
        // The floor lamp is kept down by the scene.
        scene.assets[8].support = Some(Support::Floor);
        let v = json!({"objects": [
            {"name": "bed-0", "against_wall": true, "relations": [], "facing": null},
            {"name": "nightstand-0", "against_wall": true, "relations": [], "facing": null},
            {"name": "lamp-0", "against_wall": false, "support": "on a table top",
             "relations": [{"relation": "near", "target": "bed-0"},
                           {"relation": "on", "target": "nightstand-0"}], "facing": null},
            {"name": "painting-0", "against_wall": true,
             "relations": [{"relation": "above", "target": "bed-0"}], "facing": null},
            {"name": "floor lamp-0", "against_wall": false, "support": "surface",
             "relations": [{"relation": "on", "target": "nightstand-0"}], "facing": null}
        ], "groups": [["lamp-0", "painting-0"], ["bed-0", "nightstand-0", "floor lamp-0"]]});
        let (plan, notes) = read_plan(&v, &scene).unwrap();
        let lamp = &plan.constraints["lamp-0"];
        assert_eq!(lamp.support, Some(Support::Surface));
        assert_eq!(
            lamp.relations[0].relation,
            Relation::On,
            "what holds it first"
        );
        assert_eq!(
            plan.support_of("painting-0"),
            Some(Support::Wall),
            "above means a wall"
        );
        let floor_lamp = &plan.constraints["floor lamp-0"];
        assert_eq!(floor_lamp.support, None);
        assert!(floor_lamp.relations.is_empty());
        assert_eq!(
            plan.groups,
            vec![vec![
                "bed-0".to_string(),
                "nightstand-0".into(),
                "floor lamp-0".into(),
                "lamp-0".into(),
                "painting-0".into()
            ]],
            "{notes:?}"
        );
        assert!(
            notes.iter().any(|n| n.contains("stays on the floor")),
            "{notes:?}"
        );
        assert!(
            notes
                .iter()
                .any(|n| n == "lamp-0 moved to the group of nightstand-0, which holds it"),
            "{notes:?}"
        );
    }
}
