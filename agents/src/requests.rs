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
use disco_core::scene::{Room, SceneSpec};
use glam::DVec2;
use serde::Serialize;

use crate::hints::{FormationHint, Hint, read_hints};
use crate::knowledge::Knowledge;
use disco_core::plan::FormationShape;

/// How close (cm) a piece must be to two walls to stand "in a corner".
const CORNER_GAP_CM: f64 = 10.0;

/// How far (cm) from its wall's middle a piece asked for there may stand, on a short wall.
const MID_WALL_CM: f64 = 30.0;

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
                Hint::WindowByDoor => (
                    "at the window nearest the door".to_string(),
                    every(&|a| at_door_window(a, layout)),
                ),
                Hint::CentredOnWall => (
                    "in the middle of its wall".to_string(),
                    every(&|a| mid_wall(a, &layout.room)),
                ),
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
                Hint::Behind(t) => (
                    format!("behind {}", names(t)),
                    any_target(t, &|a, b| relations::near(a, b)),
                ),
                Hint::Under(t) => (
                    format!("under {}", names(t)),
                    any_target(t, &|a, b| {
                        relations::near(a, b) || relations::hung_above(b, a)
                    }),
                ),
                Hint::Between(t) => {
                    let placed: Vec<Footprint> = t.iter().filter_map(|&i| footprint(i)).collect();
                    (
                        format!("between {}", names(t)),
                        every(&|a| between(a, &placed)),
                    )
                }
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
        FormationShape::UTables => u_met(&members, focus.as_ref()),
        FormationShape::LDesks => l_met(&members, room),
    }
}

/// Most gap (cm) between tables of a U, or desks of an L, that count as meeting.
const MEET_GAP_CM: f64 = 2.0;

/// Whether the ray from `from` along `dir` meets `fp`.
fn ray_meets(from: DVec2, dir: DVec2, fp: &Footprint) -> bool {
    let probe = Footprint::new(
        from,
        0.0,
        0.0,
        disco_core::placement::facing_rotation(DVec2::ZERO, dir),
    );
    probe.front_ray_hit(fp).is_some()
}

/// A U of tables: three or more, each meeting another, and, from the tables' middle, the way
/// to the focus open (no table) while the three other ways (the base behind, an arm either
/// side) each meet a table. Without a focus, any of the four ways square to the first table
/// may be the open one.
pub fn u_met(tables: &[Footprint], focus: Option<&Footprint>) -> bool {
    let Some(first) = tables.first() else {
        return false;
    };
    let joined = tables.iter().enumerate().all(|(i, a)| {
        tables
            .iter()
            .enumerate()
            .any(|(j, b)| i != j && a.gap(b) <= MEET_GAP_CM)
    });
    if tables.len() < 3 || !joined {
        return false;
    }
    let middle = tables.iter().map(|t| t.center).sum::<DVec2>() / tables.len() as f64;
    let covers = |t: &Footprint| {
        let l = t.to_local(middle);
        l.x.abs() < t.half.x && l.y.abs() < t.half.y
    };
    if tables.iter().any(covers) {
        return false;
    }
    let hits = |d: DVec2| tables.iter().any(|t| ray_meets(middle, d, t));
    let open = |d: DVec2| !hits(d) && hits(-d) && hits(d.perp()) && hits(-d.perp());
    match focus {
        Some(f) => (f.center - middle).try_normalize().is_some_and(|d| {
            // The way to the focus, squared to the tables' own axes.
            let axis = [first.front, -first.front, first.right, -first.right]
                .into_iter()
                .max_by(|a, b| a.dot(d).total_cmp(&b.dot(d)))
                .unwrap_or(d);
            open(axis)
        }),
        None => [first.front, -first.front, first.right, -first.right]
            .into_iter()
            .any(open),
    }
}

/// An L of desks: two of them (the first two) meeting, turned square to each other, both
/// backs against a wall.
pub fn l_met(desks: &[Footprint], room: &disco_core::scene::Room) -> bool {
    let [a, b, ..] = desks else {
        return false;
    };
    a.gap(b) <= MEET_GAP_CM
        && a.front.dot(b.front).abs() < 0.5
        && relations::against_wall(a, room)
        && relations::against_wall(b, room)
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

/// The footprint stands between the first two targets: its centre projects inside the segment
/// joining theirs, and it is near one of them (one target: near it).
fn between(a: &Footprint, targets: &[Footprint]) -> bool {
    let near_one = targets.iter().any(|t| relations::near(a, t));
    match targets {
        [p, q, ..] => {
            let span = q.center - p.center;
            let t = (a.center - p.center).dot(span) / span.length_squared().max(1e-9);
            near_one && (0.0..=1.0).contains(&t)
        }
        _ => near_one,
    }
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

/// Its back on a wall, its centre within a tenth of that wall's length (at least
/// [`MID_WALL_CM`]) of the wall's middle.
fn mid_wall(a: &Footprint, room: &Room) -> bool {
    room.walls().iter().any(|w| {
        let back = a.center - a.front * a.half.y;
        w.offset(back).abs() < CORNER_GAP_CM
            && w.direction().perp_dot(a.front).abs() > 0.9
            && (w.along(a.center) - w.length() / 2.0).abs() <= (w.length() / 10.0).max(MID_WALL_CM)
    })
}

/// Its back's middle nearer the window nearest the main door than any other window, and
/// within [`WINDOW_GAP_CM`] of that window.
fn at_door_window(a: &Footprint, layout: &Layout) -> bool {
    let room = &layout.room;
    let analysis = room.analysis();
    let Some(door) = analysis.main_door.and_then(|i| room.door_middle(i)) else {
        return false;
    };
    let mids: Vec<DVec2> = room
        .windows
        .iter()
        .filter_map(|w| room.opening_ends(w.wall, w.at, w.width))
        .map(|(a, b)| (a + b) / 2.0)
        .collect();
    let by_door = mids
        .iter()
        .copied()
        .min_by(|x, y| x.distance(door).total_cmp(&y.distance(door)));
    let back = a.back_center();
    let nearest = mids
        .iter()
        .copied()
        .min_by(|x, y| x.distance(back).total_cmp(&y.distance(back)));
    by_door.is_some()
        && by_door == nearest
        && a.gap_to_window(room).is_some_and(|g| g <= WINDOW_GAP_CM)
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

    #[test]
    fn a_u_of_tables_is_told_from_a_grid_and_an_l_from_two_apart_desks() {
        let fp = |x: f64, y: f64, w: f64, d: f64, r: f64| Footprint::new(DVec2::new(x, y), w, d, r);
        // Six 140 x 70 tables: arms of two along x, the base across at x = 535; open to the
        // left (x < 0 side), where the screen stands.
        let u = [
            fp(220.0, 390.0, 140.0, 70.0, 180.0),
            fp(360.0, 390.0, 140.0, 70.0, 180.0),
            fp(465.0, 420.0, 140.0, 70.0, 90.0),
            fp(465.0, 560.0, 140.0, 70.0, 90.0),
            fp(360.0, 590.0, 140.0, 70.0, 0.0),
            fp(220.0, 590.0, 140.0, 70.0, 0.0),
        ];
        let screen = fp(25.0, 490.0, 200.0, 50.0, 90.0);
        assert!(u_met(&u, Some(&screen)));
        assert!(u_met(&u, None));
        // The same U open away from the screen is no U towards it.
        let behind = fp(775.0, 490.0, 200.0, 50.0, 270.0);
        assert!(!u_met(&u, Some(&behind)));
        // A 3 x 2 grid with gaps between its tables is no U.
        let grid: Vec<Footprint> = (0..6)
            .map(|k| {
                fp(
                    200.0 + 200.0 * (k % 3) as f64,
                    300.0 + 200.0 * (k / 3) as f64,
                    140.0,
                    70.0,
                    0.0,
                )
            })
            .collect();
        assert!(!u_met(&grid, Some(&screen)));
        // An L: backs on the top and left walls of a 420 x 400 room, meeting.
        let room = Room::rect(420.0, 400.0);
        let main = fp(80.0, 365.0, 160.0, 70.0, 180.0);
        let ret = fp(30.0, 270.0, 120.0, 60.0, 90.0);
        assert!(l_met(&[main, ret], &room));
        let apart = fp(30.0, 150.0, 120.0, 60.0, 90.0);
        assert!(!l_met(&[main, apart], &room));
    }
}
