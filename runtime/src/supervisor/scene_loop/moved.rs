//! What a tool moved that no model asked to move: found by comparing the layout before and
//! after a PRT, explained from the layout before (what it overlapped, whether it stuck out of
//! the room, stood in a door's or window's keep-clear zone, or was off the wall its plan asks
//! for), with the plan's constraints the move broke; and the objects the plan ties to a moved
//! one (the chair in front of the desk) carried along with it where the new place is free.
//!
//! The scene loop reports each [`ToolMove`] in the next request of every agent (its
//! `SceneContext::moved`), in the trace (`moved` events) and in the layout's notes.

use std::collections::HashSet;

use glam::DVec2;

use disco_agents::vlm::formation::{formation_chair, formations_about};
use disco_core::geometry::{Footprint, normalize_degrees};
use disco_core::geometry3d;
use disco_core::layout::{Layout, PlacedObject};
use disco_core::plan::Plan;
use disco_core::relations::{ConstraintCheck, ConstraintKind, check_one, constraints_of};
use disco_core::roles::ToolMove;
use disco_core::room::ZoneKind;
use disco_core::scene::Room;

/// A centre that moved less than this (cm), without turning, did not move worth telling (the
/// PRT snaps poses to its grid), unless the snap broke a constraint that held.
pub const REPORTED_MOVE_CM: f64 = 5.0;

/// The footprint of `o` with its height (the window rules depend on it).
fn footprint(o: &PlacedObject) -> Footprint {
    o.footprint().with_height(o.size[2])
}

/// Whether `o` turned between `a` and `b` (by more than a tenth of a degree, modulo turns).
fn turned(a: f64, b: f64) -> bool {
    let t = normalize_degrees(a - b);
    t.min(360.0 - t) > 0.1
}

/// Every constraint naming `name`, as subject or as target: `(subject, constraint)`.
fn constraints_naming(plan: &Plan, name: &str) -> Vec<(String, ConstraintKind)> {
    let mut out: Vec<(String, ConstraintKind)> = constraints_of(plan, name)
        .into_iter()
        .map(|k| (name.to_string(), k))
        .collect();
    for subject in plan.constraints.keys().filter(|s| *s != name) {
        for k in constraints_of(plan, subject) {
            if k.target() == Some(name) {
                out.push((subject.clone(), k));
            }
        }
    }
    out
}

/// What was wrong with `o`'s place in `before` that a physical repair answers: overlaps, out of
/// the room, a keep-clear zone entered, off the wall the plan asks for.
fn faults(o: &PlacedObject, before: &[PlacedObject], room: &Room, plan: &Plan) -> Vec<String> {
    let f = footprint(o);
    let mut why = Vec::new();
    let overlapped: Vec<&str> = before
        .iter()
        .filter(|b| b.name != o.name && b.is_flat() == o.is_flat())
        .filter(|b| geometry3d::collide(o, b))
        .map(|b| b.name.as_str())
        .collect();
    if !overlapped.is_empty() {
        why.push(format!("it overlapped {}", overlapped.join(", ")));
    }
    let by_name = before.iter().map(|b| (b.name.as_str(), b)).collect();
    if let Some(problem) = geometry3d::support_problem(o, &by_name, room) {
        why.push(format!("it {problem}"));
    }
    if !o.on_floor() {
        // On a top or a wall: the floor's rules (room, zones, walls) are its support's.
        return why;
    }
    if !f.inside(room) {
        why.push(format!(
            "{} cm² of it stood outside the room",
            f.area_outside(room).round()
        ));
    }
    for zone in room.keep_clear() {
        if f.intrudes(&zone, o.size[2]) {
            why.push(match zone.kind {
                ZoneKind::Door(i) => format!("it stood in door {i}'s keep-clear zone"),
                ZoneKind::Window(i) => format!(
                    "it stood within 40 cm of window {i} and is {} cm tall, taller than the sill ({} cm)",
                    o.size[2].round(),
                    room.windows.get(i).map_or(0.0, |w| w.sill).round()
                ),
            });
        }
    }
    if plan.wants_wall(&o.name) && f.against_wall(room).is_none() {
        why.push("the plan puts it against a wall, and its back was not on one".into());
    }
    why
}

/// The constraints naming `name` that held in `before` and fail in `after`, in words.
fn broken(before: &Layout, after: &Layout, name: &str) -> Vec<String> {
    constraints_naming(&before.plan, name)
        .into_iter()
        .filter(|(s, k)| check_one(before, s, k) && !check_one(after, s, k))
        .map(|(subject, kind)| {
            ConstraintCheck {
                subject,
                kind,
                met: false,
            }
            .to_string()
        })
        .collect()
}

/// Where `d` stands when carried along with `from` -> `to` (the same turn about the moved
/// object's centre, then the same shift).
fn carried(d: &PlacedObject, from: &PlacedObject, to: &PlacedObject) -> PlacedObject {
    let turn = to.rotation - from.rotation;
    let (s, c) = (-turn).to_radians().sin_cos();
    let rel = DVec2::new(
        d.position[0] - from.position[0],
        d.position[1] - from.position[1],
    );
    // Rotations turn clockwise: a clockwise turn by `turn` is a counter-clockwise one by -turn.
    let r = DVec2::new(rel.x * c - rel.y * s, rel.x * s + rel.y * c);
    PlacedObject {
        position: [to.position[0] + r.x, to.position[1] + r.y],
        rotation: normalize_degrees(d.rotation + turn),
        ..d.clone()
    }
}

/// Whether `o` may stand where it is among `others` (itself left out): inside the room, out of
/// the keep-clear zones that bind it, clear of every object of its layer.
fn free_at(o: &PlacedObject, others: &[PlacedObject], room: &Room) -> bool {
    let f = footprint(o);
    let floor_ok = !o.on_floor()
        || (f.inside(room) && !room.keep_clear().iter().any(|z| f.intrudes(z, o.size[2])));
    floor_ok
        && !others
            .iter()
            .filter(|b| b.name != o.name && b.is_flat() == o.is_flat())
            .any(|b| geometry3d::collide(o, b))
}

/// The objects a tool (`by`: `prt`, `final prt`) moved between `before` and `after.objects`,
/// each with why; the objects the plan ties to a moved one and that lost that tie move with it
/// where the carried place is free (`after` is updated), each reported too.
pub fn tool_moves(before: &Layout, after: &mut Layout, by: &str) -> Vec<ToolMove> {
    let room = before.room.clone();
    let mut out = Vec::new();
    let mut moved_names: HashSet<String> = HashSet::new();
    let mut moved_pairs = Vec::new();
    for o in &after.objects {
        let Some(b) = before.object(&o.name) else {
            continue;
        };
        let shift = DVec2::from(b.position).distance(DVec2::from(o.position));
        // A snap of a few centimetres is not worth telling, unless it broke a constraint that
        // held (a centre snapped out of its zone): then it is a move like any other.
        let small = shift < REPORTED_MOVE_CM && !turned(b.rotation, o.rotation);
        if small && (shift == 0.0 || broken(before, after, &o.name).is_empty()) {
            continue;
        }
        moved_names.insert(o.name.clone());
        moved_pairs.push((b.clone(), o.clone()));
    }
    // Dependents: the plan ties them to a moved object, they did not move themselves, and the
    // move broke the tie.
    let mut carried_along = Vec::new();
    let mut stuck: Vec<(String, String)> = Vec::new();
    for (from, to) in &moved_pairs {
        for (subject, kind) in constraints_naming(&before.plan, &from.name) {
            if subject == from.name
                || moved_names.contains(&subject)
                || carried_along
                    .iter()
                    .any(|(d, _): &(PlacedObject, _)| d.name == subject)
                || !check_one(before, &subject, &kind)
                || check_one(after, &subject, &kind)
            {
                continue;
            }
            let Some(d) = after.object(&subject).cloned() else {
                continue;
            };
            let candidate = carried(&d, from, to);
            if free_at(&candidate, &after.objects, &room) {
                if let Some(slot) = after.objects.iter_mut().find(|x| x.name == subject) {
                    *slot = candidate.clone();
                }
                let tie = ConstraintCheck {
                    subject: subject.clone(),
                    kind,
                    met: true,
                };
                carried_along.push((d, (candidate, from.name.clone(), tie.to_string())));
            } else {
                stuck.push((from.name.clone(), subject));
            }
        }
    }
    for (from, to) in &moved_pairs {
        let mut why = faults(from, &before.objects, &room, &before.plan);
        if why.is_empty() {
            why.push(
                "its own place was sound: the repair moved it to keep a walkway open to the other pieces".into(),
            );
        }
        let lost = broken(before, after, &from.name);
        if !lost.is_empty() {
            why.push(format!("this breaks: {}", lost.join("; ")));
        }
        let left: Vec<&str> = stuck
            .iter()
            .filter(|(m, _)| *m == from.name)
            .map(|(_, d)| d.as_str())
            .collect();
        if !left.is_empty() {
            why.push(format!(
                "{} could not move with it (no free place there)",
                left.join(", ")
            ));
        }
        out.push(ToolMove {
            name: to.name.clone(),
            by: by.to_string(),
            from: from.position,
            from_rotation: from.rotation,
            to: to.position,
            to_rotation: to.rotation,
            why: why.join("; "),
        });
    }
    for (d, (c, with, tie)) in carried_along {
        out.push(ToolMove {
            name: d.name.clone(),
            by: format!("with {with}"),
            from: d.position,
            from_rotation: d.rotation,
            to: c.position,
            to_rotation: c.rotation,
            why: format!("the plan ties it to {with} ({tie}), so it moved with it"),
        });
    }
    out
}

/// After a refiner moved the focus of a formation (the piano of an arc), its members (and the
/// chairs of desks in rows or pods) move with it as a whole: the same turn about the focus's
/// centre, then the same shift, so the shape the formation posed stays exact. `before` is the
/// layout's objects before the refiner's moves; returns the names carried along.
pub fn carry_formations(
    plan: &Plan,
    before: &[PlacedObject],
    placed: &mut [PlacedObject],
) -> Vec<String> {
    let mut carried_names = Vec::new();
    let moved: Vec<(PlacedObject, PlacedObject)> = placed
        .iter()
        .filter_map(|o| {
            let b = before.iter().find(|b| b.name == o.name)?;
            (b.position != o.position || turned(b.rotation, o.rotation))
                .then(|| (b.clone(), o.clone()))
        })
        .collect();
    for (from, to) in &moved {
        for f in formations_about(plan, &from.name) {
            let chairs = plan.constraints.keys().filter(|n| {
                formation_chair(plan, n).is_some_and(|desk| f.members.iter().any(|m| m == desk))
            });
            for name in f.members.iter().chain(chairs) {
                if moved.iter().any(|(b, _)| &b.name == name) {
                    continue;
                }
                let (Some(b), Some(slot)) = (
                    before.iter().find(|b| &b.name == name),
                    placed.iter_mut().find(|o| &o.name == name),
                ) else {
                    continue;
                };
                *slot = carried(b, from, to);
                carried_names.push(name.clone());
            }
        }
    }
    carried_names
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use disco_core::plan::{ObjectConstraints, Relation, RelationSpec};
    use disco_core::room::Window;

    fn object(name: &str, at: [f64; 2], size: [f64; 3], rotation: f64) -> PlacedObject {
        PlacedObject {
            name: name.into(),
            category: name.trim_end_matches("-0").into(),
            size,
            position: at,
            rotation,
            ..Default::default()
        }
    }

    /// A 500 x 400 room with a window on the bottom wall (x 150-250, sill 85); a 75 cm desk
    /// under it with its chair in front, and a tall cabinet.
    fn office(desk_x: f64, desk_h: f64) -> Layout {
        let mut room = Room::rect(500.0, 400.0);
        room.windows.push(Window {
            wall: 0,
            at: 200.0,
            width: 100.0,
            sill: 85.0,
            height: 120.0,
        });
        let mut plan = Plan::default();
        plan.constraints.insert(
            "desk-0".into(),
            ObjectConstraints {
                against_wall: true,
                ..Default::default()
            },
        );
        plan.constraints.insert(
            "chair-0".into(),
            ObjectConstraints {
                relations: vec![RelationSpec {
                    relation: Relation::InFrontOf,
                    target: "desk-0".into(),
                }],
                facing: Some("desk-0".into()),
                ..Default::default()
            },
        );
        Layout {
            id: "office".into(),
            room,
            objects: vec![
                object("desk-0", [desk_x, 30.0], [120.0, 60.0, desk_h], 0.0),
                object("chair-0", [desk_x, 90.0], [50.0, 50.0, 90.0], 180.0),
                object("cabinet-0", [450.0, 300.0], [50.0, 40.0, 180.0], 270.0),
            ],
            dropped: Vec::new(),
            plan: Arc::new(plan),
            stats: Default::default(),
        }
    }

    #[test]
    fn a_moved_desk_says_why_and_its_chair_moves_with_it() {
        // A 95 cm desk under the 85 cm sill: the PRT slides it along the wall to x = 320.
        let before = office(200.0, 95.0);
        let mut after = before.clone();
        after.objects[0].position = [320.0, 30.0];
        let moves = tool_moves(&before, &mut after, "prt");
        assert_eq!(moves.len(), 2, "{moves:?}");
        assert_eq!(moves[0].name, "desk-0");
        assert!(
            moves[0]
                .why
                .contains("within 40 cm of window 0 and is 95 cm tall"),
            "{}",
            moves[0].why
        );
        assert_eq!(moves[1].name, "chair-0");
        assert_eq!(moves[1].by, "with desk-0");
        assert!(
            moves[1].why.contains("chair-0 is in front of desk-0"),
            "{}",
            moves[1].why
        );
        assert_eq!(
            after.objects[1].position,
            [320.0, 90.0],
            "the chair followed"
        );
        assert!(
            moves[0].to_string().starts_with(
                "desk-0 moved from [200, 30] rotation 0 to [320, 30] rotation 0 (prt): "
            ),
            "{}",
            moves[0]
        );
    }

    #[test]
    fn a_chair_with_no_room_to_follow_stays_and_the_move_says_so() {
        let before = office(200.0, 95.0);
        let mut after = before.clone();
        after.objects[0].position = [320.0, 30.0];
        // Something stands where the chair would go.
        after
            .objects
            .push(object("box-0", [320.0, 95.0], [40.0, 40.0, 40.0], 0.0));
        let moves = tool_moves(&before, &mut after, "prt");
        assert_eq!(moves.len(), 1, "{moves:?}");
        assert!(
            moves[0].why.contains("chair-0 could not move with it"),
            "{}",
            moves[0].why
        );
        assert!(
            moves[0]
                .why
                .contains("this breaks: chair-0 is in front of desk-0"),
            "{}",
            moves[0].why
        );
        assert_eq!(after.objects[1].position, [200.0, 90.0]);
    }

    #[test]
    fn a_turned_pair_turns_together_and_small_snaps_are_not_news() {
        let before = office(200.0, 70.0);
        let mut after = before.clone();
        // Snapped by 3 cm: not reported.
        after.objects[2].position = [450.0, 303.0];
        assert!(tool_moves(&before, &mut after.clone(), "prt").is_empty());
        // The desk turned a quarter to face +x against the left wall: the chair turns with it.
        after.objects[0].position = [30.0, 200.0];
        after.objects[0].rotation = 90.0;
        let moves = tool_moves(&before, &mut after, "final prt");
        assert_eq!(moves.len(), 2, "{moves:?}");
        let chair = &after.objects[1];
        assert!((chair.position[0] - 90.0).abs() < 1e-6, "{chair:?}");
        assert!((chair.position[1] - 200.0).abs() < 1e-6, "{chair:?}");
        assert_eq!(chair.rotation, 270.0);
        assert!(
            moves[0].why.contains("its own place was sound"),
            "{}",
            moves[0].why
        );
    }

    /// The place that was met while placing and unmet at the end: the final PRT snapped a piece
    /// 4 cm, out of its zone, and a snap under `REPORTED_MOVE_CM` went untold.
    #[test]
    fn a_small_snap_that_breaks_a_place_is_reported() {
        let mut before = office(200.0, 70.0);
        // Two zones: the main area below y = 250 and a recess above it, x 0..280.
        before.room = Room::from_polygon(vec![
            [0.0, 0.0],
            [500.0, 0.0],
            [500.0, 250.0],
            [280.0, 250.0],
            [280.0, 420.0],
            [0.0, 420.0],
        ]);
        before.objects[2] = object("cabinet-0", [100.0, 252.0], [50.0, 40.0, 100.0], 0.0);
        let mut plan = (*before.plan).clone();
        plan.constraints.insert(
            "cabinet-0".into(),
            ObjectConstraints {
                place: Some(disco_core::plan::Place {
                    zone: Some("recess".into()),
                    ..Default::default()
                }),
                ..Default::default()
            },
        );
        before.plan = Arc::new(plan);
        let mut after = before.clone();
        after.objects[2].position = [100.0, 248.0];
        let kind = constraints_of(&before.plan, "cabinet-0").remove(0);
        assert!(check_one(&before, "cabinet-0", &kind));
        assert!(!check_one(&after, "cabinet-0", &kind));
        let moves = tool_moves(&before, &mut after, "final prt");
        assert_eq!(moves.len(), 1, "{moves:?}");
        assert!(
            moves[0]
                .why
                .contains("this breaks: cabinet-0 stands in the alcove"),
            "{}",
            moves[0].why
        );
        // The same snap inside the zone is still no news.
        let mut inside = before.clone();
        inside.objects[2].position = [100.0, 255.0];
        assert!(tool_moves(&before, &mut inside, "final prt").is_empty());
    }

    #[test]
    fn a_formation_moves_with_its_focus_as_a_whole() {
        let mut plan = Plan::default();
        plan.formations.push(disco_core::plan::Formation {
            shape: disco_core::plan::FormationShape::Arc,
            focus: Some("piano-0".into()),
            members: vec!["chair-0".into(), "chair-1".into()],
            count: None,
            of: Vec::new(),
        });
        let before = vec![
            object("piano-0", [200.0, 100.0], [150.0, 150.0, 100.0], 0.0),
            object("chair-0", [150.0, 250.0], [50.0, 50.0, 90.0], 180.0),
            object("chair-1", [250.0, 250.0], [50.0, 50.0, 90.0], 180.0),
            object("lamp-0", [400.0, 300.0], [40.0, 40.0, 160.0], 0.0),
        ];
        let mut placed = before.clone();
        // The SRT turned the piano a quarter (to face +x) and moved it to (150, 200).
        placed[0].position = [150.0, 200.0];
        placed[0].rotation = 90.0;
        let carried = carry_formations(&plan, &before, &mut placed);
        assert_eq!(carried, ["chair-0", "chair-1"]);
        // chair-0 stood 50 left of and 150 before the piano's centre: now 150 right of it and
        // 50 above, turned a quarter too.
        let c0 = &placed[1];
        assert!((c0.position[0] - 300.0).abs() < 1e-6, "{c0:?}");
        assert!((c0.position[1] - 250.0).abs() < 1e-6, "{c0:?}");
        assert_eq!(c0.rotation, 270.0);
        assert_eq!(placed[3].position, [400.0, 300.0], "the lamp stays");
        // Nothing moved: nothing carried.
        let mut same = before.clone();
        assert!(carry_formations(&plan, &before, &mut same).is_empty());
    }
}
