//! The JSON schemas sent with each request, and the readers of the answers. Servers that honour
//! `response_format` hold the model to the schema (names as enums included); the readers still
//! check everything, for servers that do not.

use serde_json::{Value, json};

use disco_core::plan::Relation;
use disco_core::scene::Room;
use disco_llm::Schema;
use disco_llm::extract::{NameMap, number};

const RELATIONS: [&str; 7] = [
    "near",
    "side_of",
    "in_front_of",
    "aligned_with",
    "opposite",
    "around",
    "back_to_back",
];

/// The wall roles a plan may name (`core::room::analysis::WallRole`, as written in files).
const WALL_ROLES: [&str; 13] = [
    "opposite_door",
    "opposite_window",
    "entrance",
    "no_window",
    "with_window",
    "longest_solid",
    "left",
    "right",
    "top",
    "bottom",
    "left_from_door",
    "right_from_door",
    "slanted",
];

/// The formation shapes a plan may name (`core::plan::FormationShape`, as written in files).
const FORMATION_SHAPES: [&str; 11] = [
    "rows",
    "arc",
    "ring",
    "per_side",
    "along_front",
    "pods",
    "one_per_member",
    "behind_each",
    "aisles",
    "u_tables",
    "l_desks",
];

fn object(properties: Value, required: &[&str]) -> Value {
    json!({"type": "object", "properties": properties, "required": required, "additionalProperties": false})
}

/// The plan: per object its wall flag, relations and facing target (an object, or one of the
/// room's `parts`: `door-0`, `window-1`, `wall-2`); then the groups.
pub fn plan(names: &[String], parts: &[String]) -> Schema {
    let name = json!({"type": "string", "enum": names});
    let targets: Vec<&String> = names.iter().chain(parts).collect();
    let target = json!({"type": "string", "enum": targets});
    let relation = object(
        json!({"relation": {"type": "string", "enum": RELATIONS}, "target": target}),
        &["relation", "target"],
    );
    let place = object(
        json!({
            "zone": {"type": "string"},
            "wall": {"type": "string", "enum": WALL_ROLES},
            "far_corner": {"type": "boolean"},
            "under_window": {"type": "boolean"},
            "by_entrance": {"type": "boolean"},
        }),
        &[],
    );
    let entry = object(
        json!({
            "name": name,
            "against_wall": {"type": "boolean"},
            "relations": {"type": "array", "items": relation},
            "facing": {"anyOf": [target, {"type": "null"}]},
            "place": place,
        }),
        &["name", "against_wall", "relations", "facing"],
    );
    let formation = object(
        json!({
            "shape": {"type": "string", "enum": FORMATION_SHAPES},
            "focus": {"anyOf": [name, {"type": "null"}]},
            "members": {"type": "array", "items": name},
            "count": {"type": "integer", "minimum": 1},
            "of": {"type": "array", "items": name},
        }),
        &["shape", "members"],
    );
    Schema {
        name: "plan".into(),
        schema: object(
            json!({
                "objects": {"type": "array", "items": entry},
                "groups": {"type": "array", "items": {"type": "array", "items": name}},
                "formations": {"type": "array", "items": formation},
            }),
            &["objects", "groups"],
        ),
    }
}

/// The plan of a scene where some pieces may leave the floor: [`plan`], with each object's
/// optional "support" (`floor`, `wall`, `surface`) and the relations `on` and `above`.
pub fn plan_off_floor(names: &[String], parts: &[String]) -> Schema {
    let mut schema = plan(names, parts);
    let entry = &mut schema.schema["properties"]["objects"]["items"];
    entry["properties"]["support"] =
        json!({"type": "string", "enum": ["floor", "wall", "surface"]});
    let mut relations: Vec<&str> = RELATIONS.to_vec();
    relations.extend(["on", "above"]);
    entry["properties"]["relations"]["items"]["properties"]["relation"]["enum"] = json!(relations);
    schema
}

/// Poses for the named objects.
pub fn poses(names: &[String]) -> Schema {
    let entry = object(
        json!({
            "name": {"type": "string", "enum": names},
            "position": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2},
            "rotation": {"type": "integer", "enum": [0, 90, 180, 270]},
        }),
        &["name", "position", "rotation"],
    );
    Schema {
        name: "poses".into(),
        schema: object(
            json!({"objects": {"type": "array", "items": entry}}),
            &["objects"],
        ),
    }
}

/// Poses for a group where the pieces of `held` leave the floor: a floor piece gets its
/// "position" and "rotation" as in [`poses`]; a held piece is named with what holds it, "on"
/// (a name of `targets`) or "wall" (an index below `walls`) with "above" (a name of `targets`)
/// or a "position" near its spot, and code poses it exactly (see `mount`).
pub fn poses_off_floor(
    names: &[String],
    held: &[String],
    targets: &[String],
    walls: usize,
) -> Schema {
    let floor: Vec<&String> = names.iter().filter(|n| !held.contains(n)).collect();
    let point = json!({"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2});
    let target = json!({"type": "string", "enum": targets});
    let held_entry = object(
        json!({
            "name": {"type": "string", "enum": held},
            "on": target,
            "wall": {"type": "integer", "minimum": 0, "maximum": walls.saturating_sub(1)},
            "above": target,
            "position": point,
        }),
        &["name"],
    );
    let mut entries = Vec::new();
    if !floor.is_empty() {
        entries.push(object(
            json!({
                "name": {"type": "string", "enum": floor},
                "position": point,
                "rotation": {"type": "integer", "enum": [0, 90, 180, 270]},
            }),
            &["name", "position", "rotation"],
        ));
    }
    entries.push(held_entry);
    Schema {
        name: "poses".into(),
        schema: object(
            json!({"objects": {"type": "array", "items": {"anyOf": entries}}}),
            &["objects"],
        ),
    }
}

/// An SRT's moves for the named objects, and the failed checks (by number) it reports cannot
/// be met, each with the reason.
pub fn moves(names: &[String]) -> Schema {
    with_infeasible(poses(names))
}

/// [`moves`] where the pieces of `held` leave the floor (see [`poses_off_floor`]).
pub fn moves_off_floor(
    names: &[String],
    held: &[String],
    targets: &[String],
    walls: usize,
) -> Schema {
    with_infeasible(poses_off_floor(names, held, targets, walls))
}

/// A poses schema named `moves`, with the list of failed checks reported infeasible.
fn with_infeasible(mut schema: Schema) -> Schema {
    schema.name = "moves".into();
    let entry = object(
        json!({"check": {"type": "integer"}, "reason": {"type": "string"}}),
        &["check", "reason"],
    );
    schema.schema["properties"]["infeasible"] = json!({"type": "array", "items": entry});
    schema.schema["required"] = json!(["objects", "infeasible"]);
    schema
}

/// The checks (numbers below `count`) an answer reports cannot be met, with the reasons; an
/// entry without a known number or a reason is left out.
pub fn read_infeasible(v: &Value, count: usize) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    for item in v
        .get("infeasible")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
    {
        let Some(i) = item
            .get("check")
            .and_then(number)
            .filter(|n| *n >= 0.0 && n.fract() == 0.0)
            .map(|n| n as usize)
            .filter(|i| *i < count)
        else {
            continue;
        };
        let reason = item
            .get("reason")
            .and_then(Value::as_str)
            .unwrap_or("")
            .trim();
        if !reason.is_empty() && !out.iter().any(|(j, _)| *j == i) {
            out.push((i, reason.to_string()));
        }
    }
    out
}

/// One yes/no answer.
pub fn answer() -> Schema {
    Schema {
        name: "answer".into(),
        schema: object(
            json!({"answer": {"type": "string", "enum": ["yes", "no", "infeasible"]}, "reason": {"type": "string"}}),
            &["answer", "reason"],
        ),
    }
}

/// Answers to numbered questions.
pub fn answers() -> Schema {
    let entry = object(
        json!({"id": {"type": "integer"}, "answer": {"type": "string", "enum": ["yes", "no", "infeasible"]}, "reason": {"type": "string"}}),
        &["id", "answer", "reason"],
    );
    Schema {
        name: "answers".into(),
        schema: object(
            json!({"answers": {"type": "array", "items": entry}}),
            &["answers"],
        ),
    }
}

/// The judge's scores.
pub fn scores() -> Schema {
    Schema {
        name: "scores".into(),
        schema: object(
            json!({
                "positional": {"type": "integer", "minimum": 0, "maximum": 100},
                "rotational": {"type": "integer", "minimum": 0, "maximum": 100},
                "comment": {"type": "string"},
            }),
            &["positional", "rotational", "comment"],
        ),
    }
}

/// A list under `key`, or the value itself when the model answered with a bare list.
pub fn list<'v>(v: &'v Value, key: &str) -> Result<&'v Vec<Value>, String> {
    v.get(key)
        .and_then(Value::as_array)
        .or_else(|| v.as_array())
        .ok_or_else(|| format!("expected an object with a list `{key}`"))
}

/// A relation's name read leniently.
pub fn relation(v: &Value) -> Option<Relation> {
    v.as_str().and_then(|s| s.parse().ok())
}

/// The rotations a model may give in `room`: the four right angles, and for each slanted wall
/// the angle of a piece with its back on it, with that angle's own right angles (a stool facing
/// a dressing table on the slant). Sorted, each once.
pub fn allowed_turns(room: &Room) -> Vec<f64> {
    let mut turns = vec![0.0, 90.0, 180.0, 270.0];
    for e in room.walls() {
        let r = e.inward_rotation();
        let off_axis = (r / 90.0 - (r / 90.0).round()).abs() * 90.0;
        if off_axis > 1e-6 {
            for k in 0..4 {
                turns.push(disco_core::geometry::normalize_degrees(
                    (r + 90.0 * f64::from(k)).round(),
                ));
            }
        }
    }
    turns.sort_by(f64::total_cmp);
    turns.dedup_by(|a, b| (*a - *b).abs() < 0.5);
    turns
}

/// `schema` with every `rotation` it asks for allowed the turns of `room` ([`allowed_turns`]):
/// unchanged in a room without slanted walls.
pub fn with_turns(mut schema: Schema, room: &Room) -> Schema {
    fn widen(v: &mut Value, turns: &Value) {
        match v {
            Value::Object(map) => {
                for (key, inner) in map.iter_mut() {
                    if key == "rotation" && inner.get("enum").is_some() {
                        inner["enum"] = turns.clone();
                    } else {
                        widen(inner, turns);
                    }
                }
            }
            Value::Array(items) => items.iter_mut().for_each(|i| widen(i, turns)),
            _ => {}
        }
    }
    let turns = allowed_turns(room);
    if turns.len() > 4 {
        let list: Value = turns.iter().map(|t| json!(*t as i64)).collect();
        widen(&mut schema.schema, &list);
    }
    schema
}

/// `rotation` snapped to the nearest of `turns` (around the circle).
fn snap_turn(rotation: f64, turns: &[f64]) -> f64 {
    let r = disco_core::geometry::normalize_degrees(rotation);
    let apart = |t: f64| {
        let d = (r - t).rem_euclid(360.0);
        d.min(360.0 - d)
    };
    turns
        .iter()
        .copied()
        .min_by(|a, b| apart(*a).total_cmp(&apart(*b)))
        .unwrap_or(0.0)
}

/// One pose as a model wrote it, after checks.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadPose {
    /// The scene's name for the object.
    pub name: String,
    /// Footprint centre.
    pub position: [f64; 2],
    /// Snapped to 0, 90, 180 or 270, or to a slanted wall's angles ([`allowed_turns`]).
    pub rotation: f64,
}

/// Poses from `v` for names in `names` (taken as they are read): invented and duplicate names,
/// non-finite or absurd numbers are skipped, each with a note. An error when nothing at all is
/// usable, so the model is asked again.
pub fn read_poses(
    v: &Value,
    names: &mut NameMap,
    room: &Room,
) -> Result<(Vec<ReadPose>, Vec<String>), String> {
    let items = list(v, "objects")?;
    let turns = allowed_turns(room);
    let mut out = Vec::new();
    let mut notes = Vec::new();
    for item in items {
        let written = item.get("name").and_then(Value::as_str).unwrap_or("");
        let xy = item
            .get("position")
            .and_then(Value::as_array)
            .filter(|a| a.len() == 2)
            .map(|a| (number(&a[0]), number(&a[1])))
            .unwrap_or_else(|| {
                (
                    item.get("x").and_then(number),
                    item.get("y").and_then(number),
                )
            });
        let (Some(x), Some(y)) = xy else {
            notes.push(format!("no usable position for {written:?}"));
            continue;
        };
        // Beyond half a room outside the walls is not a pose, it is noise.
        let sane = |p: f64, side: f64| p >= -0.5 * side && p <= 1.5 * side;
        if !sane(x, room.width) || !sane(y, room.depth) {
            notes.push(format!("absurd position [{x}, {y}] for {written:?}"));
            continue;
        }
        let rotation = item.get("rotation").and_then(number).unwrap_or(0.0);
        let Some(name) = names.take(written) else {
            notes.push(format!("unknown or repeated object {written:?}"));
            continue;
        };
        out.push(ReadPose {
            name,
            position: [x, y],
            rotation: snap_turn(rotation, &turns),
        });
    }
    if out.is_empty() {
        let why = notes
            .first()
            .cloned()
            .unwrap_or_else(|| "no objects".into());
        return Err(format!("no usable pose ({why})"));
    }
    Ok((out, notes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slanted_wall_adds_its_angles_to_the_turns_a_pose_may_take() {
        let rect = Room::rect(400.0, 300.0);
        assert_eq!(allowed_turns(&rect), [0.0, 90.0, 180.0, 270.0]);
        let plain = poses(&["desk-0".to_string()]);
        assert_eq!(with_turns(plain.clone(), &rect).schema, plain.schema);
        // Wall 2 runs from (400, 200) to (200, 400): a piece backing onto it faces 225.
        let cut = Room::from_polygon(vec![
            [0.0, 0.0],
            [400.0, 0.0],
            [400.0, 200.0],
            [200.0, 400.0],
            [0.0, 400.0],
        ]);
        let turns = allowed_turns(&cut);
        assert_eq!(turns, [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0]);
        let wide = with_turns(plain, &cut);
        assert_eq!(
            wide.schema["properties"]["objects"]["items"]["properties"]["rotation"]["enum"],
            json!([0, 45, 90, 135, 180, 225, 270, 315])
        );
        let v = json!({"objects": [
            {"name": "desk-0", "position": [300, 300], "rotation": 220},
            {"name": "stool-0", "position": [250, 250], "rotation": 100}]});
        let mut names = NameMap::new(["desk-0".to_string(), "stool-0".to_string()]);
        let (read, _) = read_poses(&v, &mut names, &cut).unwrap();
        assert_eq!(read[0].rotation, 225.0);
        assert_eq!(read[1].rotation, 90.0);
        let mut names = NameMap::new(["desk-0".to_string(), "stool-0".to_string()]);
        let (read, _) = read_poses(&v, &mut names, &rect).unwrap();
        assert_eq!(read[0].rotation, 180.0, "no slant: right angles only");
    }

    #[test]
    fn infeasible_checks_need_a_known_number_and_a_reason() {
        let v = json!({"objects": [], "infeasible": [
            {"check": 1, "reason": "no wall stretch near the desk holds both"},
            {"check": 1, "reason": "again"},
            {"check": 7, "reason": "unknown check"},
            {"check": 0, "reason": "  "},
            {"check": "0", "reason": "numbers as text are read"},
        ]});
        assert_eq!(
            read_infeasible(&v, 2),
            vec![
                (1, "no wall stretch near the desk holds both".to_string()),
                (0, "numbers as text are read".to_string())
            ]
        );
        assert!(read_infeasible(&json!({"objects": []}), 2).is_empty());
        let schema = moves(&["desk-0".to_string()]);
        assert_eq!(schema.schema["required"], json!(["objects", "infeasible"]));
    }

    #[test]
    fn poses_survive_bad_entries() {
        let room = Room::rect(400.0, 300.0);
        let mut names = NameMap::new(["bed-0", "nightstand-0"].map(String::from));
        let v = json!({"objects": [
            {"name": "Bed 0", "position": [200, "150cm"], "rotation": 93},
            {"name": "bed-0", "position": [10, 10], "rotation": 0},
            {"name": "sofa-9", "position": [10, 10], "rotation": 0},
            {"name": "nightstand-0", "position": [1e9, 10], "rotation": 0},
        ]});
        let (poses, notes) = read_poses(&v, &mut names, &room).unwrap();
        assert_eq!(
            poses,
            vec![ReadPose {
                name: "bed-0".into(),
                position: [200.0, 150.0],
                rotation: 90.0
            }]
        );
        assert_eq!(notes.len(), 3, "{notes:?}");
        assert_eq!(names.missing(), ["nightstand-0"]);
        let none = read_poses(&json!({"objects": []}), &mut names, &room);
        assert!(none.unwrap_err().contains("no usable pose"));
        let nan = read_poses(
            &json!({"objects": [{"name": "nightstand-0", "position": ["NaN", 1]}]}),
            &mut names,
            &room,
        );
        assert!(nan.unwrap_err().contains("no usable position"));
    }
}
