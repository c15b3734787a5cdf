//! The prompt's explicit requests, checked against a finished layout.
//!
//! The plan-based constraint score grades a layout against the constraints the planner wrote; a
//! request the planner never turned into a constraint ("a floor lamp next to the sofa") is then
//! invisible, and the score can read 100% while the prompt was ignored. This check starts from
//! the prompt instead: every placement hint [`read_hints`] finds (centre, corner, along a wall,
//! by a window, facing, and the relations next to / beside / near / around / in front of / opposite) is
//! checked geometrically on the layout, whatever the plan says and whichever agents made it.
//!
//! It reads the prompt with the same phrase reader the rule planner uses, so it sees what that
//! reader sees and no more: a request worded in a way it does not know is not counted.

use disco_core::geometry::{Footprint, WALL_GAP_CM};
use disco_core::layout::Layout;
use disco_core::relations;
use disco_core::scene::SceneSpec;
use glam::DVec2;
use serde::Serialize;

use crate::hints::{FormationHint, Hint, read_hints};
use crate::knowledge::Knowledge;
use disco_core::plan::FormationShape;

/// How close (cm) a piece must be to two walls to stand "in a corner".
const CORNER_GAP_CM: f64 = 10.0;

/// How close (cm) a piece must come to a window's span to stand "by the window".
const WINDOW_GAP_CM: f64 = 50.0;

/// One request of the prompt and whether the layout meets it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RequestCheck {
    /// The request in words, with the asset names it applies to (`lamp-0 near sofa-0`).
    pub request: String,
    /// Whether every placed subject meets it (a dropped subject fails it).
    pub met: bool,
}

/// Every request of `scene.prompt` the phrase reader finds, checked on `layout`.
pub fn check_requests(scene: &SceneSpec, layout: &Layout) -> Vec<RequestCheck> {
    let knowledge = Knowledge::builtin();
    let footprint = |i: usize| -> Option<Footprint> {
        let name = &scene.assets.get(i)?.name;
        layout.object(name).map(|o| o.footprint())
    };
    let names = |ids: &[usize]| -> String {
        let names: Vec<&str> = ids
            .iter()
            .filter_map(|&i| scene.assets.get(i).map(|a| a.name.as_str()))
            .collect();
        names.join(", ")
    };
    read_hints(scene, &knowledge)
        .into_iter()
        .map(|h| {
            let subjects: Vec<Option<Footprint>> =
                h.subjects.iter().map(|&i| footprint(i)).collect();
            let every = |ok: &dyn Fn(&Footprint) -> bool| {
                !subjects.is_empty() && subjects.iter().all(|f| f.as_ref().is_some_and(ok))
            };
            let any_target = |targets: &[usize], ok: &dyn Fn(&Footprint, &Footprint) -> bool| {
                let placed: Vec<Footprint> = targets.iter().filter_map(|&i| footprint(i)).collect();
                every(&|a| placed.iter().any(|b| ok(a, b)))
            };
            let (words, met) = match &h.hint {
                Hint::Centre => ("in the centre".to_string(), every(&|a| central(a, layout))),
                Hint::Corner => ("in a corner".to_string(), every(&|a| in_corner(a, layout))),
                Hint::AlongWall => (
                    "against a wall".to_string(),
                    every(&|a| relations::against_wall(a, &layout.room)),
                ),
                Hint::ByWindow => (
                    "by a window".to_string(),
                    every(&|a| {
                        relations::against_wall(a, &layout.room)
                            && a.gap_to_window(&layout.room)
                                .is_some_and(|g| g <= WINDOW_GAP_CM)
                    }),
                ),
                Hint::Facing(t) => (
                    format!("facing {}", names(t)),
                    any_target(t, &|a, b| relations::facing(a, b)),
                ),
                Hint::FacingEachOther(first) => (
                    format!("and {} facing each other", names(&[*first])),
                    any_target(&[*first], &|a, b| {
                        relations::facing(a, b) && relations::facing(b, a)
                    }),
                ),
                Hint::Relation(r, t) => (
                    format!("{} {}", r.as_str().replace('_', " "), names(t)),
                    any_target(t, &|a, b| r.holds(a, b)),
                ),
                Hint::Place(place) => (
                    place.to_string(),
                    every(&|a| relations::placed_as_asked(a, &layout.room, place)),
                ),
                Hint::Formation(f) => (
                    format!("in formation ({:?})", f.shape).to_lowercase(),
                    formation_met(f, &subjects, &|i| footprint(i), &layout.room),
                ),
            };
            RequestCheck {
                request: format!("{} {words}", names(&h.subjects)),
                met,
            }
        })
        .collect()
}

/// Whether the members (their footprints, in order) stand in the formation the prompt asked:
/// seats of an arc, a ring or per side around the focus (near it and facing it), members along a
/// front or in rows on the focus's front side, each facing it unless they are desks; pods of
/// desks each back to back with another; one item in front of each object, facing it; aisles
/// of units all parallel and free of the walls (see [`aisles_met`]).
fn formation_met(
    f: &FormationHint,
    members: &[Option<Footprint>],
    find: &dyn Fn(usize) -> Option<Footprint>,
    room: &disco_core::scene::Room,
) -> bool {
    let Some(members) = members.iter().copied().collect::<Option<Vec<Footprint>>>() else {
        return false;
    };
    let focus = f.focus.first().and_then(|&i| find(i));
    match f.shape {
        FormationShape::Arc | FormationShape::Ring | FormationShape::PerSide => {
            focus.is_some_and(|t| members.iter().all(|a| relations::around(a, &t)))
        }
        FormationShape::AlongFront => {
            focus.is_some_and(|t| members.iter().all(|a| relations::in_front_of(a, &t)))
        }
        FormationShape::Rows => {
            focus.is_some_and(|t| members.iter().all(|a| t.to_local(a.center).y > t.half.y))
        }
        FormationShape::Pods => members.iter().enumerate().all(|(i, a)| {
            members
                .iter()
                .enumerate()
                .any(|(j, b)| i != j && a.front.dot(b.front) < -0.99 && a.gap(b) <= 2.0)
        }),
        FormationShape::OnePerMember => members.iter().zip(&f.of).all(|(a, &o)| {
            find(o).is_some_and(|b| relations::facing(a, &b) && relations::near(a, &b))
        }),
        // Behind each: near it, turned the same way, on its back side.
        FormationShape::BehindEach => members.iter().zip(&f.of).all(|(a, &o)| {
            find(o).is_some_and(|b| {
                relations::near(a, &b) && b.to_local(a.center).y < 0.0 && a.front.dot(b.front) > 0.0
            })
        }),
        FormationShape::Aisles => aisles_met(&members, room),
    }
}

/// Aisles: every unit turned along the same line (facing one way or the other) and none
/// against a wall, so they stand as free runs people walk between.
pub fn aisles_met(units: &[Footprint], room: &disco_core::scene::Room) -> bool {
    let Some(first) = units.first() else {
        return false;
    };
    units
        .iter()
        .all(|u| u.front.dot(first.front).abs() > 0.99 && !relations::against_wall(u, room))
}

/// The footprint's centre lies in the middle third of the room both ways and its back is on
/// no wall.
fn central(a: &Footprint, layout: &Layout) -> bool {
    let room = &layout.room;
    let third = |v: f64, extent: f64| (extent / 3.0..=2.0 * extent / 3.0).contains(&v);
    third(a.center.x, room.width)
        && third(a.center.y, room.depth)
        && !relations::against_wall(a, &layout.room)
}

/// Two walls that are not parallel each come within [`CORNER_GAP_CM`] of the footprint.
fn in_corner(a: &Footprint, layout: &Layout) -> bool {
    let near: Vec<DVec2> = layout
        .room
        .walls()
        .iter()
        .filter(|w| {
            a.corners()
                .iter()
                .any(|c| w.offset(*c).abs() < CORNER_GAP_CM + WALL_GAP_CM)
                && a.corners().iter().any(|c| {
                    let t = w.along(*c);
                    t > -CORNER_GAP_CM && t < w.length() + CORNER_GAP_CM
                })
        })
        .map(|w| w.direction())
        .collect();
    near.iter()
        .enumerate()
        .any(|(i, d)| near[i + 1..].iter().any(|e| d.perp_dot(*e).abs() > 0.5))
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::layout::{PlacedObject, Stats};
    use disco_core::plan::Plan;
    use disco_core::scene::{Asset, Room};

    fn scene(prompt: &str) -> SceneSpec {
        SceneSpec {
            id: "s".into(),
            prompt: prompt.into(),
            room_type: "living room".into(),
            room: Room::rect(500.0, 400.0),
            assets: vec![
                Asset::new("sofa-0", "sofa", [200.0, 90.0, 80.0]),
                Asset::new("floor_lamp-0", "floor lamp", [40.0, 40.0, 160.0]),
                Asset::new("plant-0", "plant", [40.0, 40.0, 100.0]),
            ],
        }
    }

    fn layout(scene: &SceneSpec, poses: &[(&str, [f64; 2], f64)]) -> Layout {
        Layout {
            id: scene.id.clone(),
            room: scene.room.clone(),
            objects: poses
                .iter()
                .map(|(name, position, rotation)| {
                    let a = scene.asset(name).unwrap();
                    PlacedObject {
                        name: a.name.clone(),
                        category: a.category.clone(),
                        size: a.size,
                        position: *position,
                        rotation: *rotation,
                        ..Default::default()
                    }
                })
                .collect(),
            dropped: vec![],
            plan: Plan::default().into(),
            stats: Stats::default(),
        }
    }

    #[test]
    fn a_request_the_plan_never_held_is_still_checked() {
        let s = scene("a living room with a floor lamp next to the sofa and a plant in a corner");
        let good = layout(
            &s,
            &[
                ("sofa-0", [250.0, 45.0], 0.0),
                ("floor_lamp-0", [375.0, 25.0], 0.0),
                ("plant-0", [480.0, 380.0], 0.0),
            ],
        );
        let checks = check_requests(&s, &good);
        assert_eq!(checks.len(), 2, "{checks:?}");
        assert!(checks.iter().all(|c| c.met), "{checks:?}");
        assert_eq!(checks[0].request, "floor_lamp-0 near sofa-0");

        let bad = layout(
            &s,
            &[
                ("sofa-0", [250.0, 45.0], 0.0),
                ("floor_lamp-0", [60.0, 300.0], 0.0),
                ("plant-0", [250.0, 250.0], 0.0),
            ],
        );
        let checks = check_requests(&s, &bad);
        assert!(checks.iter().all(|c| !c.met), "{checks:?}");
    }

    #[test]
    fn a_dropped_subject_fails_its_request() {
        let s = scene("a floor lamp next to the sofa");
        let l = layout(&s, &[("sofa-0", [250.0, 45.0], 0.0)]);
        let checks = check_requests(&s, &l);
        assert_eq!(checks.len(), 1);
        assert!(!checks[0].met);
    }

    #[test]
    fn a_plain_prompt_has_no_requests() {
        let s = scene("a cozy living room");
        let l = layout(&s, &[("sofa-0", [250.0, 45.0], 0.0)]);
        assert!(check_requests(&s, &l).is_empty());
    }
}
