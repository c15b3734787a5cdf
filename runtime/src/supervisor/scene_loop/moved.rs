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

use disco_core::geometry::{Footprint, normalize_degrees};
use disco_core::layout::{Layout, PlacedObject};
use disco_core::plan::Plan;
use disco_core::relations::{ConstraintCheck, ConstraintKind, check_one, constraints_of};
use disco_core::roles::ToolMove;
use disco_core::room::ZoneKind;
use disco_core::scene::Room;

/// A centre that moved less than this (cm), without turning, did not move worth telling: the
/// PRT snaps poses to its grid.
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
        .filter(|b| f.collides(&b.footprint()))
        .map(|b| b.name.as_str())
        .collect();
    if !overlapped.is_empty() {
        why.push(format!("it overlapped {}", overlapped.join(", ")));
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
    f.inside(room)
        && !room.keep_clear().iter().any(|z| f.intrudes(z, o.size[2]))
        && !others
            .iter()
            .filter(|b| b.name != o.name && b.is_flat() == o.is_flat())
            .any(|b| f.collides(&b.footprint()))
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
        if shift < REPORTED_MOVE_CM && !turned(b.rotation, o.rotation) {
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
}
