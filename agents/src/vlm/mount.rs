//! Objects off the floor on the model path: the model names what holds a piece, and code poses
//! it exactly.
//!
//! Models are weak at numbers and strong at names, so for a piece the plan takes off the floor
//! (its `support`) the designer and the SRT ask for words: `"on": "nightstand-0"` (the piece
//! whose top it stands on), or `"wall": 2` (the wall it hangs on, numbered as the prompts list
//! the walls) with `"above": "bed-0"` (the piece it hangs centred over) or a `"position"` near
//! where along that wall. [`pose_held`] then sets the piece on that top at the top's height, or
//! on that wall with its back on it, at the height its kind hangs (the mount of
//! `config/furniture.toml`), as the formation code does for formations: the rules designer's
//! own placement on tops and above pieces, and a slide along the named wall to the first spot
//! where the piece hangs clear of openings and of everything else. The PRT checks the result in
//! 3D like any other pose.
//!
//! Nothing here is used for a scene with nothing off the floor: [`leaves_floor`] and
//! [`plan_leaves_floor`] say when the prompts gain their off-floor parts, so the prompts (and the
//! recorded answers keyed by them) of floor-only scenes stay exactly as they were.

use std::collections::HashSet;

use glam::DVec2;
use serde_json::Value;

use super::schema::list;
use crate::hanging::{STEP_CM, bottom_for_centre, spots_on_wall, widest};
use crate::knowledge::{Knowledge, Mount};
use crate::rules::RuleDesigner;
use disco_core::geometry::{Wall, nearest_wall};
use disco_core::layout::PlacedObject;
use disco_core::plan::{Plan, Relation, RelationSpec};
use disco_core::scene::{Asset, SceneSpec, Support};
use disco_llm::extract::{NameMap, number};

/// Whether the furniture knowledge (or an asset's own `support`) takes some asset of `scene`
/// off the floor: the planner's prompt then offers supports and the `on` / `above` relations.
pub fn leaves_floor(scene: &SceneSpec) -> bool {
    let k = Knowledge::builtin();
    scene
        .assets
        .iter()
        .any(|a| k.kind_of(a).mount_for(a).is_some())
}

/// Whether the plan takes anything off the floor, or `objects` holds something off it: the
/// prompts after the plan then name the walls and say what holds each piece.
pub fn plan_leaves_floor(plan: &Plan, objects: &[PlacedObject]) -> bool {
    plan.constraints
        .keys()
        .any(|n| plan.support_of(n).is_some())
        || objects.iter().any(|o| !o.on_floor() || o.elevation > 0.0)
}

/// Where the knowledge would put `asset` off the floor, in words for the planner's prompt, with
/// the scene's pieces that fit ("usually stands on another piece's top (here: nightstand-0,
/// nightstand-1)"); `None` for a floor piece.
pub fn leaving_words(scene: &SceneSpec, asset: &Asset) -> Option<String> {
    let k = Knowledge::builtin();
    let mount = k.kind_of(asset).mount_for(asset)?;
    // As the rule planner takes them: tops 25-125 cm high, pieces up to 130 cm to hang over.
    let fitting = |to: &[String], low: f64, high: f64| -> Vec<String> {
        scene
            .assets
            .iter()
            .filter(|b| b.name != asset.name)
            .filter(|b| (low..=high).contains(&b.size[2]))
            .filter(|b| Knowledge::target_rank(b, &k.kind_of(b), to).is_some())
            .map(|b| b.name.clone())
            .collect()
    };
    let told = match asset.support {
        Some(_) => " (the scene says so)",
        None => "",
    };
    let how = match mount.support {
        Support::Surface => {
            let on = fitting(&mount.on, 25.0, 125.0);
            let mut words = format!("usually stands on another piece's top{told}");
            if !on.is_empty() {
                words.push_str(&format!(" (here: {})", on.join(", ")));
            }
            if mount.or_wall {
                words.push_str(", or hangs on a wall when nothing holds it");
            }
            words
        }
        Support::Wall => {
            let above = fitting(&mount.above, 0.0, 130.0);
            let mut words = format!("usually hangs on a wall{told}");
            if !above.is_empty() {
                words.push_str(&format!(" (above one of: {})", above.join(", ")));
            }
            words
        }
        Support::Floor => return None,
    };
    Some(how)
}

/// What holds a placed object, in words for the prompts' object lists ("on top of
/// nightstand-0, its bottom 55 cm above the floor"); `None` for an object on the floor.
pub fn held_words(o: &PlacedObject) -> Option<String> {
    let height = cm(o.elevation);
    match (&o.on, o.wall) {
        (Some(on), _) => Some(format!(
            "on top of {on}, its bottom {height} cm above the floor"
        )),
        (None, Some(w)) => Some(format!(
            "hung on wall {w}, its bottom {height} cm above the floor"
        )),
        (None, None) if o.elevation > 0.0 => Some(format!(
            "{height} cm above the floor with nothing holding it"
        )),
        (None, None) => None,
    }
}

/// What the plan says holds `name` and what to answer for it, for the designer's request;
/// `None` for a floor piece. `placed` is what stands already (the target's top height and wall
/// are given when it does).
pub fn held_request(
    scene: &SceneSpec,
    plan: &Plan,
    name: &str,
    placed: &[PlacedObject],
) -> Option<String> {
    let support = plan.support_of(name)?;
    let target = first_relation(plan, name);
    let find = |t: &str| placed.iter().find(|o| o.name == t);
    let text = match (support, target) {
        (Support::Surface, Some((Relation::On, t))) => {
            let top = find(&t)
                .map(|s| {
                    format!(
                        " (its top: {} x {} cm, {} cm high)",
                        cm(s.size[0]),
                        cm(s.size[1]),
                        cm(s.top())
                    )
                })
                .unwrap_or_default();
            format!(
                "it leaves the floor: answer \"on\": \"{t}\"{top}, or the name of another piece whose top suits it better"
            )
        }
        (Support::Surface, _) => {
            "it leaves the floor: answer \"on\" with the name of the piece whose top it stands on".to_string()
        }
        (Support::Wall, Some((Relation::Above, t))) => {
            match find(&t).and_then(|o| o.footprint().against_wall(&scene.room)) {
                Some(w) => format!(
                    "it leaves the floor: answer \"above\": \"{t}\" and \"wall\": {}, the wall {t} stands against",
                    w.index()
                ),
                None => format!(
                    "it leaves the floor: answer \"above\": \"{t}\" and the \"wall\" {t} stands against"
                ),
            }
        }
        (Support::Wall, Some((Relation::Opposite, t))) => {
            let wall = find(&t)
                .and_then(|o| wall_ahead(scene, o))
                .map(|w| format!(" (wall {w})"))
                .unwrap_or_default();
            format!(
                "it leaves the floor: answer the \"wall\" across from {t}{wall} and, as \"position\", the point of it straight ahead of {t}"
            )
        }
        (Support::Wall, _) => "it leaves the floor: answer the \"wall\" with a free stretch for it and, as \"position\", about where along it".to_string(),
        (Support::Floor, _) => return None,
    };
    Some(text)
}

/// The wall the line straight out of `o`'s front meets first, by index.
fn wall_ahead(scene: &SceneSpec, o: &PlacedObject) -> Option<usize> {
    let fp = o.footprint();
    Wall::all(&scene.room)
        .into_iter()
        .filter_map(|w| {
            let n = w.inward_normal();
            let dist = (fp.center - w.edge.start).dot(n);
            let speed = -fp.front.dot(n);
            if dist <= 0.0 || speed <= 1e-9 {
                return None;
            }
            let at = fp.center + fp.front * (dist / speed);
            let along = w.along(at);
            (-1.0..=w.length() + 1.0)
                .contains(&along)
                .then_some((dist / speed, w.index()))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, i)| i)
}

/// The plan's first relation of `name` (the one that says what holds it), if any.
fn first_relation(plan: &Plan, name: &str) -> Option<(Relation, String)> {
    plan.constraints
        .get(name)?
        .relations
        .first()
        .map(|r| (r.relation, r.target.clone()))
}

/// What a model said holds one piece off the floor.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadMount {
    /// The scene's name for the piece.
    pub name: String,
    /// The piece whose top it stands on.
    pub on: Option<String>,
    /// The wall it hangs on.
    pub wall: Option<usize>,
    /// The piece it hangs centred over.
    pub above: Option<String>,
    /// About where it goes (a point near its spot on the wall).
    pub position: Option<[f64; 2]>,
}

/// A wall index read leniently: `2`, `"2"`, `"wall 2"`.
fn wall_index(v: &Value) -> Option<f64> {
    number(v).or_else(|| {
        v.as_str()
            .map(|s| s.trim().trim_start_matches("wall").trim())
            .and_then(|s| s.parse::<f64>().ok())
    })
}

/// Splits a model's `objects` into the entries of `held` pieces, read as [`ReadMount`]s (their
/// names taken from `names`), and the rest, returned as `{"objects": [...]}` for the pose
/// reader. Support and target names resolve against `scene_names`; a wall the room does not
/// have, or a name it does not know, is left out with a note (the plan's support then holds).
pub fn read_mounts(
    v: &Value,
    names: &mut NameMap,
    held: &HashSet<String>,
    scene_names: &NameMap,
    walls: usize,
) -> Result<(Value, Vec<ReadMount>, Vec<String>), String> {
    let items = list(v, "objects")?;
    let held_names = NameMap::new(held.iter().cloned());
    let mut rest = Vec::new();
    let mut mounts = Vec::new();
    let mut notes = Vec::new();
    for item in items {
        let written = item.get("name").and_then(Value::as_str).unwrap_or("");
        if held_names.resolve(written).is_none() {
            rest.push(item.clone());
            continue;
        }
        let Some(name) = names.take(written) else {
            notes.push(format!("unknown or repeated object {written:?}"));
            continue;
        };
        let mut target = |key: &str| -> Option<String> {
            let t = item.get(key)?.as_str()?.trim();
            if t.is_empty() || t.eq_ignore_ascii_case("null") || t.eq_ignore_ascii_case("none") {
                return None;
            }
            match scene_names.resolve(t).filter(|r| *r != name) {
                Some(r) => Some(r),
                None => {
                    notes.push(format!(
                        "{name}: ignored {key} {t:?} (not another object of the scene)"
                    ));
                    None
                }
            }
        };
        let on = target("on");
        let above = target("above");
        let wall = item.get("wall").filter(|w| !w.is_null()).and_then(|w| {
            let i = wall_index(w).filter(|i| *i >= 0.0 && i.fract() == 0.0 && *i < walls as f64);
            if i.is_none() {
                notes.push(format!(
                    "{name}: ignored wall {w} (the room has walls 0 to {})",
                    walls.saturating_sub(1)
                ));
            }
            i.map(|i| i as usize)
        });
        let position = item
            .get("position")
            .and_then(Value::as_array)
            .filter(|a| a.len() == 2)
            .and_then(|a| Some([number(&a[0])?, number(&a[1])?]));
        mounts.push(ReadMount {
            name,
            on,
            wall,
            above,
            position,
        });
    }
    Ok((serde_json::json!({ "objects": rest }), mounts, notes))
}

/// The pose of `asset` off the floor as the model said (`m`), among `placed`: on the named top
/// at its height; centred above the named piece on its wall; on the named wall at the kind's
/// height, slid from where the model pointed (else from the plan's target, else the middle of
/// the wall's widest free stretch) to the first spot where it hangs clear. A model that gave
/// only a point (as for a floor piece) gets the top under that point, or the wall nearest it,
/// as the plan's support asks. What the model left out or got wrong falls back to the plan's
/// support, as the rules designer poses it; the note says so. The PRT settles what still does
/// not hold.
pub fn pose_held(
    scene: &SceneSpec,
    plan: &Plan,
    asset: &Asset,
    m: &ReadMount,
    placed: &[PlacedObject],
) -> (PlacedObject, Option<String>) {
    let stands = |t: &str| placed.iter().any(|o| o.name == t);
    let by_rules = |support: Option<Support>, relation: Option<(Relation, &str)>| {
        let mut plan = plan.clone();
        let c = plan.constraints.entry(asset.name.clone()).or_default();
        if let Some(s) = support {
            c.support = Some(s);
            c.against_wall = s == Support::Wall;
            c.relations = relation
                .map(|(r, t)| RelationSpec {
                    relation: r,
                    target: t.to_string(),
                })
                .into_iter()
                .collect();
        }
        RuleDesigner::new()
            .design_group(scene, &plan, &[asset], placed)
            .pop()
            .unwrap_or_else(|| PlacedObject {
                name: asset.name.clone(),
                category: asset.category.clone(),
                size: asset.size,
                position: [scene.room.width / 2.0, scene.room.depth / 2.0],
                ..Default::default()
            })
    };
    // A model that gave only a point: the top under it, or the wall nearest it, as the plan's
    // support asks.
    let pointed = m.position.map(DVec2::from);
    let under = pointed
        .filter(|_| m.on.is_none() && m.wall.is_none() && m.above.is_none())
        .and_then(|p| {
            (plan.support_of(&asset.name) == Some(Support::Surface))
                .then(|| {
                    placed.iter().find(|o| {
                        o.name != asset.name && o.on_floor() && {
                            let l = o.footprint().to_local(p);
                            l.x.abs() <= o.size[0] / 2.0 && l.y.abs() <= o.size[1] / 2.0
                        }
                    })
                })
                .flatten()
                .map(|o| o.name.clone())
        });
    let on = m.on.clone().or(under);
    let wall = m.wall.or_else(|| {
        let p = pointed.filter(|_| on.is_none() && m.above.is_none())?;
        (plan.support_of(&asset.name) == Some(Support::Wall))
            .then(|| nearest_wall(&scene.room, p).index())
    });
    if let Some(t) = &on {
        if stands(t) {
            return (
                by_rules(Some(Support::Surface), Some((Relation::On, t))),
                None,
            );
        }
        let note = format!(
            "{}: {t} does not stand yet, so it went where the plan puts it",
            asset.name
        );
        return (by_rules(None, None), Some(note));
    }
    if let Some(t) = m.above.as_deref().filter(|t| stands(t)) {
        return (
            by_rules(Some(Support::Wall), Some((Relation::Above, t))),
            None,
        );
    }
    if let Some(w) = wall.and_then(|i| Wall::get(&scene.room, i)) {
        let hint = m.position.map(DVec2::from).or_else(|| {
            first_relation(plan, &asset.name)
                .and_then(|(_, t)| placed.iter().find(|o| o.name == t))
                .map(|o| DVec2::from(o.position))
        });
        if let Some(o) = hang(scene, asset, &w, hint, placed) {
            return (o, None);
        }
        let note = format!(
            "{}: no free spot on wall {} at its height, so it went where the plan puts it",
            asset.name,
            w.index()
        );
        return (by_rules(None, None), Some(note));
    }
    let note = format!(
        "{}: the model named no top or wall for it, so it went where the plan puts it",
        asset.name
    );
    (by_rules(None, None), Some(note))
}

/// The mount of `asset`'s kind (its hanging height and gap), or a plain wall mount.
fn mount_of(asset: &Asset) -> Mount {
    Knowledge::builtin()
        .kind_of(asset)
        .mount_for(asset)
        .unwrap_or_else(|| Mount::plain(Support::Wall))
}

/// `asset` hung on `w` at its kind's height, as near `hint` along the wall as it hangs clear
/// (see [`crate::hanging`]); without a hint, in the middle of the wall's widest free stretch.
/// `None` when no spot of the wall holds it.
fn hang(
    scene: &SceneSpec,
    asset: &Asset,
    w: &Wall,
    hint: Option<DVec2>,
    placed: &[PlacedObject],
) -> Option<PlacedObject> {
    let mount = mount_of(asset);
    let elevation = bottom_for_centre(mount.height, asset.size[2]);
    let spots = spots_on_wall(&scene.room, asset, w, elevation, placed);
    match hint {
        Some(p) => {
            let n = spots.len() as i64;
            let at = (w.along(p) / STEP_CM).round() as i64;
            (0..n)
                .flat_map(|d| [at - d, at + d])
                .filter(|k| (0..n).contains(k))
                .find_map(|k| spots[k as usize].clone())
        }
        None => widest(&spots).map(|(_, o)| o),
    }
}

/// A length in whole centimetres where it is whole, else to a millimetre.
fn cm(v: f64) -> String {
    let r = (v * 10.0).round() / 10.0;
    if r.fract() == 0.0 && r.abs() < 1e12 {
        format!("{}", r as i64)
    } else {
        format!("{r}")
    }
}

#[cfg(test)]
mod tests;
